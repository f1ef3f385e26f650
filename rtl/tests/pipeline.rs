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
use hwmodel::design::{Design, MinDistance};
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

/// One scene's simulated frame: its name, cycles, primitives, the sum of its blocks'
/// latencies as built (the monitors') and the gray levels in its picture.
struct Measured {
    name: String,
    cycles: u64,
    primitives: u64,
    latencies: u64,
    levels: usize,
}

/// Simulates `names` on `design` at the test size; `test` keeps the runs of parallel
/// tests apart.
fn check(test: &str, design: Design, names: &[String]) -> Vec<Measured> {
    check_at(test, design, names, size())
}

/// Simulates `names` on `design` at `width`×`height`: the picture, the cycles and the
/// latencies against the model and the emulator.
fn check_at(
    test: &str,
    design: Design,
    names: &[String],
    (width, height): (u32, u32),
) -> Vec<Measured> {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &design);
    let rtl = generate::generate(&lib, &pipeline, 6).unwrap_or_else(|e| panic!("{e}"));
    let program = sim::build(&rtl, &build_root()).unwrap_or_else(|e| panic!("{e}"));
    let mut measured = Vec::new();
    for name in names {
        let hw = scene(name);
        let work = build_root()
            .join("runs")
            .join(format!("{test}-{name}-{}-{width}x{height}", design.label()));
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
        measured.push(Measured {
            name: name.clone(),
            cycles: result.cycles,
            primitives: hw.primitive_count() as u64,
            latencies: result.blocks.iter().filter_map(|b| b.simulated).sum(),
            levels: result
                .image
                .pixels
                .iter()
                .collect::<std::collections::BTreeSet<_>>()
                .len(),
        });
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
    for (a, b) in one.iter().zip(&two) {
        // Per pixel: 3n cycles with one unit, 3⌈n/2⌉ with two (the fill aside).
        let per_pixel_one = a.cycles / pixels;
        let per_pixel_two = b.cycles / pixels;
        assert_eq!(per_pixel_one, 3 * a.primitives, "{}", a.name);
        assert_eq!(per_pixel_two, 3 * a.primitives.div_ceil(2), "{}", a.name);
    }
}

/// The thesis's test bench: balls1 … balls7, cylinder1 … cylinder7, both1 … both7.
fn test_bench() -> Vec<String> {
    ["balls", "cylinder", "both"]
        .iter()
        .flat_map(|f| (1..=7).map(move |n| format!("{f}{n}")))
        .collect()
}

fn int_compare(units: u32) -> Design {
    Design {
        units,
        min_distance: MinDistance::IntegerCompare,
        ..Design::thesis()
    }
}

/// Cycles between two pixels' issues as built: a frame is W·H issues p apart, the
/// last pixel's last slot r(c − 1) after its issue, then the blocks' latencies (as the
/// monitors measured them), so p = (cycles + r − latencies) / (W·H), exactly.
fn cycles_per_pixel_as_built(m: &Measured, rate: u64, pixels: u64) -> u64 {
    let issues = m.cycles + rate - m.latencies;
    assert_eq!(issues % pixels, 0, "{}: {issues} cycles of issues", m.name);
    issues / pixels
}

/// The integer compare on the whole test bench (21 scenes; each simulates in well
/// under a second at 40x30): the emulator's picture, the model's cycles, and a slot
/// every cycle, n cycles a pixel with one unit and ⌈n/2⌉ with two (the thesis: 3n).
#[test]
#[ignore = "needs verilator"]
fn the_integer_compare_takes_a_primitive_a_cycle_on_the_test_bench() {
    let names = test_bench();
    let (width, height) = size();
    let pixels = u64::from(width * height);
    for units in [1, 2] {
        for m in check("int-compare", int_compare(units), &names) {
            let per_pixel = cycles_per_pixel_as_built(&m, 1, pixels);
            eprintln!("{} (K = {units}): {per_pixel} cycles a pixel", m.name);
            assert_eq!(
                per_pixel,
                m.primitives.max(1).div_ceil(u64::from(units)),
                "{}",
                m.name
            );
        }
    }
}

/// Rows as short as they come: one pixel a cycle on one-primitive scenes, frames one,
/// two and five pixels wide, and the thesis's design one pixel wide. A row's base is
/// then started rows ahead (the row path is 14 cycles), which counting rows once per
/// row base did not do (its pictures differed below 16 cycles a row).
#[test]
#[ignore = "needs verilator"]
fn one_pixel_a_cycle_works_down_to_a_frame_one_pixel_wide() {
    let scenes = ["balls1", "cylinder1", "cylinder3"].map(String::from);
    let shaded = |m: &Measured| {
        // Background alone would not show a wrong row base.
        assert!(m.levels > 2, "{}: {} gray levels", m.name, m.levels);
    };
    for size in [(1, 24), (2, 12), (5, 6)] {
        for m in check_at("narrow", int_compare(1), &scenes, size) {
            shaded(&m);
            let pixels = u64::from(size.0 * size.1);
            assert_eq!(
                cycles_per_pixel_as_built(&m, 1, pixels),
                m.primitives,
                "{}",
                m.name
            );
        }
    }
    check_at("narrow", Design::thesis(), &scenes, (1, 24))
        .iter()
        .for_each(shaded);
}
