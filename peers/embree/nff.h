// The scene as an NFF file describes it (Eric Haines's Neutral File Format, as rtprof
// reads and writes it: tracer/src/nff.rs, tracer/src/nff_writer.rs), and its reader.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "vec.h"

// An `f` line: colour, Kd, Ks, Phong exponent, transmittance, index of refraction.
// Primitives before any `f` get the default: white, Kd 1 (rtprof's Material::default).
struct Material {
  Rgb color{1, 1, 1};
  float kd = 1, ks = 0, shine = 1, t = 0, ior = 1;
};

struct Light {
  Vec3 position;
  Rgb color;  // the SPD default sqrt(n)/(2n) gray when the line gave none
};

struct View {
  Vec3 from, at, up;
  float angle_deg = 0;  // from the centre of the top sample row to the bottom one
  int width = 0, height = 0;
};

struct Sphere {
  Vec3 center;
  float radius;  // as written; a negative one (inside only) is drawn two-sided
  unsigned material;
};

// An open cone or cylinder (`c`), no end caps.
struct Cone {
  Vec3 base, apex;
  float base_radius, apex_radius;
  unsigned material;
};

// A polygon (`p`) or a patch (`pp`, with a normal per vertex).
struct Polygon {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;  // unit vertex normals; empty for a polygon
  Vec3 normal;                // unit, from the first three vertices, as rtprof's
  unsigned material;
};

struct Scene {
  View view;
  Rgb background;
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Sphere> spheres;
  std::vector<Cone> cones;
  std::vector<Polygon> polygons;  // polygons and patches
};

// A malformed file: the line (1-based) and what was expected.
struct NffError : std::runtime_error {
  int line;
  NffError(int line_, const std::string& what) : std::runtime_error(what), line(line_) {}
};

// Reads `path`; throws NffError (line 0 when the file cannot be read).
Scene read_nff(const std::string& path);
