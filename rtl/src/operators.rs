//! The Verilog operator library (`rtl/verilog/*.v`): the sources, embedded in the
//! crate, and what generated RTL needs to know about each operator (its module name,
//! its ports, and its latency, which comes from hwmodel's operator library and nowhere
//! else).
//!
//! Every operator module has a `parameter LATENCY` and divides its logic into stages
//! of a few LUT levels, with LATENCY registers spread over them (`fp_stage.v`, built
//! on the delay line `fp_delay.v`), so the result of the inputs of cycle k appears in
//! cycle k + LATENCY (LATENCY = 0: combinational). The arithmetic follows [`crate::float_policy`]. The modules are
//! plain Verilog-2005 for Verilator and for Yosys's `synth_intel -family cycloneive`.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use hwmodel::library::{Library, OpKind};

use crate::RtlError;

/// One Verilog source file of the library.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SourceFile {
    /// The file name, `<module>.v`.
    pub name: &'static str,
    /// The Verilog text.
    pub text: &'static str,
}

/// The delay line every operator ends in (not an operator of its own: see
/// [`Operator::Register`]).
pub const DELAY: SourceFile = SourceFile {
    name: "fp_delay.v",
    text: include_str!("../verilog/fp_delay.v"),
};

/// The pipeline's building blocks every clocked operator may use: the stage
/// registers that spread an operator's LATENCY over its stages, the prefix adder and
/// the leading-zero count that keep a stage's logic shallow (issue 38).
pub const STAGE: SourceFile = SourceFile {
    name: "fp_stage.v",
    text: include_str!("../verilog/fp_stage.v"),
};
pub const FAST_ADD: SourceFile = SourceFile {
    name: "fp_fast_add.v",
    text: include_str!("../verilog/fp_fast_add.v"),
};
pub const LZC: SourceFile = SourceFile {
    name: "fp_lzc.v",
    text: include_str!("../verilog/fp_lzc.v"),
};

/// The files every clocked operator reads besides its own.
const SHARED: [SourceFile; 4] = [DELAY, STAGE, FAST_ADD, LZC];

/// Every source file of the library: the operators in [`Operator::ALL`] order, then
/// the delay line and the building blocks they share.
pub const SOURCES: [SourceFile; 16] = [
    Operator::AddSub.source(),
    Operator::Multiply.source(),
    Operator::Divide.source(),
    Operator::Sqrt.source(),
    Operator::Compare.source(),
    Operator::FromInt.source(),
    Operator::FastSqrt.source(),
    Operator::Const.source(),
    Operator::Select.source(),
    Operator::Register.source(),
    Operator::InvSqrt.source(),
    Operator::ToU8.source(),
    DELAY,
    STAGE,
    FAST_ADD,
    LZC,
];

/// The operators of the Verilog library.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Operator {
    /// `fp_add_sub`: `y = sub ? a - b : a + b`.
    AddSub,
    /// `fp_mul`: `y = a * b`. A registered multiplier (hwmodel's `multiply_registered`)
    /// is the same module at that row's latency: see [`Operator::latency_as`].
    Multiply,
    /// `fp_div`: `y = a / b`.
    Divide,
    /// `fp_sqrt`: `y = sqrt(a)`.
    Sqrt,
    /// `fp_compare`: `lt = a < b` (one bit).
    Compare,
    /// `fp_from_int`: `y = (float) a` for a signed 32-bit `a`.
    FromInt,
    /// `fp_fast_sqrt`: `y = (a + 0x3F800000) >> 1` on the bit pattern.
    FastSqrt,
    /// `fp_const`: `y = VALUE`; no clock and no latency.
    Const,
    /// `fp_select`: `y = sel ? b : a`.
    Select,
    /// `fp_register`: `y = a`, LATENCY cycles later.
    Register,
    /// `fp_inv_sqrt`: `y = 1 / sqrt(a)`, computed as `fp_div(1.0, fp_sqrt(a))` (it
    /// instantiates both cores: see [`Operator::files`]).
    InvSqrt,
    /// `fp_to_u8`: `y = (u8) round(a)`, an 8-bit `y`, rounded half away from zero and
    /// saturated to 0..=255.
    ToU8,
}

impl Operator {
    /// Every operator.
    pub const ALL: [Operator; 12] = [
        Operator::AddSub,
        Operator::Multiply,
        Operator::Divide,
        Operator::Sqrt,
        Operator::Compare,
        Operator::FromInt,
        Operator::FastSqrt,
        Operator::Const,
        Operator::Select,
        Operator::Register,
        Operator::InvSqrt,
        Operator::ToU8,
    ];

    /// The Verilog module name.
    pub const fn module_name(self) -> &'static str {
        match self {
            Operator::AddSub => "fp_add_sub",
            Operator::Multiply => "fp_mul",
            Operator::Divide => "fp_div",
            Operator::Sqrt => "fp_sqrt",
            Operator::Compare => "fp_compare",
            Operator::FromInt => "fp_from_int",
            Operator::FastSqrt => "fp_fast_sqrt",
            Operator::Const => "fp_const",
            Operator::Select => "fp_select",
            Operator::Register => "fp_register",
            Operator::InvSqrt => "fp_inv_sqrt",
            Operator::ToU8 => "fp_to_u8",
        }
    }

    /// The module's source file.
    pub const fn source(self) -> SourceFile {
        match self {
            Operator::AddSub => SourceFile {
                name: "fp_add_sub.v",
                text: include_str!("../verilog/fp_add_sub.v"),
            },
            Operator::Multiply => SourceFile {
                name: "fp_mul.v",
                text: include_str!("../verilog/fp_mul.v"),
            },
            Operator::Divide => SourceFile {
                name: "fp_div.v",
                text: include_str!("../verilog/fp_div.v"),
            },
            Operator::Sqrt => SourceFile {
                name: "fp_sqrt.v",
                text: include_str!("../verilog/fp_sqrt.v"),
            },
            Operator::Compare => SourceFile {
                name: "fp_compare.v",
                text: include_str!("../verilog/fp_compare.v"),
            },
            Operator::FromInt => SourceFile {
                name: "fp_from_int.v",
                text: include_str!("../verilog/fp_from_int.v"),
            },
            Operator::FastSqrt => SourceFile {
                name: "fp_fast_sqrt.v",
                text: include_str!("../verilog/fp_fast_sqrt.v"),
            },
            Operator::Const => SourceFile {
                name: "fp_const.v",
                text: include_str!("../verilog/fp_const.v"),
            },
            Operator::Select => SourceFile {
                name: "fp_select.v",
                text: include_str!("../verilog/fp_select.v"),
            },
            Operator::Register => SourceFile {
                name: "fp_register.v",
                text: include_str!("../verilog/fp_register.v"),
            },
            Operator::InvSqrt => SourceFile {
                name: "fp_inv_sqrt.v",
                text: include_str!("../verilog/fp_inv_sqrt.v"),
            },
            Operator::ToU8 => SourceFile {
                name: "fp_to_u8.v",
                text: include_str!("../verilog/fp_to_u8.v"),
            },
        }
    }

    /// The files a design using this operator must read: its own, those of the modules
    /// it instantiates (`fp_inv_sqrt` is built from `fp_sqrt` and `fp_div`) and, for
    /// every operator with a clock, the delay line and the pipeline's building blocks.
    pub fn files(self) -> Vec<SourceFile> {
        let own = match self {
            Operator::Const => return vec![self.source()],
            Operator::InvSqrt => vec![
                self.source(),
                Operator::Sqrt.source(),
                Operator::Divide.source(),
            ],
            _ => vec![self.source()],
        };
        own.into_iter().chain(SHARED).collect()
    }

    /// The operator library row this module implements; `None` for the constant, which
    /// has no row (and no latency).
    ///
    /// `fp_from_int` implements the `convert` row. That row's name is "float to int
    /// (IP)"; the pipeline converts the other way (the screen iterator's counters to
    /// floats), and ALTFP_CONVERT has the same documented latency, 6, for both
    /// directions at 32 bits. `fp_to_u8` (the gray value to the frame buffer's byte)
    /// implements the same row: ALTFP_CONVERT's float-to-integer direction, whose
    /// latency, 6, does not depend on the integer's width.
    pub const fn op_kind(self) -> Option<OpKind> {
        match self {
            Operator::AddSub => Some(OpKind::AddSub),
            Operator::Multiply => Some(OpKind::Multiply),
            Operator::Divide => Some(OpKind::Divide),
            Operator::Sqrt => Some(OpKind::Sqrt),
            Operator::Compare => Some(OpKind::Compare),
            Operator::FromInt => Some(OpKind::Convert),
            Operator::FastSqrt => Some(OpKind::FastSqrt),
            Operator::Const => None,
            Operator::Select => Some(OpKind::Mux),
            Operator::Register => Some(OpKind::Register),
            Operator::InvSqrt => Some(OpKind::InvSqrt),
            Operator::ToU8 => Some(OpKind::Convert),
        }
    }

    /// The module's LATENCY in `library` (0 for the constant): the single source of
    /// latencies for the model and the RTL.
    pub fn latency(self, library: &Library) -> u32 {
        self.op_kind().map_or(0, |kind| library.op(kind).latency)
    }

    /// The LATENCY of this module standing in for the library row `kind` (a registered
    /// multiplier is `fp_mul` at `multiply_registered`'s latency; a delay line is
    /// `fp_register` at any latency). Errors when the module does not implement `kind`.
    pub fn latency_as(self, library: &Library, kind: OpKind) -> Result<u32, RtlError> {
        let fits = self.op_kind() == Some(kind)
            || matches!(
                (self, kind),
                (Operator::Multiply, OpKind::MultiplyRegistered)
            );
        if fits {
            Ok(library.op(kind).latency)
        } else {
            Err(RtlError::NotImplemented {
                module: self.module_name(),
                op: kind.key(),
            })
        }
    }

    /// The module's parameters for `library`: `LATENCY`, except for the constant,
    /// whose only parameter, `VALUE`, is the caller's.
    pub fn parameters(self, library: &Library) -> Vec<(&'static str, u32)> {
        match self {
            Operator::Const => Vec::new(),
            _ => vec![("LATENCY", self.latency(library))],
        }
    }

    /// The names of the module's ports, inputs first; the result port is last (`lt`
    /// for the comparator, `y` for everything else; `fp_to_u8`'s `y` is 8 bits wide,
    /// every other `y` 32).
    pub const fn ports(self) -> &'static [&'static str] {
        match self {
            Operator::AddSub => &["clk", "a", "b", "sub", "y"],
            Operator::Multiply | Operator::Divide => &["clk", "a", "b", "y"],
            Operator::Compare => &["clk", "a", "b", "lt"],
            Operator::Sqrt
            | Operator::InvSqrt
            | Operator::FromInt
            | Operator::ToU8
            | Operator::FastSqrt
            | Operator::Register => &["clk", "a", "y"],
            Operator::Const => &["y"],
            Operator::Select => &["clk", "sel", "a", "b", "y"],
        }
    }

    /// A Verilog instance of the module with `library`'s latency, e.g.
    /// `fp_mul #(.LATENCY(5)) m0 (.clk(clk), .a(x), .b(y), .y(p));`. `connections`
    /// pairs port names with expressions; every port of [`Operator::ports`] must be
    /// connected exactly once. `extra` adds parameters (the constant's `VALUE`).
    pub fn instance(
        self,
        library: &Library,
        name: &str,
        extra: &[(&str, u32)],
        connections: &[(&str, &str)],
    ) -> Result<String, RtlError> {
        for port in self.ports() {
            let n = connections.iter().filter(|(p, _)| p == port).count();
            if n != 1 {
                return Err(RtlError::Port {
                    module: self.module_name(),
                    port: (*port).to_string(),
                    problem: if n == 0 {
                        "not connected"
                    } else {
                        "connected twice"
                    },
                });
            }
        }
        if let Some((port, _)) = connections.iter().find(|(p, _)| !self.ports().contains(p)) {
            return Err(RtlError::Port {
                module: self.module_name(),
                port: (*port).to_string(),
                problem: "no such port",
            });
        }
        let mut params: Vec<(String, u32)> = self
            .parameters(library)
            .into_iter()
            .map(|(p, v)| (p.to_string(), v))
            .collect();
        params.extend(extra.iter().map(|(p, v)| ((*p).to_string(), *v)));
        let mut text = String::from(self.module_name());
        if !params.is_empty() {
            let list: Vec<String> = params
                .iter()
                .map(|(p, v)| {
                    if p == "VALUE" {
                        format!(".{p}(32'h{v:08X})")
                    } else {
                        format!(".{p}({v})")
                    }
                })
                .collect();
            let _ = write!(text, " #({})", list.join(", "));
        }
        let ports: Vec<String> = connections
            .iter()
            .map(|(p, e)| format!(".{p}({e})"))
            .collect();
        let _ = write!(text, " {name} ({});", ports.join(", "));
        Ok(text)
    }
}

/// Writes every file of [`SOURCES`] into `dir` (created if missing) and returns their
/// paths. Each file is written to a temporary name in `dir` and renamed into place, so
/// a reader never sees a half-written file.
pub fn write_sources(dir: &Path) -> Result<Vec<PathBuf>, RtlError> {
    fs::create_dir_all(dir).map_err(|source| RtlError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    SOURCES
        .iter()
        .map(|file| write_atomically(&dir.join(file.name), file.text))
        .collect()
}

/// Writes `text` to `path` through a temporary file beside it and a rename
/// ([`tracer::image_io::write_atomically`], the workspace's one way of writing a file),
/// with the path in the error.
pub fn write_atomically(path: &Path, text: &str) -> Result<PathBuf, RtlError> {
    tracer::image_io::write_atomically(path, text.as_bytes()).map_err(|source| RtlError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latencies_come_from_the_library() {
        let lib = Library::cyclone_iv_e();
        let got: Vec<(&str, u32)> = Operator::ALL
            .iter()
            .map(|op| (op.module_name(), op.latency(&lib)))
            .collect();
        assert_eq!(
            got,
            [
                ("fp_add_sub", 7),
                ("fp_mul", 5),
                ("fp_div", 15),
                ("fp_sqrt", 16),
                ("fp_compare", 3),
                ("fp_from_int", 6),
                ("fp_fast_sqrt", 1),
                ("fp_const", 0),
                ("fp_select", 0),
                ("fp_register", 1),
                ("fp_inv_sqrt", 28),
                ("fp_to_u8", 6),
            ]
        );
        assert_eq!(
            Operator::Multiply
                .latency_as(&lib, OpKind::MultiplyRegistered)
                .unwrap(),
            7
        );
        assert!(Operator::Sqrt.latency_as(&lib, OpKind::Divide).is_err());
        assert_eq!(
            Operator::InvSqrt.latency_as(&lib, OpKind::InvSqrt).unwrap(),
            28
        );
        assert_eq!(Operator::ToU8.latency_as(&lib, OpKind::Convert).unwrap(), 6);
        assert!(Operator::InvSqrt.latency_as(&lib, OpKind::Sqrt).is_err());
    }

    #[test]
    fn every_source_declares_its_module_and_a_latency_parameter() {
        for op in Operator::ALL {
            let file = op.source();
            assert_eq!(file.name, format!("{}.v", op.module_name()));
            assert!(
                file.text.starts_with("// "),
                "{}: module doc first",
                file.name
            );
            assert!(
                file.text
                    .contains(&format!("module {} #(", op.module_name())),
                "{}",
                file.name
            );
            let has_latency = file.text.contains("parameter LATENCY");
            assert_eq!(has_latency, op != Operator::Const, "{}", file.name);
            for port in op.ports() {
                assert!(
                    file.text.contains(&format!(" {port},"))
                        || file.text.contains(&format!(" {port}\n")),
                    "{}: port {port}",
                    file.name
                );
            }
            // Verilog-2005 for Yosys and Verilator: no SystemVerilog, no division.
            let code = strip_comments(file.text);
            for banned in [
                "logic",
                "always_comb",
                "always_ff",
                "/",
                "%",
                "initial",
                "real",
            ] {
                assert!(!code.contains(banned), "{}: {banned:?}", file.name);
            }
        }
    }

    #[test]
    fn files_hold_every_module_a_source_instantiates() {
        for op in Operator::ALL {
            let files = op.files();
            let code = strip_comments(op.source().text);
            for file in SOURCES {
                let module = file.name.trim_end_matches(".v");
                let used = code.contains(&format!("{module} #("))
                    && !code.contains(&format!("module {module} #("));
                if used {
                    assert!(files.contains(&file), "{}: {}", op.module_name(), file.name);
                }
            }
            assert_eq!(files[0], op.source());
            assert!(files.iter().all(|f| SOURCES.contains(f)));
        }
        assert_eq!(Operator::InvSqrt.files().len(), 3 + SHARED.len());
    }

    /// The text without `//` line comments and `/* */` block comments.
    fn strip_comments(text: &str) -> String {
        let mut out = String::new();
        let mut rest = text;
        while !rest.is_empty() {
            if let Some(r) = rest.strip_prefix("//") {
                rest = r.find('\n').map_or("", |i| &r[i..]);
            } else if let Some(r) = rest.strip_prefix("/*") {
                rest = r.find("*/").map_or("", |i| &r[i + 2..]);
            } else {
                let c = rest.chars().next().unwrap();
                out.push(c);
                rest = &rest[c.len_utf8()..];
            }
        }
        out
    }

    #[test]
    fn instances_carry_the_library_latency() {
        let lib = Library::cyclone_iv_e();
        let text = Operator::Multiply
            .instance(
                &lib,
                "m0",
                &[],
                &[("clk", "clk"), ("a", "x"), ("b", "z"), ("y", "p")],
            )
            .unwrap();
        assert_eq!(
            text,
            "fp_mul #(.LATENCY(5)) m0 (.clk(clk), .a(x), .b(z), .y(p));"
        );
        let text = Operator::Const
            .instance(&lib, "one", &[("VALUE", 0x3F80_0000)], &[("y", "w")])
            .unwrap();
        assert_eq!(text, "fp_const #(.VALUE(32'h3F800000)) one (.y(w));");
        let err = Operator::Sqrt
            .instance(&lib, "s", &[], &[("clk", "clk"), ("y", "r")])
            .unwrap_err();
        assert!(err.to_string().contains("`a`"), "{err}");
    }

    #[test]
    fn sources_are_written_whole() {
        let dir = std::env::temp_dir().join(format!("rtl-sources-{}", std::process::id()));
        let paths = write_sources(&dir).unwrap();
        assert_eq!(paths.len(), SOURCES.len());
        for (path, file) in paths.iter().zip(SOURCES) {
            assert_eq!(fs::read_to_string(path).unwrap(), file.text);
        }
        // Only the sources: no temporary files left behind.
        assert_eq!(fs::read_dir(&dir).unwrap().count(), SOURCES.len());
        fs::remove_dir_all(&dir).unwrap();
    }
}
