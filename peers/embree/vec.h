// Small single-precision vector and colour types. rtprof computes in f32 throughout,
// so the yardstick does too: the same sums in the same order give the same picture.
#pragma once

#include <algorithm>
#include <cmath>

struct Vec3 {
  float x = 0, y = 0, z = 0;
  Vec3() = default;
  Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// As rtprof's `normalize`: a times the reciprocal of its length.
inline Vec3 normalize(Vec3 a) { return a * (1.0f / std::sqrt(dot(a, a))); }
inline float max_abs(Vec3 a) {
  return std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
}
inline bool finite(Vec3 a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// The index of the largest component in magnitude (first of equals), as rtprof's
// `dominant_axis`.
inline int dominant_axis(Vec3 a) {
  float ax = std::fabs(a.x), ay = std::fabs(a.y), az = std::fabs(a.z);
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}

// Linear RGB, nominally in [0, 1].
struct Rgb {
  float r = 0, g = 0, b = 0;
  Rgb() = default;
  Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  static Rgb gray(float v) { return {v, v, v}; }
  // Rec. 601 luma, rtprof's gray value of a colour.
  float luminance() const { return 0.299f * r + 0.587f * g + 0.114f * b; }
};

inline Rgb operator+(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline Rgb& operator+=(Rgb& a, Rgb b) { return a = a + b; }
inline Rgb operator*(Rgb a, Rgb b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline Rgb operator*(Rgb a, float s) { return {a.r * s, a.g * s, a.b * s}; }
