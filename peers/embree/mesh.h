// NFF polygons and patches as triangle meshes for Embree's RTC_GEOMETRY_TYPE_TRIANGLE.
#pragma once

#include <array>
#include <vector>

#include "nff.h"

// One triangle mesh: a polygon's or a patch's triangles, each knowing its polygon.
struct Mesh {
  std::vector<float> vertices;     // x y z per vertex, lifted onto the polygon's plane
  std::vector<unsigned> indices;   // three per triangle
  std::vector<unsigned> polygon;   // per triangle: its index in Scene::polygons
  // Per triangle: i when it is the fan triangle (0, i, i+1) of a convex outline, so that
  // Embree's u, v are the weights of vertices i and i+1 (patch normals); 0 when the
  // outline was ear-clipped and the weights are computed from the hit point.
  std::vector<unsigned> fan;
  // Polygons whose outline crosses itself: kept as fans from vertex 0 (rtprof's
  // crossing test draws their even-odd region, which triangles cannot).
  int self_intersecting = 0;
};

// The triangles of the scene's polygons (`patches` false) or patches (`patches` true).
Mesh triangulate(const Scene& scene, bool patches);

// rtprof's patch weights (PlanarOutline::fan_weights): the first fan triangle
// (0, i, i+1) of the projected outline that holds the projected point `p`, and the
// point's weights in it; false when none does.
bool fan_weights(const Polygon& poly, Vec3 p, unsigned& i, float w[3]);
