// The NFF scene in Embree: one device, one scene of four geometries of Embree's own
// types, and what shading needs to read back from a hit (normals and materials).
#pragma once

#include <embree3/rtcore.h>

#include "mesh.h"
#include "nff.h"

// The geometry ids the scene's geometries are attached with.
enum GeometryId : unsigned { FLAT = 0, SMOOTH = 1, SPHERES = 2, CONES = 3 };

struct World {
  const Scene& nff;
  Mesh flat;    // polygons: one normal per polygon
  Mesh smooth;  // patches: vertex normals interpolated
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  // Builds the Embree scene (rtcCommitScene is the build: time it around this), with
  // `threads` build threads; `robust`: RTC_SCENE_FLAG_ROBUST (watertight triangles).
  World(const Scene& nff, int threads, bool robust);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // The hit primitive's normals at `point` as rtprof's `normals` gives them: the
  // shading normal (a patch's interpolated one) and the geometric one, both the
  // primitive's own (outward: never turned toward the ray), and its material.
  void normals(unsigned geom, unsigned prim, float u, float v, Vec3 ng, Vec3 point, Vec3& shading,
               Vec3& geometric, unsigned& material) const;

  size_t triangles() const { return flat.polygon.size() + smooth.polygon.size(); }
};
