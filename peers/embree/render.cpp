// Shading after rtprof's (tracer/src/shading.rs), read from its code:
// - diffuse-only: the first light's Lambert term N·L with the primitive's own outward
//   normal (never turned toward the viewer), gray; the background's luma where N·L < 0,
//   where nothing is hit, or when there is no light;
// - Whitted: ambient 0.1·Kd·colour, then per light (shadow ray only when the normal,
//   turned toward the ray, faces it; any primitive blocks it) Kd·(N·L)·colour·light
//   plus the Phong highlight Ks·(R·L)^Shine·light; below the maximum depth a refraction
//   ray (Snell; total internal reflection adds T to the reflection's weight) and a
//   reflection ray of weight Ks (+T) on every reflective or transmitting hit; shadow
//   and reflection rays leave 1e-4·(1 + |P|max) off the surface, refraction rays as far
//   below it.
// A pixel is accumulated as Σ weight × local colour down the ray tree (rtprof nests
// the sums instead: the same terms, added in another order). The single and the packet
// modes add every pixel's terms in the same order, so they draw the same bits.

#include "render.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

namespace {

constexpr float AMBIENT = 0.1f;        // rtprof's shading::AMBIENT
constexpr float OFFSET_SCALE = 1e-4f;  // rtprof's shading::OFFSET_SCALE

struct Ray {
  Vec3 org, dir;
};

// A hit being shaded: rtprof's Surface and LitPoint.
struct Lit {
  Vec3 point, normal, facing, lift, above, mirror;
  bool front = true, reflective = false;
  Material m;
  Rgb color;
};

struct Shadow {
  Vec3 dir;
  float distance = 0, n_dot = 0;
};

class Renderer {
 public:
  Renderer(const World& w, const Camera& c, const Options& o, std::vector<Rgb>& frame)
      : world_(w), nff_(w.nff), camera_(c), o_(o), frame_(frame) {
    background_gray_ = Rgb::gray(nff_.background.luminance());
  }

  void run() {
    int tile_rows = (o_.height + 1) / 2;
    std::atomic<int> next{0};
    auto worker = [&]() {
      for (int row; (row = next.fetch_add(1)) < tile_rows;)
        for (int x0 = 0; x0 < o_.width; x0 += 4) tile(x0, 2 * row);
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < o_.threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (o_.shading == Shading::Gray)
      for (Rgb& p : frame_) p = Rgb::gray(p.luminance());
  }

 private:
  const World& world_;
  const Scene& nff_;
  const Camera& camera_;
  Options o_;
  std::vector<Rgb>& frame_;
  Rgb background_gray_;

  static void context(RTCIntersectContext& ctx, bool coherent) {
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  }

  // One 4×2 tile at (x0, y0): lane i is pixel (x0 + i % 4, y0 + i / 4).
  void tile(int x0, int y0) {
    Ray rays[8];
    Rgb* pixels[8];
    int valid[8];
    for (int i = 0; i < 8; ++i) {
      int x = x0 + i % 4, y = y0 + i / 4;
      valid[i] = x < o_.width && y < o_.height ? -1 : 0;
      if (!valid[i]) continue;
      rays[i] = {camera_.eye, camera_.direction(x, y)};
      pixels[i] = &frame_[size_t(y) * o_.width + x];
    }
    RTCIntersectContext ctx;
    context(ctx, true);
    if (o_.mode == Mode::Single) {
      for (int i = 0; i < 8; ++i) {
        if (!valid[i]) continue;
        if (o_.shading == Shading::DiffuseOnly) {
          RTCRayHit rh = ray_hit(rays[i]);
          rtcIntersect1(world_.scene, &ctx, &rh);
          *pixels[i] = diffuse_only(rays[i], rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
                                    {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
        } else {
          trace1(rays[i], 1, Rgb::gray(1), *pixels[i]);
        }
      }
      return;
    }
    Packet p;
    for (int i = 0; i < 8; ++i) {
      p.valid[i] = valid[i];
      if (!valid[i]) continue;
      set_lane(p.rh.ray, i, rays[i], std::numeric_limits<float>::infinity());
      p.weight[i] = Rgb::gray(1);
      p.pixel[i] = pixels[i];
    }
    if (o_.shading == Shading::DiffuseOnly) {
      for (int i = 0; i < 8; ++i) p.rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect8(p.valid, world_.scene, &ctx, &p.rh);
      for (int i = 0; i < 8; ++i)
        if (valid[i]) {
          const RTCHit8& h = p.rh.hit;
          *pixels[i] = diffuse_only(rays[i], p.rh.ray.tfar[i], h.geomID[i], h.primID[i], h.u[i], h.v[i],
                                    {h.Ng_x[i], h.Ng_y[i], h.Ng_z[i]});
        }
      return;
    }
    trace8(p, 1);
  }

  // rtprof's diffuse_only.
  Rgb diffuse_only(const Ray& ray, float t, unsigned geom, unsigned prim, float u, float v, Vec3 ng) const {
    if (geom == RTC_INVALID_GEOMETRY_ID || nff_.lights.empty()) return background_gray_;
    Vec3 point = ray.org + ray.dir * t;
    Vec3 normal, geometric;
    unsigned material;
    world_.normals(geom, prim, u, v, ng, point, normal, geometric, material);
    Vec3 l = normalize(nff_.lights[0].position - point);
    float lambert = dot(normal, l);
    return lambert >= 0 ? Rgb::gray(lambert) : background_gray_;
  }

  static RTCRayHit ray_hit(const Ray& r) {
    RTCRayHit rh;
    rh.ray.org_x = r.org.x, rh.ray.org_y = r.org.y, rh.ray.org_z = r.org.z;
    rh.ray.dir_x = r.dir.x, rh.ray.dir_y = r.dir.y, rh.ray.dir_z = r.dir.z;
    rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0, rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
  }

  static void set_lane(RTCRay8& r, int i, const Ray& ray, float tfar) {
    r.org_x[i] = ray.org.x, r.org_y[i] = ray.org.y, r.org_z[i] = ray.org.z;
    r.dir_x[i] = ray.dir.x, r.dir_y[i] = ray.dir.y, r.dir_z[i] = ray.dir.z;
    r.tnear[i] = 0, r.tfar[i] = tfar, r.time[i] = 0, r.mask[i] = ~0u, r.id[i] = unsigned(i), r.flags[i] = 0;
  }

  // rtprof's lit_point: the surface with its normals turned toward the ray, the
  // ambient term, the lifted point and the mirror direction.
  Lit lit_point(const Ray& ray, float t, unsigned geom, unsigned prim, float u, float v, Vec3 ng) const {
    Lit s;
    s.point = ray.org + ray.dir * t;
    unsigned material;
    world_.normals(geom, prim, u, v, ng, s.point, s.normal, s.facing, material);
    s.m = material < nff_.materials.size() ? nff_.materials[material] : Material{};
    // A point on a sphere's centre or a cone's axis has no direction: facing the ray.
    if (!finite(s.facing) || !finite(s.normal)) s.facing = s.normal = -ray.dir;
    s.front = dot(s.facing, ray.dir) < 0;
    if (!s.front) s.facing = -s.facing;
    if (geom == SMOOTH) {
      if (dot(s.normal, s.facing) < 0) s.normal = -s.normal;
    } else {
      s.normal = s.facing;
    }
    s.color = s.m.color * (AMBIENT * s.m.kd);
    float offset = OFFSET_SCALE * (1.0f + max_abs(s.point));
    s.lift = s.facing * offset;
    s.above = s.point + s.lift;
    s.reflective = s.m.ks > 0 || s.m.t > 0;
    if (s.reflective) s.mirror = ray.dir - s.normal * (2.0f * dot(ray.dir, s.normal));
    return s;
  }

  // The shadow ray toward `light`, or false when the normal faces away from it.
  static bool shadow_ray(const Lit& s, const Light& light, Shadow& out) {
    Vec3 to_light = light.position - s.point;
    out.n_dot = dot(s.normal, to_light);
    if (out.n_dot <= 0) return false;
    out.distance = std::sqrt(dot(to_light, to_light));
    out.dir = to_light * (1.0f / out.distance);
    return true;
  }

  // Diffuse and Phong highlight of an unblocked light (rtprof's color_contribution).
  static void add_light(Lit& s, const Light& light, const Shadow& sh) {
    float cos_theta = sh.n_dot / sh.distance;
    s.color += s.m.color * light.color * (s.m.kd * cos_theta);
    if (s.reflective && s.m.ks > 0) {
      float cos_alpha = dot(s.mirror, sh.dir);
      if (cos_alpha > 0) s.color += light.color * (s.m.ks * std::pow(std::min(cos_alpha, 1.0f), s.m.shine));
    }
  }

  // The refraction and reflection rays of a hit and their weights.
  struct Spawn {
    bool refract = false, reflect = false;
    Ray refracted, reflected;
    Rgb refract_weight, reflect_weight;
  };

  Spawn spawn(const Lit& s, const Ray& ray, Rgb weight) const {
    Spawn out;
    if (!s.reflective) return out;
    float reflect_weight = s.m.ks;
    if (s.m.t > 0) {
      float eta = s.front ? 1.0f / s.m.ior : s.m.ior;
      float cos_i = -dot(ray.dir, s.normal);
      float k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
      if (k < 0) {
        reflect_weight += s.m.t;  // total internal reflection
      } else {
        Vec3 dir = ray.dir * eta + s.normal * (eta * cos_i - std::sqrt(k));
        out.refract = true;
        out.refracted = {s.point - s.lift, dir};
        out.refract_weight = weight * s.m.t;
      }
    }
    out.reflect = true;
    out.reflected = {s.above, s.mirror};
    out.reflect_weight = weight * reflect_weight;
    return out;
  }

  // One ray of the tree at `depth` (the eye ray is 1), adding weight × its colour.
  void trace1(const Ray& ray, int depth, Rgb weight, Rgb& pixel) const {
    RTCIntersectContext ctx;
    context(ctx, depth == 1);
    RTCRayHit rh = ray_hit(ray);
    rtcIntersect1(world_.scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      pixel += weight * nff_.background;
      return;
    }
    Lit s = lit_point(ray, rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
                      {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
    for (const Light& light : nff_.lights) {
      Shadow sh;
      if (shadow_ray(s, light, sh) && !occluded1(s.above, sh, depth == 1)) add_light(s, light, sh);
    }
    pixel += weight * s.color;
    if (depth >= o_.depth) return;
    Spawn next = spawn(s, ray, weight);
    if (next.refract) trace1(next.refracted, depth + 1, next.refract_weight, pixel);
    if (next.reflect) trace1(next.reflected, depth + 1, next.reflect_weight, pixel);
  }

  bool occluded1(Vec3 from, const Shadow& sh, bool coherent) const {
    RTCIntersectContext ctx;
    context(ctx, coherent);
    RTCRay r;
    r.org_x = from.x, r.org_y = from.y, r.org_z = from.z;
    r.dir_x = sh.dir.x, r.dir_y = sh.dir.y, r.dir_z = sh.dir.z;
    r.tnear = 0, r.tfar = sh.distance, r.time = 0, r.mask = ~0u, r.id = 0, r.flags = 0;
    rtcOccluded1(world_.scene, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar to -inf for an occluded ray
  }

  // Up to eight rays of one tree level, each lane on its own pixel.
  struct Packet {
    RTCRayHit8 rh;
    alignas(32) int valid[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    Rgb weight[8];
    Rgb* pixel[8] = {};
  };

  static Ray lane_ray(const RTCRay8& r, int i) {
    return {{r.org_x[i], r.org_y[i], r.org_z[i]}, {r.dir_x[i], r.dir_y[i], r.dir_z[i]}};
  }

  void trace8(Packet& p, int depth) const {
    int active = 0, last = 0;
    for (int i = 0; i < 8; ++i)
      if (p.valid[i]) ++active, last = i;
    if (active == 0) return;
    if (active == 1) {
      // One ray left: a packet does not pay.
      trace1(lane_ray(p.rh.ray, last), depth, p.weight[last], *p.pixel[last]);
      return;
    }
    for (int i = 0; i < 8; ++i) p.rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext ctx;
    context(ctx, depth == 1);
    rtcIntersect8(p.valid, world_.scene, &ctx, &p.rh);
    Lit lit[8];
    bool hit[8] = {};
    Ray rays[8];
    for (int i = 0; i < 8; ++i) {
      if (!p.valid[i]) continue;
      rays[i] = lane_ray(p.rh.ray, i);
      const RTCHit8& h = p.rh.hit;
      if (h.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
        *p.pixel[i] += p.weight[i] * nff_.background;
        continue;
      }
      hit[i] = true;
      lit[i] = lit_point(rays[i], p.rh.ray.tfar[i], h.geomID[i], h.primID[i], h.u[i], h.v[i],
                         {h.Ng_x[i], h.Ng_y[i], h.Ng_z[i]});
    }
    // Each light's shadow rays of the packet together.
    for (const Light& light : nff_.lights) {
      alignas(32) int shadow_valid[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      Shadow sh[8];
      RTCRay8 shadows;
      int count = 0, one = 0;
      for (int i = 0; i < 8; ++i) {
        if (!hit[i] || !shadow_ray(lit[i], light, sh[i])) continue;
        shadow_valid[i] = -1, ++count, one = i;
        set_lane(shadows, i, {lit[i].above, sh[i].dir}, sh[i].distance);
      }
      if (count == 0) continue;
      if (count == 1) {
        if (!occluded1(lit[one].above, sh[one], depth == 1)) add_light(lit[one], light, sh[one]);
        continue;
      }
      rtcOccluded8(shadow_valid, world_.scene, &ctx, &shadows);
      for (int i = 0; i < 8; ++i)
        if (shadow_valid[i] && !(shadows.tfar[i] < 0)) add_light(lit[i], light, sh[i]);
    }
    Packet refracted, reflected;
    for (int i = 0; i < 8; ++i) {
      if (!hit[i]) continue;
      *p.pixel[i] += p.weight[i] * lit[i].color;
      if (depth >= o_.depth) continue;
      Spawn next = spawn(lit[i], rays[i], p.weight[i]);
      if (next.refract) {
        refracted.valid[i] = -1, refracted.weight[i] = next.refract_weight, refracted.pixel[i] = p.pixel[i];
        set_lane(refracted.rh.ray, i, next.refracted, std::numeric_limits<float>::infinity());
      }
      if (next.reflect) {
        reflected.valid[i] = -1, reflected.weight[i] = next.reflect_weight, reflected.pixel[i] = p.pixel[i];
        set_lane(reflected.rh.ray, i, next.reflected, std::numeric_limits<float>::infinity());
      }
    }
    // Refraction before reflection, as rtprof (and trace1) add them.
    trace8(refracted, depth + 1);
    trace8(reflected, depth + 1);
  }
};

}  // namespace

void render(const World& world, const Camera& camera, const Options& options, std::vector<Rgb>& frame) {
  Renderer(world, camera, options, frame).run();
}
