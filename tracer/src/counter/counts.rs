//! The counts of one render as a report: nested structs in the JSON shape of
//! `rtprof count --json` (`{"ops": {"dot": N, …}, "calls": {…}, "tests": {"sphere":
//! {"tests": N, "hits": N}, …}, "rays": {…}, "accel": {…}}`), for typed access
//! (`counts.tests.sphere.tests`). Which field holds which counter, the dotted keys and
//! the order of listings come from the counter table ([`super::table`]); a field
//! missing from the table fails its tests, a table path missing here fails to compile.

use serde::{Deserialize, Serialize};

/// Ray statistics in the SPD sense, always kept by the renderer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RayCounts {
    /// Eye rays ((W+1)(H+1) in SPD corner mode, W·H otherwise).
    pub primary: u64,
    /// Eye rays that hit an object.
    pub primary_hit: u64,
    /// Shadow rays cast toward lights.
    pub shadow: u64,
    /// Shadow rays that found an occluder.
    pub shadow_blocked: u64,
    /// Reflection rays spawned.
    pub reflection: u64,
    /// Refraction rays spawned.
    pub refraction: u64,
}

impl RayCounts {
    /// Adds `other` into `self`.
    pub fn merge(&mut self, other: &Self) {
        self.primary += other.primary;
        self.primary_hit += other.primary_hit;
        self.shadow += other.shadow;
        self.shadow_blocked += other.shadow_blocked;
        self.reflection += other.reflection;
        self.refraction += other.refraction;
    }

    /// Every ray traced: eye, shadow, reflection and refraction.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection + self.refraction
    }
}

/// `ops.*`: counted vector and scalar operations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct OpCounts {
    pub dot: u64,
    pub sub: u64,
    pub add: u64,
    pub cross: u64,
    pub scale: u64,
    pub normalize: u64,
    pub sqrt: u64,
    pub pow: u64,
}

/// `calls.*`: calls of the tracer's main functions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CallCounts {
    pub trace: u64,
    pub intersect: u64,
    pub shade: u64,
    pub color_contribution: u64,
    pub primary_ray_setup: u64,
}

/// Tests and hits of one primitive kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct TestHits {
    pub tests: u64,
    pub hits: u64,
}

/// `tests.*`: ray-primitive tests and hits per primitive kind. `plane` counts the
/// plane test that opens every polygon and patch test (as the thesis's table does).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct TestCounts {
    pub sphere: TestHits,
    pub cylinder: TestHits,
    pub cone: TestHits,
    pub polygon: TestHits,
    pub patch: TestHits,
    /// The triangles of polygons and patches that the wide BVH tests in lanes (zero
    /// for the other structures, which test the outlines whole).
    #[serde(default)]
    pub triangle: TestHits,
    pub plane: TestHits,
}

impl TestCounts {
    /// Primitive tests of every kind (the plane tests open the polygon and patch tests
    /// they belong to, so they are not added again).
    pub fn total(&self) -> u64 {
        self.sphere.tests
            + self.cylinder.tests
            + self.cone.tests
            + self.polygon.tests
            + self.patch.tests
            + self.triangle.tests
    }
}

/// `accel.*`: acceleration-structure traversal (zero for brute force).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct AccelCounts {
    pub nodes_visited: u64,
    pub leaves_visited: u64,
    /// SIMD lanes issued: 8 per chunk of primitives (variant `simd`, and sphere packs of
    /// the wide BVH) or wide node (`bvh` + `simd`) tested.
    #[serde(default)]
    pub lanes_issued: u64,
    /// Lanes issued that held a primitive or a child box (the rest are padding).
    #[serde(default)]
    pub lanes_active: u64,
}

/// Every count of one render, in the JSON shape of `rtprof count --json`
/// (`{"ops": {"dot": N, …}, "calls": {…}, "tests": {"sphere": {"tests": N, "hits": N}, …},
/// "rays": {…}, "accel": {…}}`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    pub ops: OpCounts,
    pub calls: CallCounts,
    pub tests: TestCounts,
    pub rays: RayCounts,
    pub accel: AccelCounts,
}
