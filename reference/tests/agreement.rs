//! The reference and the f32 tracer's baseline agree on SPD scenes: full Whitted colour,
//! 32×32 pixel centres, RMS of the 8-bit channel differences (analysis::compare) within
//! a per-scene bound measured on today's tracer (docs/reference.md lists the figures).
//!
//! The bounds are the measured RMS rounded up, not a loose common one: a change in
//! either renderer that moves a picture shows. Where the f32 tracer is known wrong (its
//! `b² - c` sphere discriminant on small far spheres, issue 35) the bound was wider;
//! with the robust f32 tests only lattice keeps one (its thin cylinders' silhouettes).

use analysis::{RgbImage, compare};
use std::path::PathBuf;
use tracer::{
    Frame, NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, render_variant,
};

/// Where a test scene comes from.
enum Source {
    /// A file of the shared SPD scenes.
    File(&'static str),
    /// An SPD program at a size factor, generated.
    Spd(&'static str, u32),
}

impl Source {
    fn load(&self) -> Scene {
        match *self {
            Source::File(name) => {
                let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                    .join("../../shared/spd")
                    .join(format!("{name}.nff"));
                tracer::load_nff(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            }
            Source::Spd(name, factor) => {
                let text = spd::generate(name, Some(factor)).unwrap_or_else(|e| panic!("{e}"));
                tracer::parse_nff(&text, &format!("spd:{name}:{factor}"))
                    .unwrap_or_else(|e| panic!("{e}"))
            }
        }
    }

    fn name(&self) -> String {
        match self {
            Source::File(name) => format!("{name}.nff"),
            Source::Spd(name, factor) => format!("spd:{name}:{factor}"),
        }
    }
}

fn image(frame: &Frame) -> RgbImage {
    RgbImage::new(frame.width, frame.height, frame.to_rgb8()).unwrap_or_else(|e| panic!("{e}"))
}

/// RMS (0-255) between the reference and the baseline on `scene`.
fn rms(scene: &Scene, options: &RenderOptions) -> f64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let (reference, baseline) = pool.install(|| {
        let r = reference::render(scene, options, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
        let b = render_variant::<NoCount>(scene, options, &VariantSet::default(), &|_| {})
            .unwrap_or_else(|e| panic!("{e}"));
        (r, b.rendered.frame)
    });
    compare(&image(&reference), &image(&baseline))
        .unwrap_or_else(|e| panic!("{e}"))
        .rms
}

/// The bound for scenes the f32 tracer renders right: a few channels may differ by a
/// level where a value rounds to 8 bits differently (one level in one channel of one
/// pixel of 32×32 is RMS 0.018).
const EXACT: f64 = 0.1;

#[test]
fn reference_and_baseline_agree_on_spd_scenes() {
    // (scene, RMS bound). Measured today (32×32): see docs/reference.md.
    let cases = [
        // Small spheres of the sphereflake (issue 35: 5.395 before the two-stage quadric
        // tests, 0.465 with them, 0.048 once a clearly positive first stage is kept).
        (Source::File("balls"), EXACT),
        (Source::File("gears"), EXACT),
        (Source::File("jacks"), EXACT),
        // Spheres and cylinders of radius 0.02-0.05 at distance ~6 (0.906 before, 0.272).
        (Source::File("lattice"), 0.35),
        (Source::File("mount"), EXACT),
        (Source::File("rings"), EXACT),
        (Source::File("sample"), EXACT),
        (Source::File("shells"), EXACT),
        (Source::File("sombrero"), EXACT),
        (Source::File("teapot"), EXACT),
        (Source::File("tetra"), EXACT),
        (Source::File("tree"), EXACT),
    ];
    let mut failures = Vec::new();
    for (source, bound) in cases {
        let scene = source.load();
        let options = RenderOptions::new(32, 32, Sampling::PixelCenters, ShadingMode::Color);
        let rms = rms(&scene, &options);
        println!("{:<20} RMS {rms:.3} (bound {bound})", source.name());
        if rms > bound || rms.is_nan() {
            failures.push(format!("{}: RMS {rms:.3} > {bound}", source.name()));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn reference_and_baseline_agree_in_every_shading_mode_and_with_corner_rays() {
    // Scenes without small quadrics (polygons, patches; glass spheres of radius ~0.5):
    // the modes and the SPD corner sampling follow the same rules.
    let modes = [
        (Sampling::PixelCenters, ShadingMode::Gray),
        (Sampling::PixelCenters, ShadingMode::DiffuseOnly),
        (Sampling::SpdCorners, ShadingMode::Color),
    ];
    let mut failures = Vec::new();
    for source in [Source::File("teapot"), Source::Spd("mount", 2)] {
        let scene = source.load();
        for (sampling, mode) in modes {
            let options = RenderOptions::new(24, 24, sampling, mode);
            let rms = rms(&scene, &options);
            println!("{:<12} {sampling:?} {mode:?}: RMS {rms:.3}", source.name());
            if rms > EXACT || rms.is_nan() {
                failures.push(format!(
                    "{} {sampling:?} {mode:?}: RMS {rms:.3}",
                    source.name()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
