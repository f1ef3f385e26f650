//! The suite's outside tracers (docs/tracers.md): each measurement into the results
//! entry rtprof's variants have (its picture and heat map saved, judged against the
//! scene's reference variant and the f64 reference when it draws the same scene at
//! the same frame), and a failed one into the run's failures, the reason and the
//! program's last lines of standard error kept.

use std::path::Path;

use analysis::{RgbImage, compare, difference_heat_map, gray_histogram};
use results::{FailedPart, Failure, VariantName, VariantResult, slug};

use super::{RunContext, Suite};
use crate::collect::quality;
use crate::error::RunError;
use crate::outside::OutsideMeasurement;
use crate::outside::SceneFormat;
use crate::staging::save_png;

/// An outside tracer's results entry; `stem` is its images' path without extension
/// (relative to `out`), `reference` the picture of the scene's reference variant.
pub(crate) fn outside_result(
    out: &Path,
    stem: &str,
    m: OutsideMeasurement,
    reference: Option<&RgbImage>,
    truth: Option<&RgbImage>,
) -> Result<VariantResult, RunError> {
    let image_rel = save_png(out, &format!("{stem}.png"), &m.image)?;
    let same_frame = |other: &RgbImage| {
        m.prepared.def.scene != SceneFormat::Own
            && (other.width, other.height) == (m.image.width, m.image.height)
    };
    let (quality_vs_reference, heat_map) = match reference {
        Some(base) if same_frame(base) => {
            let heat = difference_heat_map(base, &m.image)?;
            let heat_rel = save_png(out, &format!("{stem}-diff.png"), &heat)?;
            (Some(quality(&compare(base, &m.image)?)), Some(heat_rel))
        }
        _ => (None, None),
    };
    let vs_f64_reference = match truth {
        Some(truth) if same_frame(truth) => Some(quality(&compare(truth, &m.image)?)),
        _ => None,
    };
    // Judged against the truth where the f64 reference ran, else the reference variant.
    let outside = m.record(truth.or(reference))?;
    let counts = m
        .prepared
        .counts()
        .map(|c| crate::collect::count_map(&c))
        .unwrap_or_default();
    Ok(VariantResult {
        variant: m.name,
        time: m.time,
        samples: m.samples,
        cpu_samples: m.cpu_samples,
        // Its preparation is in its time or not, as its definition says.
        preprocessing_seconds: None,
        // Filled for the whole run by results::change::fill_speedups.
        speedup: None,
        speedup_interval: None,
        verdict: None,
        counts,
        image: Some(image_rel),
        heat_map,
        quality: quality_vs_reference,
        vs_f64_reference,
        histogram: gray_histogram(&m.image).to_vec(),
        lane_utilization: None,
        efficiency: None,
        ray_rates: None,
        outside: Some(outside),
    })
}

/// A failed outside tracer as one of the run's failures: stopped runs stop the suite.
pub(crate) fn outside_failure(scene: &str, error: RunError) -> Result<Failure, RunError> {
    let (tracer, message) = match error {
        RunError::Stopped => return Err(RunError::Stopped),
        RunError::Outside { tracer, failure } => (tracer, failure.describe()),
        other => ("?".to_string(), other.to_string()),
    };
    let part = VariantName::outside(&tracer).map_or(FailedPart::Scene, FailedPart::Variant);
    Ok(Failure {
        scene: Some(scene.to_string()),
        part,
        message: format!("tracer {tracer}: {message}"),
    })
}

impl Suite {
    /// The suite with the outside tracers `more` added; two with one name are refused.
    pub fn with_tracers(
        mut self,
        more: impl IntoIterator<Item = crate::outside::TracerDef>,
    ) -> Result<Self, RunError> {
        for def in more {
            if let Some(other) = self.tracers.iter().find(|t| t.name == def.name) {
                return Err(RunError::Definition {
                    file: def.file.clone(),
                    message: format!(
                        "tracer name '{}' is also {}'s: give each its own name",
                        def.name, other.file
                    ),
                });
            }
            self.tracers.push(def);
        }
        Ok(self)
    }

    /// The suite with the tracers `flags` name (`--tracer`, `--peers`) added to its
    /// own; the built-in peers asked for but not installed are kept by name.
    pub fn with_tracer_flags(self, flags: &crate::outside::TracerFlags) -> Result<Self, RunError> {
        let (defs, missing) = flags.load_with_peers()?;
        let own: Vec<String> = self.tracers.iter().map(|t| t.name.clone()).collect();
        // A peer the definition already runs is not added twice.
        let defs = defs
            .into_iter()
            .filter(|d| !(flags.peers && own.contains(&d.name) && d.file.starts_with("built-in")));
        let mut suite = self.with_tracers(defs)?;
        suite.missing_peers = missing;
        Ok(suite)
    }
}

/// The Embree yardstick's built-in definitions (peers/embree/): packets, single rays.
pub const EMBREE_YARDSTICK: [&str; 2] = ["embree-yardstick", "embree-yardstick-single"];

impl Suite {
    /// `rtprof suite --embree` (when `on`): the Embree yardstick in both its modes added
    /// where it is installed, named as missing where not. Refused when neither it nor
    /// Embree inside rtprof (a build with `--features embree`) can run.
    pub fn with_embree_yardstick(mut self, on: bool) -> Result<Self, RunError> {
        if !on {
            return Ok(self);
        }
        let mut found = Vec::new();
        for (def, installed) in crate::outside::peers::peers()? {
            if !EMBREE_YARDSTICK.contains(&def.name.as_str())
                || self.tracers.iter().any(|t| t.name == def.name)
            {
                continue;
            }
            match installed {
                true => found.push(def),
                false => self.missing_peers.push(def.name),
            }
        }
        if found.is_empty() && !tracer::Variant::Embree.available() {
            return Err(RunError::Input(
                "--embree: the Embree yardstick (rtprof-embree) is not installed: build it with \
                 scripts/build-embree-peer.sh (it needs libembree-dev); this rtprof was also \
                 built without Embree inside (`cargo build --release --features embree`)"
                    .into(),
            ));
        }
        self.with_tracers(found)
    }
}

/// Each outside tracer's measurement of scene `scene` as a results entry in `variants`,
/// or a failure in `failures`; `pictures` are the scene's reference variant's picture
/// and the f64 reference's.
pub(crate) fn push_outside_results(
    ctx: &RunContext<'_>,
    scene: &str,
    measured: Vec<Result<OutsideMeasurement, RunError>>,
    (reference, truth): (Option<&RgbImage>, Option<&RgbImage>),
    variants: &mut Vec<VariantResult>,
    failures: &mut Vec<Failure>,
) -> Result<(), RunError> {
    for m in measured {
        match m {
            Ok(m) => {
                let stem = format!("images/{}-{}", slug(scene), slug(m.name.as_str()));
                match outside_result(ctx.out, &stem, m, reference, truth) {
                    Ok(v) => variants.push(v),
                    Err(e) => failures.push(outside_failure(scene, e)?),
                }
            }
            Err(e) => failures.push(outside_failure(scene, e)?),
        }
        ctx.progress.advance(1);
    }
    Ok(())
}

/// The profile's directory of tracer `name`, relative to the suite's output.
fn profile_dir(name: &str) -> String {
    format!("profile/tracer-{}", slug(name))
}

impl super::SceneRunner<'_> {
    /// Records each outside tracer named in `recorded` with perf (`rtprof record`'s
    /// recording) on `spec`, the suite's profile scene, at the profile size; its files
    /// go to `profile/tracer-NAME/`. A recording that cannot be made (perf missing or
    /// not permitted, the program failing) is one of `failures`, and the suite goes on;
    /// the only error is the stop flag ([`RunError::Stopped`]).
    pub(super) fn record_tracers(
        &self,
        spec: &crate::scenes::SceneSpec,
        recorded: &[String],
        failures: &mut Vec<Failure>,
    ) -> Result<Vec<results::OutsideProfile>, RunError> {
        let mut profiles = Vec::new();
        for def in self.tracers.iter().filter(|t| recorded.contains(&t.name)) {
            self.ctx.progress.message(&format!(
                "{}: recording tracer:{} with perf",
                spec.name, def.name
            ));
            match self.record_tracer(spec, def) {
                Ok(p) => profiles.push(p),
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => {
                    let _ = std::fs::remove_dir_all(self.ctx.out.join(profile_dir(&def.name)));
                    let message = match e {
                        RunError::Outside { failure, .. } => failure.describe(),
                        other => other.to_string(),
                    };
                    failures.push(Failure {
                        scene: Some(spec.name.clone()),
                        part: FailedPart::Profile,
                        message: format!(
                            "tracer:{} could not be recorded with perf: {message}",
                            def.name
                        ),
                    });
                }
            }
        }
        Ok(profiles)
    }

    /// One tracer's run on `spec` under perf, its profile saved.
    fn record_tracer(
        &self,
        spec: &crate::scenes::SceneSpec,
        def: &crate::outside::TracerDef,
    ) -> Result<results::OutsideProfile, RunError> {
        use crate::outside::run::{RunPlan, command_line, environment, stderr_tail};
        use crate::record::{CallGraph, DEFAULT_FREQUENCY, ProgramSetup, RecordPlan};
        let outside = |failure| RunError::Outside {
            tracer: def.name.clone(),
            failure,
        };
        let scene = tracer::parse_nff(&spec.text, &spec.source).map_err(|e| RunError::Scene {
            scene: spec.name.clone(),
            message: e.to_string(),
        })?;
        let home = self.tracer_dir.join("record").join(&def.name);
        let [width, height] = self.def.profile_size;
        let scene_file =
            crate::outside::scene_file::write_scene(&scene, def.scene, &home, (width, height))
                .map_err(outside)?;
        let workdir = home.join("run");
        let _ = std::fs::remove_dir_all(&workdir);
        std::fs::create_dir_all(&workdir).map_err(|e| RunError::io("create", &workdir, &e))?;
        let workdir =
            std::path::absolute(&workdir).map_err(|e| RunError::io("resolve", &workdir, &e))?;
        let plan = RunPlan {
            def,
            scene_file: scene_file.as_deref(),
            width,
            height,
            // As the suite's own profile: every core.
            threads: self.pool.current_num_threads(),
            spp: def.spp.unwrap_or(1),
            // As the suite renders every scene: Whitted colour at the SPD's depth.
            shading: crate::outside::Shading::default(),
        };
        let command: Vec<std::ffi::OsString> = command_line(&plan, &workdir)
            .map_err(outside)?
            .into_iter()
            .map(Into::into)
            .collect();
        let stderr = workdir.join("stderr.txt");
        let rel = profile_dir(&def.name);
        let dir = self.ctx.out.join(&rel);
        let frequency = self
            .def
            .profile_frequency
            .and_then(|f| u32::try_from(f).ok())
            .unwrap_or(DEFAULT_FREQUENCY);
        let recording = crate::record::record(&RecordPlan {
            command: &command,
            frequency,
            call_graph: CallGraph::Fp,
            dir: &dir,
            stop: self.ctx.stop,
            time_limit: Some(std::time::Duration::from_secs_f64(def.time_limit)),
            phases: None,
            baseline: None,
            pdf: self.ctx.pdf,
            setup: ProgramSetup {
                env: environment(&plan, &workdir).map_err(outside)?,
                dir: Some(workdir.clone()),
                stdin: launch::Stream::Null,
                stdout: launch::Stream::File(workdir.join("stdout.txt")),
                stderr: launch::Stream::File(stderr.clone()),
            },
        })?;
        match recording.failure() {
            Some(crate::record::Failure::Interrupted(_)) => return Err(RunError::Stopped),
            Some(crate::record::Failure::CommandFailed(_)) => {
                let kind = match recording.finished.end {
                    launch::End::TimedOut => crate::outside::FailureKind::TimedOut,
                    launch::End::Signalled(_) => crate::outside::FailureKind::Killed,
                    _ => crate::outside::FailureKind::Exited,
                };
                return Err(outside(crate::outside::Failure {
                    kind,
                    reason: format!("{} {}", recording.name(), recording.finished.end),
                    stderr_tail: stderr_tail(&stderr),
                }));
            }
            // A probe file that cannot be read leaves the profile standing.
            Some(crate::record::Failure::BadProbeFile(_)) | None => {}
        }
        let (summary, saved) = recording.save_with_profile(&dir)?;
        let within = |f: &str| format!("{rel}/{f}");
        let mut profile = saved.views.into_iter().next().ok_or_else(|| {
            RunError::Profile(format!(
                "tracer:{}: the recording wrote no profile",
                def.name
            ))
        })?;
        for path in [
            &mut profile.flat_text,
            &mut profile.callgraph_text,
            &mut profile.flame_svg,
        ] {
            *path = within(path);
        }
        Ok(results::OutsideProfile {
            variant: VariantName::outside(&def.name)?,
            scene: spec.name.clone(),
            width,
            height,
            command: recording.command.clone(),
            samples: recording.samples(),
            cpu_seconds: recording.cpu_seconds(),
            wall_seconds: recording.finished.wall.as_secs_f64(),
            frequency,
            call_graph: recording.call_graph.describe().to_string(),
            directory: rel.clone(),
            profile,
            folded: within(&format!("folded-{}.txt", slug(recording.name()))),
            files: summary.files.iter().map(|f| within(f)).collect(),
        })
    }
}
