//! The one timing policy of rtprof: how many renders are timed, what a time covers and
//! how the median and its interval are estimated. `rtprof suite`, `rtprof compare` and
//! `rtprof hw time --vs-software` all measure through [`measure`].
//!
//! A time covers **tracing only** (eye rays, intersection, shading); preprocessing
//! (scene preparation, the BVH or SIMD lanes build) is measured apart and reported
//! beside it, as the SPD rules ask.

use std::sync::atomic::{AtomicBool, Ordering};

use analysis::profile::sampler::process_cpu_time;
use analysis::{Estimate, median, median_with_bootstrap};
use std::time::Duration;

use tracer::VariantRender;

use crate::error::RunError;

/// How a render is timed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimingPolicy {
    /// Timed renders, at least.
    pub min_repeats: u32,
    /// More renders (up to `max_repeats`) until this many seconds of tracing are
    /// measured: a 10 ms render needs more than three samples for a useful interval.
    pub min_seconds: f64,
    /// Most timed renders, whatever `min_seconds` asks.
    pub max_repeats: u32,
    /// Bootstrap resamples of the median.
    pub resamples: usize,
    /// Confidence of the interval.
    pub confidence: f64,
    /// Seed of the bootstrap: the same samples always give the same interval.
    pub seed: u64,
}

/// The most timed renders of one measurement.
pub const MAX_REPEATS: u32 = 100;
/// Resamples of the percentile bootstrap: 10,000 keeps the interval ends stable to
/// well under 1 % of their width for up to [`MAX_REPEATS`] samples.
pub const RESAMPLES: usize = 10_000;
/// 95 % intervals everywhere.
pub const CONFIDENCE: f64 = 0.95;
/// The bootstrap seed.
pub const SEED: u64 = 0x5EED;

impl TimingPolicy {
    /// `repeats` renders at least, more until `min_seconds` are measured.
    pub fn new(repeats: u32, min_seconds: f64) -> Self {
        TimingPolicy {
            min_repeats: repeats.max(1),
            min_seconds,
            max_repeats: MAX_REPEATS.max(repeats),
            resamples: RESAMPLES,
            confidence: CONFIDENCE,
            seed: SEED,
        }
    }

    /// The policy as results.json records it.
    pub fn record(&self) -> results::TimingPolicy {
        results::TimingPolicy {
            min_repeats: self.min_repeats,
            min_seconds: self.min_seconds,
            max_repeats: self.max_repeats,
            bootstrap_resamples: self.resamples as u32,
            confidence: self.confidence,
            seed: self.seed,
            covers: results::TimeCovers::Tracing,
            interleaved: true,
        }
    }

    /// Median and interval of `samples` under this policy.
    pub fn estimate(&self, samples: &[f64]) -> Result<Estimate, RunError> {
        Ok(median_with_bootstrap(
            samples,
            self.resamples,
            self.confidence,
            self.seed,
        )?)
    }
}

/// A finished render that says how long its two phases took.
pub trait PhaseTimes {
    /// Tracing time (what a measurement's samples are).
    fn tracing(&self) -> Duration;
    /// Preprocessing time (reported apart).
    fn preprocessing(&self) -> Duration;
    /// CPU time its own account gives (an outside program's, from the kernel), when the
    /// measuring process's CPU clock does not see it; `None`: that clock's.
    fn cpu(&self) -> Option<Duration> {
        None
    }
}

impl<C> PhaseTimes for VariantRender<C> {
    fn tracing(&self) -> Duration {
        self.tracing
    }
    fn preprocessing(&self) -> Duration {
        self.preprocessing
    }
}

/// What [`measure`] measured.
pub struct Measured<R> {
    /// Tracing seconds of each timed render.
    pub samples: Vec<f64>,
    /// Process CPU seconds (all threads) of each timed render, preprocessing included:
    /// unlike wall time, it does not grow while the machine runs other work.
    pub cpu_samples: Vec<f64>,
    /// Median and interval of `samples`.
    pub time: Estimate,
    /// Median preprocessing seconds of the same renders.
    pub preprocessing: f64,
    /// The last render (its frame serves as the variant's image).
    pub last: R,
}

/// Times `render` under `policy`; `stop` is checked before each render.
pub fn measure<R: PhaseTimes>(
    policy: &TimingPolicy,
    stop: &AtomicBool,
    mut render: impl FnMut() -> Result<R, RunError>,
) -> Result<Measured<R>, RunError> {
    let mut samples = Vec::new();
    let mut cpu_samples = Vec::new();
    let mut preprocessing = Vec::new();
    let mut last = None;
    while samples.len() < policy.min_repeats as usize
        || (samples.iter().sum::<f64>() < policy.min_seconds
            && samples.len() < policy.max_repeats as usize)
    {
        if stop.load(Ordering::SeqCst) {
            return Err(RunError::Stopped);
        }
        let cpu_before = process_cpu_time();
        let out = render()?;
        cpu_samples.push((process_cpu_time().saturating_sub(cpu_before)).as_secs_f64());
        samples.push(out.tracing().as_secs_f64());
        preprocessing.push(out.preprocessing().as_secs_f64());
        last = Some(out);
    }
    let last = last.ok_or(RunError::Stopped)?;
    Ok(Measured {
        time: policy.estimate(&samples)?,
        preprocessing: median(&preprocessing).unwrap_or(0.0),
        samples,
        cpu_samples,
        last,
    })
}

/// The timed renders a measurement with `samples` so far will take under `policy`:
/// what it has when it needs no more; otherwise at least the policy's minimum and one
/// more than it has, and as many as its mean sample so far says `min_seconds` needs
/// (at most `max_repeats`). An estimate while the work runs, exact at its end.
pub fn planned_renders(policy: &TimingPolicy, samples: &[f64]) -> u64 {
    let have = samples.len() as u64;
    let sum: f64 = samples.iter().sum();
    let needs_more = have < u64::from(policy.min_repeats)
        || (sum < policy.min_seconds && have < u64::from(policy.max_repeats));
    if !needs_more {
        return have;
    }
    let for_time = match have {
        0 => 0,
        _ => (policy.min_seconds / (sum / have as f64).max(1e-12)).ceil() as u64,
    };
    for_time
        .min(u64::from(policy.max_repeats))
        .max(u64::from(policy.min_repeats))
        .max(have + 1)
}

/// What [`measure_interleaved`] measured: each render's outcome, in the order given, and
/// each per-round job's samples (one per round; `None` for a job that failed).
pub struct Interleaved<R> {
    pub renders: Vec<Result<Measured<R>, RunError>>,
    pub each_round: Vec<Option<KernelTimes>>,
}

/// A per-round job's times (the calibration kernel, the yardstick), one per round.
pub struct KernelTimes {
    /// Wall seconds, and their median and interval.
    pub samples: Vec<f64>,
    pub time: Estimate,
    /// Process CPU seconds.
    pub cpu_samples: Vec<f64>,
}

/// A render job of [`measure_interleaved`].
pub type RenderJob<'a, R> = Box<dyn FnMut() -> Result<R, RunError> + 'a>;

/// A job of [`measure_interleaved`] that runs at the start of every round (the
/// calibration kernel, the yardstick render) and returns its wall seconds.
pub type RoundJob<'a> = Box<dyn FnMut() -> Result<f64, RunError> + 'a>;

/// Times several renders in rounds: each round runs every job of `each_round` and then
/// every render that still needs samples under `policy`, once. A change of load during
/// the measurement then hits every render (and the per-round jobs) alike, so their
/// ratios stay true. A render or per-round job that fails drops out (a render with its
/// error); the others go on. `stop` is checked before each round. `timed` hears the
/// timed renders done and planned after each (see [`planned_renders`]), ending with
/// all of them done.
pub fn measure_interleaved<'a, R: PhaseTimes>(
    policy: &TimingPolicy,
    stop: &AtomicBool,
    renders: Vec<RenderJob<'a, R>>,
    each_round: Vec<RoundJob<'a>>,
    timed: &dyn Fn(u64, u64),
) -> Result<Interleaved<R>, RunError> {
    struct Slot<'a, R> {
        render: RenderJob<'a, R>,
        samples: Vec<f64>,
        cpu_samples: Vec<f64>,
        preprocessing: Vec<f64>,
        last: Option<R>,
        error: Option<RunError>,
    }
    let needs_more = |samples: &[f64]| {
        samples.len() < policy.min_repeats as usize
            || (samples.iter().sum::<f64>() < policy.min_seconds
                && samples.len() < policy.max_repeats as usize)
    };
    let mut slots: Vec<Slot<'a, R>> = renders
        .into_iter()
        .map(|render| Slot {
            render,
            samples: Vec::new(),
            cpu_samples: Vec::new(),
            preprocessing: Vec::new(),
            last: None,
            error: None,
        })
        .collect();
    // Each per-round job with its wall and CPU samples; `None` once it failed.
    type Timed<'a> = (RoundJob<'a>, Vec<f64>, Vec<f64>);
    let mut rounds: Vec<Option<Timed<'a>>> = each_round
        .into_iter()
        .map(|job| Some((job, Vec::new(), Vec::new())))
        .collect();
    let tell = |slots: &[Slot<'a, R>]| {
        let done: usize = slots.iter().map(|s| s.samples.len()).sum();
        let planned: u64 = slots
            .iter()
            .map(|s| match s.error {
                Some(_) => s.samples.len() as u64,
                None => planned_renders(policy, &s.samples),
            })
            .sum();
        timed(done as u64, planned);
    };
    tell(&slots);
    loop {
        let active: Vec<usize> = (0..slots.len())
            .filter(|&i| slots[i].error.is_none() && needs_more(&slots[i].samples))
            .collect();
        if active.is_empty() {
            break;
        }
        if stop.load(Ordering::SeqCst) {
            return Err(RunError::Stopped);
        }
        for slot in &mut rounds {
            let Some((job, wall, cpu)) = slot else {
                continue;
            };
            let cpu_before = process_cpu_time();
            match job() {
                Ok(seconds) => {
                    wall.push(seconds);
                    cpu.push(process_cpu_time().saturating_sub(cpu_before).as_secs_f64());
                }
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(_) => *slot = None,
            }
        }
        for i in active {
            let slot = &mut slots[i];
            let cpu_before = process_cpu_time();
            let outcome = (slot.render)();
            let cpu = process_cpu_time().saturating_sub(cpu_before).as_secs_f64();
            match outcome {
                Ok(out) => {
                    slot.cpu_samples
                        .push(out.cpu().map_or(cpu, |own| own.as_secs_f64()));
                    slot.samples.push(out.tracing().as_secs_f64());
                    slot.preprocessing.push(out.preprocessing().as_secs_f64());
                    slot.last = Some(out);
                }
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => slot.error = Some(e),
            }
            tell(&slots);
        }
    }
    let renders = slots
        .into_iter()
        .map(|slot| {
            if let Some(e) = slot.error {
                return Err(e);
            }
            let last = slot.last.ok_or(RunError::Stopped)?;
            Ok(Measured {
                time: policy.estimate(&slot.samples)?,
                preprocessing: median(&slot.preprocessing).unwrap_or(0.0),
                samples: slot.samples,
                cpu_samples: slot.cpu_samples,
                last,
            })
        })
        .collect();
    let each_round = rounds
        .into_iter()
        .map(|slot| {
            let (_, samples, cpu_samples) = slot?;
            let time = policy.estimate(&samples).ok()?;
            Some(KernelTimes {
                time,
                samples,
                cpu_samples,
            })
        })
        .collect();
    Ok(Interleaved {
        renders,
        each_round,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Fake(Duration, Duration);

    impl PhaseTimes for Fake {
        fn tracing(&self) -> Duration {
            self.0
        }
        fn preprocessing(&self) -> Duration {
            self.1
        }
    }

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn repeats_until_the_minimum_time_of_tracing_is_measured() {
        // 1/64 s renders (exact in binary), at least 3, until 1/8 s of tracing: 8
        // renders. The 1 s of preprocessing per render must not count towards it.
        let policy = TimingPolicy::new(3, 0.125);
        let stop = AtomicBool::new(false);
        let mut calls = 0;
        let m = measure(&policy, &stop, || {
            calls += 1;
            Ok(Fake(Duration::from_micros(15_625), ms(1000)))
        })
        .unwrap();
        assert_eq!(calls, 8);
        assert_eq!(m.samples.len(), 8);
        assert!((m.time.median - 0.015_625).abs() < 1e-12);
        assert!((m.preprocessing - 1.0).abs() < 1e-12);
    }

    #[test]
    fn stops_at_the_most_repeats_and_on_request() {
        let policy = TimingPolicy::new(2, 1e6);
        let stop = AtomicBool::new(false);
        let m = measure(&policy, &stop, || Ok(Fake(ms(1), ms(0)))).unwrap();
        assert_eq!(m.samples.len(), MAX_REPEATS as usize);
        stop.store(true, Ordering::SeqCst);
        let r = measure(&policy, &stop, || Ok(Fake(ms(1), ms(0))));
        assert!(matches!(r, Err(RunError::Stopped)));
    }

    #[test]
    fn the_interval_is_reproducible_and_brackets_the_median() {
        let policy = TimingPolicy::new(5, 0.0);
        let samples = [0.9, 1.0, 1.1, 1.05, 0.95, 1.2, 0.85];
        let a = policy.estimate(&samples).unwrap();
        let b = policy.estimate(&samples).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.median, 1.0);
        assert!(a.low <= a.median && a.median <= a.high);
        assert!(a.low >= 0.85 && a.high <= 1.2);
    }

    #[test]
    fn interleaved_rounds_give_each_render_its_own_quota() {
        // A 1/64 s render needs 8 samples for 1/8 s; a 1/16 s one needs 3 (the minimum,
        // 3/16 s >= 1/8 s). Rounds: 8; the calibration kernel runs once per round.
        use std::cell::RefCell;
        let policy = TimingPolicy::new(3, 0.125);
        let stop = AtomicBool::new(false);
        let order = RefCell::new(Vec::new());
        let fast: RenderJob<'_, Fake> = Box::new(|| {
            order.borrow_mut().push('f');
            Ok(Fake(Duration::from_micros(15_625), ms(0)))
        });
        let slow: RenderJob<'_, Fake> = Box::new(|| {
            order.borrow_mut().push('s');
            Ok(Fake(Duration::from_micros(62_500), ms(2)))
        });
        let failing: RenderJob<'_, Fake> = Box::new(|| Err(RunError::Input("broken".into())));
        let kernel_runs = std::cell::Cell::new(0);
        let kernel: RoundJob<'_> = Box::new(|| {
            kernel_runs.set(kernel_runs.get() + 1);
            Ok(0.002)
        });
        let failing_job: RoundJob<'_> = Box::new(|| Err(RunError::Input("no".into())));
        let m = measure_interleaved(
            &policy,
            &stop,
            vec![fast, slow, failing],
            vec![kernel, failing_job],
            &|_, _| {},
        )
        .unwrap();
        assert_eq!(m.renders[0].as_ref().unwrap().samples.len(), 8);
        assert_eq!(m.renders[1].as_ref().unwrap().samples.len(), 3);
        assert!((m.renders[1].as_ref().unwrap().preprocessing - 0.002).abs() < 1e-12);
        assert!(matches!(m.renders[2], Err(RunError::Input(_))));
        let mut each_round = m.each_round.into_iter();
        let kernel = each_round.next().flatten().unwrap();
        // The per-round job that failed drops out; the measurement goes on.
        assert!(each_round.next().flatten().is_none());
        assert_eq!(kernel.samples.len(), 8);
        assert_eq!(kernel.cpu_samples.len(), 8);
        assert_eq!(kernel.time.median, 0.002);
        assert_eq!(m.renders[0].as_ref().unwrap().cpu_samples.len(), 8);
        assert_eq!(kernel_runs.get(), 8);
        // Interleaved: the slow render's three samples come in the first three rounds.
        let order: String = order.into_inner().into_iter().collect();
        assert_eq!(order, "fsfsfsfffff");
    }

    #[test]
    fn interleaved_measurement_stops_on_request() {
        let policy = TimingPolicy::new(2, 0.0);
        let stop = AtomicBool::new(true);
        let job: RenderJob<'_, Fake> = Box::new(|| Ok(Fake(ms(1), ms(0))));
        let r = measure_interleaved(&policy, &stop, vec![job], Vec::new(), &|_, _| {});
        assert!(matches!(r, Err(RunError::Stopped)));
    }

    #[test]
    fn the_timed_renders_are_told_in_order_up_to_all_of_them() {
        // A 1/64 s render needs 8 samples for 1/8 s, a 1/16 s one 3 (the minimum), one
        // that fails after its first sample drops out: 12 renders timed in all.
        use std::cell::{Cell, RefCell};
        let policy = TimingPolicy::new(3, 0.125);
        let stop = AtomicBool::new(false);
        let runs = Cell::new(0u64);
        let fast: RenderJob<'_, Fake> = Box::new(|| {
            runs.set(runs.get() + 1);
            Ok(Fake(Duration::from_micros(15_625), ms(0)))
        });
        let slow: RenderJob<'_, Fake> = Box::new(|| {
            runs.set(runs.get() + 1);
            Ok(Fake(Duration::from_micros(62_500), ms(0)))
        });
        let failing_runs = Cell::new(0);
        let failing: RenderJob<'_, Fake> = Box::new(|| {
            failing_runs.set(failing_runs.get() + 1);
            match failing_runs.get() {
                1 => {
                    runs.set(runs.get() + 1);
                    Ok(Fake(ms(1), ms(0)))
                }
                _ => Err(RunError::Input("broken".into())),
            }
        });
        let told = RefCell::new(Vec::new());
        measure_interleaved(
            &policy,
            &stop,
            vec![fast, slow, failing],
            Vec::new(),
            &|done, total| told.borrow_mut().push((done, total)),
        )
        .unwrap();
        let told = told.into_inner();
        // Nothing done at first, against three renders each (the policy's minimum).
        assert_eq!(told[0], (0, 9));
        // One call per render (the failing one's too), done never back nor past the plan.
        assert_eq!(told.len() as u64, 1 + runs.get() + 1, "{told:?}");
        for pair in told.windows(2) {
            assert!(pair[1].0 >= pair[0].0, "{told:?}");
        }
        assert!(told.iter().all(|&(done, total)| done <= total), "{told:?}");
        assert_eq!(told.last(), Some(&(12, 12)));
        assert_eq!(runs.get(), 12);
    }

    #[test]
    fn the_plan_follows_the_policy() {
        let policy = TimingPolicy::new(3, 0.125);
        assert_eq!(planned_renders(&policy, &[]), 3);
        // 1/64 s a sample: 8 for 1/8 s.
        assert_eq!(planned_renders(&policy, &[0.015_625]), 8);
        // 1 s a sample: the minimum.
        assert_eq!(planned_renders(&policy, &[1.0]), 3);
        // Done: what it has.
        assert_eq!(planned_renders(&policy, &[1.0, 1.0, 1.0]), 3);
        // A microsecond a sample: at most the policy's most.
        assert_eq!(planned_renders(&policy, &[1e-6; 5]), u64::from(MAX_REPEATS));
    }
}
