//! Variants side by side on one scene (`rtprof compare SCENE --variants A,B,…`): each
//! measured by the variant job under the one timing policy, then compared with the
//! first (the reference): speed-up, image error, counts. With `--reference`, the f64
//! reference renderer (the `reference` crate) renders the scene once more and each
//! variant's image error is also given against that ground truth.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use analysis::verdict::{NOISE_THRESHOLD, Verdict, judge_speedup};
use analysis::{
    Band, Comparison, Estimate, P3Histograms, RgbImage, compare, difference_heat_map,
    p3_histograms, to_p3,
};
use reports::document::Table;
use reports::format;
use reports::sections::variants::{Detail, scene_table};
use results::{Quality, SceneResult, VariantName, VariantResult};
use serde::Serialize;
use tracer::{Counts, ShadingMode, VariantSet};

use crate::error::RunError;
use crate::outside::{Failure, OutsideJobs, TracerFlags};
use crate::pool::thread_pool;
use crate::progress::Progress;
use crate::reference_job::ImageError;
use crate::render_job::RenderSettings;
use crate::render_setup::RenderSetup;
use crate::scene_input::SceneInput;
use crate::staging::save_png;
use crate::timing::TimingPolicy;
use crate::variant_job::VariantMeasurement;
use reports::table_format::Exports;

/// One variant's row.
#[derive(Serialize)]
pub struct VariantRow {
    pub name: String,
    /// Tracing seconds: median and 95 % interval.
    pub seconds: Estimate,
    /// Median preprocessing seconds (scene preparation, structure build), apart.
    pub preprocessing_seconds: f64,
    /// Reference median / this median, with its 95 % bootstrap interval.
    pub speedup: Estimate,
    /// Faster, slower or within noise against the reference (`None` for the reference).
    pub verdict: Option<Verdict>,
    /// The image error against the reference's picture; absent for an outside tracer
    /// that draws a scene of its own.
    #[serde(flatten)]
    pub error: Option<RowError>,
    /// Exact counts (an outside tracer's from its probe; absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counts: Option<Counts>,
    /// An outside tracer's definition and program (`None`: one of rtprof's variants).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outside: Option<results::OutsideTracer>,
    /// The image error against the f64 reference renderer (`--reference` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vs_f64_reference: Option<ImageError>,
    /// The timed renders' seconds (the CSV's repeats).
    #[serde(skip)]
    pub samples: Vec<f64>,
    /// `name`, as results record a variant.
    #[serde(skip)]
    pub variant: VariantName,
    /// The image error against the f64 reference, as the suite's results hold it.
    #[serde(skip)]
    pub vs_f64_quality: Option<Quality>,
}

/// A row's image error against the reference's picture.
#[derive(Serialize)]
pub struct RowError {
    pub rms: f64,
    pub band: Band,
    /// `null` when the images are identical (infinite PSNR).
    pub psnr: Option<f64>,
    pub ssim: f64,
    pub max_abs_diff: u8,
}

/// An entry that failed: its name and why.
#[derive(Serialize)]
pub struct FailedRow {
    pub name: String,
    pub failure: Failure,
}

/// `rtprof compare SCENE --variants …`: the variant sets `sets` side by side on one
/// scene, each timed `repeats` times at least (no minimum time: the count is what was
/// asked), images and heat maps into `out` when given (created if missing).
pub struct SideBySide<'a> {
    pub input: &'a SceneInput,
    pub sets: &'a [VariantSet],
    pub settings: &'a RenderSettings,
    pub mode: ShadingMode,
    pub repeats: u32,
    pub out: Option<&'a Path>,
    /// Also against the f64 reference renderer.
    pub f64_reference: bool,
    /// Outside tracers run beside the variants (docs/tracers.md), and their samples
    /// per pixel.
    pub tracers: &'a TracerFlags,
}

impl SideBySide<'_> {
    /// Loads the scene, sets up the pool and runs [`compare_variants`].
    pub fn run(&self, progress: &dyn Progress) -> Result<VariantsReport, RunError> {
        let (tracers, missing) = self.tracers.load_with_peers()?;
        for name in &missing {
            progress.note(&format!("--peers: {name} is not installed"));
        }
        if let Some(dir) = self.out {
            std::fs::create_dir_all(dir).map_err(|e| RunError::io("create directory", dir, &e))?;
        }
        let scene = self.input.load(&self.settings.limits)?;
        let options = self.settings.options(&scene, self.mode);
        let pool = thread_pool(self.settings.threads)?;
        let name = self.input.to_string();
        let never = AtomicBool::new(false);
        let setup = RenderSetup {
            scene: &scene,
            name: &name,
            options: &options,
            pool: &pool,
            counting_pool: &pool,
            stop: &never,
        };
        let policy = TimingPolicy::new(self.repeats, 0.0);
        // The outside tracers' scene files and runs: beside the images when kept.
        let work = match self.out {
            Some(dir) => dir.join("tracers"),
            None => std::env::temp_dir().join(format!("rtprof-compare-{}", std::process::id())),
        };
        let outside = OutsideJobs {
            defs: &tracers,
            dir: &work,
            spp: self.tracers.spp,
        };
        let report = compare_variants(
            &setup,
            self.sets,
            &outside,
            &policy,
            self.out,
            self.f64_reference,
            progress,
        );
        if self.out.is_none() && work.exists() {
            // Only a temporary directory; what matters is in the report.
            let _ = std::fs::remove_dir_all(&work);
        }
        report
    }
}

/// Measures every set in `sets` (the first is the reference) and compares them. With
/// `out`, each variant's image and its heat map against the reference are written there.
/// With `f64_reference`, the f64 reference renderer renders the scene too (once, in the
/// same pool, before the variants), and every row gets its image error against that
/// picture (written to `out` as `f64-reference.png`, with each variant's heat map
/// against it as `<variant>-vs-f64.png`).
pub fn compare_variants(
    setup: &RenderSetup<'_>,
    sets: &[VariantSet],
    outside: &OutsideJobs<'_>,
    policy: &TimingPolicy,
    out: Option<&Path>,
    f64_reference: bool,
    progress: &dyn Progress,
) -> Result<VariantsReport, RunError> {
    let reference = sets.first().ok_or_else(|| {
        RunError::Input("no variants: name at least one (e.g. baseline,bvh)".into())
    })?;
    let truth = if f64_reference {
        progress.begin("f64 reference", 0);
        let truth = crate::reference_job::render_in(setup);
        progress.end();
        Some(truth?)
    } else {
        None
    };
    if let (Some(dir), Some(truth)) = (out, &truth) {
        save_png(dir, "f64-reference.png", &truth.image)?;
    }
    let truth_image = truth.as_ref().map(|t| &t.image);
    let (variants, failed) =
        variant_rows(setup, sets, outside, policy, out, truth_image, progress)?;
    Ok(VariantsReport {
        scene: setup.name.to_string(),
        primitives: setup.scene.primitive_count() as u64,
        width: setup.options.width,
        height: setup.options.height,
        spd: setup.options.sampling == tracer::Sampling::SpdCorners,
        threads: setup.pool.current_num_threads(),
        repeats: policy.min_repeats,
        time_covers: "tracing",
        reference: reference.to_string(),
        f64_reference: truth.map(|t| F64Reference { seconds: t.seconds }),
        variants,
        failed,
    })
}

/// One measured entry, rtprof's variant or an outside tracer, as a row is made from it.
struct Entry<'a> {
    name: String,
    variant: VariantName,
    samples: &'a [f64],
    time: Estimate,
    preprocessing: f64,
    counts: Option<Counts>,
    image: &'a RgbImage,
    /// Whether its picture is of the same scene and frame as the reference's.
    same_scene: bool,
    outside: Option<results::OutsideTracer>,
}

fn variant_rows(
    setup: &RenderSetup<'_>,
    sets: &[VariantSet],
    outside: &OutsideJobs<'_>,
    policy: &TimingPolicy,
    out: Option<&Path>,
    truth: Option<&RgbImage>,
    progress: &dyn Progress,
) -> Result<(Vec<VariantRow>, Vec<FailedRow>), RunError> {
    progress.begin("variants", 0);
    let all = setup.measure_all(
        sets,
        outside,
        policy,
        false,
        &|what| progress.message(what),
        &|done, total| progress.within(crate::progress::TIMED, done, total),
    )?;
    progress.end();
    // rtprof's own variants must all work (a failure is rtprof's, and an error); an
    // outside tracer that fails is recorded and the others go on.
    let measured: Vec<VariantMeasurement> = all.variants.into_iter().collect::<Result<_, _>>()?;
    let mut failed = Vec::new();
    let mut entries: Vec<Entry<'_>> = measured
        .iter()
        .map(|m| Entry {
            name: m.variants.to_string(),
            variant: VariantName::of(&m.variants),
            samples: &m.samples,
            time: m.time,
            preprocessing: m.preprocessing,
            counts: Some(m.counts),
            image: &m.image,
            same_scene: true,
            outside: None,
        })
        .collect();
    let outside_measured: Vec<_> = all
        .outside
        .into_iter()
        .filter_map(|m| match m {
            Ok(m) => Some(m),
            Err(RunError::Outside { tracer, failure }) => {
                failed.push(FailedRow {
                    name: format!("{}{tracer}", results::OUTSIDE_PREFIX),
                    failure,
                });
                None
            }
            Err(e) => {
                failed.push(FailedRow {
                    name: "an outside tracer".into(),
                    failure: Failure {
                        kind: crate::outside::FailureKind::Setup,
                        reason: e.to_string(),
                        stderr_tail: Vec::new(),
                    },
                });
                None
            }
        })
        .collect();
    let reference_image = measured.first().map(|m| &m.image);
    for m in &outside_measured {
        let def = &m.prepared.def;
        entries.push(Entry {
            name: m.name.to_string(),
            variant: m.name.clone(),
            samples: &m.samples,
            time: m.time,
            preprocessing: 0.0,
            counts: m.prepared.counts(),
            image: &m.image,
            same_scene: def.scene != crate::outside::SceneFormat::Own,
            outside: Some(m.record(truth.or(reference_image))?),
        });
    }
    let Some(reference) = measured.first() else {
        return Ok((Vec::new(), failed));
    };
    let mut rows = Vec::with_capacity(entries.len());
    for (index, e) in entries.into_iter().enumerate() {
        let file = e.name.replace(':', "-");
        if let Some(dir) = out {
            save_png(dir, &format!("{file}.png"), e.image)?;
        }
        let comparable = e.same_scene
            && (e.image.width, e.image.height) == (reference.image.width, reference.image.height);
        let error = if comparable {
            let m = compare(&reference.image, e.image)?;
            if let (Some(dir), true) = (out, index > 0) {
                let heat = difference_heat_map(&reference.image, e.image)?;
                save_png(dir, &format!("{file}-diff.png"), &heat)?;
            }
            Some(RowError {
                rms: m.rms,
                band: m.band,
                psnr: m.psnr.is_finite().then_some(m.psnr),
                ssim: m.ssim,
                max_abs_diff: m.max_abs_diff,
            })
        } else {
            None
        };
        let (vs_f64_reference, vs_f64_quality) = match truth {
            Some(truth) if comparable => {
                if let Some(dir) = out {
                    let heat = difference_heat_map(truth, e.image)?;
                    save_png(dir, &format!("{file}-vs-f64.png"), &heat)?;
                }
                (
                    Some(ImageError::between(truth, e.image)?),
                    Some(crate::collect::quality(&compare(truth, e.image)?)),
                )
            }
            _ => (None, None),
        };
        let speedup = results::change::speedup(&reference.samples, e.samples);
        rows.push(VariantRow {
            name: e.name,
            seconds: e.time,
            preprocessing_seconds: e.preprocessing,
            speedup: speedup.unwrap_or(Estimate {
                median: f64::NAN,
                low: f64::NAN,
                high: f64::NAN,
            }),
            verdict: speedup
                .filter(|_| index > 0)
                .map(|s| judge_speedup(&s, NOISE_THRESHOLD)),
            error,
            counts: e.counts,
            outside: e.outside,
            vs_f64_reference,
            samples: e.samples.to_vec(),
            variant: e.variant,
            vs_f64_quality,
        });
    }
    Ok((rows, failed))
}

/// `rtprof compare SCENE --variants`: the setting and one row per variant.
#[derive(Serialize)]
pub struct VariantsReport {
    pub scene: String,
    pub primitives: u64,
    pub width: u32,
    pub height: u32,
    pub spd: bool,
    pub threads: usize,
    pub repeats: u32,
    /// What `seconds` covers: tracing only (preprocessing is `preprocessing_seconds`).
    pub time_covers: &'static str,
    pub reference: String,
    /// The f64 reference render, when asked (`--reference`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub f64_reference: Option<F64Reference>,
    pub variants: Vec<VariantRow>,
    /// Outside tracers that failed, with why (the rows above are the ones that ran).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub failed: Vec<FailedRow>,
}

/// The f64 reference render of a side-by-side run.
#[derive(Serialize)]
pub struct F64Reference {
    /// Seconds of its one render (tracing, untimed by the policy: one run).
    pub seconds: f64,
}

impl VariantsReport {
    /// The setting in one line: scene, size, threads, repeats, reference, threshold.
    pub fn heading(&self) -> String {
        let r = self;
        let truth = r.f64_reference.as_ref().map_or(String::new(), |f| {
            format!(
                "; image error also against the f64 reference ({} s)",
                format::fixed(f.seconds, 3)
            )
        });
        format!(
            "{}: {}{}, {}, at least {}, timed interleaved, against {}; verdicts at a {} % noise threshold{truth}\n",
            r.scene,
            format::size(r.width, r.height),
            if r.spd { " (SPD)" } else { "" },
            format::plural(r.threads, "thread"),
            format::plural(r.repeats as usize, "repeat"),
            r.reference,
            NOISE_THRESHOLD * 100.0
        )
    }

    /// The rows as the suite's results model holds a scene, so that the table and the
    /// CSV are the report's own ([`reports::sections::variants::scene_table`],
    /// [`reports::exports::scenes_csv`]).
    pub fn scene_result(&self) -> SceneResult {
        let variants = self
            .variants
            .iter()
            .map(|v| VariantResult {
                variant: v.variant.clone(),
                time: v.seconds,
                samples: v.samples.clone(),
                cpu_samples: Vec::new(),
                // An outside program's preparation is in its time or not, as its
                // definition says: none is apart.
                preprocessing_seconds: Some(v.preprocessing_seconds)
                    .filter(|_| v.outside.is_none()),
                speedup: Some(v.speedup.median).filter(|s| s.is_finite()),
                speedup_interval: v
                    .speedup
                    .median
                    .is_finite()
                    .then_some([v.speedup.low, v.speedup.high]),
                verdict: v.verdict,
                counts: v
                    .counts
                    .as_ref()
                    .map(crate::collect::count_map)
                    .unwrap_or_default(),
                image: None,
                heat_map: None,
                quality: v.error.as_ref().map(|e| Quality {
                    rms: e.rms,
                    band: e.band,
                    psnr: e.psnr,
                    ssim: e.ssim,
                    max_abs_diff: u32::from(e.max_abs_diff),
                }),
                vs_f64_reference: v.vs_f64_quality.clone(),
                histogram: Vec::new(),
                lane_utilization: None,
                efficiency: None,
                ray_rates: None,
                outside: v.outside.clone(),
            })
            .collect();
        SceneResult {
            name: self.scene.clone(),
            source: self.scene.clone(),
            family: results::SceneFamily::Other,
            primitives: self.primitives,
            primitive_counts: Default::default(),
            width: self.width,
            height: self.height,
            spd: self.spd,
            variants,
            hardware: None,
            calibration: None,
            yardstick: None,
            published: None,
            memory: None,
            bvh_quality: Vec::new(),
            pixel_maps: Vec::new(),
            f64_reference: None,
            threads: None,
        }
    }

    /// The rows as a document table (the terminal and Markdown forms): the report's
    /// per-scene table, compact.
    pub fn table(&self) -> Table {
        let scene = self.scene_result();
        let base = scene.variants.first();
        scene_table(&scene, base, Detail::Compact)
    }
}

impl VariantsReport {
    /// "N outside tracers failed" when any did (the command's exit: parts failed).
    pub fn failure_summary(&self) -> Option<String> {
        match self.failed.len() {
            0 => None,
            1 => Some(format!("{} failed", self.failed[0].name)),
            n => Some(format!("{n} outside tracers failed")),
        }
    }

    /// The failed entries, one paragraph each ("" without any).
    pub fn failures(&self) -> String {
        let mut out = String::new();
        for f in &self.failed {
            out += &format!("\n{} failed: {}\n", f.name, f.failure.describe());
        }
        out
    }

    /// What the outside tracers' times cover, one line each ("" without any).
    pub fn outside_notes(&self) -> String {
        let mut out = String::new();
        for v in &self.variants {
            if let Some(o) = &v.outside {
                let program = o.program.as_ref().map_or("not found".to_string(), |p| {
                    format!("{}, {} bytes", p.path, format::count(p.bytes))
                });
                out += &format!(
                    "{}: {} ({program}); time: {}\n",
                    v.name,
                    o.command.join(" "),
                    o.time_covers
                );
                if let Some(note) = reports::sections::outside_tracers::picture_note(o) {
                    out += &format!("  its picture: {note}\n");
                }
            }
        }
        out
    }
}

impl Exports for VariantsReport {
    /// The table the command prints, and the entries that failed.
    fn to_text(&self) -> String {
        self.heading()
            + &reports::text::table(&self.table())
            + &self.outside_notes()
            + &self.failures()
    }

    /// A GitHub-flavoured Markdown table under a one-line heading.
    fn to_markdown(&self) -> String {
        format!(
            "**{}**\n\n{}",
            self.heading().trim_end(),
            reports::text::markdown(&self.table())
        )
    }

    /// One CSV row per variant, seconds in full: the writer of `variants.csv`.
    fn to_csv(&self) -> String {
        reports::exports::scenes_csv(&[self.scene_result()])
    }
}

/// `rtprof compare IMG_A IMG_B`: the metrics (method 1, histograms included) and, when
/// asked, the thesis's method 2: histograms computed from each image's plain-text PPM.
#[derive(Serialize)]
pub struct ImageReport {
    #[serde(skip)]
    pub a: String,
    #[serde(skip)]
    pub b: String,
    #[serde(flatten)]
    pub metrics: Comparison,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p3_histograms_a: Option<P3Histograms>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p3_histograms_b: Option<P3Histograms>,
    /// Where the difference heat map was written.
    #[serde(skip)]
    pub heat_map: Option<String>,
}

fn load(path: &Path) -> Result<RgbImage, RunError> {
    RgbImage::load(path)
        .map_err(|e| RunError::Input(format!("cannot read image {}: {e}", path.display())))
}

/// Compares two image files; writes the difference heat map to `heat_map` if given;
/// `method_2` adds the plain-text PPM histograms.
pub fn compare_images(
    a: &Path,
    b: &Path,
    heat_map: Option<&Path>,
    method_2: bool,
) -> Result<ImageReport, RunError> {
    let (img_a, img_b) = (load(a)?, load(b)?);
    let metrics = compare(&img_a, &img_b)?;
    if let Some(out) = heat_map {
        let heat = difference_heat_map(&img_a, &img_b)?;
        tracer::image_io::write_rgb8(out, heat.width, heat.height, &heat.data)
            .map_err(|e| RunError::Input(e.to_string()))?;
    }
    let p3 = |img: &RgbImage| -> Result<Option<P3Histograms>, RunError> {
        Ok(if method_2 {
            Some(p3_histograms(&to_p3(img))?)
        } else {
            None
        })
    };
    Ok(ImageReport {
        a: a.display().to_string(),
        b: b.display().to_string(),
        p3_histograms_a: p3(&img_a)?,
        p3_histograms_b: p3(&img_b)?,
        metrics,
        heat_map: heat_map.map(|p| p.display().to_string()),
    })
}

impl Exports for ImageReport {
    /// The metrics as the command prints them.
    fn to_text(&self) -> String {
        use reports::format::{count, fixed, size};
        let m = &self.metrics;
        let mut out = format!("{} vs {} ({})\n", self.a, self.b, size(m.width, m.height));
        out += &format!("RMS            {} ({})\n", fixed(m.rms, 3), m.band.name());
        if m.psnr.is_finite() {
            out += &format!("PSNR           {} dB\n", fixed(m.psnr, 2));
        } else {
            out += "PSNR           infinite (identical)\n";
        }
        out += &format!("SSIM           {}\n", fixed(m.ssim, 5));
        out += &format!("max |diff|     {}\n", m.max_abs_diff);
        out += &format!("mean |diff|    {}\n", fixed(m.mean_abs_diff, 3));
        out += &format!(
            "differing px   {} of {}\n",
            count(m.differing_pixels),
            count(u64::from(m.width) * u64::from(m.height))
        );
        if let Some(path) = &self.heat_map {
            out += &format!("difference heat map: {path}\n");
        }
        out
    }

    /// One GitHub-flavoured Markdown row under its header.
    fn to_markdown(&self) -> String {
        let header = ["A", "B"].iter().chain(&IMAGE_COLUMNS);
        let cells: Vec<String> = [self.a.clone(), self.b.clone()]
            .into_iter()
            .chain(self.cells(false))
            .collect();
        let rule: Vec<&str> = header.clone().map(|_| "---").collect();
        format!(
            "| {} |\n| {} |\n| {} |\n",
            header.copied().collect::<Vec<_>>().join(" | "),
            rule.join(" | "),
            cells.join(" | ")
        )
    }

    /// A header and one row, numbers in full.
    fn to_csv(&self) -> String {
        let quote = |s: &str| format!("\"{}\"", s.replace('"', "\"\""));
        let header: Vec<String> = ["a", "b"]
            .iter()
            .chain(&IMAGE_COLUMNS)
            .map(|h| h.to_lowercase().replace([' ', '|'], "_"))
            .collect();
        let cells: Vec<String> = [quote(&self.a), quote(&self.b)]
            .into_iter()
            .chain(self.cells(true))
            .collect();
        format!("{}\n{}\n", header.join(","), cells.join(","))
    }
}

/// The metric columns of two images' Markdown and CSV forms.
const IMAGE_COLUMNS: [&str; 7] = [
    "RMS",
    "band",
    "PSNR dB",
    "SSIM",
    "max |diff|",
    "mean |diff|",
    "differing px",
];

impl ImageReport {
    /// The metrics in [`IMAGE_COLUMNS`]' order, rounded as the table prints them or
    /// in full (`full`); PSNR empty for identical images (infinite).
    fn cells(&self, full: bool) -> Vec<String> {
        use reports::format::fixed;
        let m = &self.metrics;
        let number = |v: f64, places: usize| {
            if full {
                v.to_string()
            } else {
                fixed(v, places)
            }
        };
        vec![
            number(m.rms, 3),
            m.band.name().to_string(),
            if m.psnr.is_finite() {
                number(m.psnr, 2)
            } else {
                String::new()
            },
            number(m.ssim, 5),
            m.max_abs_diff.to_string(),
            number(m.mean_abs_diff, 3),
            m.differing_pixels.to_string(),
        ]
    }
}
