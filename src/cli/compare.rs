//! `rtprof compare`: image metrics of two images, or a side-by-side run of variants on
//! one scene (time with a bootstrap interval, speed-up, image error, counts), all
//! against the first image or variant.

use super::scene_args::{LimitArgs, parse_size, thread_pool};
use analysis::{
    Band, Comparison, Estimate, P3Histograms, RgbImage, compare, difference_heat_map,
    median_with_bootstrap, p3_histograms, to_p3,
};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::path::{Path, PathBuf};
use tracer::image_io::write_rgb8;
use tracer::{
    Count, Counts, NoCount, RenderOptions, Sampling, ShadingMode, VariantSet, render_variant,
};

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// Two images (PNG or PPM) to compare, or one NFF scene with --variants.
    #[arg(required = true, num_args = 1..=2, value_name = "IMG_A IMG_B | SCENE")]
    inputs: Vec<PathBuf>,
    /// Variants to run on the scene, the first being the reference; combine with '+',
    /// e.g. baseline,bvh,bvh+fast-sqrt.
    #[arg(long, value_name = "A,B,…")]
    variants: Option<String>,
    /// Image size WxH (default: the scene's resolution).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Timed renders per variant (median and 95 % bootstrap interval).
    #[arg(long, value_name = "N", default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeats: u32,
    /// SPD procedure: rays through pixel corners, each pixel the mean of four.
    #[arg(long)]
    spd: bool,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
    #[command(flatten)]
    limits: LimitArgs,
    /// Print the result as JSON.
    #[arg(long)]
    json: bool,
    /// Images: the difference heat map (two images), or a directory for every variant's
    /// image and heat map (scene).
    #[arg(short, long, value_name = "DIFF.png | DIR")]
    output: Option<PathBuf>,
}

pub fn run(args: &CompareArgs) -> Result<()> {
    match (&args.variants, args.inputs.as_slice()) {
        (None, [a, b]) => compare_images(args, a, b),
        (Some(list), [scene]) => compare_variants(args, scene, list),
        (None, [_]) => bail!("give two images to compare, or a scene with --variants A,B,…"),
        (Some(_), _) => bail!("--variants takes one scene, not two inputs"),
        _ => bail!("give two images to compare, or a scene with --variants A,B,…"),
    }
}

fn load(path: &Path) -> Result<RgbImage> {
    RgbImage::load(path).with_context(|| format!("cannot read image {}", path.display()))
}

fn write_png(path: &Path, img: &RgbImage) -> Result<()> {
    Ok(write_rgb8(path, img.width, img.height, &img.data)?)
}

/// `compare IMG_A IMG_B --json`: the metrics (method 1 histograms included) and the
/// thesis's method 2, histograms computed from each image's plain-text PPM form.
#[derive(Serialize)]
struct ImageReport<'a> {
    #[serde(flatten)]
    metrics: &'a Comparison,
    p3_histograms_a: P3Histograms,
    p3_histograms_b: P3Histograms,
}

fn compare_images(args: &CompareArgs, a: &Path, b: &Path) -> Result<()> {
    let (img_a, img_b) = (load(a)?, load(b)?);
    let metrics = compare(&img_a, &img_b)?;
    if let Some(out) = &args.output {
        write_png(out, &difference_heat_map(&img_a, &img_b)?)?;
    }
    if args.json {
        let report = ImageReport {
            metrics: &metrics,
            p3_histograms_a: p3_histograms(&to_p3(&img_a))?,
            p3_histograms_b: p3_histograms(&to_p3(&img_b))?,
        };
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        println!(
            "{} vs {} ({}x{})",
            a.display(),
            b.display(),
            metrics.width,
            metrics.height
        );
        print_metrics(&metrics);
        if let Some(out) = &args.output {
            println!("difference heat map: {}", out.display());
        }
    }
    Ok(())
}

fn print_metrics(m: &Comparison) {
    println!("RMS            {:.3} ({})", m.rms, m.band.name());
    if m.psnr.is_finite() {
        println!("PSNR           {:.2} dB", m.psnr);
    } else {
        println!("PSNR           infinite (identical)");
    }
    println!("SSIM           {:.5}", m.ssim);
    println!("max |diff|     {}", m.max_abs_diff);
    println!("mean |diff|    {:.3}", m.mean_abs_diff);
    println!(
        "differing px   {} of {}",
        m.differing_pixels,
        u64::from(m.width) * u64::from(m.height)
    );
}

/// One variant's row of `compare SCENE --variants`.
#[derive(Serialize)]
struct VariantRow {
    name: String,
    seconds: Estimate,
    /// Preprocessing (scene preparation, structure build) of the first timed run.
    preprocessing_seconds: f64,
    /// Reference median / this median.
    speedup: f64,
    rms: f64,
    band: Band,
    /// `null` when the images are identical (infinite PSNR).
    psnr: Option<f64>,
    ssim: f64,
    max_abs_diff: u8,
    counts: Counts,
}

#[derive(Serialize)]
struct VariantsReport {
    scene: String,
    width: u32,
    height: u32,
    spd: bool,
    threads: usize,
    repeats: u32,
    reference: String,
    variants: Vec<VariantRow>,
}

fn compare_variants(args: &CompareArgs, scene_path: &Path, list: &str) -> Result<()> {
    let sets = list
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(VariantSet::parse)
        .collect::<Result<Vec<_>, _>>()?;
    if sets.is_empty() {
        bail!("--variants is empty: name at least one variant (e.g. baseline,bvh)");
    }
    if let Some(dir) = &args.output {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create directory {}", dir.display()))?;
    }
    let scene = args.limits.load(scene_path)?;
    let (width, height) = args.size.unwrap_or((scene.view.width, scene.view.height));
    let sampling = if args.spd {
        Sampling::SpdCorners
    } else {
        Sampling::PixelCenters
    };
    let mut options = RenderOptions::new(width, height, sampling, ShadingMode::Color);
    options.limits = args.limits.limits();
    let pool = thread_pool(args.threads)?;
    let threads = pool.current_num_threads();

    let renders_per_variant = u64::from(args.repeats) + 1;
    let bar = ProgressBar::new(sets.len() as u64 * renders_per_variant);
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} {msg:<24} [{bar:30}] {pos}/{len} renders, {elapsed}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    let fail = |e: tracer::RenderError| anyhow::anyhow!("{}: {e}", scene_path.display());

    struct Measured {
        name: String,
        seconds: Estimate,
        preprocessing: f64,
        image: RgbImage,
        counts: Counts,
    }
    let mut measured = Vec::with_capacity(sets.len());
    for (index, set) in sets.iter().enumerate() {
        bar.set_message(set.to_string());
        let mut times = Vec::with_capacity(args.repeats as usize);
        let mut image = None;
        let mut preprocessing = 0.0;
        for _ in 0..args.repeats {
            let out = pool
                .install(|| render_variant::<NoCount>(&scene, &options, set, &|_| {}))
                .map_err(fail)?;
            times.push((out.preprocessing + out.tracing).as_secs_f64());
            if image.is_none() {
                preprocessing = out.preprocessing.as_secs_f64();
                let frame = &out.rendered.frame;
                image = Some(RgbImage::new(frame.width, frame.height, frame.to_rgb8())?);
            }
            bar.inc(1);
        }
        let counted = pool
            .install(|| render_variant::<Count>(&scene, &options, set, &|_| {}))
            .map_err(fail)?;
        let counts = counted
            .rendered
            .counts()
            .context("the counted render returned no counts")?;
        bar.inc(1);
        let seconds = median_with_bootstrap(&times, 10_000, 0.95, 0x5EED + index as u64)?;
        let image = image.context("no timed render ran")?;
        if let Some(dir) = &args.output {
            write_png(&dir.join(format!("{set}.png")), &image)?;
        }
        measured.push(Measured {
            name: set.to_string(),
            seconds,
            preprocessing,
            image,
            counts,
        });
    }
    bar.finish_and_clear();

    let reference = &measured[0];
    let mut rows = Vec::with_capacity(measured.len());
    for m in &measured {
        let metrics = compare(&reference.image, &m.image)?;
        if let (Some(dir), false) = (&args.output, std::ptr::eq(m, reference)) {
            let heat = difference_heat_map(&reference.image, &m.image)?;
            write_png(&dir.join(format!("{}-diff.png", m.name)), &heat)?;
        }
        rows.push(VariantRow {
            name: m.name.clone(),
            seconds: m.seconds,
            preprocessing_seconds: m.preprocessing,
            speedup: reference.seconds.median / m.seconds.median.max(1e-12),
            rms: metrics.rms,
            band: metrics.band,
            psnr: metrics.psnr.is_finite().then_some(metrics.psnr),
            ssim: metrics.ssim,
            max_abs_diff: metrics.max_abs_diff,
            counts: m.counts,
        });
    }
    let report = VariantsReport {
        scene: scene_path.display().to_string(),
        width,
        height,
        spd: args.spd,
        threads,
        repeats: args.repeats,
        reference: reference.name.clone(),
        variants: rows,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_variants(&report);
    }
    Ok(())
}

fn print_variants(r: &VariantsReport) {
    println!(
        "{}: {}x{}{}, {} thread{}, {} repeat{}, against {}",
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
    println!(
        "{:<width$}  {:>9}  {:>21}  {:>8}  {:>7}  {:<17}  {:>7}  {:>7}  {:>12}  {:>8}",
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
        println!(
            "{:<width$}  {:>9.4}  [{:>9.4}, {:>9.4}]  {:>7.2}x  {:>7.3}  {:<17}  {:>7}  {:>7.4}  {:>12}  {:>8}",
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
}
