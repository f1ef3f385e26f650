//! The generated pipeline simulated with Verilator against the model: the picture
//! equal to the emulator's bit for bit, the cycles per frame equal to the model's
//! frame timing, each block's latency as built equal to its schedule.
//!
//! Needs `verilator`, `g++` and `make` (`scripts/install-rtl-tools.sh`), so ignored by
//! default: `cargo test -p rtl --test pipeline -- --ignored`. `RTPROF_SIM_SIZE=WxH`
//! and `RTPROF_SIM_SCENES=all` widen the run to the acceptance check (21 scenes at
//! 160x120); the default is a small frame of a few scenes.

use std::path::{Path, PathBuf};

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;
use rtl::{generate, sim};

fn scene(name: &str) -> HwScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(format!("{name}.nff"));
    let s = tracer::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
    HwScene::from_scene(&s).unwrap_or_else(|e| panic!("{e}"))
}

fn size() -> (u32, u32) {
    std::env::var("RTPROF_SIM_SIZE")
        .ok()
        .and_then(|s| {
            let (w, h) = s.split_once('x')?;
            Some((w.parse().ok()?, h.parse().ok()?))
        })
        .unwrap_or((40, 30))
}

fn scenes(default: &[&str]) -> Vec<String> {
    if std::env::var("RTPROF_SIM_SCENES").as_deref() == Ok("all") {
        ["balls", "cylinder", "both"]
            .iter()
            .flat_map(|f| (1..=7).map(move |n| format!("{f}{n}")))
            .collect()
    } else {
        default.iter().map(|s| s.to_string()).collect()
    }
}

fn build_root() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../target"));
    target.join("rtl-sim")
}

/// Simulates `names` on `design`; `test` keeps the runs of parallel tests apart.
fn check(test: &str, design: Design, names: &[String]) -> Vec<(String, u64, u64)> {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &design);
    let rtl = generate::generate(&lib, &pipeline, 6).unwrap_or_else(|e| panic!("{e}"));
    let program = sim::build(&rtl, &build_root()).unwrap_or_else(|e| panic!("{e}"));
    let (width, height) = size();
    let mut measured = Vec::new();
    for name in names {
        let hw = scene(name);
        let work = build_root()
            .join("runs")
            .join(format!("{test}-{name}-{}", design.label()));
        let started = std::time::Instant::now();
        let result = sim::run(&program, &pipeline, &hw, width, height, &work)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let (reference, source) =
            sim::reference_image(&pipeline, &hw, width, height).unwrap_or_else(|e| panic!("{e}"));
        let diff = sim::compare_images(&result.image, &reference);
        eprintln!(
            "{name} ({}, {width}x{height}): cycles {} (model {}), {} of {} pixels differ from {source}, latencies {:?}, {:.1} s",
            design.label(),
            result.cycles,
            result.model_cycles,
            diff.differing_pixels,
            reference.pixels.len(),
            result
                .blocks
                .iter()
                .map(|b| (b.name.as_str(), b.simulated, b.model))
                .collect::<Vec<_>>(),
            started.elapsed().as_secs_f64()
        );
        assert_eq!(
            result.writes,
            u64::from(width * height),
            "{name}: pixels written"
        );
        assert_eq!(diff.differing_pixels, 0, "{name}: image");
        assert_eq!(
            result.cycles, result.model_cycles,
            "{name}: cycles per frame"
        );
        for b in &result.blocks {
            assert_eq!(
                b.simulated,
                Some(u64::from(b.model)),
                "{name}: {} latency",
                b.name
            );
        }
        measured.push((name.clone(), result.cycles, hw.primitive_count() as u64));
    }
    measured
}

#[test]
#[ignore = "needs verilator"]
fn the_thesis_pipeline_simulates_to_the_emulators_picture_and_the_models_cycles() {
    check(
        "thesis",
        Design::thesis(),
        &scenes(&["balls2", "cylinder3", "both7"]),
    );
}

#[test]
#[ignore = "needs verilator"]
fn two_units_halve_the_cycles_per_pixel() {
    let names = scenes(&["balls2", "both7"]);
    let one = check("units", Design::thesis(), &names);
    let two = check(
        "units",
        Design {
            units: 2,
            ..Design::thesis()
        },
        &names,
    );
    let (width, height) = size();
    let pixels = u64::from(width * height);
    for ((name, c1, n), (_, c2, _)) in one.iter().zip(&two) {
        // Per pixel: 3n cycles with one unit, 3⌈n/2⌉ with two (the fill aside).
        let per_pixel_one = c1 / pixels;
        let per_pixel_two = c2 / pixels;
        assert_eq!(per_pixel_one, 3 * n, "{name}");
        assert_eq!(per_pixel_two, 3 * n.div_ceil(2), "{name}");
    }
}
