//! Intel Embree 3 as an rtprof intersector (cargo feature `embree`): the closest-hit
//! and occlusion queries answered by a production ray tracing kernel library, so that
//! rtprof's own structures (brute force, SIMD, BVH) can be timed against it on the
//! same scenes, with the same shading and the same picture.
//!
//! Three modes ([`EmbreeMode`]):
//! - [`EmbreeMode::Exact`] ([`Embree::new`]): the baseline's picture, ray for ray.
//!   Every quadric runs rtprof's own test, so only the traversal is Embree's.
//! - [`EmbreeMode::Native`]: Embree with its own sphere test; the picture differs
//!   slightly where rtprof's quadric tests round (below).
//! - [`EmbreeMode::Curves`]: every primitive Embree has a kernel for is Embree's,
//!   cylinders and cones too; [`EmbreePackets`] (`packets.rs`) runs it through
//!   Embree's packet API.
//!
//! The files: the scene mapping (`mapping.rs`), the user geometry and its callbacks
//! (`user.rs`), the boxes they are culled with (`bounds.rs`), the errors
//! (`error.rs`), the C declarations (`ffi.rs`), the packet queries (`packets.rs`);
//! this file holds the intersector and its single-ray queries.
//!
//! How the scene maps onto Embree (one Embree scene, built with
//! `RTC_BUILD_QUALITY_HIGH` and `RTC_SCENE_FLAG_ROBUST`):
//! - polygons and patches: one triangle mesh each, ear-clipped from the outline that
//!   rtprof's crossing test sees ([`triangulate`]); a table maps each triangle back to
//!   its polygon or patch, and a hit's distance is recomputed by rtprof's plane test
//!   (Embree's triangle distance differs in the last bits, enough to tip the grazing
//!   shadow rays that follow). A patch hit carries only its primitive and
//!   distance: the shader interpolates the vertex normals itself from the hit point.
//!   Outlines that ear clipping cannot reproduce (self-intersecting, even-odd) keep
//!   rtprof's exact test as user geometry. The robust flag makes Embree's triangle
//!   test watertight: without it rays slip through the diagonal that splits a quad
//!   (rtprof's crossing test has no such inner edge; 4 of 1024 eye rays in `rings`).
//! - spheres: in `Native` mode Embree's `RTC_GEOMETRY_TYPE_SPHERE_POINT`, whose rules
//!   are rtprof's (the near root when it lies in the ray's interval, else the far one:
//!   hits from inside are kept) and whose arithmetic, like the second stage of
//!   rtprof's two-stage test, measures the ray's distance from the centre directly
//!   (the thesis's `b² - c` alone lost all of `r²` to rounding on small far spheres).
//!   The two round apart in the last bits, so a few silhouette pixels differ (RMS
//!   below 0.5 on every SPD scene, `tests.rs`). In `Curves` mode a hit's distance is
//!   then rtprof's test of the sphere Embree found, as for triangles, which keeps the
//!   rays that follow the baseline's. In `Exact` mode, and always
//!   for spheres that show only their inside (negative radius, no Embree
//!   counterpart), rtprof's test runs as user geometry. Zero-radius spheres, which
//!   rtprof's test never hits, are left out.
//! - cylinders and cones: user geometry whose callbacks run rtprof's exact tests
//!   ([`intersect_primitive`] with [`NoCount`]); in `Curves` mode Embree's open cone
//!   curves (`RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE`, exactly rtprof's truncated cones;
//!   `mapping.rs` says how their end caps are removed), refined like the spheres,
//!   except those that show only their inside.
//!
//! A user hit stores the test's `aux` value (the axial coordinate `m`) in the hit's
//! `u`, which Embree hands back untouched, so no test is repeated after the query.
//! User primitives are culled by their boxes: in `Native` and `Curves` mode the boxes of rtprof's
//! BVH (which therefore gives `Native`'s cylinder and cone hits), in `Exact` mode
//! boxes widened by the rounding of the quadric tests ([`QuadricSlack`]), so that
//! the hits rtprof reports beside a small far quadric are found too. Those wide boxes
//! make `Exact` slow on scenes of many tiny quadrics (`tree`, `shells`).
//!
//! Counting: each query tallies one `calls.intersect`, as every intersector does, and
//! runs as one `traversal` phase. What happens inside Embree is not counted: no
//! `accel.*` node or leaf visits, no `tests.*`, no `ops.*` (user-geometry tests run
//! uncounted too, so the counts are not a partial mix). The `rays.*` and shading
//! counts are the renderer's and agree with the other intersectors.

mod bounds;
mod error;
mod ffi;
mod mapping;
mod packets;
mod user;

use std::ffi::c_void;

use super::{Intersector, intersect_primitive, triangulate};
use crate::counter::{Counter, NoCount, Phase, Stat};
use crate::ray::{Hit, PrimKind, PrimRef, Ray};
use crate::scene::Scene;
use bounds::QuadricSlack;
pub use error::{EmbreeCode, EmbreeError};
use error::{ErrorLog, on_error};
use ffi::*;
use mapping::{GeometryTable, HitFrom};
pub use packets::{EmbreePackets, NativeWidths};
use user::UserPrims;

/// What [`Embree`] optimizes for (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EmbreeMode {
    /// The baseline's hits and picture: rtprof's tests for every sphere, cylinder
    /// and cone, in boxes wide enough for their rounding.
    #[default]
    Exact,
    /// Embree's own sphere test and tight boxes: its speed, and a picture that
    /// differs from the baseline's on small far quadrics (RMS up to about 5 on
    /// 8-bit channels at 32x32 for `balls`).
    Native,
    /// `Native` with Embree's cone curves for the cylinders and cones too: every
    /// primitive Embree has a kernel for is Embree's (the `embree-packets` variant).
    Curves,
}

/// Embree 3 intersector over a scene: spheres as Embree spheres, polygons and patches
/// as triangle meshes, everything else as user geometry running rtprof's own tests
/// (see the module documentation).
#[derive(Debug)]
pub struct Embree<'s> {
    source: &'s Scene,
    device: RTCDevice,
    scene: RTCScene,
    /// Indexed by geometry id.
    geometries: Vec<GeometryTable>,
    /// Read by the user-geometry callbacks: must outlive `scene` (dropped after it).
    user: Option<Box<UserPrims<'s>>>,
    /// Read by the error callback: must outlive `device`.
    errors: Box<ErrorLog>,
    /// Bytes of the vertex and index buffers handed to Embree.
    buffer_bytes: usize,
}

// SAFETY: after `new` returns, the scene is committed and never modified again;
// Embree documents rtcIntersect1 and rtcOccluded1 on a committed scene as safe to call
// from any number of threads at once. The callbacks only read `UserPrims` (a shared
// `&Scene`, which is Sync, and plain vectors), and the error log is behind a mutex.
// Dropping from another thread is fine: Embree objects are not tied to a thread.
unsafe impl Send for Embree<'_> {}
// SAFETY: see `Send`: every `&self` method only runs queries on the committed scene.
unsafe impl Sync for Embree<'_> {}

impl Drop for Embree<'_> {
    fn drop(&mut self) {
        // SAFETY: the handles come from rtcNewScene / rtcNewDevice and are released once
        // each, the scene before its device; `user` and `errors` are dropped after this
        // body, so no callback can see them freed.
        unsafe {
            if !self.scene.is_null() {
                rtcReleaseScene(self.scene);
            }
            if !self.device.is_null() {
                rtcReleaseDevice(self.device);
            }
        }
    }
}

impl<'s> Embree<'s> {
    /// Builds and commits the Embree scene for `scene` in [`EmbreeMode::Exact`].
    pub fn new(scene: &'s Scene) -> Result<Self, EmbreeError> {
        Self::with_mode(scene, EmbreeMode::Exact)
    }

    /// Builds and commits the Embree scene for `scene` in `mode`.
    pub fn with_mode(scene: &'s Scene, mode: EmbreeMode) -> Result<Self, EmbreeError> {
        // SAFETY: a null configuration string selects Embree's defaults.
        let device = unsafe { rtcNewDevice(std::ptr::null()) };
        if device.is_null() {
            // SAFETY: with a null device, rtcGetDeviceError reports the thread's error
            // from device creation.
            let code = unsafe { rtcGetDeviceError(std::ptr::null_mut()) };
            return Err(EmbreeError::Device(EmbreeCode::from_raw(code)));
        }
        let mut this = Self {
            source: scene,
            device,
            scene: std::ptr::null_mut(),
            geometries: Vec::new(),
            user: None,
            errors: Box::default(),
            buffer_bytes: 0,
        };
        let log: *const ErrorLog = &*this.errors;
        // SAFETY: the log lives in a Box owned by `this`, released after the device.
        unsafe { rtcSetDeviceErrorFunction(device, Some(on_error), log as *mut c_void) };
        // SAFETY: a live device.
        this.scene = unsafe { rtcNewScene(device) };
        this.check("creating the scene")?;
        if this.scene.is_null() {
            return Err(this.failure("creating the scene"));
        }
        // SAFETY: a live scene.
        unsafe {
            rtcSetSceneBuildQuality(this.scene, RTC_BUILD_QUALITY_HIGH);
            rtcSetSceneFlags(this.scene, RTC_SCENE_FLAG_ROBUST);
        }

        let mut user = UserPrims {
            scene,
            prims: Vec::new(),
            boxes: Vec::new(),
        };
        let polygons = scene.polygons.iter().map(|p| &p.outline);
        this.add_mesh(PrimKind::Polygon, polygons, &mut user)?;
        let patches = scene.patches.iter().map(|p| &p.outline);
        this.add_mesh(PrimKind::Patch, patches, &mut user)?;
        let slack = QuadricSlack::new(scene, mode);
        this.add_spheres(scene, mode, slack, &mut user)?;
        this.add_axial(scene, mode, slack, &mut user)?;
        if !user.prims.is_empty() {
            this.add_user(user)?;
        }
        // SAFETY: a live scene whose geometries are committed and attached.
        unsafe { rtcCommitScene(this.scene) };
        this.check("building the scene (rtcCommitScene)")?;
        Ok(this)
    }

    /// Best estimate of the memory this intersector holds: the vertex and index
    /// buffers handed to Embree and the tables that map Embree's ids back to rtprof's
    /// primitives (with the user primitives' boxes). Embree's own BVH is not included:
    /// Embree 3 exposes no per-scene size of its acceleration structure (only a
    /// device-wide memory monitor callback, not used here).
    pub fn memory_bytes(&self) -> usize {
        let prim = std::mem::size_of::<PrimRef>();
        let tables: usize = self
            .geometries
            .iter()
            .map(|g| g.prims.capacity() * prim)
            .sum();
        let user = self.user.as_ref().map_or(0, |u| {
            std::mem::size_of::<UserPrims<'_>>()
                + u.prims.capacity() * prim
                + u.boxes.capacity() * std::mem::size_of::<RTCBounds>()
        });
        std::mem::size_of::<Self>() + self.buffer_bytes + tables + user
    }
}

/// Embree's form of `ray` over `(t_min, t_max)`.
fn rtc_ray(ray: &Ray, t_min: f32, t_max: f32) -> RTCRay {
    let [org_x, org_y, org_z] = ray.origin.to_array();
    let [dir_x, dir_y, dir_z] = ray.dir.to_array();
    RTCRay {
        org_x,
        org_y,
        org_z,
        tnear: t_min,
        dir_x,
        dir_y,
        dir_z,
        time: 0.0,
        tfar: t_max,
        mask: u32::MAX,
        id: 0,
        flags: 0,
    }
}

impl Embree<'_> {
    /// The hit Embree reported for `ray` (tfar, ids and `u` of its hit record), as
    /// rtprof's [`Hit`]; `None` for a miss or ids Embree should not have given.
    fn hit(&self, ray: &Ray, t_min: f32, tfar: f32, ids: (u32, u32), u: f32) -> Option<Hit> {
        let (geom_id, prim_id) = ids;
        let table = self.geometries.get(geom_id as usize)?;
        let prim = *table.prims.get(prim_id as usize)?;
        let i = prim.index as usize;
        let at = |t, aux| Some(Hit { t, prim, aux });
        match table.hit {
            HitFrom::UserU => at(tfar, u),
            HitFrom::Embree => at(tfar, 0.0),
            HitFrom::Plane => {
                // A triangle's distance differs from rtprof's plane distance in the last
                // bits, enough to move the hit point to the other side of a shadow ray's
                // grazing test; rtprof's own plane distance (one plane test) keeps the
                // rays that follow the baseline's.
                let outline = match prim.kind {
                    PrimKind::Polygon => self.source.polygons.get(i).map(|p| &p.outline),
                    PrimKind::Patch => self.source.patches.get(i).map(|p| &p.outline),
                    _ => None,
                };
                let t = outline
                    .and_then(|o| o.intersect_plane(ray, t_min, f32::INFINITY, &mut NoCount));
                at(t.unwrap_or(tfar), 0.0)
            }
            HitFrom::Refined => {
                // As for triangles: Embree's sphere and cone-curve distances round apart
                // from rtprof's, which moves the points shadow and reflected rays leave
                // from (at 64x64 it changed `rays.*` on five SPD scenes); rtprof's test
                // of the one primitive Embree found gives the baseline's point and `m`.
                let exact =
                    intersect_primitive(self.source, prim, ray, t_min, f32::INFINITY, &mut NoCount)
                        .filter(|&(t, _)| (t - tfar).abs() <= 1e-3 * tfar.abs());
                if let Some((t, aux)) = exact {
                    return at(t, aux);
                }
                // A cone curve's `u` is the hit's axial fraction from the first vertex
                // (the base): `m` is that fraction of the length.
                let length = match prim.kind {
                    PrimKind::Cylinder => self.source.cylinders.get(i).map_or(0.0, |c| c.length),
                    PrimKind::Cone => self.source.cones.get(i).map_or(0.0, |c| c.length),
                    _ => 0.0,
                };
                at(tfar, u * length)
            }
        }
    }
}

impl Intersector for Embree<'_> {
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        c.tally(Stat::Intersect);
        let _phase = C::enter_phase(Phase::Traversal);
        let mut rayhit = RTCRayHit {
            ray: rtc_ray(ray, t_min, f32::INFINITY),
            hit: RTCHit {
                ng_x: 0.0,
                ng_y: 0.0,
                ng_z: 0.0,
                u: 0.0,
                v: 0.0,
                prim_id: RTC_INVALID_GEOMETRY_ID,
                geom_id: RTC_INVALID_GEOMETRY_ID,
                inst_id: [RTC_INVALID_GEOMETRY_ID],
            },
        };
        let mut context = RTCIntersectContext::new();
        // SAFETY: a committed scene; the context and ray live across the call.
        unsafe { rtcIntersect1(self.scene, &mut context, &mut rayhit) };
        let ids = (rayhit.hit.geom_id, rayhit.hit.prim_id);
        self.hit(ray, t_min, rayhit.ray.tfar, ids, rayhit.hit.u)
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        c.tally(Stat::Intersect);
        let _phase = C::enter_phase(Phase::Traversal);
        let mut rtc = rtc_ray(ray, t_min, t_max);
        let mut context = RTCIntersectContext::new();
        // SAFETY: as in `closest_hit`.
        unsafe { rtcOccluded1(self.scene, &mut context, &mut rtc) };
        rtc.tfar == f32::NEG_INFINITY
    }
}

#[cfg(test)]
mod tests;
