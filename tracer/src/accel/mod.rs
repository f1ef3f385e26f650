//! Closest-hit and occlusion queries over a scene. Brute force is the thesis's software
//! reference; the SIMD batches ([`Simd`]), the BVH ([`Bvh`]) and the wide BVH with SIMD
//! lanes ([`WideBvh`]) answer the same queries faster.
//!
//! Phases: the intersectors mark the node work of the BVH as `traversal` and each
//! primitive test (or SIMD chunk of tests) as its kind's test phase; the queries
//! themselves (`closest hit`, `shadow query`) are marked by the shader that asks them.

mod brute_force;
mod bvh;
#[cfg(feature = "embree")]
mod embree;
mod simd;
pub(crate) mod triangulate;

pub use brute_force::BruteForce;
use brute_force::occluded_by_cones_and_planars;
pub use bvh::{
    Bvh, BvhBuilder, BvhShape, BvhStats, PACKET, WIDTH as BVH_WIDTH, WideBvh, WideBvhStats,
};
#[cfg(feature = "embree")]
pub use embree::{Embree, EmbreeCode, EmbreeError, EmbreeMode, EmbreePackets, NativeWidths};
pub use simd::Simd;

use crate::counter::{Counter, Phase};
use crate::ray::{Hit, PrimKind, PrimRef, Ray};
use crate::scene::Scene;

/// Answers the two queries a Whitted tracer asks of its scene.
pub trait Intersector: Sync {
    /// Whether this intersector walks packets of rays together (variant `packets`, the
    /// wide BVH only). The renderer compiles its packet path only where it is true.
    const PACKETS: bool = false;

    /// The closest intersection beyond `t_min` (counts one `calls.intersect`).
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit>;

    /// The closest hit of an eye ray that starts at the origin (the `bounded`
    /// variant); the default forgets the marker and runs [`Intersector::closest_hit`].
    fn closest_hit_from_eye<C: Counter>(&self, ray: &Ray<true>, c: &mut C) -> Option<Hit> {
        self.closest_hit(&ray.plain(), 0.0, c)
    }

    /// Whether anything lies in `(t_min, t_max)` (a shadow ray; counts one
    /// `calls.intersect`). May stop at the first blocker.
    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool;

    /// The closest hits of a packet of eye rays (variant `packets`): `hits[i]` for
    /// `rays[i]`, its work counted on `counters[i]`. The default asks one ray at a time;
    /// the wide BVH traverses the packet together.
    fn closest_hits<C: Counter>(&self, rays: &[Ray], hits: &mut [Option<Hit>], counters: &mut [C]) {
        for ((ray, hit), c) in rays.iter().zip(hits).zip(counters) {
            *hit = self.closest_hit(ray, 0.0, c);
        }
    }

    /// Whether anything lies in `(0, t_max[i])` along `rays[i]`, for a packet of shadow
    /// rays (variant `packets`): `blocked[i]`, its work counted on `counters[i]`. The
    /// default asks one ray at a time.
    fn occluded_packet<C: Counter>(
        &self,
        rays: &[Ray],
        t_max: &[f32],
        blocked: &mut [bool],
        counters: &mut [C],
    ) {
        for (((ray, &t_max), blocked), c) in rays.iter().zip(t_max).zip(blocked).zip(counters) {
            *blocked = self.occluded(ray, 0.0, t_max, c);
        }
    }

    /// [`Intersector::closest_hits`] for eye rays that start at the origin (`bounded`).
    fn closest_hits_from_eye<C: Counter>(
        &self,
        rays: &[Ray<true>],
        hits: &mut [Option<Hit>],
        counters: &mut [C],
    ) {
        for ((ray, hit), c) in rays.iter().zip(hits).zip(counters) {
            *hit = self.closest_hit_from_eye(ray, c);
        }
    }
}

/// Whether the CPU runs the AVX2 + FMA paths of the lane code (SIMD batches, wide BVH);
/// detected at run time, so the binary still runs on any x86-64.
#[cfg(target_arch = "x86_64")]
pub(crate) fn cpu_has_avx2_fma() -> bool {
    std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
}

#[cfg(not(target_arch = "x86_64"))]
pub(crate) fn cpu_has_avx2_fma() -> bool {
    false
}

/// Tests one primitive of `scene` against `ray` in `(t_min, t_max)`: the distance and
/// the hit's `aux` value, in the kind's test phase. The one dispatch on primitive kind
/// that the BVH leaves use.
#[inline(always)]
pub(crate) fn intersect_primitive<C: Counter, const FROM_EYE: bool>(
    scene: &Scene,
    prim: PrimRef,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    t_max: f32,
    c: &mut C,
) -> Option<(f32, f32)> {
    let i = prim.index as usize;
    match prim.kind {
        PrimKind::Sphere => {
            let _phase = C::enter_phase(Phase::SphereTest);
            scene.spheres[i]
                .intersect(ray, t_min, t_max, c)
                .map(|t| (t, 0.0))
        }
        PrimKind::Cylinder => {
            let _phase = C::enter_phase(Phase::CylinderTest);
            scene.cylinders[i].intersect(ray, t_min, t_max, c)
        }
        PrimKind::Cone => {
            let _phase = C::enter_phase(Phase::ConeTest);
            scene.cones[i].intersect(ray, t_min, t_max, c)
        }
        PrimKind::Polygon => {
            let _phase = C::enter_phase(Phase::PolygonTest);
            scene.polygons[i]
                .intersect(ray, t_min, t_max, c)
                .map(|t| (t, 0.0))
        }
        PrimKind::Patch => {
            let _phase = C::enter_phase(Phase::PatchTest);
            scene.patches[i]
                .intersect(ray, t_min, t_max, c)
                .map(|t| (t, 0.0))
        }
    }
}
