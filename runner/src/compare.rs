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
    pub rms: f64,
    pub band: Band,
    /// `null` when the images are identical (infinite PSNR).
    pub psnr: Option<f64>,
    pub ssim: f64,
    pub max_abs_diff: u8,
    pub counts: Counts,
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
}

impl SideBySide<'_> {
    /// Loads the scene, sets up the pool and runs [`compare_variants`].
    pub fn run(&self, progress: &dyn Progress) -> Result<VariantsReport, RunError> {
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
        compare_variants(
            &setup,
            self.sets,
            &policy,
            self.out,
            self.f64_reference,
            progress,
        )
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
    let variants = variant_rows(setup, sets, policy, out, truth_image, progress)?;
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
    })
}

fn variant_rows(
    setup: &RenderSetup<'_>,
    sets: &[VariantSet],
    policy: &TimingPolicy,
    out: Option<&Path>,
    truth: Option<&RgbImage>,
    progress: &dyn Progress,
) -> Result<Vec<VariantRow>, RunError> {
    progress.begin("variants", 0);
    let all = setup.measure_all(
        sets,
        policy,
        false,
        &|what| progress.message(what),
        &|done, total| progress.within(crate::progress::TIMED, done, total),
    )?;
    progress.end();
    let measured: Vec<VariantMeasurement> = all.variants.into_iter().collect::<Result<_, _>>()?;
    let Some(reference) = measured.first() else {
        return Ok(Vec::new());
    };
    let mut rows = Vec::with_capacity(measured.len());
    for (index, m) in measured.iter().enumerate() {
        if let Some(dir) = out {
            save_png(dir, &format!("{}.png", m.variants), &m.image)?;
        }
        let metrics = compare(&reference.image, &m.image)?;
        if let (Some(dir), true) = (out, index > 0) {
            let heat = difference_heat_map(&reference.image, &m.image)?;
            save_png(dir, &format!("{}-diff.png", m.variants), &heat)?;
        }
        let (vs_f64_reference, vs_f64_quality) = match truth {
            Some(truth) => {
                if let Some(dir) = out {
                    let heat = difference_heat_map(truth, &m.image)?;
                    save_png(dir, &format!("{}-vs-f64.png", m.variants), &heat)?;
                }
                (
                    Some(ImageError::between(truth, &m.image)?),
                    Some(crate::collect::quality(&compare(truth, &m.image)?)),
                )
            }
            None => (None, None),
        };
        let speedup = results::change::speedup(&reference.samples, &m.samples);
        rows.push(VariantRow {
            name: m.variants.to_string(),
            seconds: m.time,
            preprocessing_seconds: m.preprocessing,
            speedup: speedup.unwrap_or(Estimate {
                median: f64::NAN,
                low: f64::NAN,
                high: f64::NAN,
            }),
            verdict: speedup
                .filter(|_| index > 0)
                .map(|s| judge_speedup(&s, NOISE_THRESHOLD)),
            rms: metrics.rms,
            band: metrics.band,
            psnr: metrics.psnr.is_finite().then_some(metrics.psnr),
            ssim: metrics.ssim,
            max_abs_diff: metrics.max_abs_diff,
            counts: m.counts,
            vs_f64_reference,
            samples: m.samples.clone(),
            variant: VariantName::of(&m.variants),
            vs_f64_quality,
        });
    }
    Ok(rows)
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
                preprocessing_seconds: Some(v.preprocessing_seconds),
                speedup: Some(v.speedup.median).filter(|s| s.is_finite()),
                speedup_interval: v
                    .speedup
                    .median
                    .is_finite()
                    .then_some([v.speedup.low, v.speedup.high]),
                verdict: v.verdict,
                counts: crate::collect::count_map(&v.counts),
                image: None,
                heat_map: None,
                quality: Some(Quality {
                    rms: v.rms,
                    band: v.band,
                    psnr: v.psnr,
                    ssim: v.ssim,
                    max_abs_diff: u32::from(v.max_abs_diff),
                }),
                vs_f64_reference: v.vs_f64_quality.clone(),
                histogram: Vec::new(),
                lane_utilization: None,
                efficiency: None,
                ray_rates: None,
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

impl Exports for VariantsReport {
    /// The table the command prints.
    fn to_text(&self) -> String {
        self.heading() + &reports::text::table(&self.table())
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

impl ImageReport {
    /// The metrics as the command prints them.
    pub fn to_text(&self) -> String {
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
}
