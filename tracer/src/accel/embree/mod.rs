//! Intel Embree 3 as an rtprof intersector (cargo feature `embree`): the closest-hit
//! and occlusion queries answered by a production ray tracing kernel library, so that
//! rtprof's own structures (brute force, SIMD, BVH) can be timed against it on the
//! same scenes, with the same shading and the same picture.
//!
//! Two modes ([`EmbreeMode`]):
//! - [`EmbreeMode::Exact`] ([`Embree::new`]): the baseline's picture, ray for ray.
//!   Every quadric runs rtprof's own test, so only the traversal is Embree's.
//! - [`EmbreeMode::Native`]: Embree as fast as it goes, with its own sphere test;
//!   the picture differs slightly where rtprof's quadric tests round (below).
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
//!   below 0.5 on every SPD scene, `tests.rs`). In `Exact` mode, and always
//!   for spheres that show only their inside (negative radius, no Embree
//!   counterpart), rtprof's test runs as user geometry. Zero-radius spheres, which
//!   rtprof's test never hits, are left out.
//! - cylinders and cones: user geometry whose callbacks run rtprof's exact tests
//!   ([`intersect_primitive`] with [`NoCount`]).
//!
//! A user hit stores the test's `aux` value (the axial coordinate `m`) in the hit's
//! `u`, which Embree hands back untouched, so no test is repeated after the query.
//! User primitives are culled by their boxes: in `Native` mode the boxes of rtprof's
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

mod ffi;

use std::ffi::{CStr, c_char, c_void};
use std::sync::Mutex;

use super::{Intersector, intersect_primitive, triangulate};
use crate::counter::{Counter, NoCount, Phase, Stat};
use crate::primitives::PlanarOutline;
use crate::ray::{Hit, PrimKind, PrimRef, Ray};
use crate::scene::Scene;
use crate::vec3::Vec3;
use ffi::*;

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
}

/// An Embree error code (`enum RTCError`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmbreeCode {
    Unknown,
    InvalidArgument,
    InvalidOperation,
    OutOfMemory,
    UnsupportedCpu,
    Cancelled,
    /// A code this version of the bindings does not know.
    Other(u32),
}

impl EmbreeCode {
    fn from_raw(code: u32) -> Self {
        match code {
            RTC_ERROR_INVALID_ARGUMENT => Self::InvalidArgument,
            RTC_ERROR_INVALID_OPERATION => Self::InvalidOperation,
            RTC_ERROR_OUT_OF_MEMORY => Self::OutOfMemory,
            RTC_ERROR_UNSUPPORTED_CPU => Self::UnsupportedCpu,
            RTC_ERROR_CANCELLED => Self::Cancelled,
            RTC_ERROR_UNKNOWN => Self::Unknown,
            other => Self::Other(other),
        }
    }
}

impl std::fmt::Display for EmbreeCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Unknown => write!(f, "unknown error"),
            Self::InvalidArgument => write!(f, "invalid argument"),
            Self::InvalidOperation => write!(f, "invalid operation"),
            Self::OutOfMemory => write!(f, "out of memory"),
            Self::UnsupportedCpu => write!(
                f,
                "this CPU lacks the instruction set this Embree build needs (SSE2 or better)"
            ),
            Self::Cancelled => write!(f, "cancelled"),
            Self::Other(code) => write!(f, "error code {code}"),
        }
    }
}

/// Why the Embree scene could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EmbreeError {
    #[error("could not create the Embree device: {0}")]
    Device(EmbreeCode),
    #[error("Embree failed while {step}: {code}{}", detail(.message))]
    Call {
        /// What the intersector was doing, e.g. "building the scene".
        step: &'static str,
        code: EmbreeCode,
        /// The text Embree's error callback gave, when it gave one.
        message: Option<String>,
    },
    #[error("{count} {what} exceed Embree's 32-bit primitive ids")]
    TooMany { what: &'static str, count: usize },
}

fn detail(message: &Option<String>) -> String {
    message
        .as_deref()
        .map(|m| format!(" ({m})"))
        .unwrap_or_default()
}

/// The first message of Embree's error callback since it was last read.
#[derive(Debug, Default)]
struct ErrorLog(Mutex<Option<String>>);

impl ErrorLog {
    fn take(&self) -> Option<String> {
        self.0.lock().ok().and_then(|mut m| m.take())
    }
}

/// Embree's error callback: keeps the first message. It may run on Embree's worker
/// threads during a commit, hence the mutex.
unsafe extern "C" fn on_error(user_ptr: *mut c_void, _code: u32, message: *const c_char) {
    if user_ptr.is_null() || message.is_null() {
        return;
    }
    // SAFETY: `user_ptr` is the `ErrorLog` registered with the device, alive until the
    // device is released; `message` is a NUL-terminated string Embree owns for the call.
    let (log, text) = unsafe {
        (
            &*(user_ptr as *const ErrorLog),
            CStr::from_ptr(message).to_string_lossy(),
        )
    };
    if let Ok(mut slot) = log.0.lock() {
        slot.get_or_insert_with(|| text.into_owned());
    }
}

/// How the primitive ids of one Embree geometry map back to rtprof's primitives.
#[derive(Debug)]
struct GeometryTable {
    prims: Vec<PrimRef>,
    /// User geometry: the hit's `u` holds the test's `aux` value.
    aux_in_u: bool,
}

/// The user-geometry primitives: rtprof's exact tests, run by Embree's callbacks.
#[derive(Debug)]
struct UserPrims<'s> {
    scene: &'s Scene,
    prims: Vec<PrimRef>,
    boxes: Vec<RTCBounds>,
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
        for (i, cylinder) in scene.cylinders.iter().enumerate() {
            let (r, axis) = (cylinder.radius, cylinder.axis);
            let base = disk_box(cylinder.base, axis, slack.radius(r, cylinder.base));
            let b = base.union(disk_box(
                cylinder.apex,
                axis,
                slack.radius(r, cylinder.apex),
            ));
            user.push(prim_ref(PrimKind::Cylinder, i)?, b);
        }
        for (i, cone) in scene.cones.iter().enumerate() {
            let b = disk_box(
                cone.base,
                cone.axis,
                slack.radius(cone.base_radius, cone.base),
            )
            .union(disk_box(
                cone.apex,
                cone.axis,
                slack.radius(cone.apex_radius, cone.apex),
            ));
            user.push(prim_ref(PrimKind::Cone, i)?, b);
        }
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

    /// The error Embree reports for the calling thread, with the callback's message.
    fn check(&self, step: &'static str) -> Result<(), EmbreeError> {
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
    fn failure(&self, step: &'static str) -> EmbreeError {
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
    fn add_mesh<'o>(
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
            aux_in_u: false,
        };
        self.attach(geometry, table, step)
    }

    /// The spheres: Embree's for the ordinary ones in `Native` mode, the user
    /// geometry for the rest, and zero-radius ones nowhere (rtprof's test never hits
    /// them).
    fn add_spheres(
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
            aux_in_u: false,
        };
        self.attach(geometry, table, step)
    }

    /// One user geometry for every primitive that keeps rtprof's exact test.
    fn add_user(&mut self, user: UserPrims<'s>) -> Result<(), EmbreeError> {
        let step = "building the user geometry";
        let count = u32::try_from(user.prims.len()).map_err(|_| EmbreeError::TooMany {
            what: "user primitives",
            count: user.prims.len(),
        })?;
        let geometry = self.new_geometry(RTC_GEOMETRY_TYPE_USER, step)?;
        let table = GeometryTable {
            prims: user.prims.clone(),
            aux_in_u: true,
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

fn prim_ref(kind: PrimKind, index: usize) -> Result<PrimRef, EmbreeError> {
    let index = u32::try_from(index).map_err(|_| EmbreeError::TooMany {
        what: "primitives of one kind",
        count: index,
    })?;
    Ok(PrimRef { kind, index })
}

impl UserPrims<'_> {
    fn push(&mut self, prim: PrimRef, b: Aabb) {
        self.prims.push(prim);
        self.boxes.push(b.padded().into());
    }
}

/// An axis-aligned box (build time only).
#[derive(Clone, Copy, Debug)]
struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    fn grow(self, p: Vec3) -> Aabb {
        let p = p.to_array();
        Aabb {
            min: std::array::from_fn(|i| self.min[i].min(p[i])),
            max: std::array::from_fn(|i| self.max[i].max(p[i])),
        }
    }

    /// The box widened by `e` on each side.
    fn grow_by(self, e: [f32; 3]) -> Aabb {
        Aabb {
            min: std::array::from_fn(|i| self.min[i] - e[i]),
            max: std::array::from_fn(|i| self.max[i] + e[i]),
        }
    }

    fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: std::array::from_fn(|i| self.min[i].min(o.min[i])),
            max: std::array::from_fn(|i| self.max[i].max(o.max[i])),
        }
    }

    /// Grown by a relative margin (as the BVH's boxes) so that rounding in the exact
    /// tests never reports a hit outside the box Embree culls with.
    fn padded(self) -> Aabb {
        let extent = (0..3).fold(0.0f32, |m, i| {
            m.max(self.max[i] - self.min[i])
                .max(self.max[i].abs())
                .max(self.min[i].abs())
        });
        let pad = extent * 1e-5 + f32::MIN_POSITIVE;
        self.grow_by([pad; 3])
    }
}

impl From<Aabb> for RTCBounds {
    fn from(b: Aabb) -> Self {
        RTCBounds {
            lower_x: b.min[0],
            lower_y: b.min[1],
            lower_z: b.min[2],
            align0: 0.0,
            upper_x: b.max[0],
            upper_y: b.max[1],
            upper_z: b.max[2],
            align1: 0.0,
        }
    }
}

/// How far from its surface rtprof's quadric tests (sphere, cylinder, cone) can
/// report a hit, as a wider radius for the boxes Embree culls user primitives with
/// in [`EmbreeMode::Exact`].
///
/// The tests' first stage computes `b² - c` from terms of size `|O - C|²` and assumes
/// `|dir| = 1`; a hit is decided by the second stage, which has no such error, or by
/// the first where its discriminant is far above that error (so the ray certainly
/// crosses the true quadric and its box), so this bound (of the first stage's error)
/// is conservative.
/// Their discriminant is off by up to about `γ |O - C|²` with `γ = 8 ε`: in units of
/// the rounding `u = ε/2`, 7 from `(R·Voc)²`, 4 from `Voc·Voc - r²`, 4 from
/// `|dir|² - 1` of a normalized f32 vector. A hit can then be reported up to
/// `sqrt(r² + γ |O - C|²)` from the centre or axis: more than `r` for small far
/// quadrics (`tree`'s leaves, radius 0.0012, are hit 1.5 radii off). Boxes of the
/// true radius would cull those hits, as rtprof's own BVH does (its `tree` differs
/// from the baseline's by RMS 0.77 at 32x32). Every ray starts at the eye or on a
/// primitive, so the farthest corner of the box of the eye and all primitives
/// bounds `|O - C|`.
#[derive(Clone, Copy, Debug)]
struct QuadricSlack {
    /// The box of every possible ray origin; `None` for tight boxes.
    origins: Option<Aabb>,
}

impl QuadricSlack {
    const GAMMA: f32 = 8.0 * f32::EPSILON;

    fn new(scene: &Scene, mode: EmbreeMode) -> Self {
        if mode == EmbreeMode::Native {
            return Self { origins: None };
        }
        let mut b = Aabb::EMPTY.grow(scene.view.from);
        for s in &scene.spheres {
            let r = s.radius.abs();
            b = b.union(Aabb::EMPTY.grow(s.center).grow_by([r; 3]));
        }
        for c in &scene.cylinders {
            let r = c.radius.abs();
            b = b.union(Aabb::EMPTY.grow(c.base).grow(c.apex).grow_by([r; 3]));
        }
        for c in &scene.cones {
            let r = c.base_radius.abs().max(c.apex_radius.abs());
            b = b.union(Aabb::EMPTY.grow(c.base).grow(c.apex).grow_by([r; 3]));
        }
        let outlines = scene.polygons.iter().map(|p| &p.outline);
        for o in outlines.chain(scene.patches.iter().map(|p| &p.outline)) {
            b = o.vertices.iter().fold(b, |b, v| b.grow(*v));
        }
        Self { origins: Some(b) }
    }

    /// The box radius for a quadric of radius `r` (either sign) around `center` (a
    /// sphere's centre, or an end of a cylinder or cone, whose distance to the
    /// other end's origins the other end's radius covers).
    fn radius(self, r: f32, center: Vec3) -> f32 {
        let Some(b) = self.origins else {
            return r.abs();
        };
        let c = center.to_array();
        let reach_sq: f32 = (0..3)
            .map(|i| {
                let d = (c[i] - b.min[i]).abs().max((b.max[i] - c[i]).abs());
                d * d
            })
            .sum();
        NoCount.sqrt(r * r + Self::GAMMA * reach_sq)
    }
}

/// The box of a disk of radius `r` around unit `axis` at `center`: half-extents
/// `|r| sqrt(1 - axis_i²)`.
fn disk_box(center: Vec3, axis: Vec3, r: f32) -> Aabb {
    let a = axis.to_array();
    let e = a.map(|ai| NoCount.sqrt((1.0 - ai * ai).max(0.0)) * r.abs());
    Aabb::EMPTY.grow(center).grow_by(e)
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
unsafe extern "C" fn user_bounds(args: *const RTCBoundsFunctionArguments) {
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
unsafe extern "C" fn user_intersect(args: *const RTCIntersectFunctionNArguments) {
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
unsafe extern "C" fn user_occluded(args: *const RTCOccludedFunctionNArguments) {
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
        let table = self.geometries.get(rayhit.hit.geom_id as usize)?;
        let prim = *table.prims.get(rayhit.hit.prim_id as usize)?;
        if table.aux_in_u {
            return Some(Hit {
                t: rayhit.ray.tfar,
                prim,
                aux: rayhit.hit.u,
            });
        }
        // A triangle's distance differs from rtprof's plane distance in the last bits,
        // enough to move the hit point to the other side of a shadow ray's grazing
        // test; rtprof's own plane distance (one plane test) keeps the rays that follow
        // the baseline's.
        let outline = match prim.kind {
            PrimKind::Polygon => self
                .source
                .polygons
                .get(prim.index as usize)
                .map(|p| &p.outline),
            PrimKind::Patch => self
                .source
                .patches
                .get(prim.index as usize)
                .map(|p| &p.outline),
            _ => None,
        };
        let t = outline
            .and_then(|o| o.intersect_plane(ray, t_min, f32::INFINITY, &mut NoCount))
            .unwrap_or(rayhit.ray.tfar);
        Some(Hit { t, prim, aux: 0.0 })
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
