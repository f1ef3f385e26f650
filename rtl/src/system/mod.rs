//! The thesis's whole system around the generated pipeline (thesis fig. 17): the
//! serial scene loader, the pipeline, the frame memory and the VGA controller.
//!
//! ```text
//!  uart_rx ─► uart_scene_loader ─► raycaster_top ─► vga_frame_buffer ─► vga_controller ─► VGA pins
//!  (8N1)      (magic, header,      (the generated   (one gray byte      (sync timing,
//!              memory words, CRC)   pipeline)        per pixel)          RGB)
//! ```
//!
//! The loader and the VGA side are written by hand (`rtl/verilog/uart_*.v`,
//! `vga_*.v`); [`generate_system`] writes the top that joins them to the generated
//! pipeline (`raycaster_system`), with the loader's frame registers on the pipeline's
//! frame-constant inputs and its `loaded` on `start`. Two clocks: the system clock
//! (the thesis's 50 MHz: UART, loader, pipeline, frame-memory writes) and the pixel
//! clock (25.175 MHz from a PLL for the standard mode: VGA and frame-memory reads).
//!
//! - [`uart`]: the stream's framing and its serializer (one home for both);
//! - [`vga`]: the video mode's timing and the decoder that reads the pins back into
//!   measurements and a picture;
//! - [`run`]: Verilator testbenches of the whole system, the loader alone and the VGA
//!   controller alone (`tests/system.rs`).

pub mod run;
pub mod uart;
pub mod vga;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use hwmodel::blocks::{ADDRESS_BITS, Pipeline};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;

use crate::RtlError;
use crate::generate::{self, GeneratedRtl, TOP};
use crate::operators::SourceFile;
use crate::operators::write_atomically;
use crate::sim::{FRAME_VECTORS, frame_setup};
use vga::VgaTiming;

/// The system's hand-written modules.
pub const SOURCES: [SourceFile; 4] = [
    SourceFile {
        name: "uart_rx.v",
        text: include_str!("../../verilog/uart_rx.v"),
    },
    SourceFile {
        name: "uart_scene_loader.v",
        text: include_str!("../../verilog/uart_scene_loader.v"),
    },
    SourceFile {
        name: "vga_controller.v",
        text: include_str!("../../verilog/vga_controller.v"),
    },
    SourceFile {
        name: "vga_frame_buffer.v",
        text: include_str!("../../verilog/vga_frame_buffer.v"),
    },
];

/// The system top's module name.
pub const SYSTEM_TOP: &str = "raycaster_system";

/// What the system is built for besides the pipeline's design.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SystemConfig {
    /// The video mode; its visible area is the frame the pipeline renders.
    pub timing: VgaTiming,
    /// System clock cycles per UART bit ([`uart::clocks_per_bit`]).
    pub clocks_per_bit: u32,
    /// Scene-memory address bits (2^bits primitives).
    pub depth_bits: u32,
}

impl SystemConfig {
    /// The thesis's system: 640 × 480 at 60 Hz, 115,200 baud at 50 MHz.
    pub fn thesis(depth_bits: u32) -> Result<SystemConfig, RtlError> {
        Ok(SystemConfig {
            timing: VgaTiming::VESA_640X480_60,
            clocks_per_bit: uart::clocks_per_bit(uart::SYSTEM_CLOCK_HZ, uart::DEFAULT_BAUD)?,
            depth_bits,
        })
    }
}

/// The whole system: the pipeline's files, the system's modules and top.
#[derive(Clone, Debug)]
pub struct GeneratedSystem {
    /// `(file name, text)`: the pipeline's files, [`SOURCES`], the system top.
    pub files: Vec<(String, String)>,
    /// The pipeline as generated.
    pub pipeline: GeneratedRtl,
    pub config: SystemConfig,
}

/// Bits of the scene-memory field index on the loader port (`load_field`).
const FIELD_BITS: u32 = 4;

/// The system for `pipeline` as configured.
pub fn generate_system(
    lib: &Library,
    pipeline: &Pipeline,
    config: SystemConfig,
) -> Result<GeneratedSystem, RtlError> {
    config.timing.check()?;
    if config.clocks_per_bit < 4 {
        return Err(RtlError::Generate(format!(
            "the UART receiver needs at least 4 cycles per bit, not {}",
            config.clocks_per_bit
        )));
    }
    if config.timing.h_visible > 0xFFFF || config.timing.v_visible > 0xFFFF {
        return Err(RtlError::Generate(
            "the frame does not fit the pipeline's 16-bit width and height".into(),
        ));
    }
    let rtl = generate::generate(lib, pipeline, config.depth_bits)?;
    let mut files = rtl.files.clone();
    for source in SOURCES {
        files.push((source.name.to_string(), source.text.to_string()));
    }
    files.push((
        format!("{SYSTEM_TOP}.v"),
        system_top(&config, pipeline.design.words_per_primitive()),
    ));
    Ok(GeneratedSystem {
        files,
        pipeline: rtl,
        config,
    })
}

/// Writes `system`'s files and its testbench into `dir` (created if needed), each
/// atomically; returns how many.
pub fn write(system: &GeneratedSystem, dir: &Path) -> Result<usize, RtlError> {
    std::fs::create_dir_all(dir).map_err(|source| RtlError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let testbench = &run::TESTBENCH_SYSTEM;
    for (name, text) in system
        .files
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .chain([(testbench.name, testbench.text)])
    {
        write_atomically(&dir.join(name), text)?;
    }
    Ok(system.files.len() + 1)
}

/// The file [`write_upload`] writes.
pub const UPLOAD_FILE: &str = "scene_upload.bin";

/// Writes the UART upload of `scene` for `system` (at its frame size) into
/// `dir/`[`UPLOAD_FILE`]: the bytes a host sends to the `uart_rx` pin.
pub fn write_upload(
    system: &GeneratedSystem,
    pipeline: &Pipeline,
    scene: &HwScene,
    dir: &Path,
) -> Result<PathBuf, RtlError> {
    let t = &system.config.timing;
    let setup = frame_setup(pipeline, scene, t.h_visible, t.v_visible)?;
    let stream = uart::scene_stream(&setup)?;
    let path = dir.join(UPLOAD_FILE);
    tracer::image_io::write_atomically(&path, &stream).map_err(|source| RtlError::Io {
        path: path.clone(),
        source,
    })?;
    Ok(path)
}

fn parameters(list: &[(&str, u32)]) -> String {
    list.iter()
        .map(|(name, value)| format!(".{name}({value})"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The system top's text.
fn system_top(config: &SystemConfig, fields: u64) -> String {
    let t = &config.timing;
    let ab = ADDRESS_BITS;
    let fb_bits = t.fb_address_bits();
    let words = u64::from(t.h_visible) * u64::from(t.v_visible);
    let mut vectors = String::new();
    for (k, name) in FRAME_VECTORS.iter().enumerate() {
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            let word = 3 * k + i;
            let _ = write!(
                vectors,
                "\n        .{name}_{axis}(vectors[{}:{}]),",
                32 * word + 31,
                32 * word
            );
        }
    }
    let loader = parameters(&[
        ("CLKS_PER_BIT", config.clocks_per_bit),
        ("ADDRESS_BITS", ab),
        ("DEPTH_BITS", config.depth_bits),
        ("FIELDS", u32::try_from(fields).unwrap_or(u32::MAX)),
        ("WIDTH", t.h_visible),
        ("HEIGHT", t.v_visible),
    ]);
    let vga = parameters(&t.parameters());
    format!(
        r#"// Generated by rtprof: the thesis's whole system (fig. 17): the serial scene loader,
// the pipeline ({TOP}), the frame memory and the VGA controller, {w} x {h} at
// {rate:.2} Hz with a {mhz:.3} MHz pixel clock, {cpb} clock cycles per UART bit.
module {SYSTEM_TOP} (
    // The system clock: UART, loader, pipeline, frame-memory writes.
    input clk,
    // The pixel clock: VGA and frame-memory reads.
    input pixel_clk,
    input uart_rx,
    output vga_hsync,
    output vga_vsync,
    output vga_blank_n,
    output [7:0] vga_r,
    output [7:0] vga_g,
    output [7:0] vga_b,
    output loaded,
    output load_error,
    output done
);
    wire load_we;
    wire [{ab1}:0] load_addr;
    wire [{fb1}:0] load_field;
    wire [31:0] load_data;
    wire [15:0] width, height, per_unit, prim_count;
    wire [7:0] background;
    wire [{vb1}:0] vectors;
    uart_scene_loader #({loader}) loader (
        .clk(clk), .rx(uart_rx),
        .load_we(load_we), .load_addr(load_addr), .load_field(load_field), .load_data(load_data),
        .width(width), .height(height), .per_unit(per_unit), .prim_count(prim_count),
        .background(background), .vectors(vectors), .loaded(loaded), .error(load_error)
    );

    wire fb_we;
    wire [31:0] fb_addr;
    wire [7:0] fb_data;
    {TOP} pipeline (
        .clk(clk), .start(loaded),
        .load_we(load_we), .load_addr(load_addr), .load_field(load_field), .load_data(load_data),
        .width(width), .height(height), .per_unit(per_unit), .prim_count(prim_count),
        .background(background),{vectors}
        .fb_we(fb_we), .fb_addr(fb_addr), .fb_data(fb_data), .done(done),
        .issuing(), .mon_in(), .mon_out()
    );

    wire [{fba1}:0] read_addr;
    wire [7:0] read_data;
    vga_frame_buffer #(.WORDS({words}), .ADDRESS_BITS({fb_bits})) frame (
        .write_clk(clk), .we(fb_we), .write_addr(fb_addr), .write_data(fb_data),
        .read_clk(pixel_clk), .read_addr(read_addr), .read_data(read_data)
    );

    vga_controller #({vga}) vga (
        .clk(pixel_clk), .fb_addr(read_addr), .fb_data(read_data),
        .hsync(vga_hsync), .vsync(vga_vsync), .video_on(vga_blank_n),
        .red(vga_r), .green(vga_g), .blue(vga_b), .column(), .row()
    );
endmodule
"#,
        w = t.h_visible,
        h = t.v_visible,
        rate = t.frame_rate_hz(),
        mhz = t.pixel_clock_hz / 1e6,
        cpb = config.clocks_per_bit,
        ab1 = ab - 1,
        fb1 = FIELD_BITS - 1,
        vb1 = 32 * 3 * FRAME_VECTORS.len() - 1,
        fba1 = fb_bits - 1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use hwmodel::design::Design;

    /// The text from `open` (an opening parenthesis) to its matching close.
    fn balanced(text: &str) -> (&str, &str) {
        let mut depth = 0;
        for (i, c) in text.char_indices() {
            match c {
                '(' => depth += 1,
                ')' if depth == 1 => return (&text[1..i], &text[i + 1..]),
                ')' => depth -= 1,
                _ => {}
            }
        }
        panic!("unbalanced: {text}")
    }

    /// The names of a module's ports, from its header (comments left out).
    fn ports(text: &str, module: &str) -> Vec<String> {
        let text: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap_or(""))
            .collect::<Vec<_>>()
            .join("\n");
        let start = text.find(&format!("module {module} ")).unwrap();
        let mut rest = text[start + 8 + module.len()..].trim_start();
        if let Some(after) = rest.strip_prefix('#') {
            rest = balanced(after.trim_start()).1.trim_start();
        }
        balanced(rest)
            .0
            .split(',')
            .filter_map(|item| item.split_whitespace().last().map(str::to_string))
            .collect()
    }

    /// The `.port(` names of the instance of `module` in `text`.
    fn connections(text: &str, module: &str) -> Vec<String> {
        let start = text.find(&format!("    {module} ")).unwrap();
        let body = &text[start..];
        let body = &body[..body.find(");").unwrap()];
        body.split('.')
            .skip(1)
            .filter_map(|s| s.split('(').next())
            .map(str::to_string)
            .filter(|s| !s.chars().next().unwrap().is_ascii_uppercase())
            .collect()
    }

    #[test]
    fn the_system_top_connects_every_port_of_each_block() {
        let lib = Library::cyclone_iv_e();
        for design in [
            Design::thesis(),
            Design {
                no_rsqrt_shading: true,
                ..Design::thesis()
            },
        ] {
            let pipeline = Pipeline::build(&lib, &design);
            let config = SystemConfig {
                timing: VgaTiming::small(40, 30),
                clocks_per_bit: 16,
                depth_bits: 6,
            };
            let system = generate_system(&lib, &pipeline, config).unwrap();
            let file = |name: &str| {
                system
                    .files
                    .iter()
                    .find(|(n, _)| n == name)
                    .map(|(_, t)| t.clone())
                    .unwrap()
            };
            let top = file("raycaster_system.v");
            for (module, source) in [
                (TOP, format!("{TOP}.v")),
                ("uart_scene_loader", "uart_scene_loader.v".into()),
                ("vga_frame_buffer", "vga_frame_buffer.v".into()),
                ("vga_controller", "vga_controller.v".into()),
            ] {
                let mut declared = ports(&file(&source), module);
                let mut connected = connections(&top, module);
                declared.sort();
                connected.sort();
                assert_eq!(connected, declared, "{module}");
            }
            let fields = design.words_per_primitive();
            assert!(top.contains(&format!(".FIELDS({fields})")), "{fields}");
            assert!(top.contains(".WORDS(1200), .ADDRESS_BITS(11)"));
            // The 21 vector words, the last one at the top of the bus.
            assert!(top.contains(".light_dir_z(vectors[671:640])"));
        }
    }

    #[test]
    fn the_thesis_system_is_the_standard_mode_at_115200_baud() {
        let c = SystemConfig::thesis(6).unwrap();
        assert_eq!(c.clocks_per_bit, 434);
        assert_eq!(c.timing, VgaTiming::VESA_640X480_60);
        let lib = Library::cyclone_iv_e();
        let pipeline = Pipeline::build(&lib, &Design::thesis());
        let system = generate_system(&lib, &pipeline, c).unwrap();
        let top = &system.files.last().unwrap().1;
        assert!(top.contains(".WORDS(307200), .ADDRESS_BITS(19)"), "{top}");
        assert!(top.contains(".H_SYNC(96)") && top.contains(".HSYNC_ACTIVE(0)"));
    }
}
