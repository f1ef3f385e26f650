//! The thesis's whole system simulated and synthesized: a scene uploaded through the
//! UART pin as a bit-level serial waveform, rendered by the generated pipeline and read
//! back from the VGA pins is the emulator's picture; the VGA controller's timing at
//! the standard's parameters is 640 × 480 at 60 Hz as VESA publishes it; the loader
//! turns the bytes of the upload into the words the serializer put in; the loader and
//! the VGA controller synthesize shallow enough for 50 MHz.
//!
//! Needs `verilator`, `g++`, `make` and `yosys` (`scripts/install-rtl-tools.sh`), so
//! ignored by default: `cargo test -p rtl --test system -- --ignored`. The whole
//! system's model takes a few minutes to build (it holds the pipeline); the rest take
//! seconds.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;
use rtl::sim;
use rtl::synth::{self, fmax};
use rtl::system::run::{self, LoaderRun};
use rtl::system::uart;
use rtl::system::vga::{VgaTiming, decode};
use rtl::system::{SOURCES, SystemConfig, generate_system};

fn scene(name: &str) -> HwScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(format!("{name}.nff"));
    let s = tracer::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
    HwScene::from_scene(&s).unwrap_or_else(|e| panic!("{e}"))
}

fn build_root() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../target"));
    target.join("rtl-sim")
}

fn work(name: &str) -> PathBuf {
    build_root()
        .join("runs")
        .join(format!("system-{name}-{}", std::process::id()))
}

/// The frame of the whole-system test: the timing generator at 80 × 60.
const FRAME: (u32, u32) = (80, 60);

/// (a) A test-bench scene through the UART pin, the pipeline and the VGA pins.
#[test]
#[ignore = "needs verilator"]
fn a_scene_sent_through_the_uart_comes_out_of_the_vga_as_the_emulators_picture() {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &Design::thesis());
    let timing = VgaTiming::small(FRAME.0, FRAME.1);
    // 16 cycles a bit: the same receiver as 434 (115,200 baud at 50 MHz), an upload
    // the simulation runs through quickly (the loader test below runs 434).
    let config = SystemConfig {
        timing,
        clocks_per_bit: 16,
        depth_bits: sim::depth_bits_for(7),
    };
    let system = generate_system(&lib, &pipeline, config).unwrap_or_else(|e| panic!("{e}"));
    let started = Instant::now();
    let program = run::build_system(&system, &build_root()).unwrap_or_else(|e| panic!("{e}"));
    let built = started.elapsed();
    let hw = scene("both7");
    let started = Instant::now();
    let out = run::simulate_scene(&program, &system, &pipeline, &hw, 16.0, &work("both7"))
        .unwrap_or_else(|e| panic!("{e}"));
    let (reference, source) =
        sim::reference_image(&pipeline, &hw, FRAME.0, FRAME.1).unwrap_or_else(|e| panic!("{e}"));
    let diff = sim::compare_images(&out.frame.image, &reference);
    eprintln!(
        "both7 at {}x{}: {} bytes uploaded (line idle at cycle {}), loaded at {:?}, done at {:?} \
         (prologue {}, model {} cycles); VGA {:?}; {} of {} pixels differ from {source}; \
         built in {:.0} s, ran in {:.1} s",
        FRAME.0,
        FRAME.1,
        out.stream_bytes,
        out.tx_end,
        out.loaded,
        out.done,
        system.pipeline.prologue,
        hwmodel::frame_timing::frame_timing(&pipeline, 7, FRAME.0, FRAME.1, 1.0).cycles,
        out.frame.measurement,
        diff.differing_pixels,
        reference.pixels.len(),
        built.as_secs_f64(),
        started.elapsed().as_secs_f64()
    );
    assert!(!out.load_error, "the loader reported an error");
    let loaded = out.loaded.expect("the upload never completed");
    // The CRC is the stream's last byte: loaded within a bit or so of its stop bit.
    assert!(
        loaded <= out.tx_end && loaded + 2 * 16 >= out.tx_end,
        "loaded {loaded}, line idle {}",
        out.tx_end
    );
    let done = out.done.expect("the frame never finished");
    let model = hwmodel::frame_timing::frame_timing(&pipeline, 7, FRAME.0, FRAME.1, 1.0).cycles;
    // `loaded` is `start`: the top counts its prologue (P cycles) and issues the first
    // pixel one cycle later; the model's cycles run from that issue to the last
    // frame-buffer write; `done` rises the cycle after it (the write counter).
    let prologue = u64::from(system.pipeline.prologue);
    assert_eq!(
        done,
        loaded + prologue + 1 + model + 1,
        "done {done}, loaded {loaded}, prologue {prologue}, model {model}"
    );
    assert!(out.frame.measurement.matches(&timing));
    assert_eq!(out.frame.measurement.blank_not_black, 0);
    assert_eq!(out.frame.measurement.not_gray, 0);
    assert_eq!(
        (out.frame.image.width, out.frame.image.height),
        FRAME,
        "frame size"
    );
    assert_eq!(diff.differing_pixels, 0, "the picture on the VGA pins");
    let _ = std::fs::remove_dir_all(work("both7"));
}

/// (b) The VGA controller alone at the standard's parameters, for two frames.
#[test]
#[ignore = "needs verilator"]
fn the_vga_timing_is_640x480_at_60_hz_as_vesa_publishes_it() {
    let timing = VgaTiming::VESA_640X480_60;
    let program = run::build_vga(&build_root(), &timing).unwrap_or_else(|e| panic!("{e}"));
    // A frame memory of seeded noise: every pixel must land where it belongs.
    let mut rng = fastrand::Rng::with_seed(38);
    let frame: Vec<u8> = (0..640 * 480).map(|_| rng.u8(..)).collect();
    let started = Instant::now();
    let pins = run::run_vga(&program, &frame, 2 * 800 * 525 + 1600, &work("vga"))
        .unwrap_or_else(|e| panic!("{e}"));
    let d = decode(&pins).unwrap_or_else(|e| panic!("{e}"));
    let m = d.measurement;
    eprintln!(
        "VGA at the standard's parameters: {m:?}, {:.1} s",
        started.elapsed().as_secs_f64()
    );
    // VESA DMT, 640 x 480 at 60 Hz: 25.175 MHz; lines of 800 clocks (640 visible,
    // front porch 16, sync 96, back porch 48); frames of 525 lines (480 visible, front
    // porch 10, sync 2, back porch 33); both syncs negative.
    assert!(m.hsync_negative && m.vsync_negative, "sync polarity");
    assert_eq!(m.line_clocks, 800);
    assert_eq!(
        (m.h_visible, m.h_front, m.hsync_clocks, m.h_back),
        (640, 16, 96, 48)
    );
    assert_eq!(m.frame_lines, 525);
    assert_eq!(
        (m.v_visible, m.v_front, m.vsync_lines, m.v_back),
        (480, 10, 2, 33)
    );
    // 25.175 MHz / (800 × 525) = 59.94 Hz, the mode's frame rate.
    let rate = 25.175e6 / (m.line_clocks * m.frame_lines) as f64;
    assert!((rate - 59.94).abs() < 0.01, "{rate} Hz");
    assert_eq!((m.blank_not_black, m.not_gray), (0, 0));
    assert_eq!(d.image.pixels, frame, "the picture is the frame memory");
    let _ = std::fs::remove_dir_all(work("vga"));
}

/// (c) The loader alone at 115,200 baud and 50 MHz: the words the serializer put in
/// arrive at their addresses, with the sender's clock off by ±3 %, after noise on the
/// line; a corrupted byte is refused.
#[test]
#[ignore = "needs verilator"]
fn the_uart_loader_writes_the_words_the_serializer_sent() {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &Design::thesis());
    let frame = (40, 30);
    let setup = sim::frame_setup(&pipeline, &scene("both7"), frame.0, frame.1)
        .unwrap_or_else(|e| panic!("{e}"));
    let stream = uart::scene_stream(&setup).unwrap_or_else(|e| panic!("{e}"));
    let cpb = uart::clocks_per_bit(uart::SYSTEM_CLOCK_HZ, uart::DEFAULT_BAUD).unwrap();
    let program =
        run::build_loader(&build_root(), cpb, 6, 9, frame).unwrap_or_else(|e| panic!("{e}"));
    let (writes, registers) = LoaderRun::expected(&setup);
    let header = uart::header_words(&setup).unwrap();
    let dir = work("loader");
    let started = Instant::now();
    // A sender exact, 3 % slow, 3 % fast; then noise first: a byte of 0x00 (a start
    // bit and eight zeros) and the magic's first half.
    let mut noisy = vec![0x00, b'R', b'T'];
    noisy.extend_from_slice(&stream);
    for (what, bytes, rate) in [
        ("exact", &stream, 1.0),
        ("3 % slow", &stream, 1.03),
        ("3 % fast", &stream, 0.97),
        ("after noise", &noisy, 1.0),
    ] {
        let run = run::run_loader(&program, bytes, f64::from(cpb) * rate, &dir)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(run.writes, writes, "{what}: memory writes");
        assert_eq!(run.registers, registers, "{what}: frame registers");
        assert_eq!(run.vectors, header[3..], "{what}: vectors");
        assert!(run.loaded.is_some() && !run.error, "{what}: {run:?}");
        assert_eq!(run.errors, 0, "{what}");
    }
    // One bit flipped in a memory word: the words arrive (one of them wrong), the CRC
    // does not match, `loaded` never rises.
    let mut bad = stream.clone();
    bad[4 + 4 * uart::HEADER_WORDS + 10] ^= 0x04;
    let run = run::run_loader(&program, &bad, f64::from(cpb), &dir).unwrap();
    assert_eq!(run.writes.len(), writes.len());
    assert_ne!(run.writes, writes);
    assert!(
        run.loaded.is_none() && run.error && run.errors == 1,
        "{run:?}"
    );
    // A header the memory cannot hold (prim_count 65 > 2^6): refused at H2.
    let mut big = setup.clone();
    big.prim_count = 65;
    big.words = vec![vec![0; 9]; 65];
    let run = run::run_loader(
        &program,
        &uart::scene_stream(&big).unwrap(),
        f64::from(cpb),
        &dir,
    )
    .unwrap();
    assert!(
        run.writes.is_empty() && run.error && run.loaded.is_none(),
        "{run:?}"
    );
    // 12 % slow: the stop bit is sampled past its end; the upload is refused.
    let run = run::run_loader(&program, &stream, f64::from(cpb) * 1.12, &dir).unwrap();
    assert!(run.loaded.is_none(), "{run:?}");
    eprintln!(
        "loader: {} bytes at {cpb} cycles a bit ({:.3} s on the line at 115,200 baud), 7 runs in {:.1} s",
        stream.len(),
        uart::upload_seconds(stream.len(), uart::DEFAULT_BAUD),
        started.elapsed().as_secs_f64()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The two new blocks through Yosys's default Cyclone IV E flow: LUT4, flip-flops and
/// the longest path between registers, at the thesis's parameters.
#[test]
#[ignore = "needs yosys"]
fn the_loader_and_the_vga_controller_synthesize_within_12_lut_levels_and_the_frame_fits_m9ks() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("rtl-system-synth");
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for s in SOURCES {
        let path = dir.join(s.name);
        std::fs::write(&path, s.text).unwrap();
        files.push(path);
    }
    let t = VgaTiming::VESA_640X480_60;
    let vga: Vec<(&str, i64)> = t
        .parameters()
        .into_iter()
        .map(|(n, v)| (n, i64::from(v)))
        .collect();
    let loader: [(&str, i64); 5] = [
        ("CLKS_PER_BIT", 434),
        ("DEPTH_BITS", 6),
        ("FIELDS", 9),
        ("WIDTH", 640),
        ("HEIGHT", 480),
    ];
    for (top, parameters) in [
        ("uart_scene_loader", &loader[..]),
        ("vga_controller", &vga[..]),
    ] {
        let report = synth::logic_depth(
            &dir.join(top),
            &files,
            top,
            parameters,
            Duration::from_secs(600),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let fmax = report.estimated_fmax_mhz();
        eprintln!(
            "{top}: {} LUT levels ({} -> {}), {} LUT4, {} FF, est. {fmax:.1} MHz, {:.0} s",
            report.levels, report.from, report.to, report.lut4, report.ff, report.seconds
        );
        assert!(report.other_cells.is_empty(), "{:?}", report.other_cells);
        assert!(
            report.levels <= synth::MAX_LUT_LEVELS,
            "{top}: {}",
            report.levels
        );
        assert!(fmax >= fmax::THESIS_CLOCK_MHZ);
        assert!(report.lut4 > 0 && report.ff > 0);
    }
    // The frame memory at 640 x 480: 2,457,600 bits in 300 M9Ks of 8,192 data bits
    // (1 Ki bytes each), of the EP4CE115's 432.
    let report = synth::synthesize(&dir.join("frame"), &files, "vga_frame_buffer", &[], &[])
        .unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "vga_frame_buffer 640x480: {:?}, {:.0} s",
        report.total, report.seconds
    );
    assert!(report.unmapped.is_empty(), "{:?}", report.unmapped);
    assert_eq!(report.total.mem_bits, 640 * 480 * 8);
    assert_eq!(report.total.m9k, 300);
}
