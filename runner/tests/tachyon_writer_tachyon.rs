//! Tachyon draws rtprof's scene from rtprof's Tachyon file (`tracer::scene_to_tachyon_at`)
//! of each classic SPD scene (`../shared/spd/NAME.nff`): at 128x128 its picture is the
//! same scene as rtprof's own render by the likeness rules outside tracers are judged
//! by (`analysis::likeness`, as runner/src/outside/measure.rs uses it): `same` or
//! `other conventions`, never `different`. Each scene's likeness measures and its
//! channel RMS (0-255) are printed.
//!
//! Lives in the runner's tests because the likeness rules are the analysis crate's
//! (the tracer crate depends on no other workspace crate).
//!
//! Needs `tachyon` on PATH (Debian's `tachyon-bin-nox`, or TACHYON=path); `cargo test
//! -p runner --test tachyon_writer_tachyon -- --ignored --nocapture` prints the table.

use std::path::{Path, PathBuf};
use std::process::Command;

use analysis::{Likeness, RgbImage, likeness};
use tracer::{Bvh, NoCount, RenderMethod, RenderOptions};

/// The seven classic SPD scenes.
const SCENES: [&str; 7] = [
    "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
];

/// Picture width and height.
const SIZE: u32 = 128;

fn spd_scene(name: &str) -> tracer::Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../shared/spd/{name}.nff"));
    tracer::load_nff(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// rtprof's picture of `scene` at SIZE x SIZE (the baseline's camera and shading).
fn rtprof_picture(scene: &tracer::Scene) -> RgbImage {
    let mut options = RenderOptions::for_scene(scene);
    (options.width, options.height) = (SIZE, SIZE);
    let accel = Bvh::build(scene);
    let out =
        tracer::render::<NoCount, _>(scene, &accel, &options, &RenderMethod::default(), &|_| {})
            .unwrap_or_else(|e| panic!("{e}"));
    RgbImage::new(SIZE, SIZE, out.frame.to_rgb8()).unwrap_or_else(|e| panic!("{e}"))
}

/// Tachyon's picture of `text` (a Tachyon scene), run as runner/tracers/tachyon.toml
/// runs it, one thread.
fn tachyon_picture(dir: &Path, stem: &str, text: &str) -> RgbImage {
    let tachyon = std::env::var("TACHYON").unwrap_or_else(|_| "tachyon".to_string());
    let input = dir.join(format!("{stem}.dat"));
    let output = dir.join(format!("{stem}.tga"));
    std::fs::write(&input, text).unwrap_or_else(|e| panic!("{}: {e}", input.display()));
    let size = SIZE.to_string();
    let result = Command::new(&tachyon)
        .arg(&input)
        .args(["-res", &size, &size, "-numthreads", "1", "-shade_phong"])
        .args(["-format", "TARGA", "-o"])
        .arg(&output)
        .output()
        .unwrap_or_else(|e| panic!("{tachyon}: {e} (install Debian's tachyon-bin-nox)"));
    let log = String::from_utf8_lossy(&result.stdout);
    assert!(
        result.status.success() && output.is_file() && !log.contains("Parse Error"),
        "Tachyon failed on {stem} ({}):\n{log}",
        result.status
    );
    let picture = image::open(&output)
        .unwrap_or_else(|e| panic!("{}: {e}", output.display()))
        .to_rgb8();
    RgbImage::new(SIZE, SIZE, picture.into_raw()).unwrap_or_else(|e| panic!("{e}"))
}

/// Root mean square of the channel differences, 0-255 scale.
fn rms(a: &RgbImage, b: &RgbImage) -> f64 {
    let sum: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2))
        .sum();
    (sum / a.data.len() as f64).sqrt()
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-tachyon-writer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

#[test]
#[ignore = "needs tachyon"]
fn tachyon_draws_rtprofs_scene_from_rtprofs_file() {
    let dir = scratch();
    let mut failures = Vec::new();
    println!("scene    likeness           edge agreement  edges (Tachyon/rtprof)  tone RMS    RMS");
    for name in SCENES {
        let scene = spd_scene(name);
        let ours = rtprof_picture(&scene);
        let text = tracer::scene_to_tachyon_at(&scene, SIZE, SIZE);
        let theirs = tachyon_picture(&dir, name, &text);
        let verdict = likeness(&theirs, &ours).unwrap_or_else(|e| panic!("{e}"));
        let (word, m) = match &verdict {
            Likeness::Same { measures } => ("same", measures),
            Likeness::OtherConventions { measures } => ("other conventions", measures),
            Likeness::Different { measures, .. } => ("different", measures),
        };
        println!(
            "{name:8} {word:18} {:14.3}  {:>10}/{:<11} {:9.2} {:6.2}",
            m.edge_agreement,
            m.picture_edges,
            m.reference_edges,
            m.tone_rms,
            rms(&theirs, &ours)
        );
        if matches!(verdict, Likeness::Different { .. }) {
            failures.push(format!("{name}: {verdict:?}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        failures.is_empty(),
        "Tachyon drew another scene: {failures:?}"
    );
}
