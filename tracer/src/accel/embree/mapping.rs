//! How a scene maps onto Embree's geometries: the build steps of [`Embree`] (one
//! triangle mesh per outline kind, Embree's spheres and cone curves, one user geometry
//! for the rest) and the tables that map Embree's ids back to rtprof's primitives.

use std::ffi::c_void;

use super::bounds::{Aabb, QuadricSlack, disk_box};
use super::ffi::*;
use super::user::{UserPrims, user_bounds, user_intersect, user_occluded};
use super::{Embree, EmbreeCode, EmbreeError, EmbreeMode, triangulate};
use crate::primitives::PlanarOutline;
use crate::ray::{PrimKind, PrimRef};
use crate::scene::Scene;
use crate::vec3::Vec3;

/// How the primitive ids of one Embree geometry map back to rtprof's primitives.
#[derive(Debug)]
pub(super) struct GeometryTable {
    pub(super) prims: Vec<PrimRef>,
    pub(super) hit: HitFrom,
}

/// How a hit of the geometry becomes rtprof's [`Hit`](crate::ray::Hit): its distance
/// and its `aux` value (the axial coordinate `m` of a cylinder or cone).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum HitFrom {
    /// Triangles: Embree's primitive at rtprof's plane distance.
    Plane,
    /// Embree's spheres in [`EmbreeMode::Native`]: Embree's distance as it is.
    Embree,
    /// User geometry: rtprof's test ran in the callback and left `aux` in `u`.
    UserU,
    /// Embree's spheres and cone curves in [`EmbreeMode::Curves`]: Embree's primitive
    /// at the distance and `aux` of rtprof's test of it (Embree's own where that test
    /// misses: a silhouette both round apart on).
    Refined,
}

/// Releases a geometry handle (the scene keeps its own reference once attached).
struct GeometryHandle(RTCGeometry);

impl Drop for GeometryHandle {
    fn drop(&mut self) {
        if !self.0.is_null() {
            // SAFETY: a handle from rtcNewGeometry, released exactly once here.
            unsafe { rtcReleaseGeometry(self.0) };
        }
    }
}

impl<'s> Embree<'s> {
    /// The error Embree reports for the calling thread, with the callback's message.
    pub(super) fn check(&self, step: &'static str) -> Result<(), EmbreeError> {
        // SAFETY: a live device.
        let code = unsafe { rtcGetDeviceError(self.device) };
        let message = self.errors.take();
        if code == RTC_ERROR_NONE && message.is_none() {
            return Ok(());
        }
        let code = if code == RTC_ERROR_NONE {
            EmbreeCode::Unknown
        } else {
            EmbreeCode::from_raw(code)
        };
        Err(EmbreeError::Call {
            step,
            code,
            message,
        })
    }

    /// The error of a step that returned null: Embree's, or "unknown" if it set none.
    pub(super) fn failure(&self, step: &'static str) -> EmbreeError {
        match self.check(step) {
            Err(e) => e,
            Ok(()) => EmbreeError::Call {
                step,
                code: EmbreeCode::Unknown,
                message: None,
            },
        }
    }

    fn new_geometry(&self, kind: u32, step: &'static str) -> Result<GeometryHandle, EmbreeError> {
        // SAFETY: a live device; the handle is released by GeometryHandle.
        let geometry = GeometryHandle(unsafe { rtcNewGeometry(self.device, kind) });
        self.check(step)?;
        if geometry.0.is_null() {
            return Err(self.failure(step));
        }
        Ok(geometry)
    }

    /// A new Embree buffer (slot 0 of `kind`, in `format`) for `geometry`, holding a
    /// copy of `items`.
    fn set_buffer<T: Copy>(
        &mut self,
        geometry: &GeometryHandle,
        (kind, format): (u32, u32),
        items: &[T],
        step: &'static str,
    ) -> Result<(), EmbreeError> {
        let stride = std::mem::size_of::<T>();
        // SAFETY: a live geometry; Embree allocates `items.len()` items of `stride`
        // bytes (plus the padding its vector loads need) and returns their start.
        let data =
            unsafe { rtcSetNewGeometryBuffer(geometry.0, kind, 0, format, stride, items.len()) };
        self.check(step)?;
        if data.is_null() {
            return Err(self.failure(step));
        }
        // SAFETY: `data` holds `items.len()` items of size_of::<T>() bytes, aligned to
        // 16 bytes by Embree, and does not overlap `items`.
        unsafe {
            std::ptr::copy_nonoverlapping(items.as_ptr(), data.cast::<T>(), items.len());
        }
        self.buffer_bytes += std::mem::size_of_val(items);
        Ok(())
    }

    /// Commits `geometry`, attaches it under the next geometry id and records its table.
    fn attach(
        &mut self,
        geometry: GeometryHandle,
        table: GeometryTable,
        step: &'static str,
    ) -> Result<(), EmbreeError> {
        let id = u32::try_from(self.geometries.len()).map_err(|_| EmbreeError::TooMany {
            what: "geometries",
            count: self.geometries.len(),
        })?;
        // SAFETY: live geometry and scene; the scene takes its own reference, and
        // GeometryHandle drops ours.
        unsafe {
            rtcCommitGeometry(geometry.0);
            rtcAttachGeometryByID(self.scene, geometry.0, id);
        }
        self.check(step)?;
        self.geometries.push(table);
        Ok(())
    }

    /// One triangle mesh for the outlines of one kind (polygons or patches); outlines
    /// that ear clipping refuses go to the user geometry.
    pub(super) fn add_mesh<'o>(
        &mut self,
        kind: PrimKind,
        outlines: impl Iterator<Item = &'o PlanarOutline>,
        user: &mut UserPrims<'_>,
    ) -> Result<(), EmbreeError> {
        let mut vertices: Vec<[f32; 3]> = Vec::new();
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        let mut prims = Vec::new();
        for (i, outline) in outlines.enumerate() {
            let prim = prim_ref(kind, i)?;
            let lifted = triangulate::lift(outline);
            let Some(tris) = lifted.triangles else {
                let b = lifted
                    .vertices
                    .iter()
                    .fold(Aabb::EMPTY, |b, &v| b.grow(Vec3::from_array(v)));
                user.push(prim, b);
                continue;
            };
            let first = u32::try_from(vertices.len()).map_err(|_| EmbreeError::TooMany {
                what: "mesh vertices",
                count: vertices.len(),
            })?;
            vertices.extend_from_slice(&lifted.vertices);
            triangles.extend(tris.iter().map(|t| t.map(|v| v + first)));
            prims.extend(std::iter::repeat_n(prim, tris.len()));
        }
        if triangles.is_empty() {
            return Ok(());
        }
        let too_many = |count| EmbreeError::TooMany {
            what: "mesh triangles or vertices",
            count,
        };
        u32::try_from(vertices.len()).map_err(|_| too_many(vertices.len()))?;
        u32::try_from(triangles.len()).map_err(|_| too_many(triangles.len()))?;
        let step = match kind {
            PrimKind::Patch => "building the patch mesh",
            _ => "building the polygon mesh",
        };
        let geometry = self.new_geometry(RTC_GEOMETRY_TYPE_TRIANGLE, step)?;
        let vertex = (RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3);
        self.set_buffer(&geometry, vertex, &vertices, step)?;
        let index = (RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3);
        self.set_buffer(&geometry, index, &triangles, step)?;
        let table = GeometryTable {
            prims,
            hit: HitFrom::Plane,
        };
        self.attach(geometry, table, step)
    }

    /// The spheres: Embree's for the ordinary ones in `Native` mode, the user
    /// geometry for the rest, and zero-radius ones nowhere (rtprof's test never hits
    /// them).
    pub(super) fn add_spheres(
        &mut self,
        scene: &Scene,
        mode: EmbreeMode,
        slack: QuadricSlack,
        user: &mut UserPrims<'_>,
    ) -> Result<(), EmbreeError> {
        let mut points: Vec<[f32; 4]> = Vec::new();
        let mut prims = Vec::new();
        for (i, sphere) in scene.spheres.iter().enumerate() {
            if !(sphere.radius_sq() > 0.0) {
                continue;
            }
            let prim = prim_ref(PrimKind::Sphere, i)?;
            if sphere.inside_visible() || mode == EmbreeMode::Exact {
                let r = slack.radius(sphere.radius, sphere.center);
                user.push(prim, Aabb::EMPTY.grow(sphere.center).grow_by([r; 3]));
            } else {
                let [x, y, z] = sphere.center.to_array();
                points.push([x, y, z, sphere.radius]);
                prims.push(prim);
            }
        }
        if points.is_empty() {
            return Ok(());
        }
        u32::try_from(points.len()).map_err(|_| EmbreeError::TooMany {
            what: "spheres",
            count: points.len(),
        })?;
        let step = "building the spheres";
        let geometry = self.new_geometry(RTC_GEOMETRY_TYPE_SPHERE_POINT, step)?;
        let vertex = (RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4);
        self.set_buffer(&geometry, vertex, &points, step)?;
        let table = GeometryTable {
            prims,
            hit: if mode == EmbreeMode::Curves {
                HitFrom::Refined
            } else {
                HitFrom::Embree
            },
        };
        self.attach(geometry, table, step)
    }

    /// The cylinders and cones: in [`EmbreeMode::Curves`] Embree's cone curves, one
    /// two-vertex segment each; otherwise, and for the ones that show only their
    /// inside (no Embree counterpart), the user geometry. Zero-radius cylinders, which
    /// rtprof's test never hits, have no curve.
    ///
    /// A cone curve is exactly rtprof's open truncated cone: the surface at distance
    /// `r0 + (r1 - r0) y / L` from the axis for axial `y` in `(0, L)` (from Embree's
    /// `coneline_intersector.h`), entered or left (a hit from inside is kept, as in
    /// rtprof's test). But Embree closes each end that has no neighbour segment with
    /// a disk (its intersector tests the cap where `RTC_CURVE_FLAG_NEIGHBOR_LEFT` or
    /// `_RIGHT` is clear): so, for NFF's open cylinders and cones, every segment is
    /// flagged as having both neighbours. The cone kernel reads no neighbour's
    /// vertices, so the flags only remove the caps.
    pub(super) fn add_axial(
        &mut self,
        scene: &Scene,
        mode: EmbreeMode,
        slack: QuadricSlack,
        user: &mut UserPrims<'_>,
    ) -> Result<(), EmbreeError> {
        let curves = mode == EmbreeMode::Curves;
        let mut vertices: Vec<[f32; 4]> = Vec::new();
        let mut prims = Vec::new();
        let mut segment = |base: Vec3, rb: f32, apex: Vec3, ra: f32, prim| {
            let ([bx, by, bz], [ax, ay, az]) = (base.to_array(), apex.to_array());
            vertices.push([bx, by, bz, rb.abs()]);
            vertices.push([ax, ay, az, ra.abs()]);
            prims.push(prim);
        };
        for (i, cylinder) in scene.cylinders.iter().enumerate() {
            let prim = prim_ref(PrimKind::Cylinder, i)?;
            let (r, axis) = (cylinder.radius, cylinder.axis);
            if curves && !cylinder.inside_visible() {
                if cylinder.radius_sq() > 0.0 {
                    segment(cylinder.base, r, cylinder.apex, r, prim);
                }
                continue;
            }
            let base = disk_box(cylinder.base, axis, slack.radius(r, cylinder.base));
            let apex = disk_box(cylinder.apex, axis, slack.radius(r, cylinder.apex));
            user.push(prim, base.union(apex));
        }
        for (i, cone) in scene.cones.iter().enumerate() {
            let prim = prim_ref(PrimKind::Cone, i)?;
            let (rb, ra) = (cone.base_radius, cone.apex_radius);
            // Both radii zero: a line, which rtprof's test may still graze; kept exact.
            if curves && !cone.inside_visible() && (rb != 0.0 || ra != 0.0) {
                segment(cone.base, rb, cone.apex, ra, prim);
                continue;
            }
            let base = disk_box(cone.base, cone.axis, slack.radius(rb, cone.base));
            let apex = disk_box(cone.apex, cone.axis, slack.radius(ra, cone.apex));
            user.push(prim, base.union(apex));
        }
        if prims.is_empty() {
            return Ok(());
        }
        let too_many = |count| EmbreeError::TooMany {
            what: "cylinder and cone vertices",
            count,
        };
        u32::try_from(vertices.len()).map_err(|_| too_many(vertices.len()))?;
        let starts: Vec<u32> = (0..prims.len()).map(|k| 2 * k as u32).collect();
        let open_ends = RTC_CURVE_FLAG_NEIGHBOR_LEFT | RTC_CURVE_FLAG_NEIGHBOR_RIGHT;
        let flags = vec![open_ends; prims.len()];
        let step = "building the cylinders and cones (cone curves)";
        let geometry = self.new_geometry(RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE, step)?;
        let vertex = (RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4);
        self.set_buffer(&geometry, vertex, &vertices, step)?;
        let index = (RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT);
        self.set_buffer(&geometry, index, &starts, step)?;
        self.set_buffer(
            &geometry,
            (RTC_BUFFER_TYPE_FLAGS, RTC_FORMAT_UCHAR),
            &flags,
            step,
        )?;
        let table = GeometryTable {
            prims,
            hit: HitFrom::Refined,
        };
        self.attach(geometry, table, step)
    }

    /// One user geometry for every primitive that keeps rtprof's exact test.
    pub(super) fn add_user(&mut self, user: UserPrims<'s>) -> Result<(), EmbreeError> {
        let step = "building the user geometry";
        let count = u32::try_from(user.prims.len()).map_err(|_| EmbreeError::TooMany {
            what: "user primitives",
            count: user.prims.len(),
        })?;
        let geometry = self.new_geometry(RTC_GEOMETRY_TYPE_USER, step)?;
        let table = GeometryTable {
            prims: user.prims.clone(),
            hit: HitFrom::UserU,
        };
        let user = Box::new(user);
        let ptr: *const UserPrims<'s> = &*user;
        let ptr = ptr as *mut c_void;
        // Stored before Embree sees the pointer, so that `self` owns it on every path.
        self.user = Some(user);
        // SAFETY: a live geometry; `ptr` stays valid while the scene lives (the Box is
        // owned by `self` and dropped after the scene is released); the callbacks match
        // the C signatures.
        unsafe {
            rtcSetGeometryUserPrimitiveCount(geometry.0, count);
            rtcSetGeometryUserData(geometry.0, ptr);
            rtcSetGeometryBoundsFunction(geometry.0, Some(user_bounds), ptr);
            rtcSetGeometryIntersectFunction(geometry.0, Some(user_intersect));
            rtcSetGeometryOccludedFunction(geometry.0, Some(user_occluded));
        }
        self.check(step)?;
        self.attach(geometry, table, step)
    }
}

pub(super) fn prim_ref(kind: PrimKind, index: usize) -> Result<PrimRef, EmbreeError> {
    let index = u32::try_from(index).map_err(|_| EmbreeError::TooMany {
        what: "primitives of one kind",
        count: index,
    })?;
    Ok(PrimRef { kind, index })
}
