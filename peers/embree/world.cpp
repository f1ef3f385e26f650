// Building the Embree scene the way Embree's users do: Embree's own geometry types
// (triangles, sphere points, cone curves), buffers it allocates, build quality high.

#include "world.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

void on_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "rtprof-embree: Embree error %d: %s\n", int(code), message ? message : "");
  std::exit(1);
}

RTCGeometry mesh_geometry(RTCDevice device, const Mesh& mesh) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  size_t vertices = mesh.vertices.size() / 3, triangles = mesh.indices.size() / 3;
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), vertices));
  std::memcpy(v, mesh.vertices.data(), mesh.vertices.size() * sizeof(float));
  auto* i = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(unsigned), triangles));
  std::memcpy(i, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
  return g;
}

RTCGeometry sphere_geometry(RTCDevice device, const Scene& s) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                        4 * sizeof(float), s.spheres.size()));
  for (const Sphere& sp : s.spheres) {
    // Embree's spheres are two-sided: a negative (inside-only) NFF radius draws both.
    *v++ = sp.center.x, *v++ = sp.center.y, *v++ = sp.center.z, *v++ = std::fabs(sp.radius);
  }
  return g;
}

// NFF's `c` is an open cone (or cylinder): no end caps. Embree 3.13's cone curve caps
// a segment's ends with discs unless the segment says it has neighbours
// (RTC_CURVE_FLAG_NEIGHBOR_LEFT/RIGHT, coneline_intersector.h: cL = !leftExists): every
// segment here is its own curve and says it has both, so neither end is capped and
// the surface is rtprof's open cone. The cone intersector reads no neighbour vertex.
RTCGeometry cone_geometry(RTCDevice device, const Scene& s) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
  size_t n = s.cones.size();
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2 * n));
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), n));
  auto* flags = static_cast<unsigned char*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, n));
  for (size_t i = 0; i < n; ++i) {
    const Cone& c = s.cones[i];
    // rtprof's cone: radii by magnitude (a negative pair only hides the outer wall).
    *v++ = c.base.x, *v++ = c.base.y, *v++ = c.base.z, *v++ = std::fabs(c.base_radius);
    *v++ = c.apex.x, *v++ = c.apex.y, *v++ = c.apex.z, *v++ = std::fabs(c.apex_radius);
    index[i] = unsigned(2 * i);
    flags[i] = RTC_CURVE_FLAG_NEIGHBOR_LEFT | RTC_CURVE_FLAG_NEIGHBOR_RIGHT;
  }
  return g;
}

}  // namespace

World::World(const Scene& s, int threads, bool robust) : nff(s), flat(triangulate(s, false)), smooth(triangulate(s, true)) {
  // Build threads as asked (Embree's default is every core), so that a one-thread run
  // leaves no builder threads spinning beside the render.
  std::string config = "threads=" + std::to_string(threads);
  device = rtcNewDevice(config.c_str());
  if (!device) {
    std::fprintf(stderr, "rtprof-embree: cannot create an Embree device (error %d)\n", int(rtcGetDeviceError(nullptr)));
    std::exit(1);
  }
  rtcSetDeviceErrorFunction(device, on_error, nullptr);
  scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  // Embree's default triangle test is not watertight: a ray through a shared edge
  // can miss both triangles (the diagonal of rings' floor, a pixel in a thousand at
  // most). --robust asks for the watertight test, at 5-20 % of the trace time.
  if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  auto attach = [&](RTCGeometry g, unsigned id) {
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, id);
    rtcReleaseGeometry(g);
  };
  if (!flat.polygon.empty()) attach(mesh_geometry(device, flat), FLAT);
  if (!smooth.polygon.empty()) attach(mesh_geometry(device, smooth), SMOOTH);
  if (!s.spheres.empty()) attach(sphere_geometry(device, s), SPHERES);
  if (!s.cones.empty()) attach(cone_geometry(device, s), CONES);
  rtcCommitScene(scene);
}

World::~World() {
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}

void World::normals(unsigned geom, unsigned prim, float u, float v, Vec3 ng, Vec3 point, Vec3& shading,
                    Vec3& geometric, unsigned& material) const {
  switch (geom) {
    case FLAT: {
      // The polygon's own normal (its first three vertices), as rtprof shades it;
      // the triangle's Ng would follow the ear's winding instead.
      const Polygon& p = nff.polygons[flat.polygon[prim]];
      shading = geometric = p.normal;
      material = p.material;
      return;
    }
    case SMOOTH: {
      const Polygon& p = nff.polygons[smooth.polygon[prim]];
      geometric = p.normal;
      material = p.material;
      unsigned i = smooth.fan[prim];
      float w[3];
      if (i != 0) {
        // A fan triangle (0, i, i+1): Embree's u, v weigh vertices i and i+1.
        w[1] = u, w[2] = v, w[0] = 1.0f - u - v;
      } else if (!fan_weights(p, point, i, w)) {
        shading = p.normal;
        return;
      }
      Vec3 sum = p.normals[0] * w[0] + p.normals[i] * w[1];
      sum = sum + p.normals[i + 1] * w[2];
      shading = dot(sum, sum) > 1e-12f ? normalize(sum) : p.normal;
      return;
    }
    case SPHERES: {
      // Embree's Ng of a sphere point is the hit point less the centre.
      material = nff.spheres[prim].material;
      shading = geometric = normalize(ng);
      return;
    }
    default: {
      // Embree's Ng of a cone curve is the cone's outward normal at the hit.
      material = nff.cones[prim].material;
      shading = geometric = normalize(ng);
      return;
    }
  }
}
