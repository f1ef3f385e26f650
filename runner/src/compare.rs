//! Variants side by side on one scene (`rtprof compare SCENE --variants A,B,…`): each
//! measured by the variant job under the one timing policy, then compared with the
//! first (the reference): speed-up, image error, counts.

use std::path::Path;

use analysis::{
    Band, Comparison, Estimate, P3Histograms, RgbImage, compare, difference_heat_map,
    p3_histograms, to_p3,
};
use serde::Serialize;
use tracer::{Counts, VariantSet};

use crate::error::RunError;
use crate::progress::Progress;
use crate::staging::save_png;
use crate::timing::TimingPolicy;
use crate::variant_job::{RenderSetup, VariantMeasurement};

/// One variant's row.
#[derive(Serialize)]
pub struct VariantRow {
    pub name: String,
    /// Tracing seconds: median and 95 % interval.
    pub seconds: Estimate,
    /// Median preprocessing seconds (scene preparation, structure build), apart.
    pub preprocessing_seconds: f64,
    /// Reference median / this median.
    pub speedup: f64,
    pub rms: f64,
    pub band: Band,
    /// `null` when the images are identical (infinite PSNR).
    pub psnr: Option<f64>,
    pub ssim: f64,
    pub max_abs_diff: u8,
    pub counts: Counts,
}

/// Measures every set in `sets` (the first is the reference) and compares them. With
/// `out`, each variant's image and its heat map against the reference are written there.
pub fn compare_variants(
    setup: &RenderSetup<'_>,
    sets: &[VariantSet],
    policy: &TimingPolicy,
    out: Option<&Path>,
    progress: &dyn Progress,
) -> Result<VariantsReport, RunError> {
    let reference = sets.first().ok_or_else(|| {
        RunError::Input("no variants: name at least one (e.g. baseline,bvh)".into())
    })?;
    let variants = variant_rows(setup, sets, policy, out, progress)?;
    Ok(VariantsReport {
        scene: setup.name.to_string(),
        width: setup.options.width,
        height: setup.options.height,
        spd: setup.options.sampling == tracer::Sampling::SpdCorners,
        threads: setup.pool.current_num_threads(),
        repeats: policy.min_repeats,
        time_covers: "tracing",
        reference: reference.to_string(),
        variants,
    })
}

fn variant_rows(
    setup: &RenderSetup<'_>,
    sets: &[VariantSet],
    policy: &TimingPolicy,
    out: Option<&Path>,
    progress: &dyn Progress,
) -> Result<Vec<VariantRow>, RunError> {
    progress.begin("variants", sets.len() as u64);
    let mut measured: Vec<VariantMeasurement> = Vec::with_capacity(sets.len());
    for set in sets {
        progress.message(&set.to_string());
        let m = setup.measure(set, policy)?;
        if let Some(dir) = out {
            save_png(dir, &format!("{set}.png"), &m.image)?;
        }
        measured.push(m);
        progress.advance(1);
    }
    progress.end();
    let Some(reference) = measured.first() else {
        return Ok(Vec::new());
    };
    let mut rows = Vec::with_capacity(measured.len());
    for (index, m) in measured.iter().enumerate() {
        let metrics = compare(&reference.image, &m.image)?;
        if let (Some(dir), true) = (out, index > 0) {
            let heat = difference_heat_map(&reference.image, &m.image)?;
            save_png(dir, &format!("{}-diff.png", m.variants), &heat)?;
        }
        rows.push(VariantRow {
            name: m.variants.to_string(),
            seconds: m.time,
            preprocessing_seconds: m.preprocessing,
            speedup: reference.time.median / m.time.median.max(1e-12),
            rms: metrics.rms,
            band: metrics.band,
            psnr: metrics.psnr.is_finite().then_some(metrics.psnr),
            ssim: metrics.ssim,
            max_abs_diff: metrics.max_abs_diff,
            counts: m.counts,
        });
    }
    Ok(rows)
}

/// `rtprof compare SCENE --variants`: the setting and one row per variant.
#[derive(Serialize)]
pub struct VariantsReport {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub spd: bool,
    pub threads: usize,
    pub repeats: u32,
    /// What `seconds` covers: tracing only (preprocessing is `preprocessing_seconds`).
    pub time_covers: &'static str,
    pub reference: String,
    pub variants: Vec<VariantRow>,
}

impl VariantsReport {
    /// The table the command prints.
    pub fn to_text(&self) -> String {
        let r = self;
        let mut out = String::new();
        out += &format!(
            "{}: {}x{}{}, {} thread{}, {} repeat{}, against {}\n",
            r.scene,
            r.width,
            r.height,
            if r.spd { " (SPD)" } else { "" },
            r.threads,
            if r.threads == 1 { "" } else { "s" },
            r.repeats,
            if r.repeats == 1 { "" } else { "s" },
            r.reference
        );
        let width = r
            .variants
            .iter()
            .map(|v| v.name.len())
            .max()
            .unwrap_or(8)
            .max(7);
        out += &format!(
            "{:<width$}  {:>9}  {:>21}  {:>8}  {:>7}  {:<17}  {:>7}  {:>7}  {:>12}  {:>8}\n",
            "variant",
            "median s",
            "95 % interval",
            "speedup",
            "RMS",
            "band",
            "PSNR",
            "SSIM",
            "tests",
            "rays"
        );
        let reference_rays = r.variants.first().map(|v| v.counts.rays);
        for v in &r.variants {
            let t = &v.counts.tests;
            let tests =
                t.sphere.tests + t.cylinder.tests + t.cone.tests + t.polygon.tests + t.patch.tests;
            let psnr = v.psnr.map_or("inf".to_string(), |p| format!("{p:.1}"));
            let rays = if Some(v.counts.rays) == reference_rays {
                "same"
            } else {
                "differ"
            };
            out += &format!(
                "{:<width$}  {:>9.4}  [{:>9.4}, {:>9.4}]  {:>7.2}x  {:>7.3}  {:<17}  {:>7}  {:>7.4}  {:>12}  {:>8}\n",
                v.name,
                v.seconds.median,
                v.seconds.low,
                v.seconds.high,
                v.speedup,
                v.rms,
                v.band.name(),
                psnr,
                v.ssim,
                tests,
                rays
            );
        }
        out
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
        let m = &self.metrics;
        let mut out = format!("{} vs {} ({}x{})\n", self.a, self.b, m.width, m.height);
        out += &format!("RMS            {:.3} ({})\n", m.rms, m.band.name());
        if m.psnr.is_finite() {
            out += &format!("PSNR           {:.2} dB\n", m.psnr);
        } else {
            out += "PSNR           infinite (identical)\n";
        }
        out += &format!("SSIM           {:.5}\n", m.ssim);
        out += &format!("max |diff|     {}\n", m.max_abs_diff);
        out += &format!("mean |diff|    {:.3}\n", m.mean_abs_diff);
        out += &format!(
            "differing px   {} of {}\n",
            m.differing_pixels,
            u64::from(m.width) * u64::from(m.height)
        );
        if let Some(path) = &self.heat_map {
            out += &format!("difference heat map: {path}\n");
        }
        out
    }
}
