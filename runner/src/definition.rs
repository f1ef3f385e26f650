//! A suite definition (`scenes/suite.toml`, embedded as the default): which scenes at
//! which size, which variants, how long to time, profile and model, and the smaller
//! `[quick]` form CI runs.

use serde::Deserialize;
use tracer::VariantSet;

use crate::error::RunError;
use crate::timing::TimingPolicy;

/// The default suite, embedded in the binary.
pub const DEFAULT_SUITE: &str = include_str!("../../scenes/suite.toml");

/// Its name in messages.
pub const DEFAULT_SUITE_FILE: &str = "suite.toml (embedded)";

/// Least samples per profile when the definition does not say: the same as
/// `rtprof profile`.
fn default_profile_samples() -> u64 {
    crate::profile_job::DEFAULT_MIN_SAMPLES
}

fn yes() -> bool {
    true
}

/// Threads of the timed renders when the definition does not say: one (see
/// [`SuiteDef::timing_threads`]).
fn one() -> u16 {
    1
}

/// A suite definition.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteDef {
    pub name: String,
    pub size: [u32; 2],
    pub repeats: u32,
    /// Keep repeating a timed render (beyond `repeats`, up to the timing policy's most)
    /// until this much tracing time is measured.
    #[serde(default)]
    pub min_seconds: f64,
    /// Threads of the timed renders (default: one; `--threads` sets another). The
    /// untimed work (counted renders, pictures, the f64 reference, the profile) uses
    /// every core. On a machine with other work a pool as wide as the machine shares
    /// its cores with that work, and its times measure the scheduler: five runs of a
    /// small suite with one core kept busy moved a variant's relative time by up to 29 %
    /// on two threads and 14 % on one (docs/gate.md).
    #[serde(default = "one")]
    pub timing_threads: u16,
    pub variants: Vec<String>,
    pub scenes: Vec<String>,
    pub extra_size: [u32; 2],
    pub profile_size: [u32; 2],
    /// Sampling rate asked of the profiler's timer, Hz; unset: the timer's default
    /// (4,000 for perf cpu-clock, 1,000 for setitimer).
    #[serde(default)]
    pub profile_frequency: Option<i32>,
    /// Least sampled seconds per profile (a faster render is repeated).
    #[serde(default = "default_profile_samples")]
    pub profile_samples: u64,
    pub hardware_repeats: u32,
    /// Whether each scene the hardware can render also runs the hardware model and
    /// emulator (default: yes).
    #[serde(default = "yes")]
    pub hardware: bool,
    /// Whether a scene is profiled (default: yes).
    #[serde(default = "yes")]
    pub profile: bool,
    /// The scene profiled (an entry as in `scenes`, e.g. `spd:rings`, the thesis's
    /// table 6), at `profile_size`, with baseline and the fastest variant that kept its
    /// picture on the suite's run of the same scene (`NAME` or `NAME-small`); unset:
    /// the suite's heaviest scene.
    #[serde(default)]
    pub profile_scene: Option<String>,
    /// Whether every scene is also rendered once by the f64 reference renderer, each
    /// variant's picture measured against it (default: yes).
    #[serde(default = "yes")]
    pub f64_reference: bool,
    /// Scenes (by their name in results, e.g. `balls4`, `rings-small`) whose baseline,
    /// simd and bvh renders also write per-pixel maps.
    #[serde(default)]
    pub pixel_stats: Vec<String>,
    /// The SPD databases, generated, each run twice (see [`SpdDef`]).
    #[serde(default)]
    pub spd: Option<SpdDef>,
    /// Outside tracers run beside the variants on every scene but the SPD's small runs
    /// (docs/tracers.md), each also recorded with perf on the profile scene when it says
    /// `record = true`: each `{ peer = "povray" }`, `{ file = "tracer.toml" }` (from
    /// the suite file's directory) or a definition in place.
    #[serde(default)]
    pub tracers: Vec<crate::outside::entry::TracerEntry>,
    pub quick: Option<QuickDef>,
}

/// The SPD part of a suite. Each scene runs twice: every variant on a small frame
/// (brute force tests every primitive against every ray, so at the SPD's frame it would
/// take hours), and the accelerated variants at the SPD's own frame with its procedure
/// (corner rays), whose ray counts are those the SPD publishes.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpdDef {
    /// Scene entries, normally `spd:NAME` (the SPD's size factor).
    pub scenes: Vec<String>,
    /// The frame of the every-variant run.
    pub size: [u32; 2],
    /// The frame of the accelerated run (512 × 512: the SPD's).
    pub full_size: [u32; 2],
    /// The variants of the accelerated run (none of them brute force).
    pub full_variants: Vec<String>,
    /// Whether the every-variant run renders on one thread. Its frame is small, so an
    /// accelerated render there lasts about a millisecond, and on several threads part
    /// of that is waking the workers: its speed-up would measure the threads as much as
    /// the structure. On one thread every variant's time is its work alone.
    #[serde(default)]
    pub small_on_one_thread: bool,
}

/// Overrides for `--quick`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuickDef {
    pub size: Option<[u32; 2]>,
    pub repeats: Option<u32>,
    pub min_seconds: Option<f64>,
    pub variants: Option<Vec<String>>,
    pub scenes: Option<Vec<String>>,
    pub extra_size: Option<[u32; 2]>,
    pub profile_size: Option<[u32; 2]>,
    pub profile_samples: Option<u64>,
    pub hardware_repeats: Option<u32>,
    pub pixel_stats: Option<Vec<String>>,
    pub spd: Option<SpdDef>,
}

impl SuiteDef {
    /// Reads and parses the definition at `path`, or the embedded default suite.
    pub fn load(path: Option<&std::path::Path>) -> Result<Self, RunError> {
        match path {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| RunError::io("read suite", path, &e))?;
                Self::parse(&text, &path.display().to_string())
            }
            None => Self::parse(DEFAULT_SUITE, DEFAULT_SUITE_FILE),
        }
    }

    /// Parses a definition and checks it, with and without its `[quick]` overrides
    /// (`file` names it in errors).
    pub fn parse(text: &str, file: &str) -> Result<Self, RunError> {
        let def: SuiteDef = toml::from_str(text).map_err(|e| RunError::Definition {
            // FILE:LINE:COLUMN, as compilers say where, rather than toml's drawing of
            // the line (several lines, which a one-line message would mangle).
            file: match e.span() {
                Some(span) => {
                    let (line, column) = crate::text_position::line_and_column(text, span.start);
                    format!("{file}:{line}:{column}")
                }
                None => file.to_string(),
            },
            message: e.message().trim().to_string(),
        })?;
        def.check(file)?;
        def.clone().quick().check(file).map_err(|e| match e {
            RunError::Definition { file, message } => RunError::Definition {
                file,
                message: format!("in [quick]: {message}"),
            },
            other => other,
        })?;
        Ok(def)
    }

    /// A definition built in code (`rtprof serve`'s jobs), checked as a file would be.
    pub fn checked(self, file: &str) -> Result<Self, RunError> {
        self.check(file)?;
        Ok(self)
    }

    fn check(&self, file: &str) -> Result<(), RunError> {
        let bad = |message: String| {
            Err(RunError::Definition {
                file: file.to_string(),
                message,
            })
        };
        if self.repeats == 0 || self.repeats > 1000 {
            return bad("repeats must be 1 to 1000".into());
        }
        if !(0.0..=60.0).contains(&self.min_seconds) {
            return bad("min_seconds must be 0 to 60".into());
        }
        if let Err(e) = crate::pool::check_threads(u64::from(self.timing_threads)) {
            return bad(format!("timing_threads: {e}"));
        }
        if !(1..=1_000_000).contains(&self.profile_samples) {
            return bad("profile_samples must be 1 to 1000000".into());
        }
        if self
            .profile_frequency
            .is_some_and(|f| !(10..=10_000).contains(&f))
        {
            return bad("profile_frequency must be 10 to 10000 Hz".into());
        }
        match self.variants.first().map(|v| VariantSet::parse(v)) {
            Some(Ok(set)) if set == VariantSet::default() => {}
            _ => return bad("the first variant must be baseline (the reference)".into()),
        }
        for v in &self.variants {
            if let Err(e) = VariantSet::parse(v) {
                return bad(format!("variant '{v}': {e}"));
            }
        }
        let mut sizes = vec![self.size, self.extra_size, self.profile_size];
        if let Some(spd) = &self.spd {
            sizes.extend([spd.size, spd.full_size]);
            for v in &spd.full_variants {
                match VariantSet::parse(v) {
                    Err(e) => return bad(format!("[spd] variant '{v}': {e}")),
                    Ok(set) if set.config().accel == tracer::Accelerator::BruteForce => {
                        return bad(format!(
                            "[spd] full_variants: '{v}' is brute force, which would take hours at full_size; \
                             give accelerated variants (bvh, simd) or run it in the small frame"
                        ));
                    }
                    Ok(_) => {}
                }
            }
        }
        if let Some(at) = self.tracers.iter().position(|t| t.record())
            && !self.profile
        {
            return bad(format!(
                "[[tracers]] #{}: record = true records the tracer on the suite's profile scene, but profile = false: profile a scene, or drop record",
                at + 1
            ));
        }
        for size in sizes {
            if let Err(e) =
                tracer::Limits::default().check_size(u64::from(size[0]), u64::from(size[1]))
            {
                return bad(e.to_string());
            }
        }
        Ok(())
    }

    /// The definition with Embree inside rtprof's renderer, in both its modes (`embree`,
    /// single rays; `embree-packets`), added to every run where this build has Embree:
    /// `rtprof suite --embree`, which also runs the yardstick
    /// ([`Suite::with_embree_yardstick`](crate::suite::Suite::with_embree_yardstick)).
    pub fn with_embree_variants(self) -> Self {
        if !tracer::Variant::Embree.available() {
            return self;
        }
        let peers = [tracer::Variant::Embree, tracer::Variant::EmbreePackets];
        peers
            .into_iter()
            .fold(self, |def, peer| def.with_variant(peer.name()))
    }

    /// The definition with `variant` (a peer such as `embree`) added to every run: the
    /// suite's variants and the SPD's accelerated run, with or without `--quick`.
    pub fn with_variant(mut self, variant: &str) -> Self {
        let add = |list: &mut Vec<String>| {
            if !list.iter().any(|v| v == variant) {
                list.push(variant.to_string());
            }
        };
        add(&mut self.variants);
        if let Some(spd) = &mut self.spd {
            add(&mut spd.full_variants);
        }
        if let Some(q) = &mut self.quick {
            if let Some(list) = &mut q.variants {
                add(list);
            }
            if let Some(spd) = &mut q.spd {
                add(&mut spd.full_variants);
            }
        }
        self
    }

    /// The definition with the `[quick]` overrides applied.
    pub fn quick(mut self) -> Self {
        if let Some(q) = self.quick.take() {
            self.size = q.size.unwrap_or(self.size);
            self.repeats = q.repeats.unwrap_or(self.repeats);
            self.min_seconds = q.min_seconds.unwrap_or(self.min_seconds);
            self.variants = q.variants.unwrap_or(self.variants);
            self.scenes = q.scenes.unwrap_or(self.scenes);
            self.extra_size = q.extra_size.unwrap_or(self.extra_size);
            self.profile_size = q.profile_size.unwrap_or(self.profile_size);
            self.profile_samples = q.profile_samples.unwrap_or(self.profile_samples);
            self.hardware_repeats = q.hardware_repeats.unwrap_or(self.hardware_repeats);
            self.pixel_stats = q.pixel_stats.unwrap_or(self.pixel_stats);
            self.spd = q.spd.or(self.spd);
        }
        self
    }

    /// How the variants' renders are timed.
    pub fn timing(&self) -> TimingPolicy {
        TimingPolicy::new(self.repeats, self.min_seconds)
    }

    /// How the software side of the hardware comparison is timed.
    pub fn hardware_timing(&self) -> TimingPolicy {
        TimingPolicy::new(self.hardware_repeats.max(1), self.min_seconds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::resolve_scene;
    use std::path::Path;

    #[test]
    fn the_embedded_suite_parses_and_its_quick_form_is_smaller() {
        let def = SuiteDef::parse(DEFAULT_SUITE, "suite.toml").unwrap();
        assert_eq!(def.variants[0], "baseline");
        let quick = def.clone().quick();
        assert!(quick.size[0] * quick.size[1] < def.size[0] * def.size[1]);
        assert!(quick.scenes.len() < def.scenes.len());
        for s in &def.scenes {
            resolve_scene(s, (8, 8), Path::new(".")).unwrap();
        }
    }

    #[test]
    fn a_toml_error_names_file_line_and_column_on_one_line() {
        // The third line's value is a string where a number belongs.
        let text = DEFAULT_SUITE.replacen("repeats = 3", "repeats = \"three\"", 1);
        let line = text
            .lines()
            .position(|l| l.starts_with("repeats ="))
            .unwrap()
            + 1;
        let e = SuiteDef::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(e.starts_with(&format!("my.toml:{line}:11: ")), "{e}");
        assert!(!e.contains('\n'), "{e}");
        let e = SuiteDef::parse("name = \"x\"\n", "my.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing field"), "{e}");
        assert!(!e.contains('\n') && !e.contains(" | "), "{e}");
    }

    #[test]
    fn timing_threads_default_to_one_and_are_checked() {
        let def = SuiteDef::parse(DEFAULT_SUITE, "suite.toml").unwrap();
        assert_eq!(def.timing_threads, 1);
        let without = DEFAULT_SUITE.replacen("timing_threads = 1\n", "", 1);
        assert_ne!(without, DEFAULT_SUITE);
        assert_eq!(
            SuiteDef::parse(&without, "s.toml").unwrap().timing_threads,
            1
        );
        let zero = DEFAULT_SUITE.replacen("timing_threads = 1", "timing_threads = 0", 1);
        let e = SuiteDef::parse(&zero, "s.toml").unwrap_err().to_string();
        assert!(e.contains("timing_threads"), "{e}");
    }

    #[test]
    fn a_peer_variant_joins_every_run_with_and_without_quick() {
        let def = SuiteDef::parse(DEFAULT_SUITE, "suite.toml")
            .unwrap()
            .with_variant("embree");
        for d in [def.clone(), def.quick()] {
            assert_eq!(d.variants.iter().filter(|v| *v == "embree").count(), 1);
            assert_eq!(d.variants[0], "baseline");
            let spd = d.spd.as_ref().unwrap();
            assert_eq!(spd.full_variants.last().map(String::as_str), Some("embree"));
            // Adding it twice changes nothing.
            let again = d.clone().with_variant("embree");
            assert_eq!(again.variants, d.variants);
        }
    }

    #[test]
    fn bad_suites_are_refused_with_the_file_name() {
        let bad = DEFAULT_SUITE.replace("\"baseline\", \"simd\"", "\"simd\", \"baseline\"");
        let err = SuiteDef::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(err.contains("x.toml") && err.contains("baseline"), "{err}");
        let err = SuiteDef::parse("name = 1", "y.toml")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("y.toml"), "{err}");
        // The [quick] overrides are checked too.
        let bad = DEFAULT_SUITE.replace("min_seconds = 0.02", "min_seconds = -1");
        let err = SuiteDef::parse(&bad, "z.toml").unwrap_err().to_string();
        assert!(
            err.contains("[quick]") && err.contains("min_seconds"),
            "{err}"
        );
    }
}
