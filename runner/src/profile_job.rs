//! The profile job: a counted render gives the exact calls, a sampled render (repeated
//! until enough time is sampled) gives the stacks; from both come the gprof flat
//! profile and call graph, folded stacks and the Amdahl table. `rtprof profile` and
//! the suite's profile of its heaviest scene both run it.

use std::collections::{BTreeMap, BTreeSet};
use std::time::{Duration, Instant};

use analysis::profile::amdahl::{AmdahlRow, amdahl_table, amdahl_text};
use analysis::profile::folded::{differential_svg, flamegraph_svg, folded};
use analysis::profile::gprof::{CallGraph, FlatProfile, call_graph, flat_profile};
use analysis::profile::names::{BareMethods, display_name};
use analysis::profile::sampler::{process_cpu_time, sample};
use analysis::profile::{CallCounts, Stack, StackSamples};
use serde::Serialize;
use tracer::{Count, NoCount, RenderOptions, Scene, VariantSet, render_variant};

use crate::error::RunError;
use crate::progress::Progress;
use crate::staging::save;

/// Least sampled time per profile: a faster render is repeated until it is reached.
pub const MIN_SAMPLED: Duration = Duration::from_millis(300);
/// Most renders per profile, however fast.
pub const MAX_RENDERS: u64 = 10_000;

/// One variant's profile, as data.
#[derive(Serialize)]
pub struct VariantProfile {
    pub variant: String,
    /// Renders sampled (a fast render is repeated to gather samples); calls cover all.
    pub renders: u64,
    pub samples: u64,
    pub seconds_per_sample: f64,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
    pub flat: FlatProfile,
    pub call_graph: CallGraph,
    pub amdahl: Vec<AmdahlRow>,
    pub folded: String,
    #[serde(skip)]
    pub flat_text: String,
    #[serde(skip)]
    pub call_graph_text: String,
}

/// `rtprof profile`: the setting, the profile and the optional second variant's.
#[derive(Serialize)]
pub struct ProfileReport {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub threads: usize,
    pub frequency: i32,
    /// Wall time of the same render without the profiler (with --measure-overhead).
    pub unprofiled_seconds: Option<f64>,
    /// Profiled / unprofiled wall time.
    pub overhead: Option<f64>,
    pub profile: VariantProfile,
    pub diff: Option<VariantProfile>,
}

/// A scene to profile, how, and on which threads.
pub struct ProfileJob<'a> {
    pub scene: &'a Scene,
    pub options: RenderOptions,
    pub pool: &'a rayon::ThreadPool,
    /// Sampling rate asked of the kernel, Hz.
    pub frequency: i32,
    /// The scene's name in messages.
    pub name: &'a str,
    /// Least sampled time.
    pub min_sampled: Duration,
}

impl ProfileJob<'_> {
    fn fail(&self, e: &tracer::RenderError) -> RunError {
        RunError::render(self.name, e)
    }

    /// Counted render (calls), then the sampled render.
    pub fn profile(
        &self,
        set: &VariantSet,
        progress: &dyn Progress,
    ) -> Result<VariantProfile, RunError> {
        progress.message(&format!("counting {set}"));
        let counted = self
            .pool
            .install(|| render_variant::<Count>(self.scene, &self.options, set, &|_| {}))
            .map_err(|e| self.fail(&e))?;
        let counts = counted
            .rendered
            .counts()
            .ok_or_else(|| RunError::Profile("the counted render returned no counts".into()))?;
        progress.message(&format!("sampling {set}"));
        // A fast render (a BVH on a small image) can finish between two samples: render
        // again until the sampler has had `min_sampled` of CPU time, and scale the calls
        // to match. CPU, not wall, time: SIGPROF samples CPU time, and on a loaded
        // machine a wall-clock budget can pass with almost no CPU and no samples.
        let run = sample(
            self.frequency,
            |name| name.starts_with("tracer::"),
            || {
                let start = process_cpu_time();
                let mut renders = 0u64;
                loop {
                    renders += 1;
                    let out = self.pool.install(|| {
                        render_variant::<NoCount>(self.scene, &self.options, set, &|_| {})
                    });
                    let sampled = process_cpu_time().saturating_sub(start);
                    if out.is_err() || sampled >= self.min_sampled || renders >= MAX_RENDERS {
                        return out.map(|_| renders);
                    }
                }
            },
        )
        .map_err(|e| RunError::Profile(e.to_string()))?;
        let renders = run.output.map_err(|e| self.fail(&e))?;
        if renders > 1 {
            progress.note(&format!(
                "{set}: rendered {renders} times to gather samples (calls are for all {renders})"
            ));
        }
        let samples = shorten(&run.samples);
        let calls: CallCounts = counts
            .function_calls()
            .into_iter()
            .map(|(name, n)| (name.to_string(), n * renders))
            .collect();
        Ok(build_profile(
            set.to_string(),
            renders,
            &samples,
            &calls,
            run.cpu.as_secs_f64(),
            run.wall.as_secs_f64(),
        ))
    }

    /// `rtprof profile`: `set` profiled (and timed without the profiler first when
    /// `measure_overhead`), and `diff_with` profiled for the differential flamegraph.
    pub fn report(
        &self,
        set: &VariantSet,
        diff_with: Option<&VariantSet>,
        measure_overhead: bool,
        progress: &dyn Progress,
    ) -> Result<ProfileReport, RunError> {
        progress.begin("profile", 0);
        let unprofiled = if measure_overhead {
            progress.message(&format!("timing {set} without the profiler"));
            Some(self.unprofiled_seconds(set)?)
        } else {
            None
        };
        let profile = self.profile(set, progress)?;
        let diff = diff_with
            .map(|other| self.profile(other, progress))
            .transpose()?;
        progress.end();
        Ok(ProfileReport {
            scene: self.name.to_string(),
            width: self.options.width,
            height: self.options.height,
            threads: self.pool.current_num_threads(),
            frequency: self.frequency,
            unprofiled_seconds: unprofiled,
            overhead: unprofiled.map(|u| profile.wall_seconds / u.max(1e-9)),
            profile,
            diff,
        })
    }

    /// Wall seconds of one render without the profiler.
    pub fn unprofiled_seconds(&self, set: &VariantSet) -> Result<f64, RunError> {
        let start = Instant::now();
        self.pool
            .install(|| render_variant::<NoCount>(self.scene, &self.options, set, &|_| {}))
            .map_err(|e| self.fail(&e))?;
        Ok(start.elapsed().as_secs_f64())
    }
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

fn build_profile(
    variant: String,
    renders: u64,
    samples: &StackSamples,
    calls: &CallCounts,
    cpu_seconds: f64,
    wall_seconds: f64,
) -> VariantProfile {
    // Counts for functions this run never entered (another accelerator's queries) would
    // list them with zero time; keep the counts of the functions the samples saw.
    let seen: BTreeSet<&String> = samples
        .stacks
        .iter()
        .flat_map(|s| s.frames.iter())
        .collect();
    let calls: CallCounts = calls
        .iter()
        .filter(|(name, _)| seen.contains(name))
        .map(|(name, n)| (name.clone(), *n))
        .collect();
    let flat = flat_profile(samples, &calls);
    let graph = call_graph(samples, &calls);
    let self_times: Vec<(String, f64)> = flat
        .rows
        .iter()
        .map(|r| (r.name.clone(), r.self_seconds))
        .collect();
    VariantProfile {
        variant,
        renders,
        samples: samples.total(),
        seconds_per_sample: samples.seconds_per_sample,
        cpu_seconds,
        wall_seconds,
        flat_text: flat.to_text(),
        call_graph_text: graph.to_text(),
        amdahl: amdahl_table(&self_times, 10),
        folded: folded(samples),
        flat,
        call_graph: graph,
    }
}

impl ProfileReport {
    /// Writes flat.txt, callgraph.txt, folded.txt, flame.svg and amdahl.txt into `dir`,
    /// and with a second variant its folded and flat texts and flame-diff.svg.
    pub fn write_files(&self, dir: &std::path::Path) -> Result<(), RunError> {
        let p = &self.profile;
        let svg_error =
            |e: analysis::profile::folded::FlamegraphError| RunError::Profile(e.to_string());
        let title = format!(
            "{} ({}x{}, {})",
            self.scene, self.width, self.height, p.variant
        );
        save(dir, "flat.txt", p.flat_text.as_bytes())?;
        save(dir, "callgraph.txt", p.call_graph_text.as_bytes())?;
        save(dir, "folded.txt", p.folded.as_bytes())?;
        let svg = flamegraph_svg(&p.folded, &title).map_err(svg_error)?;
        save(dir, "flame.svg", svg.as_bytes())?;
        save(dir, "amdahl.txt", amdahl_text(&p.amdahl).as_bytes())?;
        if let Some(d) = &self.diff {
            save(
                dir,
                &format!("folded-{}.txt", d.variant),
                d.folded.as_bytes(),
            )?;
            save(
                dir,
                &format!("flat-{}.txt", d.variant),
                d.flat_text.as_bytes(),
            )?;
            let diff_title = format!(
                "{}: {} → {} (red grew, blue shrank)",
                self.scene, p.variant, d.variant
            );
            let svg = differential_svg(&p.folded, &d.folded, &diff_title).map_err(svg_error)?;
            save(dir, "flame-diff.svg", svg.as_bytes())?;
        }
        Ok(())
    }

    /// The summary the command prints; `dir` is where the files were written.
    pub fn to_text(&self, dir: &std::path::Path) -> String {
        let r = self;
        let mut out = String::new();
        let p = &r.profile;
        out += &format!(
            "{} {}x{}, variant {}, {} thread{}: {} samples, {:.3} s CPU, {:.3} s wall ({:.2} ms of CPU per sample)\n",
            r.scene,
            r.width,
            r.height,
            p.variant,
            r.threads,
            if r.threads == 1 { "" } else { "s" },
            p.samples,
            p.cpu_seconds,
            p.wall_seconds,
            p.seconds_per_sample * 1e3
        );
        if let (Some(u), Some(o)) = (r.unprofiled_seconds, r.overhead) {
            out += &format!("without the profiler: {u:.3} s wall; overhead {o:.3}x\n");
        }
        out.push('\n');
        for line in p.flat_text.lines().take(18) {
            out += line;
            out.push('\n');
        }
        out.push('\n');
        out += &amdahl_text(&p.amdahl);
        out += &format!(
            "\nwrote {}/{{flat.txt, callgraph.txt, folded.txt, flame.svg, amdahl.txt{}}}\n",
            dir.display(),
            if r.diff.is_some() {
                ", flame-diff.svg"
            } else {
                ""
            }
        );
        out
    }
}
