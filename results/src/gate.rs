//! The regression gate: a run against an earlier one (`rtprof gate OLD NEW`, `rtprof
//! suite --baseline OLD`).
//!
//! It gates what is stable between two runs on a shared machine:
//! - **exact counts**: counts do not depend on the machine or its load, so any change of
//!   any counter is a changed program and fails the gate;
//! - **instruction counts** (gungraun, when both files have them): deterministic up to
//!   the build; an increase beyond [`INSTRUCTION_THRESHOLD`] fails;
//! - **time relative to a render timed in the same rounds**, not absolute time: each
//!   variant's time divided by a reference that does the same kind of work on the same
//!   scene ([`references`]: baseline; bvh on a scene run without baseline; for the
//!   scene's root variant itself, the f64 reference renderer on the same scene at a
//!   smaller frame), each a median of per-round ratios, or with too few shared
//!   rounds a ratio of medians ([`crate::change::Ratio`]). A machine that is busier or
//!   slower on the second run moves both alike. The change of a relative time
//!   between the runs, with its bootstrap interval, is labelled by the one verdict
//!   rule ([`analysis::verdict::judge`]) at a noise threshold calibrated from
//!   run-to-run noise ([`analysis::verdict::NOISE_THRESHOLD`], docs/gate.md),
//!   widened for an entry whose own intervals are wider ([`entry_threshold`]). Slower
//!   fails.
//!
//! Times are process CPU times of each render when both runs recorded them (they do
//! not grow while the machine runs other work), wall times otherwise.
//!
//! Runs that cannot be compared (another suite, frame sizes, thread count or machine)
//! are refused with every reason, and so are runs with no scene × variant in common,
//! `--force` or not ([`GateError`]); runs that are too short to gate well (`--quick`)
//! and entries gated on seconds (files without a yardstick) come with a warning.
//!
//! **Strict** gates ([`GateOptions::strict`]) hold a run against a baseline kept in a
//! repository (`benches/baseline.json`, docs/benchmarks.md), measured on another day and
//! maybe on another machine of the same kind: a change of an instruction count beyond
//! [`INSTRUCTION_THRESHOLD`] either way fails (an improvement not written into the
//! baseline would hide the next regression up to it), and so does any scene × variant or
//! benchmark that only one side has (a baseline that no longer covers the run gates
//! less than it says); another machine is allowed, with a warning.

use serde::Serialize;

use analysis::verdict::judge;

use crate::change::{Ratio, of_medians};
use crate::schema::{Estimate, InstructionCount, Results, SceneResult, VariantResult, Verdict};
use crate::timing_policy::TimeCovers;
use crate::variant_name::VariantName;

/// An instruction count that grows by more than this fraction fails the gate (in a
/// strict gate, one that changes by more either way): valgrind's counts repeat exactly
/// for one build; 1 % leaves room for a rebuilt toolchain's noise.
pub const INSTRUCTION_THRESHOLD: f64 = 0.01;

/// The noise threshold of a strict gate's times (a fraction), when none is given: a
/// baseline in the repository was timed on another day, maybe on another machine of the
/// same kind, with `--quick` renders of a few milliseconds, so its relative times are
/// known far less well than two runs' of one afternoon. Measured: docs/benchmarks.md
/// ("The performance baseline"). The instruction counts are the fine-grained check.
pub const STRICT_THRESHOLD: f64 = 0.5;

/// Renders shorter than this (an entry's own median time in either run, on the gated
/// clock) are timed too coarsely for the default threshold: at a millisecond or so,
/// the pool's wake-up, the process clock's reading and the caches' state are a large
/// share of the time, and they change from run to run, not within one (their
/// intervals are narrow). Back-to-back default suites gave such renders changes of up
/// to 31 % with nothing changed, renders of 5 to 20 ms at most 15 % (docs/gate.md).
/// The references' length does not count: the calibration kernel and the yardstick
/// are a few milliseconds of fixed work, and entries gated on them did not move so.
pub const SHORT_SECONDS: f64 = 0.005;

/// The least threshold of an entry with a render shorter than [`SHORT_SECONDS`]: a
/// change of half again is still caught there, run-to-run noise is not.
pub const SHORT_THRESHOLD: f64 = 0.5;

/// What an entry's times are measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Measure {
    /// The variant's time divided by baseline's, same scene, same rounds.
    RelativeToReference,
    /// The variant's time divided by bvh's, same scene, same rounds (a scene run
    /// without baseline, such as the SPD's full frames).
    RelativeToBvh,
    /// The scene's root variant (baseline, or bvh without baseline) divided by the f64
    /// reference renderer's time on the same scene at a smaller frame, same rounds.
    RelativeToYardstick,
    /// The root variant divided by the calibration kernel's time, same rounds (files
    /// from before the yardstick).
    RelativeToCalibration,
    /// Seconds (a file without the reference or the calibration kernel): a busier
    /// machine reads as slower.
    Seconds,
}

impl Measure {
    /// How the measure is written in a table header or cell.
    pub fn describe(self) -> &'static str {
        match self {
            Measure::RelativeToReference => "÷ baseline",
            Measure::RelativeToBvh => "÷ bvh",
            Measure::RelativeToYardstick => "÷ f64 reference",
            Measure::RelativeToCalibration => "÷ calibration",
            Measure::Seconds => "seconds",
        }
    }
}

/// Which clock an entry's samples come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Clock {
    /// Process CPU time of each render: it does not grow while the machine runs other
    /// work (what the gate uses when both runs recorded it).
    Cpu,
    /// Wall time (files from before CPU times were recorded).
    Wall,
}

/// A counter whose value differs between the runs; a missing counter reads 0.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct CountChange {
    pub counter: String,
    pub old: u64,
    pub new: u64,
}

/// One compared scene × variant.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Entry {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub variant: VariantName,
    pub measure: Measure,
    pub clock: Clock,
    /// The measured quantity (a relative time, or seconds) in each run: median and
    /// 95 % interval.
    pub old: Estimate,
    pub new: Estimate,
    /// Median seconds of the variant in each run, for the reader.
    pub old_seconds: f64,
    pub new_seconds: f64,
    /// new / old of the measure, with its 95 % bootstrap interval (1.25: 25 % slower).
    pub change: Estimate,
    /// The noise threshold of this entry's verdict (a fraction): the gate's, or wider
    /// where the entry's own intervals are ([`entry_threshold`]) or its renders short
    /// ([`SHORT_THRESHOLD`]).
    pub threshold: f64,
    /// The shorter median time (seconds) of the entry's render in the two runs, on the
    /// gated clock: under [`SHORT_SECONDS`] the entry is short.
    pub shortest_seconds: f64,
    pub verdict: Verdict,
    pub count_changes: Vec<CountChange>,
}

impl Entry {
    /// Whether a render it compares is shorter than [`SHORT_SECONDS`].
    pub fn short(&self) -> bool {
        self.shortest_seconds < SHORT_SECONDS
    }

    /// Slower, or a count changed.
    pub fn failed(&self) -> bool {
        self.verdict == Verdict::Slower || !self.count_changes.is_empty()
    }
}

/// One benchmark's instruction count in both runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InstructionEntry {
    pub id: String,
    pub old: u64,
    pub new: u64,
    /// new / old − 1.
    pub change: f64,
    /// Grew beyond [`INSTRUCTION_THRESHOLD`].
    pub regressed: bool,
    /// Shrank beyond [`INSTRUCTION_THRESHOLD`] (fails a strict gate only).
    pub improved: bool,
}

/// The whole comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GateReport {
    /// The noise threshold of the time verdicts (a fraction).
    pub threshold: f64,
    pub instruction_threshold: f64,
    pub entries: Vec<Entry>,
    pub instructions: Vec<InstructionEntry>,
    /// `scene/variant` present in only one of the runs.
    pub unmatched: Vec<String>,
    /// Entries that failed in either run (`scene/variant failed in the new run: why`):
    /// nothing to compare.
    pub failed_entries: Vec<String>,
    /// How many of them failed in the new run and not in the old one: each fails the
    /// gate (an outside tracer that stopped working is a regression, not a missing
    /// entry); one that failed in both runs did not get worse.
    pub newly_failed: usize,
    /// Benchmark ids with an instruction count in only one of the runs (`id (old)` or
    /// `id (new)`), when both runs have instruction counts.
    pub instructions_unmatched: Vec<String>,
    /// A strict gate ([`GateOptions::strict`]).
    pub strict: bool,
    /// What the reader should know about the verdicts (short runs, old files).
    pub warnings: Vec<String>,
    /// Set when the runs' times cover different things (a `/1` file timed
    /// preprocessing and tracing together).
    pub covers_differ: Option<(TimeCovers, TimeCovers)>,
    /// Reasons the runs are not comparable, when gated anyway (`--force`).
    pub forced_over: Vec<String>,
}

impl GateReport {
    /// True when some entry failed in the new run only, is slower, changed a count, or
    /// an instruction count grew; in
    /// a strict gate also when an instruction count shrank beyond the threshold or an
    /// entry or benchmark is in only one run.
    pub fn failed(&self) -> bool {
        self.newly_failed > 0
            || self.entries.iter().any(Entry::failed)
            || self.instructions.iter().any(|i| self.instruction_failed(i))
            || (self.strict
                && !(self.unmatched.is_empty() && self.instructions_unmatched.is_empty()))
    }

    /// Whether one instruction count fails this gate.
    pub fn instruction_failed(&self, i: &InstructionEntry) -> bool {
        i.regressed || (self.strict && i.improved)
    }

    /// How many entries got each verdict, and how many changed counts.
    pub fn tally(&self) -> Tally {
        let mut t = Tally::default();
        for e in &self.entries {
            match e.verdict {
                Verdict::Faster => t.faster += 1,
                Verdict::Slower => t.slower += 1,
                Verdict::WithinNoise => t.within_noise += 1,
            }
            t.count_changes += usize::from(!e.count_changes.is_empty());
        }
        t.instructions_regressed = self.instructions.iter().filter(|i| i.regressed).count();
        t.instructions_improved = self.instructions.iter().filter(|i| i.improved).count();
        t
    }

    /// The largest change of any entry's median in either direction, as a fraction
    /// (0.08: some entry moved 8 %), and the entry: the run-to-run noise seen.
    pub fn largest_change(&self) -> Option<(&Entry, f64)> {
        self.entries
            .iter()
            .map(|e| (e, (e.change.median.ln()).abs().exp() - 1.0))
            .filter(|(_, c)| c.is_finite())
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// Verdict counts of a gate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Tally {
    pub faster: usize,
    pub slower: usize,
    pub within_noise: usize,
    pub count_changes: usize,
    pub instructions_regressed: usize,
    pub instructions_improved: usize,
}

/// How to gate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GateOptions {
    /// Noise threshold, a fraction.
    pub threshold: f64,
    /// Gate runs that are not comparable anyway (the reasons are kept in the report).
    pub force: bool,
    /// Against a baseline kept in a repository: instruction counts gated both ways,
    /// every entry and benchmark required on both sides, another machine allowed (see
    /// the module documentation).
    pub strict: bool,
}

impl Default for GateOptions {
    fn default() -> Self {
        GateOptions {
            threshold: analysis::verdict::NOISE_THRESHOLD,
            force: false,
            strict: false,
        }
    }
}

/// Runs that cannot be gated.
#[derive(Debug, thiserror::Error)]
pub enum GateError {
    #[error("the runs are not comparable: {}; gate runs of the same suite on the same machine (--force gates them anyway)", .0.join("; "))]
    NotComparable(Vec<String>),
    /// No scene × variant at the same frame size is in both runs: a gate of nothing
    /// would pass whatever the runs hold. (Instruction counts do not count: they are the
    /// build's micro-benchmarks, which any two runs share, not the runs' scenes.)
    #[error(
        "the runs have nothing in common: no scene × variant at the same frame size is in both (old: {old}; new: {new}); gate two runs of the same scenes"
    )]
    NothingInCommon { old: String, new: String },
}

/// Why two runs cannot be compared: every difference that makes their relative times
/// or counts mean different things.
pub fn incomparable(old: &Results, new: &Results) -> Vec<String> {
    let mut reasons = suite_differences(old, new);
    if let Some(machine) = machine_difference(old, new) {
        reasons.push(machine);
    }
    reasons
}

/// Another machine (CPU model or logical CPUs), as a reason.
fn machine_difference(old: &Results, new: &Results) -> Option<String> {
    let (m, n) = (&old.machine, &new.machine);
    (m.cpu_model != n.cpu_model || m.cores != n.cores).then(|| {
        format!(
            "machine '{}' ({} CPUs) against '{}' ({} CPUs)",
            m.cpu_model, m.cores, n.cpu_model, n.cores
        )
    })
}

/// The differences of suite, thread count and frame sizes, as reasons.
fn suite_differences(old: &Results, new: &Results) -> Vec<String> {
    let mut reasons = Vec::new();
    let (a, b) = (&old.suite, &new.suite);
    if a.name != b.name {
        reasons.push(format!("suite '{}' against '{}'", a.name, b.name));
    }
    if a.quick != b.quick {
        reasons.push("a --quick run against a full one".to_string());
    }
    if a.threads != b.threads {
        reasons.push(format!("{} threads against {}", a.threads, b.threads));
    }
    let mut sizes = Vec::new();
    for s in &new.scenes {
        if let Some(o) = old.scenes.iter().find(|o| o.name == s.name)
            && !old
                .scenes
                .iter()
                .any(|o| o.name == s.name && o.width == s.width && o.height == s.height)
        {
            sizes.push(format!(
                "{} at {}x{} against {}x{}",
                s.name, o.width, o.height, s.width, s.height
            ));
        }
    }
    if !sizes.is_empty() {
        reasons.push(format!("frame sizes differ ({})", sizes.join(", ")));
    }
    reasons
}

/// Compares `new` against `old`.
pub fn gate(old: &Results, new: &Results, options: GateOptions) -> Result<GateReport, GateError> {
    // A strict gate's baseline was measured on another day, maybe on another machine of
    // the same kind: that is its purpose, so it is a warning, not a refusal.
    let across_machines = machine_difference(old, new).filter(|_| options.strict);
    let reasons = match across_machines {
        Some(_) => suite_differences(old, new),
        None => incomparable(old, new),
    };
    if !reasons.is_empty() && !options.force {
        return Err(GateError::NotComparable(reasons));
    }
    let threshold = options.threshold.max(0.0);
    let mut entries = Vec::new();
    let mut unmatched = Vec::new();
    let mut uncalibrated = 0usize;
    for scene in &new.scenes {
        let old_scene = old
            .scenes
            .iter()
            .find(|s| s.name == scene.name && s.width == scene.width && s.height == scene.height);
        for v in &scene.variants {
            let old_v = old_scene.and_then(|s| Some((s, find(s, &v.variant)?)));
            match old_v {
                Some((old_scene, o)) => {
                    let entry = compare_entry((old_scene, o), (scene, v), threshold);
                    uncalibrated += usize::from(entry.measure == Measure::Seconds);
                    entries.push(entry);
                }
                None => unmatched.push(format!("{}/{} (new)", scene.name, v.variant)),
            }
        }
    }
    for scene in &old.scenes {
        for v in &scene.variants {
            let present = new.scenes.iter().any(|s| {
                s.name == scene.name
                    && s.width == scene.width
                    && s.height == scene.height
                    && find(s, &v.variant).is_some()
            });
            if !present {
                unmatched.push(format!("{}/{} (old)", scene.name, v.variant));
            }
        }
    }
    let mut warnings = Vec::new();
    if old.suite.quick || new.suite.quick {
        warnings.push(
            "--quick runs time renders of a few milliseconds with few repeats: their relative times move more between runs than a full suite's; gate full runs where it matters"
                .to_string(),
        );
    }
    if uncalibrated > 0 {
        warnings.push(format!(
            "{uncalibrated} entr{} gated on seconds (a file without a reference timed in the same rounds): a busier machine reads as slower",
            if uncalibrated == 1 { "y" } else { "ies" }
        ));
    }
    if let Some(machine) = across_machines {
        warnings.push(format!(
            "a strict gate across machines ({machine}): relative times move more between machines than between runs on one; the instruction counts do not"
        ));
    }
    let failed_in = |r: &Results| -> Vec<(String, VariantName, String)> {
        r.failures
            .iter()
            .filter_map(|f| match (&f.scene, &f.part) {
                (Some(scene), crate::FailedPart::Variant(v)) => {
                    Some((scene.clone(), v.clone(), f.message.clone()))
                }
                _ => None,
            })
            .collect()
    };
    let (old_failed, new_failed) = (failed_in(old), failed_in(new));
    let mut failed_entries = Vec::new();
    let mut newly_failed = 0;
    for (run, list) in [("old", &old_failed), ("new", &new_failed)] {
        for (scene, v, message) in list {
            failed_entries.push(format!("{scene}/{v} failed in the {run} run: {message}"));
            unmatched.retain(|u| !u.starts_with(&format!("{scene}/{v} (")));
            let before = old_failed.iter().any(|(s, o, _)| s == scene && o == v);
            newly_failed += usize::from(run == "new" && !before);
        }
    }
    let instructions = instruction_entries(&old.instructions, &new.instructions);
    let instructions_unmatched =
        unmatched_ids(&old.instructions, &new.instructions, options.strict);
    if entries.is_empty() {
        return Err(GateError::NothingInCommon {
            old: scene_list(old),
            new: scene_list(new),
        });
    }
    let (old_covers, new_covers) = (old.suite.timing.covers, new.suite.timing.covers);
    Ok(GateReport {
        threshold,
        instruction_threshold: INSTRUCTION_THRESHOLD,
        entries,
        instructions,
        unmatched,
        failed_entries,
        newly_failed,
        instructions_unmatched,
        strict: options.strict,
        warnings,
        covers_differ: (old_covers != new_covers).then_some((old_covers, new_covers)),
        forced_over: reasons,
    })
}

fn find<'a>(scene: &'a SceneResult, variant: &VariantName) -> Option<&'a VariantResult> {
    scene.variants.iter().find(|v| &v.variant == variant)
}

/// The scenes of a run as a gate error lists them (`balls3 640x480, ...`; the first
/// few).
fn scene_list(r: &Results) -> String {
    const SHOWN: usize = 4;
    if r.scenes.is_empty() {
        return "no scenes".to_string();
    }
    let mut names: Vec<String> = r
        .scenes
        .iter()
        .take(SHOWN)
        .map(|s| format!("{} {}x{}", s.name, s.width, s.height))
        .collect();
    if r.scenes.len() > SHOWN {
        names.push(format!("{} more", r.scenes.len() - SHOWN));
    }
    names.join(", ")
}

/// A reference's wall and CPU samples, one per round, and the measure it makes.
type Reference<'a> = (&'a [f64], &'a [f64], Measure);

/// What a variant's time can be measured against in its run, best first: each a render
/// timed in the same rounds on the same scene.
///
/// - a variant other than baseline: **baseline**; on a scene run without baseline (the
///   SPD's full frames), **bvh**: the same scene, the same kind of work, so load moves
///   both alike;
/// - the scene's root variant (baseline, or bvh without baseline; any variant when
///   neither ran): the **yardstick**, the f64 reference renderer on the same scene at a
///   smaller frame. It does the same kind of work (the same scene's rays, shading and a
///   hierarchy walk) with none of the tracer's code, so a slower tracer is not divided
///   away; the **calibration kernel** in files from before it.
///
/// The later entries are fallbacks for runs that lack the earlier ones: the gate takes
/// the first measure both runs have.
pub fn references<'a>(scene: &'a SceneResult, v: &VariantResult) -> Vec<Reference<'a>> {
    let mut out = Vec::new();
    let baseline = scene.variants.iter().find(|r| r.variant.is_reference());
    let bvh = scene.variants.iter().find(|r| r.variant.as_str() == "bvh");
    match (baseline, bvh) {
        (Some(r), _) if !v.variant.is_reference() => {
            out.push((
                &r.samples[..],
                &r.cpu_samples[..],
                Measure::RelativeToReference,
            ));
        }
        (None, Some(r)) if v.variant != r.variant => {
            out.push((&r.samples[..], &r.cpu_samples[..], Measure::RelativeToBvh));
        }
        _ => {}
    }
    if let Some(y) = &scene.yardstick {
        out.push((
            &y.samples[..],
            &y.cpu_samples[..],
            Measure::RelativeToYardstick,
        ));
    }
    if let Some(c) = &scene.calibration {
        out.push((
            &c.samples[..],
            &c.cpu_samples[..],
            Measure::RelativeToCalibration,
        ));
    }
    out
}

/// The noise threshold of one entry: the gate's `threshold`, or, where the entry's own
/// measure is known less well, the sum of the relative half-widths of its 95 % intervals
/// in the two runs (a half-width `sqrt(high / low) - 1`, symmetric in log scale as the
/// verdicts are). Two medians each known to ±w can lie w_old + w_new apart with nothing
/// changed, so a change within that is not called slower (docs/gate.md).
pub fn entry_threshold(threshold: f64, old: &Estimate, new: &Estimate) -> f64 {
    let half_width = |e: &Estimate| {
        let w = (e.high / e.low).sqrt() - 1.0;
        if w.is_finite() && w > 0.0 { w } else { 0.0 }
    };
    threshold.max(half_width(old) + half_width(new))
}

fn compare_entry(
    (old_scene, o): (&SceneResult, &VariantResult),
    (new_scene, v): (&SceneResult, &VariantResult),
    threshold: f64,
) -> Entry {
    // The first measure both runs have.
    let new_refs = references(new_scene, v);
    let sticks = references(old_scene, o).into_iter().find_map(|old_ref| {
        let new_ref = new_refs.iter().find(|n| n.2 == old_ref.2)?;
        Some((old_ref, *new_ref))
    });
    // CPU time when every set has it (it does not grow while the machine is busy).
    let cpu = match sticks {
        Some(((_, a, _), (_, b, _))) => [a, b, &o.cpu_samples, &v.cpu_samples]
            .iter()
            .all(|s| !s.is_empty()),
        None => !o.cpu_samples.is_empty() && !v.cpu_samples.is_empty(),
    };
    let clock = if cpu { Clock::Cpu } else { Clock::Wall };
    let pick = |wall: &'_ [f64], cpu_samples: &'_ [f64]| -> Vec<f64> {
        if cpu {
            cpu_samples.to_vec()
        } else {
            wall.to_vec()
        }
    };
    let (o_samples, v_samples) = (
        pick(&o.samples, &o.cpu_samples),
        pick(&v.samples, &v.cpu_samples),
    );
    let median_of = |samples: &[f64]| analysis::median(samples).unwrap_or(f64::INFINITY);
    let shortest = median_of(&o_samples).min(median_of(&v_samples));
    let (measure, old, new, change) = match sticks {
        Some(((old_wall, old_cpu, measure), (new_wall, new_cpu, _))) => {
            let old_ratio = Ratio::of(&o_samples, &pick(old_wall, old_cpu));
            let new_ratio = Ratio::of(&v_samples, &pick(new_wall, new_cpu));
            let (old, new) = (old_ratio.estimate(), new_ratio.estimate());
            let change = Ratio::change(&new_ratio, &old_ratio);
            (measure, old, new, change)
        }
        _ => {
            let old = of_medians(&[&o_samples], |m| m[0]);
            let new = of_medians(&[&v_samples], |m| m[0]);
            let change = of_medians(&[&v_samples, &o_samples], |m| m[0] / m[1]);
            (Measure::Seconds, old, new, change)
        }
    };
    let unknown = Estimate {
        median: f64::NAN,
        low: f64::NAN,
        high: f64::NAN,
    };
    let change = change.unwrap_or(unknown);
    let (old, new) = (old.unwrap_or(unknown), new.unwrap_or(unknown));
    let threshold = match shortest < SHORT_SECONDS {
        true => entry_threshold(threshold, &old, &new).max(SHORT_THRESHOLD),
        false => entry_threshold(threshold, &old, &new),
    };
    Entry {
        scene: new_scene.name.clone(),
        width: new_scene.width,
        height: new_scene.height,
        variant: v.variant.clone(),
        measure,
        clock,
        old,
        new,
        old_seconds: o.time.median,
        new_seconds: v.time.median,
        change,
        threshold,
        shortest_seconds: shortest,
        verdict: judge(&change, threshold),
        count_changes: count_changes(o, v),
    }
}

fn count_changes(old: &VariantResult, new: &VariantResult) -> Vec<CountChange> {
    let mut names: Vec<&String> = old.counts.keys().chain(new.counts.keys()).collect();
    names.sort();
    names.dedup();
    names
        .into_iter()
        .filter_map(|name| {
            let a = old.counts.get(name).copied().unwrap_or(0);
            let b = new.counts.get(name).copied().unwrap_or(0);
            (a != b).then(|| CountChange {
                counter: name.clone(),
                old: a,
                new: b,
            })
        })
        .collect()
}

fn instruction_entries(
    old: &[InstructionCount],
    new: &[InstructionCount],
) -> Vec<InstructionEntry> {
    new.iter()
        .filter_map(|n| {
            let o = old.iter().find(|o| o.id == n.id)?;
            let change = if o.instructions == 0 {
                if n.instructions == 0 {
                    0.0
                } else {
                    f64::INFINITY
                }
            } else {
                n.instructions as f64 / o.instructions as f64 - 1.0
            };
            Some(InstructionEntry {
                id: n.id.clone(),
                old: o.instructions,
                new: n.instructions,
                change,
                regressed: change > INSTRUCTION_THRESHOLD,
                improved: change < -INSTRUCTION_THRESHOLD,
            })
        })
        .collect()
}

/// The benchmark ids that only one run has an instruction count for, when both have
/// some (a run without any was simply not measured with the benchmarks), or in a strict
/// gate whenever the baseline has some (its benchmarks must run).
fn unmatched_ids(old: &[InstructionCount], new: &[InstructionCount], strict: bool) -> Vec<String> {
    if old.is_empty() || (new.is_empty() && !strict) {
        return Vec::new();
    }
    let only = |a: &[InstructionCount], b: &[InstructionCount], side: &str| {
        a.iter()
            .filter(|x| !b.iter().any(|y| y.id == x.id))
            .map(|x| format!("{} ({side})", x.id))
            .collect::<Vec<_>>()
    };
    let mut ids = only(old, new, "old");
    ids.extend(only(new, old, "new"));
    ids
}
