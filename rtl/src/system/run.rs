//! The system's Verilator testbenches: the whole system fed through its UART pin and
//! read back from its VGA pins ([`build_system`], [`simulate_scene`]), the serial
//! loader alone ([`build_loader`], [`run_loader`]) and the VGA controller alone
//! ([`build_vga`], [`run_vga`]). Each model is built once per source and parameters
//! ([`crate::sim::build_model`]); runs write their files in a work directory.

use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use hwmodel::blocks::{ADDRESS_BITS, Pipeline};
use hwmodel::frame_timing::frame_timing;
use hwmodel::hw_scene::HwScene;

use super::uart::{self, HEADER_WORDS};
use super::vga::{DecodedFrame, VgaSample, VgaTiming, decode};
use super::{GeneratedSystem, SOURCES, SYSTEM_TOP};
use crate::RtlError;
use crate::operators::SourceFile;
use crate::sim::{FrameSetup, build_model, frame_setup};

/// The whole system's testbench.
pub const TESTBENCH_SYSTEM: SourceFile = SourceFile {
    name: "tb_system.cpp",
    text: include_str!("../../verilog/tb/tb_system.cpp"),
};

/// The loader's testbench.
pub const TESTBENCH_LOADER: SourceFile = SourceFile {
    name: "tb_uart_loader.cpp",
    text: include_str!("../../verilog/tb/tb_uart_loader.cpp"),
};

/// The VGA controller's testbench.
pub const TESTBENCH_VGA: SourceFile = SourceFile {
    name: "tb_vga.cpp",
    text: include_str!("../../verilog/tb/tb_vga.cpp"),
};

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> RtlError + '_ {
    move |source| RtlError::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn source(name: &str) -> Result<(String, String), RtlError> {
    SOURCES
        .iter()
        .find(|s| s.name == name)
        .map(|s| (s.name.to_string(), s.text.to_string()))
        .ok_or_else(|| RtlError::Generate(format!("no system source {name}")))
}

fn parameters(list: &[(&str, u32)]) -> Vec<String> {
    list.iter().map(|(n, v)| format!("-G{n}={v}")).collect()
}

/// Runs `program` with `args`; errors with its output when it fails.
fn run_program(program: &Path, args: &[OsString]) -> Result<(), RtlError> {
    let output = Command::new(program)
        .args(args)
        .output()
        .map_err(io(program))?;
    if output.status.success() {
        return Ok(());
    }
    Err(RtlError::Tool {
        tool: "simulation",
        message: format!(
            "{} exited with {} (3: out of cycles): {}",
            program.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ),
    })
}

fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), RtlError> {
    tracer::image_io::write_atomically(path, bytes).map_err(io(path))
}

// --- The loader alone ---

/// The loader as a testbench saw it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoaderRun {
    /// Memory writes in order: (primitive, word, value).
    pub writes: Vec<(u32, u32, u32)>,
    /// Rises of the error output.
    pub errors: u32,
    /// The error output at the end.
    pub error: bool,
    /// The cycle `loaded` rose.
    pub loaded: Option<u64>,
    /// The frame registers at the end: width, height, per_unit, prim_count, background.
    pub registers: [u32; 5],
    /// The 21 vector words at the end.
    pub vectors: Vec<u32>,
}

impl LoaderRun {
    /// The writes and registers a correct upload of `setup` leaves: every memory word
    /// at its primitive and field, in stream order, and the header's values.
    pub fn expected(setup: &FrameSetup) -> (Vec<(u32, u32, u32)>, [u32; 5]) {
        let mut writes = Vec::new();
        for (p, words) in setup.words.iter().enumerate() {
            for (f, &w) in words.iter().enumerate() {
                writes.push((p as u32, f as u32, w));
            }
        }
        let registers = [
            setup.width,
            setup.height,
            setup.per_unit,
            setup.prim_count,
            u32::from(setup.background),
        ];
        (writes, registers)
    }
}

/// Builds the loader (with its receiver) for the design's memory: `clocks_per_bit`,
/// 2^`depth_bits` primitives of `fields` words, a `width` × `height` frame.
pub fn build_loader(
    root: &Path,
    clocks_per_bit: u32,
    depth_bits: u32,
    fields: u32,
    (width, height): (u32, u32),
) -> Result<PathBuf, RtlError> {
    let files = vec![
        source("uart_rx.v")?,
        source("uart_scene_loader.v")?,
        (
            TESTBENCH_LOADER.name.to_string(),
            TESTBENCH_LOADER.text.to_string(),
        ),
    ];
    let args = parameters(&[
        ("CLKS_PER_BIT", clocks_per_bit),
        ("ADDRESS_BITS", ADDRESS_BITS),
        ("DEPTH_BITS", depth_bits),
        ("FIELDS", fields),
        ("WIDTH", width),
        ("HEIGHT", height),
    ]);
    build_model(
        &files,
        "uart_scene_loader",
        TESTBENCH_LOADER.name,
        &args,
        root,
    )
}

/// Sends `stream` to the loader, `tx_clocks_per_bit` cycles a bit, in `work`.
pub fn run_loader(
    program: &Path,
    stream: &[u8],
    tx_clocks_per_bit: f64,
    work: &Path,
) -> Result<LoaderRun, RtlError> {
    fs::create_dir_all(work).map_err(io(work))?;
    let input = work.join("stream.bin");
    let results = work.join("loader_results.txt");
    write_bytes(&input, stream)?;
    run_program(
        program,
        &[
            input.into(),
            tx_clocks_per_bit.to_string().into(),
            results.clone().into(),
        ],
    )?;
    let text = fs::read_to_string(&results).map_err(io(&results))?;
    let bad = |line: &str| RtlError::Tool {
        tool: "simulation",
        message: format!("{}: unexpected line `{line}`", results.display()),
    };
    let mut run = LoaderRun {
        writes: Vec::new(),
        errors: 0,
        error: false,
        loaded: None,
        registers: [0; 5],
        vectors: vec![0; HEADER_WORDS - 3],
    };
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        let dec = |s: &str| s.parse::<u64>().map_err(|_| bad(line));
        let hex = |s: &str| u32::from_str_radix(s, 16).map_err(|_| bad(line));
        match w.as_slice() {
            ["write", a, f, v] => run.writes.push((dec(a)? as u32, dec(f)? as u32, hex(v)?)),
            ["errors", n] => run.errors = dec(n)? as u32,
            ["error", e] => run.error = *e == "1",
            ["loaded", c] => run.loaded = c.parse::<u64>().ok(),
            ["vector", k, v] => {
                let k = dec(k)? as usize;
                *run.vectors.get_mut(k).ok_or_else(|| bad(line))? = hex(v)?;
            }
            ["width", v] => run.registers[0] = dec(v)? as u32,
            ["height", v] => run.registers[1] = dec(v)? as u32,
            ["per_unit", v] => run.registers[2] = dec(v)? as u32,
            ["prim_count", v] => run.registers[3] = dec(v)? as u32,
            ["background", v] => run.registers[4] = dec(v)? as u32,
            _ => return Err(bad(line)),
        }
    }
    Ok(run)
}

// --- The VGA controller alone ---

/// Builds the VGA controller for `timing`.
pub fn build_vga(root: &Path, timing: &VgaTiming) -> Result<PathBuf, RtlError> {
    timing.check()?;
    let files = vec![
        source("vga_controller.v")?,
        (
            TESTBENCH_VGA.name.to_string(),
            TESTBENCH_VGA.text.to_string(),
        ),
    ];
    build_model(
        &files,
        "vga_controller",
        TESTBENCH_VGA.name,
        &parameters(&timing.parameters()),
        root,
    )
}

/// Runs the VGA controller on the frame memory `frame` for `pixels` pixel clocks and
/// returns the pins, one sample per clock.
pub fn run_vga(
    program: &Path,
    frame: &[u8],
    pixels: u64,
    work: &Path,
) -> Result<Vec<VgaSample>, RtlError> {
    fs::create_dir_all(work).map_err(io(work))?;
    let input = work.join("frame.bin");
    let trace = work.join("vga_trace.bin");
    write_bytes(&input, frame)?;
    run_program(
        program,
        &[
            input.into(),
            pixels.to_string().into(),
            trace.clone().into(),
        ],
    )?;
    let bytes = fs::read(&trace).map_err(io(&trace))?;
    Ok(VgaSample::parse_trace(&bytes))
}

// --- The whole system ---

/// Builds the whole system.
pub fn build_system(system: &GeneratedSystem, root: &Path) -> Result<PathBuf, RtlError> {
    let mut files = system.files.clone();
    files.push((
        TESTBENCH_SYSTEM.name.to_string(),
        TESTBENCH_SYSTEM.text.to_string(),
    ));
    build_model(&files, SYSTEM_TOP, TESTBENCH_SYSTEM.name, &[], root)
}

/// System clock cycles per pixel clock in the simulation: 50 MHz / 25 MHz. (The
/// standard's 25.175 MHz comes from a PLL; the ratio does not change what is shown.)
pub const PIXEL_DIVIDE: u32 = 2;

/// One scene through the whole system: uploaded, rendered and shown.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemFrame {
    /// Bytes sent through the UART pin.
    pub stream_bytes: usize,
    /// System cycles when the upload ended on the line, when `loaded` rose and when the
    /// pipeline's frame was done.
    pub tx_end: u64,
    pub loaded: Option<u64>,
    pub done: Option<u64>,
    /// The loader's error output rose.
    pub load_error: bool,
    /// The VGA pins decoded (the first whole frame after `done`).
    pub frame: DecodedFrame,
}

/// Uploads `scene` through the UART pin of the system `program` was built from
/// (`config` and `pipeline` as generated), `tx_clocks_per_bit` cycles a bit, runs the
/// frame and decodes the VGA pins.
pub fn simulate_scene(
    program: &Path,
    system: &GeneratedSystem,
    pipeline: &Pipeline,
    scene: &HwScene,
    tx_clocks_per_bit: f64,
    work: &Path,
) -> Result<SystemFrame, RtlError> {
    let t = &system.config.timing;
    let setup = frame_setup(pipeline, scene, t.h_visible, t.v_visible)?;
    let stream = uart::scene_stream(&setup)?;
    fs::create_dir_all(work).map_err(io(work))?;
    let input = work.join("stream.bin");
    let trace = work.join("vga_trace.bin");
    let results = work.join("system_results.txt");
    write_bytes(&input, &stream)?;
    // Two frames and two lines of pixels: two whole vsync pulses from any start.
    let trace_pixels = 2 * t.frame_clocks() + 2 * u64::from(t.h_total());
    let upload = (tx_clocks_per_bit * 10.0 * stream.len() as f64) as u64;
    let render = frame_timing(
        pipeline,
        scene.primitives.len() as u64,
        t.h_visible,
        t.v_visible,
        1.0,
    )
    .cycles;
    let max_cycles = upload + 2 * render + u64::from(PIXEL_DIVIDE) * trace_pixels + 100_000;
    run_program(
        program,
        &[
            input.into(),
            tx_clocks_per_bit.to_string().into(),
            PIXEL_DIVIDE.to_string().into(),
            max_cycles.to_string().into(),
            trace_pixels.to_string().into(),
            trace.clone().into(),
            results.clone().into(),
        ],
    )?;
    let text = fs::read_to_string(&results).map_err(io(&results))?;
    let value = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key)?.strip_prefix(' ')?.parse::<i64>().ok())
    };
    let cycle = |key: &str| value(key).and_then(|v| u64::try_from(v).ok());
    let bytes = fs::read(&trace).map_err(io(&trace))?;
    let frame = decode(&VgaSample::parse_trace(&bytes))?;
    Ok(SystemFrame {
        stream_bytes: stream.len(),
        tx_end: cycle("tx_end").unwrap_or(0),
        loaded: cycle("loaded"),
        done: cycle("done"),
        load_error: value("load_error") == Some(1),
        frame,
    })
}
