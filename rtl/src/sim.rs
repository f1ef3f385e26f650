//! Cycle-accurate simulation of the generated pipeline with Verilator.
//!
//! [`build`] compiles the generated Verilog and its testbench (`tb_pipeline.cpp`) into
//! a program, once per design (the build directory is keyed by a hash of the files,
//! so the scenes of one design share it); [`run`] writes the scene (its memory words
//! and the frame constants the scene block precomputes) for the testbench, runs one
//! frame and reads back the frame buffer, the cycles from the first pixel's issue to
//! the last frame-buffer write, and each block's latency as built (the first valid
//! output after the first valid input, from the blocks' structural monitors).
//! [`SimCheck`] holds one frame against the model and the reference picture: what
//! `rtprof hw sim` prints and whether it agrees. [`verilator_command`] is the one
//! Verilator command line (the operator tests build with it too).

use std::fmt::Write as _;
use std::fs;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};

use serde::Serialize;

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::emulator::{HwImage, to_gray8};
use hwmodel::frame_timing::{cycles_per_pixel, frame_timing};
use hwmodel::graph_eval::{FrameConstants, light_direction, shading_words};
use hwmodel::hw_scene::{HwPrimitive, HwScene};

use crate::RtlError;
use crate::generate::{self, GeneratedRtl, TOP};
use crate::operators::write_atomically;

/// What one simulated frame measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimResult {
    /// Cycles from the first pixel's issue to the last frame-buffer write.
    pub cycles: u64,
    /// The model's figure for the same frame ([`frame_timing`]).
    pub model_cycles: u64,
    /// Frame-buffer writes (W·H when every pixel came out).
    pub writes: u64,
    /// Per block: name, latency as simulated (`None`: no valid output), model latency.
    pub blocks: Vec<BlockLatency>,
    #[serde(skip)]
    pub image: HwImage,
}

/// One block's simulated latency beside the model's.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct BlockLatency {
    pub name: String,
    pub simulated: Option<u64>,
    pub model: u32,
}

impl BlockLatency {
    /// The block as built has its schedule's latency.
    pub fn agrees(&self) -> bool {
        self.simulated == Some(u64::from(self.model))
    }
}

/// Scene-memory address bits for `primitives` (at least 64 primitives, so that the
/// test-bench scenes share one build).
pub fn depth_bits_for(primitives: usize) -> u32 {
    let n = primitives.max(64) as u64;
    64 - (n - 1).leading_zeros()
}

fn tool_missing(tool: &'static str) -> RtlError {
    RtlError::ToolMissing {
        tool,
        hint: "install it with `bash scripts/install-rtl-tools.sh` (Debian: apt-get install verilator g++ make)",
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> RtlError + '_ {
    move |source| RtlError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Verilator's command line for a C++ model of `top` with a C++ main, built in
/// `dir/obj` as the program `program` with `jobs` compilers: the flags the pipeline's
/// simulation and the operator tests share (the callers add their sources).
pub fn verilator_command(dir: &Path, top: &str, program: &str, jobs: u32) -> Command {
    let mut command = Command::new("verilator");
    command
        .current_dir(dir)
        .args(["--cc", "--exe", "--build", "-j"])
        .arg(jobs.to_string())
        .args([
            "-O3",
            "--x-assign",
            "fast",
            "--x-initial",
            "fast",
            "-Wno-fatal",
            "--top-module",
            top,
            "-Mdir",
            "obj",
            "-o",
            program,
        ]);
    command
}

/// Where Verilator builds the models when no directory is given: the user's cache
/// (`$XDG_CACHE_HOME/rtprof/rtl`, else `~/.cache/rtprof/rtl`), else the temporary
/// directory.
pub fn default_build_root() -> PathBuf {
    match dirs::cache_dir() {
        Some(cache) => cache.join("rtprof").join("rtl"),
        None => std::env::temp_dir().join("rtprof-rtl"),
    }
}

/// Compiles `rtl` with Verilator under `root` (in `root/<hash>`, reused when the files
/// are unchanged) and returns the simulator program.
pub fn build(rtl: &GeneratedRtl, root: &Path) -> Result<PathBuf, RtlError> {
    build_model(&rtl.files, TOP, generate::TESTBENCH.name, &[], root)
}

/// Compiles the Verilog of `files` with `top` as the top module (Verilator's
/// `extra_args` added, e.g. `-G` parameters) and the C++ testbench `testbench` (one of
/// `files`) under `root`, in `root/<hash>` (reused when the files and arguments are
/// unchanged), and returns the simulator program.
pub fn build_model(
    files: &[(String, String)],
    top: &str,
    testbench: &str,
    extra_args: &[String],
    root: &Path,
) -> Result<PathBuf, RtlError> {
    let mut hasher = DefaultHasher::new();
    (files, top, testbench, extra_args).hash(&mut hasher);
    let hash = format!("{:016x}", hasher.finish());
    let dir = root.join(&hash);
    let program = dir.join("obj").join("Vsim");
    if program.exists() {
        return Ok(program);
    }
    // Built aside and renamed into place, so that two builds of one design at once
    // (tests in parallel, two commands) never share a half-built directory.
    static BUILDS: AtomicU64 = AtomicU64::new(0);
    let staging = root.join(format!(
        "{hash}.building-{}-{}",
        std::process::id(),
        BUILDS.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = fs::remove_dir_all(&staging);
    fs::create_dir_all(&staging).map_err(io(&staging))?;
    for (name, text) in files {
        write_atomically(&staging.join(name), text)?;
    }
    let sources: Vec<String> = files
        .iter()
        .map(|(name, _)| name.clone())
        .filter(|n| n.ends_with(".v"))
        .collect();
    let output = verilator_command(&staging, top, "Vsim", 2)
        // The generated modules leave inputs unused by design (constants, monitors).
        .args(["-Wno-lint", "-Wno-style"])
        // The operators' prefix adders as `+` and the multiplier's Wallace tree as `*`
        // (fp_fast_add.v, fp_mul.v): the same sums and products, and a model that
        // compiles in minutes; the operator tests simulate the trees themselves.
        .arg("+define+RTPROF_BEHAVIOURAL_ARITHMETIC")
        .args(extra_args)
        .args(&sources)
        .arg(testbench)
        .output()
        .map_err(|_| tool_missing("verilator"))?;
    if !output.status.success() || !staging.join("obj").join("Vsim").exists() {
        let log = staging.join("verilator.log");
        let mut text = String::from_utf8_lossy(&output.stdout).to_string();
        text += &String::from_utf8_lossy(&output.stderr);
        write_atomically(&log, &text)?;
        let tail: Vec<&str> = text.lines().rev().take(12).collect();
        return Err(RtlError::Tool {
            tool: "verilator",
            message: format!(
                "the build failed (log: {}):\n{}",
                log.display(),
                tail.into_iter().rev().collect::<Vec<_>>().join("\n")
            ),
        });
    }
    if fs::rename(&staging, &dir).is_err() {
        // Another build of the same design finished first: use it.
        let _ = fs::remove_dir_all(&staging);
    }
    if program.exists() {
        Ok(program)
    } else {
        Err(RtlError::Tool {
            tool: "verilator",
            message: format!("{} is missing after the build", program.display()),
        })
    }
}

/// The names of the frame vectors the top reads (its ports `<name>_x|y|z`), in the
/// order the testbench's input and the UART loader's stream carry them.
pub const FRAME_VECTORS: [&str; 7] = [
    "scan_line",
    "row_step",
    "column_step",
    "eye",
    "view_dir",
    "light",
    "light_dir",
];

/// One frame's set-up as the scene block holds it: the top's frame registers and the
/// scene memory's words. What the testbench's input and the UART loader's stream carry.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameSetup {
    pub width: u32,
    pub height: u32,
    /// Primitives per intersection unit, c = ⌈n/K⌉.
    pub per_unit: u32,
    pub prim_count: u32,
    /// The background's gray level.
    pub background: u8,
    /// The frame vectors, in [`FRAME_VECTORS`] order.
    pub vectors: [[f32; 3]; 7],
    /// Per primitive, its memory words (the MIF's 9, then the rsqrt-free shading's 5).
    pub words: Vec<Vec<u32>>,
}

/// The set-up of `scene` at `width`×`height` on `pipeline`: the frame constants and
/// the scene memory's words (read back from the scene's MIF).
pub fn frame_setup(
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
) -> Result<FrameSetup, RtlError> {
    let k = FrameConstants::new(scene, width, height);
    let n = scene.primitives.len() as u64;
    let units = pipeline.design.units.max(1);
    let per_unit = cycles_per_pixel(n, units, 1);
    // The memory's words as the MIF holds them (`rtprof hw mif`), read back from it.
    let mif = hwmodel::mif::parse_mif(&hwmodel::mif::to_mif(scene))
        .map_err(|e| RtlError::Generate(format!("the scene's MIF does not read back: {e}")))?;
    let words = scene
        .primitives
        .iter()
        .zip(mif.chunks(HwPrimitive::WORDS))
        .map(|(p, words)| {
            let mut words = words.to_vec();
            if pipeline.design.no_rsqrt_shading {
                words.extend(shading_words(p, scene.light).map(f32::to_bits));
            }
            words
        })
        .collect();
    let too_big = |what: &str, v: u64| {
        RtlError::Generate(format!("{what} {v} does not fit the top's 16-bit register"))
    };
    Ok(FrameSetup {
        width,
        height,
        per_unit: u32::try_from(per_unit).map_err(|_| too_big("per_unit", per_unit))?,
        prim_count: u32::try_from(n).map_err(|_| too_big("prim_count", n))?,
        background: to_gray8(scene.background_gray),
        vectors: [
            k.rays.scan_line,
            k.rays.pixel_height,
            k.rays.pixel_width,
            scene.eye,
            view_direction(scene),
            scene.light,
            light_direction(scene.light),
        ],
        words,
    })
}

/// The testbench's input for `scene` at `width`×`height` on `pipeline`: the frame
/// set-up ([`frame_setup`]) and a cycle limit.
pub fn testbench_input(
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
) -> Result<String, RtlError> {
    let setup = frame_setup(pipeline, scene, width, height)?;
    let n = scene.primitives.len() as u64;
    let timing = frame_timing(pipeline, n, width, height, 1.0);
    let mut out = String::new();
    let hex = |v: [f32; 3]| {
        format!(
            "{:08X} {:08X} {:08X}",
            v[0].to_bits(),
            v[1].to_bits(),
            v[2].to_bits()
        )
    };
    writeln!(
        out,
        "width {width}\nheight {height}\nper_unit {}\nprim_count {n}\nmax_cycles {}\nbackground {}",
        setup.per_unit,
        timing.cycles * 2 + 100_000,
        setup.background
    )
    .ok();
    for (name, v) in FRAME_VECTORS.iter().zip(setup.vectors) {
        writeln!(out, "{name} {}", hex(v)).ok();
    }
    for (i, words) in setup.words.iter().enumerate() {
        for (field, w) in words.iter().enumerate() {
            writeln!(out, "word {i} {field} {w:08X}").ok();
        }
    }
    Ok(out)
}

/// The unit view direction (the orthographic design's constant ray).
fn view_direction(scene: &HwScene) -> [f32; 3] {
    let d = [0, 1, 2].map(|i| hwmodel::float_policy::sub(scene.look_at[i], scene.eye[i]));
    // The same normalization as the light's direction.
    light_direction(d)
}

/// Writes the testbench's input for `scene` (`sim_input.txt`) and its scene memory
/// (`scene.mif`) into `dir`, beside the generated RTL; returns the files written.
pub fn write_scene_files(
    dir: &Path,
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
) -> Result<Vec<PathBuf>, RtlError> {
    let input = testbench_input(pipeline, scene, width, height)?;
    Ok(vec![
        write_atomically(&dir.join("sim_input.txt"), &input)?,
        write_atomically(&dir.join("scene.mif"), &hwmodel::mif::to_mif(scene))?,
    ])
}

/// Runs `program` on `scene` in `work` (input, image and results files).
pub fn run(
    program: &Path,
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
    work: &Path,
) -> Result<SimResult, RtlError> {
    fs::create_dir_all(work).map_err(io(work))?;
    let input = work.join("sim_input.txt");
    write_atomically(&input, &testbench_input(pipeline, scene, width, height)?)?;
    let image_path = work.join("frame.pgm");
    let results = work.join("sim_results.txt");
    let output = Command::new(program)
        .arg(&input)
        .arg(&image_path)
        .arg(&results)
        .output()
        .map_err(io(program))?;
    if !output.status.success() {
        return Err(RtlError::Tool {
            tool: "simulation",
            message: format!(
                "{} exited with {} (3: the frame did not finish in time): {}",
                program.display(),
                output.status,
                String::from_utf8_lossy(&output.stderr)
            ),
        });
    }
    let text = fs::read_to_string(&results).map_err(io(&results))?;
    let bytes = fs::read(&image_path).map_err(io(&image_path))?;
    let image = parse_pgm(&bytes, width, height).ok_or_else(|| RtlError::Tool {
        tool: "simulation",
        message: format!("{}: not a {width}x{height} PGM", image_path.display()),
    })?;
    let mut cycles = None;
    let mut writes = 0;
    let mut simulated = std::collections::HashMap::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["cycles", v] => cycles = v.parse::<u64>().ok(),
            ["writes", v] => writes = v.parse::<u64>().unwrap_or(0),
            ["latency", name, v] => {
                simulated.insert(name.to_string(), v.parse::<u64>().ok());
            }
            _ => {}
        }
    }
    let n = scene.primitives.len() as u64;
    let model = frame_timing(pipeline, n, width, height, 1.0);
    let blocks = pipeline
        .blocks_in_order()
        .into_iter()
        .map(|b| BlockLatency {
            name: b.name.to_string(),
            simulated: simulated.get(b.name).copied().flatten(),
            model: b.latency(),
        })
        .collect();
    Ok(SimResult {
        cycles: cycles.ok_or_else(|| RtlError::Tool {
            tool: "simulation",
            message: "no frame-buffer write: the pipeline produced no pixel".into(),
        })?,
        model_cycles: model.cycles,
        writes,
        blocks,
        image,
    })
}

/// The picture the simulation must reproduce, and where it comes from: the emulator
/// for the thesis's arithmetic (any number of units), the block graphs evaluated on
/// values ([`hwmodel::graph_eval`]) for the what-ifs that change it.
pub fn reference_image(
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
) -> Result<(HwImage, &'static str), RtlError> {
    let d = &pipeline.design;
    if !d.fast_sqrt && !d.ortho && !d.no_rsqrt_shading {
        return Ok((
            hwmodel::emulator::render(scene, width, height),
            "the emulator (rtprof hw render)",
        ));
    }
    hwmodel::graph_eval::render(pipeline, scene, width, height)
        .map(|image| (image, "the block graphs evaluated"))
        .map_err(|e| RtlError::Generate(e.to_string()))
}

/// How far two gray images are apart.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ImageDifference {
    pub differing_pixels: u64,
    pub rms: f64,
}

/// Pixels that differ and the RMS difference in gray levels (images of one size).
pub fn compare_images(a: &HwImage, b: &HwImage) -> ImageDifference {
    let mut differing = 0;
    let mut sum = 0.0;
    for (x, y) in a.pixels.iter().zip(&b.pixels) {
        let d = f64::from(*x) - f64::from(*y);
        if d != 0.0 {
            differing += 1;
        }
        sum += d * d;
    }
    let n = a.pixels.len().max(1) as f64;
    ImageDifference {
        differing_pixels: differing,
        rms: (sum / n).sqrt(),
    }
}

/// One simulated frame held against the model and the reference picture: what
/// `rtprof hw sim` reports, and whether it agrees.
#[derive(Clone, Debug)]
pub struct SimCheck {
    /// The scene's name as the user gave it.
    pub scene: String,
    pub design: Design,
    pub width: u32,
    pub height: u32,
    pub primitives: usize,
    pub result: SimResult,
    /// Where the simulated picture was written.
    pub image: PathBuf,
    /// Where the reference picture comes from ([`reference_image`]).
    pub reference: &'static str,
    /// The simulated picture against the reference.
    pub difference: ImageDifference,
}

impl SimCheck {
    /// Runs `program` on `scene` in a work directory beside its build (removed after),
    /// and compares the frame with the reference picture. `image` is where the caller
    /// writes the simulated picture.
    pub fn run(
        program: &Path,
        pipeline: &Pipeline,
        name: &str,
        scene: &HwScene,
        (width, height): (u32, u32),
        image: &Path,
    ) -> Result<SimCheck, RtlError> {
        let work = program
            .parent()
            .and_then(|p| p.parent())
            .map(|p| p.join("runs").join(format!("{}", std::process::id())))
            .ok_or_else(|| RtlError::Tool {
                tool: "simulation",
                message: "the simulator has no build directory".into(),
            })?;
        let result = run(program, pipeline, scene, width, height, &work);
        // The run's files are scratch: its figures are in `result`.
        let _ = fs::remove_dir_all(&work);
        let result = result?;
        let (reference, source) = reference_image(pipeline, scene, width, height)?;
        let difference = compare_images(&result.image, &reference);
        Ok(SimCheck {
            scene: name.to_string(),
            design: pipeline.design,
            width,
            height,
            primitives: scene.primitive_count(),
            result,
            image: image.to_path_buf(),
            reference: source,
            difference,
        })
    }

    /// Every block's latency as built equals its schedule's.
    pub fn latencies_agree(&self) -> bool {
        self.result.blocks.iter().all(BlockLatency::agrees)
    }

    /// The frame agrees with the model and the reference: the same picture, the
    /// model's cycles per frame, one write per pixel, every block's latency.
    pub fn agrees(&self) -> bool {
        self.difference.differing_pixels == 0
            && self.result.cycles == self.result.model_cycles
            && self.result.writes == u64::from(self.width) * u64::from(self.height)
            && self.latencies_agree()
    }

    /// `rtprof hw sim --json`: the check's figures and verdict (not the picture).
    pub fn summary(&self) -> SimSummary<'_> {
        SimSummary {
            scene: &self.scene,
            design: self.design.label(),
            units: self.design.units,
            width: self.width,
            height: self.height,
            primitives: self.primitives,
            result: &self.result,
            image: &self.image,
            reference: self.reference,
            differing_pixels: self.difference.differing_pixels,
            rms: self.difference.rms,
            agrees: self.agrees(),
        }
    }

    /// `rtprof hw sim`'s report: cycles, block latencies and the picture, each with
    /// its verdict.
    pub fn to_text(&self) -> String {
        let verdict = |equal: bool| if equal { "equal" } else { "DIFFERENT" };
        let r = &self.result;
        let mut text = String::new();
        let _ = writeln!(
            text,
            "{} on the {} design, {}x{}, {} primitives",
            self.scene,
            self.design.label(),
            self.width,
            self.height,
            self.primitives
        );
        let _ = writeln!(
            text,
            "  cycles per frame   {:>12}  model {:>12}  {}",
            r.cycles,
            r.model_cycles,
            verdict(r.cycles == r.model_cycles)
        );
        text.push_str("  block latencies (first valid output after the first input):\n");
        for b in &r.blocks {
            let sim = b.simulated.map_or("none".to_string(), |v| v.to_string());
            let _ = writeln!(
                text,
                "    {:<14} {:>5}  model {:>5}  {}",
                b.name,
                sim,
                b.model,
                verdict(b.agrees())
            );
        }
        let _ = writeln!(
            text,
            "  image {}: {} of {} pixels differ from {} (RMS {:.3})",
            self.image.display(),
            self.difference.differing_pixels,
            r.image.pixels.len(),
            self.reference,
            self.difference.rms
        );
        text
    }
}

/// What `rtprof hw sim --json` prints of a [`SimCheck`].
#[derive(Clone, Debug, Serialize)]
pub struct SimSummary<'a> {
    pub scene: &'a str,
    pub design: String,
    pub units: u32,
    pub width: u32,
    pub height: u32,
    pub primitives: usize,
    /// `cycles`, `model_cycles`, `writes`, `blocks`.
    #[serde(flatten)]
    pub result: &'a SimResult,
    pub image: &'a Path,
    pub reference: &'static str,
    pub differing_pixels: u64,
    pub rms: f64,
    pub agrees: bool,
}

/// A binary PGM (`P5`) of `width`×`height`, 8-bit.
fn parse_pgm(bytes: &[u8], width: u32, height: u32) -> Option<HwImage> {
    let header = format!("P5\n{width} {height}\n255\n");
    let pixels = bytes.strip_prefix(header.as_bytes())?;
    (pixels.len() == width as usize * height as usize).then(|| HwImage {
        width,
        height,
        pixels: pixels.to_vec(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_depth_covers_the_scene_with_a_floor_of_64() {
        assert_eq!(depth_bits_for(0), 6);
        assert_eq!(depth_bits_for(7), 6);
        assert_eq!(depth_bits_for(64), 6);
        assert_eq!(depth_bits_for(65), 7);
        assert_eq!(depth_bits_for(1000), 10);
    }

    #[test]
    fn pgm_round_trip_checks_the_size() {
        let bytes = b"P5\n2 1\n255\n\x07\x09";
        let image = parse_pgm(bytes, 2, 1).map(|i| i.pixels);
        assert_eq!(image, Some(vec![7, 9]));
        assert!(parse_pgm(bytes, 1, 2).is_none());
        assert!(parse_pgm(b"P5\n2 1\n255\n\x07", 2, 1).is_none());
    }
}
