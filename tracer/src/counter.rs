//! The counting layer: exact operation counts at no cost when counting is off.
//!
//! Every vector operation, square root and power in the tracer is a method of
//! [`Counter`]. The renderer is generic over the counter type: [`NoCount`] makes every
//! tally an empty inline function (the optimizer removes it), [`Count`] adds one to a
//! plain `u64`. One binary therefore runs counted (`rtprof count`) and uncounted
//! (`rtprof render`) without a runtime branch in the hot loops.
//!
//! Conventions (they decide what a number means):
//! - a `normalize` counts as itself, not as the dot product and square root inside it;
//! - scalar arithmetic is not counted, nor are colour sums (they use [`Rgb`](crate::Rgb));
//! - `sub`, `add`, `scale`, `cross` and `dot` count one per call, whatever the width;
//! - a test is counted when a primitive is tested against a ray, a hit when that test
//!   reports an intersection inside the ray's interval (not only the closest one).
//!
//! Ray counts (`rays.*`) are not kept here: they cost one increment per ray, so the
//! renderer always keeps them in a [`RayCounts`] and the uncounted render can report
//! rays per second.

use crate::vec3::Vec3;
use serde::{Deserialize, Serialize};

/// One countable event. The names follow the thesis's gprof table 6.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(usize)]
pub enum Stat {
    Dot,
    Sub,
    Add,
    Cross,
    Scale,
    Normalize,
    Sqrt,
    Pow,
    Trace,
    Intersect,
    Shade,
    ColorContribution,
    PrimaryRaySetup,
    SphereTest,
    SphereHit,
    CylinderTest,
    CylinderHit,
    ConeTest,
    ConeHit,
    PolygonTest,
    PolygonHit,
    PatchTest,
    PatchHit,
    PlaneTest,
    PlaneHit,
    NodesVisited,
    LeavesVisited,
}

/// Number of [`Stat`] variants.
pub const STAT_COUNT: usize = Stat::LeavesVisited as usize + 1;

/// A sink for operation counts, and the home of every counted operation.
///
/// Implementors only provide [`Counter::tally`] and [`Counter::merge`]; the maths
/// methods are provided so that counting and computing cannot drift apart.
pub trait Counter: Default + Clone + Send + Sync {
    /// Whether this counter records anything.
    const ENABLED: bool;

    /// Records one occurrence of `stat`.
    fn tally(&mut self, stat: Stat);

    /// Records `n` occurrences of `stat` (batched tests: one call per SIMD chunk).
    #[inline(always)]
    fn tally_n(&mut self, stat: Stat, n: u64) {
        for _ in 0..n {
            self.tally(stat);
        }
    }

    /// The bare square root this counter's maths uses, uncounted: for batched code
    /// that counts its roots with [`Counter::tally_n`].
    #[inline(always)]
    fn sqrt_kernel(x: f32) -> f32 {
        #[allow(clippy::disallowed_methods)]
        x.sqrt()
    }

    /// Adds another counter's totals into this one (used after the parallel loop).
    fn merge(&mut self, other: &Self);

    /// The totals as an array indexed by `Stat as usize`, or `None` when not counting.
    fn totals(&self) -> Option<[u64; STAT_COUNT]>;

    /// Dot product `a · b`.
    #[inline(always)]
    fn dot(&mut self, a: Vec3, b: Vec3) -> f32 {
        self.tally(Stat::Dot);
        #[allow(clippy::disallowed_methods)]
        a.0.dot(b.0)
    }

    /// Difference `a - b`.
    #[inline(always)]
    fn sub(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        self.tally(Stat::Sub);
        Vec3(a.0 - b.0)
    }

    /// Sum `a + b`.
    #[inline(always)]
    fn add(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        self.tally(Stat::Add);
        Vec3(a.0 + b.0)
    }

    /// Cross product `a × b`.
    #[inline(always)]
    fn cross(&mut self, a: Vec3, b: Vec3) -> Vec3 {
        self.tally(Stat::Cross);
        #[allow(clippy::disallowed_methods)]
        Vec3(a.0.cross(b.0))
    }

    /// Vector times scalar `a s`.
    #[inline(always)]
    fn scale(&mut self, a: Vec3, s: f32) -> Vec3 {
        self.tally(Stat::Scale);
        Vec3(a.0 * s)
    }

    /// `a / |a|`. The caller guarantees `a` is not the zero vector.
    #[inline(always)]
    fn normalize(&mut self, a: Vec3) -> Vec3 {
        self.tally(Stat::Normalize);
        #[allow(clippy::disallowed_methods)]
        let length_sq = a.0.dot(a.0);
        Vec3(a.0 * (1.0 / Self::sqrt_kernel(length_sq)))
    }

    /// Square root of a scalar.
    #[inline(always)]
    fn sqrt(&mut self, x: f32) -> f32 {
        self.tally(Stat::Sqrt);
        Self::sqrt_kernel(x)
    }

    /// `x` raised to `e` (the Phong highlight).
    #[inline(always)]
    fn pow(&mut self, x: f32, e: f32) -> f32 {
        self.tally(Stat::Pow);
        #[allow(clippy::disallowed_methods)]
        x.powf(e)
    }
}

/// A counter that counts nothing; every method compiles to the bare maths.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoCount;

impl Counter for NoCount {
    const ENABLED: bool = false;

    #[inline(always)]
    fn tally(&mut self, _stat: Stat) {}

    #[inline(always)]
    fn tally_n(&mut self, _stat: Stat, _n: u64) {}

    #[inline(always)]
    fn merge(&mut self, _other: &Self) {}

    fn totals(&self) -> Option<[u64; STAT_COUNT]> {
        None
    }
}

/// A counter holding one plain `u64` per [`Stat`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    values: [u64; STAT_COUNT],
}

impl Default for Count {
    fn default() -> Self {
        Self {
            values: [0; STAT_COUNT],
        }
    }
}

impl Count {
    /// The count of one event.
    pub fn get(&self, stat: Stat) -> u64 {
        self.values[stat as usize]
    }
}

impl Counter for Count {
    const ENABLED: bool = true;

    #[inline(always)]
    fn tally(&mut self, stat: Stat) {
        self.values[stat as usize] += 1;
    }

    #[inline(always)]
    fn tally_n(&mut self, stat: Stat, n: u64) {
        self.values[stat as usize] += n;
    }

    fn merge(&mut self, other: &Self) {
        for (mine, theirs) in self.values.iter_mut().zip(other.values.iter()) {
            *mine += theirs;
        }
    }

    fn totals(&self) -> Option<[u64; STAT_COUNT]> {
        Some(self.values)
    }
}

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
    pub plane: TestHits,
}

/// `accel.*`: acceleration-structure traversal (zero for brute force).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct AccelCounts {
    pub nodes_visited: u64,
    pub leaves_visited: u64,
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

impl Counts {
    /// Assembles the report from a counter's totals and the ray counts.
    pub fn from_parts(totals: &[u64; STAT_COUNT], rays: RayCounts) -> Self {
        let g = |s: Stat| totals[s as usize];
        let th = |t: Stat, h: Stat| TestHits {
            tests: g(t),
            hits: g(h),
        };
        Self {
            ops: OpCounts {
                dot: g(Stat::Dot),
                sub: g(Stat::Sub),
                add: g(Stat::Add),
                cross: g(Stat::Cross),
                scale: g(Stat::Scale),
                normalize: g(Stat::Normalize),
                sqrt: g(Stat::Sqrt),
                pow: g(Stat::Pow),
            },
            calls: CallCounts {
                trace: g(Stat::Trace),
                intersect: g(Stat::Intersect),
                shade: g(Stat::Shade),
                color_contribution: g(Stat::ColorContribution),
                primary_ray_setup: g(Stat::PrimaryRaySetup),
            },
            tests: TestCounts {
                sphere: th(Stat::SphereTest, Stat::SphereHit),
                cylinder: th(Stat::CylinderTest, Stat::CylinderHit),
                cone: th(Stat::ConeTest, Stat::ConeHit),
                polygon: th(Stat::PolygonTest, Stat::PolygonHit),
                patch: th(Stat::PatchTest, Stat::PatchHit),
                plane: th(Stat::PlaneTest, Stat::PlaneHit),
            },
            rays,
            accel: AccelCounts {
                nodes_visited: g(Stat::NodesVisited),
                leaves_visited: g(Stat::LeavesVisited),
            },
        }
    }

    /// Every count as `(dotted name, value)`, in the order of the thesis's table 6
    /// (calls first, then operations, then tests, rays and acceleration).
    pub fn rows(&self) -> Vec<(&'static str, u64)> {
        let (o, c, t, r, a) = (&self.ops, &self.calls, &self.tests, &self.rays, &self.accel);
        vec![
            ("calls.primary_ray_setup", c.primary_ray_setup),
            ("calls.trace", c.trace),
            ("calls.intersect", c.intersect),
            ("calls.shade", c.shade),
            ("calls.color_contribution", c.color_contribution),
            ("ops.add", o.add),
            ("ops.sub", o.sub),
            ("ops.cross", o.cross),
            ("ops.dot", o.dot),
            ("ops.normalize", o.normalize),
            ("ops.scale", o.scale),
            ("ops.sqrt", o.sqrt),
            ("ops.pow", o.pow),
            ("tests.sphere.tests", t.sphere.tests),
            ("tests.sphere.hits", t.sphere.hits),
            ("tests.cylinder.tests", t.cylinder.tests),
            ("tests.cylinder.hits", t.cylinder.hits),
            ("tests.cone.tests", t.cone.tests),
            ("tests.cone.hits", t.cone.hits),
            ("tests.polygon.tests", t.polygon.tests),
            ("tests.polygon.hits", t.polygon.hits),
            ("tests.patch.tests", t.patch.tests),
            ("tests.patch.hits", t.patch.hits),
            ("tests.plane.tests", t.plane.tests),
            ("tests.plane.hits", t.plane.hits),
            ("rays.primary", r.primary),
            ("rays.primary_hit", r.primary_hit),
            ("rays.shadow", r.shadow),
            ("rays.shadow_blocked", r.shadow_blocked),
            ("rays.reflection", r.reflection),
            ("rays.refraction", r.refraction),
            ("accel.nodes_visited", a.nodes_visited),
            ("accel.leaves_visited", a.leaves_visited),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_count_records_nothing_and_count_records_each_call() {
        let (a, b) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 5.0, 6.0));
        let mut none = NoCount;
        assert_eq!(none.dot(a, b), 32.0);
        assert!(none.totals().is_none());

        let mut c = Count::default();
        assert_eq!(c.dot(a, b), 32.0);
        assert_eq!(c.sub(b, a).to_array(), [3.0, 3.0, 3.0]);
        assert_eq!(c.cross(a, b).to_array(), [-3.0, 6.0, -3.0]);
        let n = c.normalize(Vec3::new(3.0, 0.0, 4.0));
        assert!((n.x() - 0.6).abs() < 1e-6 && (n.z() - 0.8).abs() < 1e-6);
        assert_eq!(c.sqrt(16.0), 4.0);
        assert_eq!(
            c.get(Stat::Dot),
            1,
            "normalize must not count its inner dot"
        );
        assert_eq!(
            c.get(Stat::Sqrt),
            1,
            "normalize must not count its inner sqrt"
        );
        assert_eq!(c.get(Stat::Normalize), 1);
        assert_eq!(c.get(Stat::Sub), 1);
        assert_eq!(c.get(Stat::Cross), 1);
    }

    #[test]
    fn merge_adds_fieldwise_and_counts_serialize_under_their_names() {
        let mut a = Count::default();
        let mut b = Count::default();
        a.tally(Stat::SphereTest);
        b.tally(Stat::SphereTest);
        b.tally(Stat::SphereHit);
        a.merge(&b);
        let counts = Counts::from_parts(
            &a.totals().unwrap_or([0; STAT_COUNT]),
            RayCounts {
                primary: 7,
                ..RayCounts::default()
            },
        );
        assert_eq!(counts.tests.sphere, TestHits { tests: 2, hits: 1 });
        let json = serde_json::to_value(counts).unwrap_or_default();
        assert_eq!(json["tests"]["sphere"]["tests"], 2);
        assert_eq!(json["rays"]["primary"], 7);
        assert_eq!(json["calls"]["color_contribution"], 0);
        assert_eq!(counts.rows().len(), 33);
    }
}
