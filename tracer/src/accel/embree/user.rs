//! Embree's user geometry: the primitives that keep rtprof's own tests, and the bounds,
//! intersect and occluded callbacks Embree calls for them. The callbacks take packets
//! of `N` rays (`N` = 1 from the single-ray queries, 8 from `rtcIntersect8` /
//! `rtcOccluded8`) in Embree's SoA layout, and test each lane its `valid` mask marks.

use std::ffi::c_void;

use super::bounds::Aabb;
use super::ffi::*;
use crate::accel::intersect_primitive;
use crate::counter::NoCount;
use crate::ray::{PrimRef, Ray};
use crate::scene::Scene;
use crate::vec3::Vec3;

/// The user-geometry primitives: rtprof's exact tests, run by Embree's callbacks.
#[derive(Debug)]
pub(super) struct UserPrims<'s> {
    pub(super) scene: &'s Scene,
    pub(super) prims: Vec<PrimRef>,
    pub(super) boxes: Vec<RTCBounds>,
}

impl UserPrims<'_> {
    pub(super) fn push(&mut self, prim: PrimRef, b: Aabb) {
        self.prims.push(prim);
        self.boxes.push(b.padded().into());
    }
}

/// Word `field` of ray `i` in an Embree SoA block of `n` rays.
///
/// # Safety
/// `base` must point to an `RTCRayN` / `RTCRayHitN` of `n` rays holding `field`.
unsafe fn word(base: *mut c_void, field: usize, n: usize, i: usize) -> *mut f32 {
    // SAFETY: in bounds by the caller's contract.
    unsafe { base.cast::<f32>().add(field * n + i) }
}

/// The ray `i` of an SoA block, with its interval.
///
/// # Safety
/// As [`word`].
unsafe fn soa_ray(base: *mut c_void, n: usize, i: usize) -> (Ray, f32, f32) {
    // SAFETY: the caller's contract covers every ray field.
    unsafe {
        let get = |field| *word(base, field, n, i);
        let ray = Ray {
            origin: Vec3::new(get(soa::ORG_X), get(soa::ORG_Y), get(soa::ORG_Z)),
            dir: Vec3::new(get(soa::DIR_X), get(soa::DIR_Y), get(soa::DIR_Z)),
        };
        (ray, get(soa::TNEAR), get(soa::TFAR))
    }
}

/// The user primitives `prim_id` of the geometry whose user data is `user_ptr`.
///
/// # Safety
/// `user_ptr` must be the `UserPrims` registered with the geometry.
unsafe fn user_prim<'a>(user_ptr: *mut c_void, prim_id: u32) -> Option<(&'a Scene, PrimRef)> {
    // SAFETY: by the caller's contract; the data outlives every query.
    let user = unsafe { &*(user_ptr as *const UserPrims<'a>) };
    let prim = *user.prims.get(prim_id as usize)?;
    Some((user.scene, prim))
}

/// Bounds callback: the padded box computed at build time.
pub(super) unsafe extern "C" fn user_bounds(args: *const RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes valid arguments whose user pointer is our `UserPrims`,
    // and a writable `bounds_o`.
    unsafe {
        let args = &*args;
        let user = &*(args.geometry_user_ptr as *const UserPrims<'_>);
        let b = user
            .boxes
            .get(args.prim_id as usize)
            .copied()
            .unwrap_or(RTCBounds::from(Aabb::EMPTY));
        *args.bounds_o = b;
    }
}

/// Intersect callback: rtprof's exact test in the ray's current interval; a hit
/// shortens the ray and records the primitive, with `aux` in `u`.
pub(super) unsafe extern "C" fn user_intersect(args: *const RTCIntersectFunctionNArguments) {
    // SAFETY: Embree passes valid arguments: `valid` and `rayhit` cover `n` rays, the
    // user pointer is our `UserPrims`, `context` is the query's context.
    unsafe {
        let args = &*args;
        let Some((scene, prim)) = user_prim(args.geometry_user_ptr, args.prim_id) else {
            return;
        };
        let n = args.n as usize;
        let inst = (*args.context).inst_id[0];
        for i in 0..n {
            if *args.valid.add(i) == 0 {
                continue;
            }
            let (ray, t_min, t_max) = soa_ray(args.rayhit, n, i);
            let Some((t, aux)) = intersect_primitive(scene, prim, &ray, t_min, t_max, &mut NoCount)
            else {
                continue;
            };
            let hit = args.rayhit;
            let [dx, dy, dz] = ray.dir.to_array();
            *word(hit, soa::TFAR, n, i) = t;
            *word(hit, soa::NG_X, n, i) = -dx;
            *word(hit, soa::NG_Y, n, i) = -dy;
            *word(hit, soa::NG_Z, n, i) = -dz;
            *word(hit, soa::U, n, i) = aux;
            *word(hit, soa::V, n, i) = 0.0;
            *word(hit, soa::PRIM_ID, n, i).cast::<u32>() = args.prim_id;
            *word(hit, soa::GEOM_ID, n, i).cast::<u32>() = args.geom_id;
            *word(hit, soa::INST_ID, n, i).cast::<u32>() = inst;
        }
    }
}

/// Occluded callback: any hit of rtprof's test in the interval blocks the ray
/// (Embree's convention: `tfar = -inf`).
pub(super) unsafe extern "C" fn user_occluded(args: *const RTCOccludedFunctionNArguments) {
    // SAFETY: as in `user_intersect`, with `ray` covering `n` rays.
    unsafe {
        let args = &*args;
        let Some((scene, prim)) = user_prim(args.geometry_user_ptr, args.prim_id) else {
            return;
        };
        let n = args.n as usize;
        for i in 0..n {
            if *args.valid.add(i) == 0 {
                continue;
            }
            let (ray, t_min, t_max) = soa_ray(args.ray, n, i);
            if intersect_primitive(scene, prim, &ray, t_min, t_max, &mut NoCount).is_some() {
                *word(args.ray, soa::TFAR, n, i) = f32::NEG_INFINITY;
            }
        }
    }
}
