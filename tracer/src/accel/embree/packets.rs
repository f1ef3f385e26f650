//! Embree's packet API as an intersector (the `embree-packets` variant): the renderer's
//! packets of [`PACKET`] neighbouring eye rays go to `rtcIntersect8`, and their shadow
//! rays, light by light, to `rtcOccluded8`, with the coherent-rays flag; reflected and
//! refracted rays, traced one at a time, to the single-ray queries. The scene is
//! Embree's [`EmbreeMode::Curves`] mapping: every primitive Embree has a kernel for is
//! Embree's.
//!
//! Eight lanes because the renderer's packets are eight rays, and eight is what
//! Embree runs natively with AVX/AVX2 ([`EmbreePackets::native_widths`]);
//! `rtcIntersect16` is native only with AVX-512 and would need packets of sixteen.
//!
//! Counting is the single-ray queries': one `calls.intersect` per ray of a packet
//! (on that ray's counter), nothing inside Embree; the packet runs as one `traversal`
//! phase.

use super::ffi::*;
use super::{Embree, EmbreeError, EmbreeMode};
use crate::accel::{Intersector, PACKET};
use crate::counter::{Counter, Phase, Stat};
use crate::ray::{Hit, Ray};
use crate::scene::Scene;
use crate::vec3::Vec3;

/// The lanes of `rtcIntersect8` / `rtcOccluded8`.
const LANES: usize = 8;
// The renderer's packets fill Embree's eight lanes exactly.
const _: () = assert!(PACKET == LANES);

/// `rtcIntersect8`'s valid mask: -1 for an active lane, 0 for an inactive one; Embree
/// reads it with aligned vector loads.
#[repr(C, align(32))]
struct Valid8([i32; LANES]);

/// Embree 3 answering the renderer's packets with its packet API (see the module
/// documentation).
#[derive(Debug)]
pub struct EmbreePackets<'s> {
    /// The scene, and the single-ray queries.
    pub(super) embree: Embree<'s>,
}

/// Which packet widths this Embree build runs natively on this CPU
/// (`rtcGetDeviceProperty`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NativeWidths {
    pub ray8: bool,
    pub ray16: bool,
}

impl<'s> EmbreePackets<'s> {
    /// Builds and commits the Embree scene for `scene` ([`EmbreeMode::Curves`]).
    pub fn new(scene: &'s Scene) -> Result<Self, EmbreeError> {
        let embree = Embree::with_mode(scene, EmbreeMode::Curves)?;
        Ok(Self { embree })
    }

    /// As [`Embree::memory_bytes`].
    pub fn memory_bytes(&self) -> usize {
        self.embree.memory_bytes()
    }

    /// Whether `rtcIntersect8` and `rtcIntersect16` run natively here (otherwise
    /// Embree splits the packet into narrower ones).
    pub fn native_widths(&self) -> NativeWidths {
        // SAFETY: a live device; the properties are read-only queries.
        let (ray8, ray16) = unsafe {
            (
                rtcGetDeviceProperty(
                    self.embree.device,
                    RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED,
                ),
                rtcGetDeviceProperty(
                    self.embree.device,
                    RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED,
                ),
            )
        };
        NativeWidths {
            ray8: ray8 == 1,
            ray16: ray16 == 1,
        }
    }

    /// The closest hits in `(0, ∞)` of at most [`LANES`] rays, one `rtcIntersect8`.
    fn closest8<C: Counter>(&self, rays: &[Ray], hits: &mut [Option<Hit>], counters: &mut [C]) {
        let n = rays.len().min(hits.len()).min(counters.len()).min(LANES);
        if n == 0 {
            return;
        }
        for c in &mut counters[..n] {
            c.tally(Stat::Intersect);
        }
        let _phase = C::enter_phase(Phase::Traversal);
        let (valid, ray) = packet(&rays[..n], &[f32::INFINITY; LANES]);
        let mut rayhit = RTCRayHit8 {
            ray,
            hit: RTCHit8 {
                ng_x: [0.0; LANES],
                ng_y: [0.0; LANES],
                ng_z: [0.0; LANES],
                u: [0.0; LANES],
                v: [0.0; LANES],
                prim_id: [RTC_INVALID_GEOMETRY_ID; LANES],
                geom_id: [RTC_INVALID_GEOMETRY_ID; LANES],
                inst_id: [[RTC_INVALID_GEOMETRY_ID; LANES]],
            },
        };
        let mut context = RTCIntersectContext::with_flags(RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
        // SAFETY: a committed scene; the mask and the packet are 32-byte aligned (their
        // types') and live across the call, as does the context.
        unsafe {
            rtcIntersect8(
                valid.0.as_ptr(),
                self.embree.scene,
                &mut context,
                &mut rayhit,
            )
        };
        for (i, (ray, hit)) in rays.iter().zip(hits.iter_mut()).take(n).enumerate() {
            let ids = (rayhit.hit.geom_id[i], rayhit.hit.prim_id[i]);
            *hit = self
                .embree
                .hit(ray, 0.0, rayhit.ray.tfar[i], ids, rayhit.hit.u[i]);
        }
    }

    /// Whether anything lies in `(0, t_max[i])` along each of at most [`LANES`] rays,
    /// one `rtcOccluded8`.
    fn occluded8<C: Counter>(
        &self,
        rays: &[Ray],
        t_max: &[f32],
        blocked: &mut [bool],
        counters: &mut [C],
    ) {
        let n = rays.len().min(t_max.len()).min(blocked.len());
        let n = n.min(counters.len()).min(LANES);
        if n == 0 {
            return;
        }
        for c in &mut counters[..n] {
            c.tally(Stat::Intersect);
        }
        let _phase = C::enter_phase(Phase::Traversal);
        let mut reach = [f32::NEG_INFINITY; LANES];
        reach[..n].copy_from_slice(&t_max[..n]);
        let (valid, mut ray) = packet(&rays[..n], &reach);
        let mut context = RTCIntersectContext::with_flags(RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
        // SAFETY: as in `closest8`.
        unsafe { rtcOccluded8(valid.0.as_ptr(), self.embree.scene, &mut context, &mut ray) };
        for (i, b) in blocked.iter_mut().take(n).enumerate() {
            *b = ray.tfar[i] == f32::NEG_INFINITY;
        }
    }
}

/// The valid mask and Embree's SoA form of `rays` (at most [`LANES`]) over
/// `(0, t_max[i])`; the unused lanes are inactive and hold an empty interval.
fn packet(rays: &[Ray], t_max: &[f32; LANES]) -> (Valid8, RTCRay8) {
    let mut valid = Valid8([0; LANES]);
    let mut out = RTCRay8 {
        org_x: [0.0; LANES],
        org_y: [0.0; LANES],
        org_z: [0.0; LANES],
        tnear: [0.0; LANES],
        dir_x: [0.0; LANES],
        dir_y: [0.0; LANES],
        dir_z: [1.0; LANES],
        time: [0.0; LANES],
        tfar: [f32::NEG_INFINITY; LANES],
        mask: [u32::MAX; LANES],
        id: [0; LANES],
        flags: [0; LANES],
    };
    for (i, ray) in rays.iter().take(LANES).enumerate() {
        let ([ox, oy, oz], [dx, dy, dz]) = (ray.origin.to_array(), ray.dir.to_array());
        (out.org_x[i], out.org_y[i], out.org_z[i]) = (ox, oy, oz);
        (out.dir_x[i], out.dir_y[i], out.dir_z[i]) = (dx, dy, dz);
        out.tfar[i] = t_max[i];
        valid.0[i] = -1;
    }
    (valid, out)
}

impl Intersector for EmbreePackets<'_> {
    const PACKETS: bool = true;

    /// A single ray (reflected, refracted, or a render without packets): `rtcIntersect1`.
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        self.embree.closest_hit(ray, t_min, c)
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        self.embree.occluded(ray, t_min, t_max, c)
    }

    fn closest_hits<C: Counter>(&self, rays: &[Ray], hits: &mut [Option<Hit>], counters: &mut [C]) {
        for ((rays, hits), counters) in rays
            .chunks(LANES)
            .zip(hits.chunks_mut(LANES))
            .zip(counters.chunks_mut(LANES))
        {
            self.closest8(rays, hits, counters);
        }
    }

    fn occluded_packet<C: Counter>(
        &self,
        rays: &[Ray],
        t_max: &[f32],
        blocked: &mut [bool],
        counters: &mut [C],
    ) {
        for (((rays, t_max), blocked), counters) in rays
            .chunks(LANES)
            .zip(t_max.chunks(LANES))
            .zip(blocked.chunks_mut(LANES))
            .zip(counters.chunks_mut(LANES))
        {
            self.occluded8(rays, t_max, blocked, counters);
        }
    }

    /// Eye rays of the `bounded` walk: Embree takes them as ordinary rays from the eye.
    fn closest_hits_from_eye<C: Counter>(
        &self,
        rays: &[Ray<true>],
        hits: &mut [Option<Hit>],
        counters: &mut [C],
    ) {
        for ((rays, hits), counters) in rays
            .chunks(LANES)
            .zip(hits.chunks_mut(LANES))
            .zip(counters.chunks_mut(LANES))
        {
            let unused = Ray {
                origin: Vec3::ZERO,
                dir: Vec3::ZERO,
            };
            let plain: [Ray; LANES] =
                std::array::from_fn(|i| rays.get(i).map_or(unused, Ray::plain));
            self.closest8(&plain[..rays.len()], hits, counters);
        }
    }
}
