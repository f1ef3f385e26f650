//! A counter that counts nothing but times the intersection queries, for the time
//! split by ray kind (eye, secondary and shadow rays per second).
//!
//! [`QueryClock`] reads the time-stamp counter when a closest-hit or shadow query
//! starts and when it ends (its phase guard, so the hot loops stay as they are) and
//! adds the difference to the calling thread's total of that kind: a closest hit
//! inside a reflection or refraction set-up ([`Phase::SecondaryRays`]) is a secondary
//! ray's, any other an eye ray's. The sample rows are timed too: a worker's busy time,
//! so that the time it waited for work is not taken for shading. The totals are per thread (no shared cache line on
//! the query path); [`take_query_ticks`] reads and clears the calling thread's.
//!
//! The clock reads cost some cycles per query, so a clocked pass is a separate pass:
//! its shares of the time, not its times, are applied to an unclocked render.

use std::cell::Cell;

use super::{Counter, Phase, STAT_COUNT, Stat};

/// The kinds of work timed, the index in [`QueryTicks`]: the three queries, and the
/// sample rows that hold them (a worker's busy time; the rest of its time it waited).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueryKind {
    Eye = 0,
    Secondary = 1,
    Shadow = 2,
    Row = 3,
}

/// Clock ticks spent per [`QueryKind`].
pub type QueryTicks = [u64; 4];

thread_local! {
    static TICKS: Cell<QueryTicks> = const { Cell::new([0; 4]) };
    /// Reflection/refraction set-ups the thread is inside.
    static SECONDARY: Cell<u32> = const { Cell::new(0) };
}

/// The clock: the time-stamp counter on x86-64 (constant rate on every core of the
/// processors that run this), nanoseconds since the first read elsewhere.
#[inline(always)]
pub fn clock_ticks() -> u64 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `rdtsc` has no preconditions on x86-64.
        unsafe { std::arch::x86_64::_rdtsc() }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        static EPOCH: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
        EPOCH
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_nanos() as u64
    }
}

/// Reads and clears the calling thread's totals.
pub fn take_query_ticks() -> QueryTicks {
    TICKS.with(|t| t.replace([0; 4]))
}

/// What [`QueryClock::enter_phase`] returns: on drop, a timed query adds its ticks, a
/// secondary-ray scope ends.
pub enum QueryTimer {
    Untimed,
    Query { kind: QueryKind, start: u64 },
    SecondaryScope,
}

impl Drop for QueryTimer {
    #[inline(always)]
    fn drop(&mut self) {
        match *self {
            QueryTimer::Untimed => {}
            QueryTimer::Query { kind, start } => {
                let spent = clock_ticks().wrapping_sub(start);
                TICKS.with(|t| {
                    let mut ticks = t.get();
                    ticks[kind as usize] += spent;
                    t.set(ticks);
                });
            }
            QueryTimer::SecondaryScope => SECONDARY.with(|d| d.set(d.get().saturating_sub(1))),
        }
    }
}

/// A counter that counts nothing (the maths of [`super::NoCount`]) and times the
/// queries (module doc).
#[derive(Clone, Copy, Debug, Default)]
pub struct QueryClock;

impl Counter for QueryClock {
    const ENABLED: bool = false;
    type PhaseGuard = QueryTimer;

    #[inline(always)]
    fn enter_phase(phase: Phase) -> QueryTimer {
        let kind = match phase {
            Phase::ClosestHit if SECONDARY.with(Cell::get) > 0 => QueryKind::Secondary,
            Phase::ClosestHit => QueryKind::Eye,
            Phase::ShadowQuery => QueryKind::Shadow,
            Phase::SampleRow => QueryKind::Row,
            Phase::SecondaryRays => {
                SECONDARY.with(|d| d.set(d.get() + 1));
                return QueryTimer::SecondaryScope;
            }
            _ => return QueryTimer::Untimed,
        };
        QueryTimer::Query {
            kind,
            start: clock_ticks(),
        }
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
