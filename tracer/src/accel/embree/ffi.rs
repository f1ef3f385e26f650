//! The few declarations of Embree 3's C API (`embree3/rtcore*.h`, 3.13.5) that the
//! intersector uses, written by hand.
//!
//! Why by hand: the intersector needs about twenty-five functions and twelve structs. A
//! generated `-sys` crate would need bindgen and the headers at build time. The
//! crates.io `embree3` (0.4) safe wrapper does offer user geometry, but, as its
//! documentation describes, calls it through heap-owned closures found in a
//! per-geometry table: an indirection inside every sphere, cylinder and cone test, in
//! a crate whose point is to time intersection, and one more dependency for every
//! build. These declarations need no build script and no headers: `cargo check` and
//! clippy pass with the feature on where Embree is not installed; only linking needs
//! `libembree3.so`.
//!
//! Every layout below is checked against the headers by the `const` assertions at the
//! end (sizes, alignments, field offsets). Embree's C enums are passed as `u32`: their
//! values are all non-negative and small, so the C compiler gives them a 32-bit
//! unsigned type, and they are 32-bit integers in the x86-64 and AArch64 calling
//! conventions either way. The build-dependent parts of the structs follow Debian's
//! `rtcore_config.h`: `RTC_MAX_INSTANCE_LEVEL_COUNT` is 1 and `RTC_MIN_WIDTH` is 0, so
//! `RTCIntersectContext` has no `instStackSize` and no `minWidthDistanceFactor`.

use std::ffi::{c_char, c_void};

/// Opaque `RTCDeviceTy`.
#[repr(C)]
pub struct DeviceTy {
    _private: [u8; 0],
}
/// Opaque `RTCSceneTy`.
#[repr(C)]
pub struct SceneTy {
    _private: [u8; 0],
}
/// Opaque `RTCGeometryTy`.
#[repr(C)]
pub struct GeometryTy {
    _private: [u8; 0],
}

pub type RTCDevice = *mut DeviceTy;
pub type RTCScene = *mut SceneTy;
pub type RTCGeometry = *mut GeometryTy;

/// `RTC_INVALID_GEOMETRY_ID`.
pub const RTC_INVALID_GEOMETRY_ID: u32 = u32::MAX;

// enum RTCError
pub const RTC_ERROR_NONE: u32 = 0;
pub const RTC_ERROR_UNKNOWN: u32 = 1;
pub const RTC_ERROR_INVALID_ARGUMENT: u32 = 2;
pub const RTC_ERROR_INVALID_OPERATION: u32 = 3;
pub const RTC_ERROR_OUT_OF_MEMORY: u32 = 4;
pub const RTC_ERROR_UNSUPPORTED_CPU: u32 = 5;
pub const RTC_ERROR_CANCELLED: u32 = 6;

// enum RTCBuildQuality
pub const RTC_BUILD_QUALITY_HIGH: u32 = 2;

// enum RTCSceneFlags
pub const RTC_SCENE_FLAG_ROBUST: u32 = 1 << 2;

// enum RTCIntersectContextFlags
pub const RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT: u32 = 0;
pub const RTC_INTERSECT_CONTEXT_FLAG_COHERENT: u32 = 1 << 0;

// enum RTCDeviceProperty
pub const RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED: u32 = 33;
pub const RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED: u32 = 34;

// enum RTCGeometryType
pub const RTC_GEOMETRY_TYPE_TRIANGLE: u32 = 0;
pub const RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE: u32 = 15;
pub const RTC_GEOMETRY_TYPE_SPHERE_POINT: u32 = 50;
pub const RTC_GEOMETRY_TYPE_USER: u32 = 120;

// enum RTCBufferType
pub const RTC_BUFFER_TYPE_INDEX: u32 = 0;
pub const RTC_BUFFER_TYPE_VERTEX: u32 = 1;
pub const RTC_BUFFER_TYPE_FLAGS: u32 = 32;

// enum RTCCurveFlags (one byte per segment in the flags buffer)
pub const RTC_CURVE_FLAG_NEIGHBOR_LEFT: u8 = 1 << 0;
pub const RTC_CURVE_FLAG_NEIGHBOR_RIGHT: u8 = 1 << 1;

// enum RTCFormat
pub const RTC_FORMAT_UCHAR: u32 = 0x1001;
pub const RTC_FORMAT_UINT: u32 = 0x5001;
pub const RTC_FORMAT_UINT3: u32 = 0x5003;
pub const RTC_FORMAT_FLOAT3: u32 = 0x9003;
pub const RTC_FORMAT_FLOAT4: u32 = 0x9004;

/// `struct RTCRay` (`RTC_ALIGN(16)`).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug)]
pub struct RTCRay {
    pub org_x: f32,
    pub org_y: f32,
    pub org_z: f32,
    pub tnear: f32,
    pub dir_x: f32,
    pub dir_y: f32,
    pub dir_z: f32,
    pub time: f32,
    pub tfar: f32,
    pub mask: u32,
    pub id: u32,
    pub flags: u32,
}

/// `struct RTCHit` (`RTC_ALIGN(16)`).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug)]
pub struct RTCHit {
    pub ng_x: f32,
    pub ng_y: f32,
    pub ng_z: f32,
    pub u: f32,
    pub v: f32,
    pub prim_id: u32,
    pub geom_id: u32,
    pub inst_id: [u32; 1],
}

/// `struct RTCRayHit`: 16-byte aligned through its members.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RTCRayHit {
    pub ray: RTCRay,
    pub hit: RTCHit,
}

/// `struct RTCRay8` (`RTC_ALIGN(32)`): eight rays, one array per field.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub struct RTCRay8 {
    pub org_x: [f32; 8],
    pub org_y: [f32; 8],
    pub org_z: [f32; 8],
    pub tnear: [f32; 8],
    pub dir_x: [f32; 8],
    pub dir_y: [f32; 8],
    pub dir_z: [f32; 8],
    pub time: [f32; 8],
    pub tfar: [f32; 8],
    pub mask: [u32; 8],
    pub id: [u32; 8],
    pub flags: [u32; 8],
}

/// `struct RTCHit8` (`RTC_ALIGN(32)`), for `RTC_MAX_INSTANCE_LEVEL_COUNT` 1.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub struct RTCHit8 {
    pub ng_x: [f32; 8],
    pub ng_y: [f32; 8],
    pub ng_z: [f32; 8],
    pub u: [f32; 8],
    pub v: [f32; 8],
    pub prim_id: [u32; 8],
    pub geom_id: [u32; 8],
    pub inst_id: [[u32; 8]; 1],
}

/// `struct RTCRayHit8`: 32-byte aligned through its members.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RTCRayHit8 {
    pub ray: RTCRay8,
    pub hit: RTCHit8,
}

/// `RTCFilterFunctionN` (never set: the intersector uses no filter).
pub type RTCFilterFunctionN = Option<unsafe extern "C" fn(args: *const c_void)>;

/// `struct RTCIntersectContext` for `RTC_MAX_INSTANCE_LEVEL_COUNT` 1, no min width.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RTCIntersectContext {
    pub flags: u32,
    pub filter: RTCFilterFunctionN,
    pub inst_id: [u32; 1],
}

impl RTCIntersectContext {
    /// `rtcInitIntersectContext`, a `RTC_FORCEINLINE` function of the header that no
    /// library exports: incoherent rays, no filter, no instance on the stack.
    pub fn new() -> Self {
        Self::with_flags(RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT)
    }

    /// `rtcInitIntersectContext` followed by setting `flags` (e.g. coherent rays).
    pub fn with_flags(flags: u32) -> Self {
        Self {
            flags,
            filter: None,
            inst_id: [RTC_INVALID_GEOMETRY_ID],
        }
    }
}

/// `struct RTCBounds` (`RTC_ALIGN(16)`).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RTCBounds {
    pub lower_x: f32,
    pub lower_y: f32,
    pub lower_z: f32,
    pub align0: f32,
    pub upper_x: f32,
    pub upper_y: f32,
    pub upper_z: f32,
    pub align1: f32,
}

/// `struct RTCBoundsFunctionArguments`.
#[repr(C)]
pub struct RTCBoundsFunctionArguments {
    pub geometry_user_ptr: *mut c_void,
    pub prim_id: u32,
    pub time_step: u32,
    pub bounds_o: *mut RTCBounds,
}

/// `struct RTCIntersectFunctionNArguments`. `rayhit` points to an `RTCRayHitN`: the
/// ray and hit fields of `n` rays in SoA order, one 4-byte word per field and ray.
#[repr(C)]
pub struct RTCIntersectFunctionNArguments {
    pub valid: *mut i32,
    pub geometry_user_ptr: *mut c_void,
    pub prim_id: u32,
    pub context: *mut RTCIntersectContext,
    pub rayhit: *mut c_void,
    pub n: u32,
    pub geom_id: u32,
}

/// `struct RTCOccludedFunctionNArguments`. `ray` points to an `RTCRayN` (SoA).
#[repr(C)]
pub struct RTCOccludedFunctionNArguments {
    pub valid: *mut i32,
    pub geometry_user_ptr: *mut c_void,
    pub prim_id: u32,
    pub context: *mut RTCIntersectContext,
    pub ray: *mut c_void,
    pub n: u32,
    pub geom_id: u32,
}

pub type RTCErrorFunction =
    Option<unsafe extern "C" fn(user_ptr: *mut c_void, code: u32, message: *const c_char)>;
pub type RTCBoundsFunction = Option<unsafe extern "C" fn(args: *const RTCBoundsFunctionArguments)>;
pub type RTCIntersectFunctionN =
    Option<unsafe extern "C" fn(args: *const RTCIntersectFunctionNArguments)>;
pub type RTCOccludedFunctionN =
    Option<unsafe extern "C" fn(args: *const RTCOccludedFunctionNArguments)>;

/// Word index of each field in an `RTCRayN` / `RTCRayHitN` of `N` rays: field `k` of
/// ray `i` is word `k N + i` (the `RTCRayN_*` and `RTCHitN_*` accessors of
/// `rtcore_ray.h`; the hit part starts at word `12 N`).
pub mod soa {
    pub const ORG_X: usize = 0;
    pub const ORG_Y: usize = 1;
    pub const ORG_Z: usize = 2;
    pub const TNEAR: usize = 3;
    pub const DIR_X: usize = 4;
    pub const DIR_Y: usize = 5;
    pub const DIR_Z: usize = 6;
    pub const TFAR: usize = 8;
    pub const NG_X: usize = 12;
    pub const NG_Y: usize = 13;
    pub const NG_Z: usize = 14;
    pub const U: usize = 15;
    pub const V: usize = 16;
    pub const PRIM_ID: usize = 17;
    pub const GEOM_ID: usize = 18;
    pub const INST_ID: usize = 19;
}

#[link(name = "embree3")]
unsafe extern "C" {
    pub fn rtcNewDevice(config: *const c_char) -> RTCDevice;
    pub fn rtcReleaseDevice(device: RTCDevice);
    pub fn rtcGetDeviceError(device: RTCDevice) -> u32;
    pub fn rtcGetDeviceProperty(device: RTCDevice, prop: u32) -> isize;
    pub fn rtcSetDeviceErrorFunction(
        device: RTCDevice,
        error: RTCErrorFunction,
        user_ptr: *mut c_void,
    );

    pub fn rtcNewScene(device: RTCDevice) -> RTCScene;
    pub fn rtcSetSceneBuildQuality(scene: RTCScene, quality: u32);
    pub fn rtcSetSceneFlags(scene: RTCScene, flags: u32);
    pub fn rtcAttachGeometryByID(scene: RTCScene, geometry: RTCGeometry, geom_id: u32);
    pub fn rtcCommitScene(scene: RTCScene);
    pub fn rtcReleaseScene(scene: RTCScene);

    pub fn rtcNewGeometry(device: RTCDevice, kind: u32) -> RTCGeometry;
    pub fn rtcSetNewGeometryBuffer(
        geometry: RTCGeometry,
        kind: u32,
        slot: u32,
        format: u32,
        byte_stride: usize,
        item_count: usize,
    ) -> *mut c_void;
    pub fn rtcSetGeometryUserPrimitiveCount(geometry: RTCGeometry, count: u32);
    pub fn rtcSetGeometryUserData(geometry: RTCGeometry, ptr: *mut c_void);
    pub fn rtcSetGeometryBoundsFunction(
        geometry: RTCGeometry,
        bounds: RTCBoundsFunction,
        user_ptr: *mut c_void,
    );
    pub fn rtcSetGeometryIntersectFunction(geometry: RTCGeometry, intersect: RTCIntersectFunctionN);
    pub fn rtcSetGeometryOccludedFunction(geometry: RTCGeometry, occluded: RTCOccludedFunctionN);
    pub fn rtcCommitGeometry(geometry: RTCGeometry);
    pub fn rtcReleaseGeometry(geometry: RTCGeometry);

    pub fn rtcIntersect1(
        scene: RTCScene,
        context: *mut RTCIntersectContext,
        rayhit: *mut RTCRayHit,
    );
    pub fn rtcOccluded1(scene: RTCScene, context: *mut RTCIntersectContext, ray: *mut RTCRay);
    pub fn rtcIntersect8(
        valid: *const i32,
        scene: RTCScene,
        context: *mut RTCIntersectContext,
        rayhit: *mut RTCRayHit8,
    );
    pub fn rtcOccluded8(
        valid: *const i32,
        scene: RTCScene,
        context: *mut RTCIntersectContext,
        ray: *mut RTCRay8,
    );
}

// The layouts of the headers (x86-64 / AArch64, LP64).
const _: () = {
    use std::mem::{align_of, offset_of, size_of};
    assert!(size_of::<RTCRay>() == 48 && align_of::<RTCRay>() == 16);
    assert!(offset_of!(RTCRay, tnear) == 12 && offset_of!(RTCRay, dir_x) == 16);
    assert!(offset_of!(RTCRay, tfar) == 32 && offset_of!(RTCRay, flags) == 44);
    assert!(size_of::<RTCHit>() == 32 && align_of::<RTCHit>() == 16);
    assert!(offset_of!(RTCHit, u) == 12 && offset_of!(RTCHit, prim_id) == 20);
    assert!(offset_of!(RTCHit, geom_id) == 24 && offset_of!(RTCHit, inst_id) == 28);
    assert!(size_of::<RTCRayHit>() == 80 && align_of::<RTCRayHit>() == 16);
    assert!(offset_of!(RTCRayHit, hit) == 48);
    // The SoA word indices of one ray (N = 1) are the AoS offsets of RTCRayHit / 4.
    assert!(soa::TFAR * 4 == offset_of!(RTCRay, tfar));
    assert!(soa::U * 4 == offset_of!(RTCRayHit, hit) + offset_of!(RTCHit, u));
    assert!(soa::INST_ID * 4 == offset_of!(RTCRayHit, hit) + offset_of!(RTCHit, inst_id));
    assert!(size_of::<RTCRay8>() == 384 && align_of::<RTCRay8>() == 32);
    assert!(offset_of!(RTCRay8, tfar) == 256 && offset_of!(RTCRay8, flags) == 352);
    assert!(size_of::<RTCHit8>() == 256 && align_of::<RTCHit8>() == 32);
    assert!(offset_of!(RTCHit8, prim_id) == 160 && offset_of!(RTCHit8, inst_id) == 224);
    assert!(size_of::<RTCRayHit8>() == 640 && offset_of!(RTCRayHit8, hit) == 384);
    // The SoA word indices of eight rays (N = 8) are the offsets of RTCRayHit8 / 4.
    assert!(soa::TFAR * 8 * 4 == offset_of!(RTCRay8, tfar));
    assert!(soa::U * 8 * 4 == offset_of!(RTCRayHit8, hit) + offset_of!(RTCHit8, u));
    assert!(soa::INST_ID * 8 * 4 == offset_of!(RTCRayHit8, hit) + offset_of!(RTCHit8, inst_id));
    assert!(size_of::<RTCIntersectContext>() == 24);
    assert!(offset_of!(RTCIntersectContext, filter) == 8);
    assert!(offset_of!(RTCIntersectContext, inst_id) == 16);
    assert!(size_of::<RTCBounds>() == 32 && align_of::<RTCBounds>() == 16);
    assert!(offset_of!(RTCBounds, upper_x) == 16);
    assert!(size_of::<RTCBoundsFunctionArguments>() == 24);
    assert!(offset_of!(RTCBoundsFunctionArguments, bounds_o) == 16);
    assert!(size_of::<RTCIntersectFunctionNArguments>() == 48);
    assert!(offset_of!(RTCIntersectFunctionNArguments, prim_id) == 16);
    assert!(offset_of!(RTCIntersectFunctionNArguments, context) == 24);
    assert!(offset_of!(RTCIntersectFunctionNArguments, rayhit) == 32);
    assert!(offset_of!(RTCIntersectFunctionNArguments, n) == 40);
    assert!(offset_of!(RTCIntersectFunctionNArguments, geom_id) == 44);
    assert!(size_of::<RTCOccludedFunctionNArguments>() == 48);
    assert!(offset_of!(RTCOccludedFunctionNArguments, ray) == 32);
    assert!(offset_of!(RTCOccludedFunctionNArguments, geom_id) == 44);
};
