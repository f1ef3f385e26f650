//! The counting layer: exact operation counts at no cost when counting is off.
//!
//! Every vector operation, square root and power in the tracer is a method of
//! [`Counter`]. The renderer is generic over the counter type: [`NoCount`] makes every
//! tally an empty inline function (the optimizer removes it), [`Count`] adds one to a
//! plain `u64`. One binary therefore runs counted (`rtprof count`) and uncounted
//! (`rtprof render`) without a runtime branch in the hot loops. A third counter,
//! [`Phased`], counts nothing either but records which [`Phase`] of the work each
//! thread is in ([`phase`]), for a sampling profiler's phase view: the renderer marks
//! its work with [`Counter::enter_phase`] (or [`Counter::in_phase`]), which the other
//! two compile to nothing.
//!
//! Every counter is declared once, in the counter table ([`table`]: its [`Stat`], its
//! key, what it counts, the profiled functions it gives the calls of); the report of a
//! counted render is a [`Counts`] ([`counts`]).
//!
//! Conventions (they decide what a number means):
//! - a `normalize` counts as itself, not as the dot product and square root inside it;
//! - scalar arithmetic is not counted, nor are colour sums (they use [`Rgb`](crate::Rgb));
//! - `sub`, `add`, `scale`, `cross` and `dot` count one per call, whatever the width;
//! - a test is counted when a primitive is tested against a ray, a hit when that test
//!   reports an intersection inside the ray's interval (not only the closest one).
//!
//! Ray counts (`rays.*`) are not tallied here: they cost one increment per ray, so the
//! renderer always keeps them in a [`RayCounts`] and the uncounted render can report
//! rays per second. They are rows of the counter table all the same.

pub mod counts;
pub mod phase;
pub mod query_clock;
pub mod table;

pub use counts::{AccelCounts, CallCounts, Counts, OpCounts, RayCounts, TestCounts, TestHits};
pub use phase::{
    Phase, PhaseGuard, enter_phase, phase_calls, phase_depth, phase_names, phase_stack_key,
    phases_of, with_phase,
};
pub use query_clock::{QueryClock, QueryKind, QueryTicks, clock_ticks, take_query_ticks};
pub use table::{
    COUNTERS, CounterDef, DERIVED_CALLS, DerivedCalls, STAT_COUNT, Stat, by_key, counted_operations,
};

use crate::vec3::Vec3;

/// The types whose methods are the counted operations (the trait, its three counters and
/// the square-root adaptor of the `fast-sqrt*` variants): a profile prints their
/// methods by the bare operation name, as the thesis's table 6 does (`dot`, not
/// `Counter::dot`). A test checks each against the source.
pub const COUNTING_LAYER: [&str; 6] = [
    "Counter",
    "NoCount",
    "Count",
    "Phased",
    "QueryClock",
    "WithSqrt",
];

/// A sink for operation counts, and the home of every counted operation.
///
/// Implementors only provide [`Counter::tally`] and [`Counter::merge`]; the maths
/// methods are provided so that counting and computing cannot drift apart.
pub trait Counter: Default + Clone + Send + Sync {
    /// Whether this counter records anything.
    const ENABLED: bool;

    /// Whether [`Counter::enter_phase`] records phases on the thread's phase stack.
    const PHASES: bool = false;

    /// What [`Counter::enter_phase`] returns: the phase ends when it is dropped. `()`
    /// for the counters that do not record phases.
    type PhaseGuard;

    /// Starts `phase` on the calling thread until the guard is dropped (also when the
    /// work unwinds). Only [`Phased`] records it (see [`phase`]); for the others the
    /// guard is `()` and the plain and counted renders compile as if it were not
    /// there. The renderer uses this form in its hot loops: a guard in a block keeps
    /// the code as it was, where a closure might not be inlined.
    fn enter_phase(phase: Phase) -> Self::PhaseGuard;

    /// Runs `f` as the work of `phase` ([`Counter::enter_phase`] around `f`).
    #[inline(always)]
    fn in_phase<R>(phase: Phase, f: impl FnOnce() -> R) -> R {
        let _phase = Self::enter_phase(phase);
        f()
    }

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

    /// [`Counter::sqrt_kernel`] of four values, lane by lane the same roots (one
    /// `sqrtps` for the standard root).
    #[inline(always)]
    fn sqrt_kernel4(x: glam::Vec4) -> glam::Vec4 {
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
    type PhaseGuard = ();

    #[inline(always)]
    fn enter_phase(_phase: Phase) {}

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

/// A counter that counts nothing (the maths of [`NoCount`]) but records the phase of
/// the work on the calling thread's phase stack, for the phase view of a profile.
#[derive(Clone, Copy, Debug, Default)]
pub struct Phased;

impl Counter for Phased {
    const ENABLED: bool = false;
    const PHASES: bool = true;
    type PhaseGuard = PhaseGuard;

    #[inline(always)]
    fn enter_phase(phase: Phase) -> PhaseGuard {
        phase::enter_phase(phase)
    }

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
    type PhaseGuard = ();

    #[inline(always)]
    fn enter_phase(_phase: Phase) {}

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
        assert_eq!(counts.rows().len(), 37);
    }
}
