// Triangulation of NFF polygons, after rtprof's own for its Embree variant
// (tracer/src/accel/triangulate.rs): rtprof's polygon test hits the plane of the first
// three vertices and keeps the hit when its projection onto two coordinate axes (the
// normal's largest component dropped) lies inside the projected outline. So the
// outline is ear-clipped in that projection (concave outlines too: the SPD's gears)
// and each vertex is moved along the dropped axis onto that plane; for a planar
// polygon this moves vertices by rounding only.

#include "mesh.h"

#include <array>
#include <cmath>

namespace {

using P2 = std::array<double, 2>;

double cross2(P2 o, P2 q, P2 r) { return (q[0] - o[0]) * (r[1] - o[1]) - (q[1] - o[1]) * (r[0] - o[0]); }

bool in_triangle(P2 p, P2 a, P2 b, P2 c, double sign) {
  return cross2(a, b, p) * sign >= 0 && cross2(b, c, p) * sign >= 0 && cross2(c, a, p) * sign >= 0;
}

enum class Ear { Unknown, Collinear, Clip, Not };

struct EarStatus {
  Ear ear = Ear::Unknown;
  double diagonal = 0;  // squared length of the diagonal an ear cuts
};

EarStatus ear_at(const std::vector<P2>& p, const std::vector<size_t>& next, size_t a, size_t b,
                 size_t c, double sign) {
  double turn = cross2(p[a], p[b], p[c]) * sign;
  if (turn == 0) return {Ear::Collinear, 0};
  if (turn < 0) return {Ear::Not, 0};  // reflex
  for (size_t j = next[c]; j != a; j = next[j]) {
    bool corner = p[j] == p[a] || p[j] == p[b] || p[j] == p[c];
    if (!corner && in_triangle(p[j], p[a], p[b], p[c], sign)) return {Ear::Not, 0};
  }
  double dx = p[c][0] - p[a][0], dy = p[c][1] - p[a][1];
  return {Ear::Clip, dx * dx + dy * dy};
}

// Ear clipping of a simple outline, rtprof's way: the ear of the shortest diagonal
// first (no fans of slivers), collinear and repeated vertices dropped. False for an
// outline that crosses itself (the ears' area is not the outline's).
bool ear_clip(const std::vector<P2>& p, std::vector<std::array<unsigned, 3>>& out) {
  size_t count = p.size();
  double area2 = 0;
  for (size_t i = 0; i < count; ++i) {
    P2 a = p[i], b = p[(i + 1) % count];
    area2 += a[0] * b[1] - b[0] * a[1];
  }
  if (area2 == 0 || !std::isfinite(area2)) return false;
  double sign = area2 > 0 ? 1 : -1;
  std::vector<size_t> prev(count), next(count);
  for (size_t i = 0; i < count; ++i) prev[i] = (i + count - 1) % count, next[i] = (i + 1) % count;
  std::vector<EarStatus> status(count);
  size_t head = 0, left = count;
  double clipped = 0;
  auto pick = [&](size_t& chosen) {
    bool found = false;
    double best = 0;
    size_t v = head;
    for (size_t k = 0; k < left; ++k, v = next[v]) {
      if (status[v].ear == Ear::Unknown) status[v] = ear_at(p, next, prev[v], v, next[v], sign);
      if (status[v].ear == Ear::Collinear) {
        chosen = v;
        return true;
      }
      if (status[v].ear == Ear::Clip && (!found || status[v].diagonal < best))
        found = true, best = status[v].diagonal, chosen = v;
    }
    return found;
  };
  while (left > 3) {
    size_t b = 0;
    if (!pick(b)) {
      // Cached refusals are stale only for degenerate outlines: look again afresh.
      for (auto& s : status) s.ear = Ear::Unknown;
      if (!pick(b)) return false;
    }
    size_t a = prev[b], c = next[b];
    if (status[b].ear != Ear::Collinear) {
      clipped += cross2(p[a], p[b], p[c]) * sign;
      out.push_back({unsigned(a), unsigned(b), unsigned(c)});
    }
    next[a] = c, prev[c] = a;
    status[a].ear = status[c].ear = Ear::Unknown;
    if (head == b) head = c;
    --left;
  }
  size_t r0 = head, r1 = next[head], r2 = next[next[head]];
  double turn = cross2(p[r0], p[r1], p[r2]) * sign;
  if (turn < 0) return false;
  if (turn > 0) clipped += turn, out.push_back({unsigned(r0), unsigned(r1), unsigned(r2)});
  return std::fabs(clipped - std::fabs(area2)) <= 1e-9 * std::fabs(area2);
}

// Whether the projected outline turns one way at every vertex (a fan from vertex 0
// then covers it, and gives rtprof's patch weights directly).
bool convex(const std::vector<P2>& p) {
  size_t n = p.size();
  int sign = 0;
  for (size_t i = 0; i < n; ++i) {
    double turn = cross2(p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
    int s = (turn > 0) - (turn < 0);
    if (s == 0) continue;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

}  // namespace

Mesh triangulate(const Scene& scene, bool patches) {
  Mesh mesh;
  for (size_t index = 0; index < scene.polygons.size(); ++index) {
    const Polygon& poly = scene.polygons[index];
    if (poly.normals.empty() == patches) continue;
    int dropped = dominant_axis(poly.normal);
    int a = (dropped + 1) % 3, b = (dropped + 2) % 3;
    double n[3] = {poly.normal.x, poly.normal.y, poly.normal.z};
    Vec3 v0 = poly.vertices[0];
    std::vector<P2> projected;
    unsigned base = unsigned(mesh.vertices.size() / 3);
    for (Vec3 v : poly.vertices) {
      projected.push_back({double(v[a]), double(v[b])});
      // Onto the plane n·(p - v0) = 0 along the dropped axis (|n[dropped]| ≥ 1/√3).
      double lifted = double(v0[dropped]) -
                      (n[a] * (double(v[a]) - v0[a]) + n[b] * (double(v[b]) - v0[b])) / n[dropped];
      Vec3 p = v;
      p[dropped] = float(lifted);
      mesh.vertices.insert(mesh.vertices.end(), {p.x, p.y, p.z});
    }
    std::vector<std::array<unsigned, 3>> triangles;
    std::vector<unsigned> fans;
    bool fan = patches && convex(projected);
    if (!fan && !ear_clip(projected, triangles)) {
      ++mesh.self_intersecting;
      triangles.clear();
      fan = true;
    }
    if (fan) {
      // Fan triangles of zero projected area are skipped, as rtprof's fan_weights does.
      for (unsigned i = 1; i + 1 < poly.vertices.size(); ++i)
        if (cross2(projected[0], projected[i], projected[i + 1]) != 0)
          triangles.push_back({0, i, i + 1}), fans.push_back(i);
    } else {
      fans.assign(triangles.size(), 0);
    }
    for (size_t t = 0; t < triangles.size(); ++t) {
      for (unsigned k : triangles[t]) mesh.indices.push_back(base + k);
      mesh.polygon.push_back(unsigned(index));
      mesh.fan.push_back(patches ? fans[t] : 0);
    }
  }
  return mesh;
}

bool fan_weights(const Polygon& poly, Vec3 p, unsigned& i, float w[3]) {
  // rtprof's projection: the axes kept when the normal's largest component is dropped.
  static const int axes[3][2] = {{1, 2}, {2, 0}, {0, 1}};
  const int* ax = axes[dominant_axis(poly.normal)];
  auto project = [&](Vec3 v) { return std::array<float, 2>{v[ax[0]], v[ax[1]]}; };
  auto cross = [](std::array<float, 2> a, std::array<float, 2> b) { return a[0] * b[1] - a[1] * b[0]; };
  auto rel = [](std::array<float, 2> a, std::array<float, 2> o) {
    return std::array<float, 2>{a[0] - o[0], a[1] - o[1]};
  };
  const float slack = -1e-4f;
  auto p0 = project(poly.vertices[0]);
  auto d = rel(project(p), p0);
  for (size_t k = 1; k + 1 < poly.vertices.size(); ++k) {
    auto e1 = rel(project(poly.vertices[k]), p0), e2 = rel(project(poly.vertices[k + 1]), p0);
    float area = cross(e1, e2);
    if (area == 0) continue;
    float w1 = cross(d, e2) / area, w2 = cross(e1, d) / area, w0 = 1.0f - w1 - w2;
    if (w0 >= slack && w1 >= slack && w2 >= slack) {
      i = unsigned(k), w[0] = w0, w[1] = w1, w[2] = w2;
      return true;
    }
  }
  return false;
}
