//! The profile job: a counted render gives the exact calls per render; sampled renders
//! (repeated until the sampler has its minimum number of samples) give two views of
//! the same SIGPROF signals:
//! - **phases**: the tracer's own record of what each thread was doing (camera ray,
//!   traversal, each primitive's test, shading, …), kept on a per-thread phase stack
//!   by the `Phased` counter and read at each signal. It does not depend on what the
//!   optimizer inlined, so it is the view the profile's tables and headlines use;
//! - **native**: the symbols of the binary's debug info at each signal, what the
//!   compiler made of the code.
//!
//! From each view come the gprof flat profile and call graph (calls per render, self
//! and inclusive shares with 95 % intervals), folded stacks under one root and the
//! Amdahl table. `rtprof profile` and the suite's profile of its heaviest scene both
//! run it ([`ProfileJob::report`]) and save it with one naming scheme
//! ([`crate::profile_files`]).

use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use analysis::Estimate;
use analysis::profile::amdahl::{AmdahlRow, amdahl_table};
use analysis::profile::flat::{FlatProfile, flat_profile};
use analysis::profile::folded::{folded, under_one_root};
use analysis::profile::gprof::{CallGraph, call_graph};
use analysis::profile::names::{BareMethods, display_name};
use analysis::profile::perf_clock::WorkThreads;
use analysis::profile::sampler::{RepeatedError, SampleOptions, effective_rate, sample_repeated};
use analysis::profile::tally::ProfileInput;
use analysis::profile::timer::Timer;
use analysis::profile::{CallCounts, Origin, Stack, StackSamples};
use results::ProfileView;
use serde::Serialize;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use tracer::{
    Count, Counts, NoCount, Phased, RenderOptions, Scene, VariantSet, render_variant_until,
};

use crate::error::RunError;
use crate::progress::{Progress, SAMPLES};

/// Samples a profile gathers at least, by default: enough for a 95 % interval of
/// about ±3 points on a 50 % share.
pub const DEFAULT_MIN_SAMPLES: u64 = 1000;
/// Most renders per profile, however fast.
pub const MAX_RENDERS: u64 = 10_000;
/// The phase-view frame of samples taken outside any phase (idle workers, set-up).
pub const OUTSIDE_PHASES: &str = "[outside the tracer's phases]";
/// The Amdahl row of all primitive tests together.
pub const ALL_TESTS: &str = "all primitive tests";
/// Rows of the Amdahl table.
const AMDAHL_ROWS: usize = 10;
/// Unprofiled renders timed for `--measure-overhead`, at least and at most.
const OVERHEAD_RENDERS: (usize, usize) = (5, 30);

/// One view of a profile: the same samples attributed to phases or to symbols.
#[derive(Serialize)]
pub struct ViewProfile {
    pub view: ProfileView,
    pub flat: FlatProfile,
    pub call_graph: CallGraph,
    pub amdahl: Vec<AmdahlRow>,
    /// Folded stacks, every stack under one root (the scene's name).
    pub folded: String,
    #[serde(skip)]
    pub stacks: StackSamples,
    #[serde(skip)]
    pub flat_text: String,
    #[serde(skip)]
    pub call_graph_text: String,
}

impl ViewProfile {
    /// One view's tables from its stacks (`root` names the folded stacks' root) and
    /// the calls per run of its functions (`runs`: renders, or 1 for one program run).
    pub fn new(
        view: ProfileView,
        stacks: StackSamples,
        calls: &CallCounts,
        runs: u64,
        root: &str,
    ) -> ViewProfile {
        Self::with_origin(view, stacks, calls, runs, root, Origin::Sampled)
    }

    /// One view of one run of another program (`rtprof record`, recorded here or
    /// imported): no call counts, and its texts say it is one run, not a render.
    pub fn of_run(view: ProfileView, stacks: StackSamples, root: &str) -> ViewProfile {
        Self::with_origin(view, stacks, &CallCounts::new(), 1, root, Origin::Recorded)
    }

    fn with_origin(
        view: ProfileView,
        stacks: StackSamples,
        calls: &CallCounts,
        runs: u64,
        root: &str,
        origin: Origin,
    ) -> ViewProfile {
        // Counts for functions this run never entered (another accelerator's queries)
        // would list them with zero time; keep the counts of those the samples saw.
        let seen: BTreeSet<&String> = stacks.stacks.iter().flat_map(|s| &s.frames).collect();
        let calls: CallCounts = calls
            .iter()
            .filter(|(name, _)| seen.contains(name))
            .map(|(name, n)| (name.clone(), *n))
            .collect();
        let input = ProfileInput {
            samples: &stacks,
            calls: &calls,
            renders: runs,
        };
        let mut flat = flat_profile(&input);
        let mut graph = call_graph(&input);
        // The figures are the same; the origin says what the texts call the run.
        flat.origin = origin;
        graph.origin = origin;
        let amdahl = amdahl_table(&flat, AMDAHL_ROWS);
        ViewProfile {
            view,
            amdahl,
            folded: folded(&under_one_root(&stacks, root)),
            flat_text: flat.to_text(),
            call_graph_text: graph.to_text(),
            flat,
            call_graph: graph,
            stacks,
        }
    }
}

/// One variant's profile, as data.
#[derive(Serialize)]
pub struct VariantProfile {
    pub variant: String,
    /// Renders sampled (a fast render is repeated to gather samples); calls are per
    /// render, seconds cover them all.
    pub renders: u64,
    /// SIGPROF signals taken, and the number the asked rate would have given in the
    /// sampled CPU time (setitimer delivers fewer at high rates).
    pub samples: u64,
    pub samples_asked: u64,
    /// The timer that sent the signals, and the rate asked of it (Hz of CPU time).
    pub timer: Timer,
    pub frequency: i32,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
    /// Wall seconds of each sampled render (phases recorded, sampler running).
    pub render_seconds: Vec<f64>,
    /// Exact counts of one render.
    #[serde(skip)]
    pub counts: Counts,
    pub phases: ViewProfile,
    pub native: ViewProfile,
}

impl VariantProfile {
    /// CPU seconds one sample stands for.
    pub fn seconds_per_sample(&self) -> f64 {
        self.cpu_seconds / self.samples.max(1) as f64
    }

    /// Samples per CPU second actually taken.
    pub fn effective_rate(&self) -> f64 {
        effective_rate(self.samples, self.cpu_seconds)
    }

    /// "sampled with perf cpu-clock: 3,987 samples per CPU second (asked 4,000 Hz)".
    pub fn timer_text(&self) -> String {
        format!(
            "sampled with {}: {} samples per CPU second (asked {} Hz)",
            self.timer,
            reports::format::count(self.effective_rate().round() as u64),
            reports::format::count(u64::try_from(self.frequency).unwrap_or(0)),
        )
    }
}

/// The profiler's cost: profiled against unprofiled render time, both repeated.
#[derive(Serialize)]
pub struct Overhead {
    /// Median wall seconds of one profiled render, with its 95 % interval.
    pub profiled: Estimate,
    pub unprofiled: Estimate,
    /// profiled / unprofiled (ratio of medians), with its bootstrap 95 % interval.
    pub ratio: Estimate,
    pub profiled_renders: usize,
    pub unprofiled_renders: usize,
}

impl Overhead {
    /// "profiled render took 1.04x the unprofiled one (95 % interval 1.01x-1.07x; …)".
    pub fn to_text(&self) -> String {
        format!(
            "profiled render took {:.2}x the unprofiled one (95 % interval {:.2}x-{:.2}x; medians {:.4} s and {:.4} s over {} and {} renders)\n",
            self.ratio.median,
            self.ratio.low,
            self.ratio.high,
            self.profiled.median,
            self.unprofiled.median,
            self.profiled_renders,
            self.unprofiled_renders
        )
    }
}

/// `rtprof profile`: the setting, the profile and the optional second variant's.
#[derive(Serialize)]
pub struct ProfileReport {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub threads: usize,
    /// The rate asked of the profile's timer, Hz (the variant profiles say which timer).
    pub frequency: i32,
    pub min_samples: u64,
    /// With --measure-overhead.
    pub overhead: Option<Overhead>,
    pub profile: VariantProfile,
    pub diff: Option<VariantProfile>,
}

/// A scene to profile, how, and on which threads.
pub struct ProfileJob<'a> {
    pub scene: &'a Scene,
    pub options: RenderOptions,
    pub pool: &'a rayon::ThreadPool,
    /// Sampling rate asked of the timer, Hz of CPU time; `None`: the timer's default
    /// (4,000 for perf cpu-clock, 1,000 for setitimer).
    pub frequency: Option<i32>,
    /// The scene's name in messages and the root of the folded stacks.
    pub name: &'a str,
    /// Samples to gather at least (renders are repeated until there are).
    pub min_samples: u64,
    /// Set to stop: the render under way ends within a row ([`RunError::Stopped`]).
    pub stop: &'a AtomicBool,
}

impl ProfileJob<'_> {
    fn fail(&self, e: &tracer::RenderError) -> RunError {
        RunError::render(self.name, e)
    }

    /// `set` profiled (with its overhead measured when `measure_overhead`), and
    /// `diff_with` profiled for the differential flamegraphs.
    pub fn report(
        &self,
        set: &VariantSet,
        diff_with: Option<&VariantSet>,
        measure_overhead: bool,
        progress: &dyn Progress,
    ) -> Result<ProfileReport, RunError> {
        progress.begin("profile", 0);
        let profile = self.profile(set, progress)?;
        let overhead = if measure_overhead {
            progress.message(&format!("timing {set} without the profiler"));
            Some(self.overhead(set, &profile.render_seconds)?)
        } else {
            None
        };
        let diff = diff_with
            .map(|other| self.profile(other, progress))
            .transpose()?;
        progress.end();
        Ok(ProfileReport {
            scene: self.name.to_string(),
            width: self.options.width,
            height: self.options.height,
            threads: self.pool.current_num_threads(),
            frequency: profile.frequency,
            min_samples: self.min_samples,
            overhead,
            profile,
            diff,
        })
    }

    /// Counted render (calls per render), then sampled renders with phases recorded.
    pub fn profile(
        &self,
        set: &VariantSet,
        progress: &dyn Progress,
    ) -> Result<VariantProfile, RunError> {
        progress.message(&format!("counting {set}"));
        let counted = self
            .pool
            .install(|| {
                render_variant_until::<Count>(self.scene, &self.options, set, &|_| {}, self.stop)
            })
            .map_err(|e| self.fail(&e))?;
        let counts = counted
            .rendered
            .counts()
            .ok_or_else(|| RunError::Profile("the counted render returned no counts".into()))?;
        progress.message(&format!("sampling {set}"));
        // The render runs on the pool's threads: under perf each gets its own timer.
        let open_on_workers = |open: &(dyn Fn() + Sync)| {
            self.pool.broadcast(|_| open());
        };
        let options = SampleOptions {
            frequency: self.frequency,
            threads: Some(WorkThreads(&open_on_workers)),
            min_samples: self.min_samples,
            max_runs: MAX_RENDERS,
            probe: Some(tracer::phase_stack_key),
            ..SampleOptions::timer_default()
        };
        let render_seconds = RefCell::new(Vec::new());
        // The samples gathered of those asked, told as each row ends when the
        // hundredth they make up grows (at most a hundred calls, none per sample).
        let wanted = self.min_samples;
        let told = AtomicU64::new(0);
        let tell = |gathered: u64| {
            let shown = gathered.min(wanted);
            let hundredths = shown * 100 / wanted.max(1);
            if wanted > 0 && told.fetch_max(hundredths + 1, Ordering::Relaxed) < hundredths + 1 {
                progress.within(SAMPLES, shown, wanted);
            }
        };
        tell(0);
        let run = sample_repeated(
            &options,
            |name| name.starts_with("tracer::"),
            |live| {
                let start = Instant::now();
                let out = self.pool.install(|| {
                    render_variant_until::<Phased>(
                        self.scene,
                        &self.options,
                        set,
                        &|_| tell(live.signals()),
                        self.stop,
                    )
                });
                render_seconds
                    .borrow_mut()
                    .push(start.elapsed().as_secs_f64());
                out.map(|_| ())
            },
        )
        .map_err(|e| match e {
            RepeatedError::Profile(e) => RunError::Profile(e.to_string()),
            RepeatedError::Work { error, .. } => self.fail(&error),
        })?;
        // Done: all that was asked, or what the caps on runs and time let it gather.
        if wanted > 0 {
            let gathered = run.signals.min(wanted);
            progress.within(SAMPLES, gathered, gathered);
        }
        let renders = run.output.runs;
        if renders > 1 {
            progress.note(&format!(
                "{set}: rendered {renders} times to gather {} samples (calls are per render)",
                run.signals
            ));
        }
        let cpu = run.cpu.as_secs_f64();
        let phase_stacks = phase_samples(&run.phase_keys, cpu);
        let native_stacks = shorten(&run.samples);
        let phases = self.view(
            ProfileView::Phases,
            phase_stacks,
            &phase_calls(&counts),
            renders,
        );
        let native = self.view(
            ProfileView::Native,
            native_stacks,
            &native_calls(&counts),
            renders,
        );
        Ok(VariantProfile {
            variant: set.to_string(),
            renders,
            samples: run.signals,
            samples_asked: run.samples_asked,
            timer: run.timer,
            frequency: run.frequency,
            cpu_seconds: cpu,
            wall_seconds: run.wall.as_secs_f64(),
            render_seconds: render_seconds.into_inner(),
            counts,
            phases,
            native,
        })
    }

    /// One view's tables from its stacks and the calls per render of its functions.
    fn view(
        &self,
        view: ProfileView,
        stacks: StackSamples,
        calls: &CallCounts,
        renders: u64,
    ) -> ViewProfile {
        let mut v = ViewProfile::new(view, stacks, calls, renders, self.name);
        if view == ProfileView::Phases {
            add_all_tests_row(&v.flat, &mut v.amdahl);
        }
        v
    }

    /// Times unprofiled renders and sets them against the profiled ones.
    fn overhead(&self, set: &VariantSet, profiled: &[f64]) -> Result<Overhead, RunError> {
        let n = profiled.len().clamp(OVERHEAD_RENDERS.0, OVERHEAD_RENDERS.1);
        let mut unprofiled = Vec::with_capacity(n);
        for _ in 0..n {
            let start = Instant::now();
            self.pool
                .install(|| {
                    render_variant_until::<NoCount>(
                        self.scene,
                        &self.options,
                        set,
                        &|_| {},
                        self.stop,
                    )
                })
                .map_err(|e| self.fail(&e))?;
            unprofiled.push(start.elapsed().as_secs_f64());
        }
        let policy = crate::timing::TimingPolicy::new(1, 0.0);
        let ratio = analysis::timing::ratio_of_medians_with_bootstrap(
            profiled,
            &unprofiled,
            policy.resamples,
            policy.confidence,
            policy.seed,
        )?;
        Ok(Overhead {
            profiled: policy.estimate(profiled)?,
            unprofiled: policy.estimate(&unprofiled)?,
            ratio,
            profiled_renders: profiled.len(),
            unprofiled_renders: n,
        })
    }
}

/// The Amdahl row of every primitive test together ("the intersection tests"), when
/// more than one kind was sampled and they are not the whole run: tests are leaves, one per sample at most, so their
/// self shares add up and the group's inclusive share is the same sum.
fn add_all_tests_row(flat: &FlatProfile, amdahl: &mut Vec<AmdahlRow>) {
    let tests: Vec<_> = flat
        .rows
        .iter()
        .filter(|r| tracer::Phase::from_name(&r.name).is_some_and(|p| p.is_primitive_test()))
        .collect();
    if tests.len() < 2 || flat.samples == 0 {
        return;
    }
    let share = tests.iter().map(|r| r.self_samples).sum::<u64>() as f64 / flat.samples as f64;
    // Like a whole-run frame, a group on (nearly) every sample tells nothing.
    if share * 100.0 >= analysis::profile::flat::WHOLE_RUN_PERCENT {
        return;
    }
    let row = AmdahlRow::new(ALL_TESTS, share, share);
    let at = amdahl
        .iter()
        .position(|r| r.inclusive_fraction < share)
        .unwrap_or(amdahl.len());
    amdahl.insert(at, row);
}

/// The phase view's stacks: each recorded phase-stack key as its phase names.
fn phase_samples(keys: &BTreeMap<u64, u64>, cpu_seconds: f64) -> StackSamples {
    let total: u64 = keys.values().sum();
    let stacks = keys
        .iter()
        .filter(|&(_, &count)| count > 0)
        .map(|(&key, &count)| {
            let names = tracer::phase_names(key);
            let frames = if names.is_empty() {
                vec![OUTSIDE_PHASES.to_string()]
            } else {
                names.into_iter().map(str::to_string).collect()
            };
            Stack { frames, count }
        })
        .collect();
    StackSamples {
        stacks,
        seconds_per_sample: cpu_seconds / total.max(1) as f64,
    }
}

/// Calls per render of each phase, from the counters.
fn phase_calls(counts: &Counts) -> CallCounts {
    tracer::phase_calls(counts)
        .into_iter()
        .map(|(phase, n)| (phase.name().to_string(), n))
        .collect()
}

/// Calls per render of the profiled native functions, from the counters.
fn native_calls(counts: &Counts) -> CallCounts {
    counts
        .function_calls()
        .into_iter()
        .map(|(name, n)| (name.to_string(), n))
        .collect()
}

/// Stacks with the reports' short names; stacks that become equal merge.
fn shorten(samples: &StackSamples) -> StackSamples {
    let operations = tracer::counter::counted_operations();
    let bare = BareMethods {
        owners: &tracer::counter::COUNTING_LAYER,
        methods: &operations,
    };
    let mut merged: BTreeMap<Vec<String>, u64> = BTreeMap::new();
    for stack in &samples.stacks {
        let mut frames: Vec<String> = stack
            .frames
            .iter()
            .map(|f| display_name(f, &bare))
            .collect();
        frames.dedup();
        *merged.entry(frames).or_default() += stack.count;
    }
    StackSamples {
        stacks: merged
            .into_iter()
            .map(|(frames, count)| Stack { frames, count })
            .collect(),
        seconds_per_sample: samples.seconds_per_sample,
    }
}
