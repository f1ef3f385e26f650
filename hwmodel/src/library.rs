//! The operator library of a device family, read from TOML (`hwmodel/data/*.toml`).
//!
//! A library lists the floating-point IP cores the blocks are built from (latency and
//! resources per instance), the fixed "glue" blocks around the pipeline, the devices of
//! the family, and two rules: how long a delay line must be to go to memory, and what a
//! multiplier element costs when it has to be built in logic. The Cyclone IV E file
//! carries the thesis's table 7 rows; anything not measured there says it is assumed
//! and why. The families are embedded, so the model runs anywhere; `--library FILE`
//! style overrides go through [`Library::from_toml`].

use std::collections::BTreeMap;
use std::ops::{Add, AddAssign, Mul};

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Resources of one instance, or of a sum of instances.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Resources {
    /// Logic elements.
    pub le: u64,
    /// Combinational functions.
    pub comb: u64,
    /// Logic registers.
    pub regs: u64,
    /// Memory bits.
    pub mem_bits: u64,
    /// 9-bit embedded multiplier elements.
    pub mult: u64,
}

impl Add for Resources {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            le: self.le + o.le,
            comb: self.comb + o.comb,
            regs: self.regs + o.regs,
            mem_bits: self.mem_bits + o.mem_bits,
            mult: self.mult + o.mult,
        }
    }
}

impl AddAssign for Resources {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl Mul<u64> for Resources {
    type Output = Self;
    fn mul(self, k: u64) -> Self {
        Self {
            le: self.le * k,
            comb: self.comb * k,
            regs: self.regs * k,
            mem_bits: self.mem_bits * k,
            mult: self.mult * k,
        }
    }
}

impl std::iter::Sum for Resources {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::default(), |a, b| a + b)
    }
}

/// The operators a dataflow graph is built from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OpKind {
    AddSub,
    Multiply,
    MultiplyRegistered,
    Sqrt,
    Divide,
    InvSqrt,
    Compare,
    /// A magnitude compare of non-negative IEEE distances as integers (their bit
    /// patterns order as the numbers do): the one-primitive-a-cycle minimum distance.
    IntCompare,
    Convert,
    Mux,
    Register,
    RamRead,
    FastSqrt,
}

impl OpKind {
    /// Every operator, in table order.
    pub const ALL: [OpKind; 13] = [
        OpKind::AddSub,
        OpKind::Multiply,
        OpKind::MultiplyRegistered,
        OpKind::Sqrt,
        OpKind::Divide,
        OpKind::InvSqrt,
        OpKind::Compare,
        OpKind::IntCompare,
        OpKind::Convert,
        OpKind::Mux,
        OpKind::Register,
        OpKind::RamRead,
        OpKind::FastSqrt,
    ];

    /// The key in the library file.
    pub fn key(self) -> &'static str {
        match self {
            OpKind::AddSub => "add_sub",
            OpKind::Multiply => "multiply",
            OpKind::MultiplyRegistered => "multiply_registered",
            OpKind::Sqrt => "sqrt",
            OpKind::Divide => "divide",
            OpKind::InvSqrt => "inv_sqrt",
            OpKind::Compare => "compare",
            OpKind::IntCompare => "int_compare",
            OpKind::Convert => "convert",
            OpKind::Mux => "mux",
            OpKind::Register => "register",
            OpKind::RamRead => "ram_read",
            OpKind::FastSqrt => "fast_sqrt",
        }
    }
}

/// One operator's row: latency and resources per instance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OpSpec {
    pub name: String,
    /// Where the figures come from ("thesis table 7 …" or "assumed: …").
    pub source: String,
    pub latency: u32,
    #[serde(flatten)]
    pub resources: Resources,
}

/// A fixed block outside the four modelled ones (screen iterator, VGA, loader).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GlueSpec {
    pub name: String,
    pub source: String,
    #[serde(flatten)]
    pub resources: Resources,
}

/// A RAM block of a family: its name, its bits and the shapes it can take.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct MemoryBlock {
    /// `M9K`, `M10K`, `M20K`.
    pub name: String,
    /// Bits a block holds (parity bits included).
    pub bits: u64,
    /// The shapes as `[depth, width]`, e.g. `[1024, 9]`.
    pub shapes: Vec<[u64; 2]>,
}

/// Blocks a memory of `depth` words × `width` bits takes in the best of `block`'s
/// shapes (0 for an empty memory).
pub fn blocks_for(block: &MemoryBlock, depth: u64, width: u64) -> u64 {
    if depth == 0 || width == 0 {
        return 0;
    }
    block
        .shapes
        .iter()
        .map(|&[d, w]| depth.div_ceil(d.max(1)) * width.div_ceil(w.max(1)))
        .min()
        .unwrap_or(u64::MAX)
}

/// A device of the family.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DeviceSpec {
    pub name: String,
    /// The board or product line it is known from.
    pub board: String,
    /// Whether the thesis measured on it (the library's TOML says which device).
    pub validated: bool,
    /// Logic elements (LE equivalents for families built of ALMs).
    pub le: u64,
    /// 9-bit multiplier elements (or their equivalents).
    pub mult: u64,
    pub mem_bits: u64,
    pub plls: u32,
}

/// A device family's operator library.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Library {
    pub family: String,
    /// False when the figures are not measurements on this family.
    pub validated: bool,
    #[serde(default)]
    pub note: Option<String>,
    pub word_bits: u32,
    /// Delay lines at least this long go to memory.
    pub memory_delay_min_cycles: u32,
    /// LEs per 9-bit multiplier element built in logic.
    pub soft_mult9_le: u64,
    /// Registers per 9-bit multiplier element built in logic.
    pub soft_mult9_regs: u64,
    /// The family's RAM block ([`crate::memory`]): a device's `mem_bits` is a whole
    /// number of them.
    pub memory_block: MemoryBlock,
    ops: BTreeMap<String, OpSpec>,
    #[serde(default)]
    glue: BTreeMap<String, GlueSpec>,
    pub devices: Vec<DeviceSpec>,
}

/// A library file that cannot be used.
#[derive(Debug, Error)]
pub enum LibraryError {
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    #[error("{file}: operator `{op}` is missing (every library needs all of: {all})")]
    MissingOp {
        file: String,
        op: &'static str,
        all: String,
    },
    #[error("{file}: no devices listed")]
    NoDevices { file: String },
    #[error("unknown device '{name}': known devices are {known}")]
    UnknownDevice { name: String, known: String },
}

/// The Cyclone IV E library (thesis table 7), embedded.
pub const CYCLONE_IV_E: &str = include_str!("../data/cyclone_iv_e.toml");
/// The Cyclone V library (not validated), embedded.
pub const CYCLONE_V: &str = include_str!("../data/cyclone_v.toml");
/// The Arria 10 library (hard floating-point DSP blocks, not validated), embedded.
pub const ARRIA_10: &str = include_str!("../data/arria_10.toml");

impl Library {
    /// The RAM blocks of `device` (its memory bits over the block's).
    pub fn memory_blocks(&self, device: &DeviceSpec) -> u64 {
        device.mem_bits / self.memory_block.bits.max(1)
    }

    /// The device the thesis measured on, as the library's TOML marks it (`validated`).
    pub fn validated_device(&self) -> Option<&DeviceSpec> {
        self.devices.iter().find(|d| d.validated)
    }

    /// Parses a library file; `file` names it in errors.
    pub fn from_toml(text: &str, file: &str) -> Result<Self, LibraryError> {
        let library: Library = toml::from_str(text).map_err(|e| LibraryError::Parse {
            file: file.to_string(),
            message: e.to_string(),
        })?;
        for op in OpKind::ALL {
            if !library.ops.contains_key(op.key()) {
                return Err(LibraryError::MissingOp {
                    file: file.to_string(),
                    op: op.key(),
                    all: OpKind::ALL.map(OpKind::key).join(", "),
                });
            }
        }
        if library.devices.is_empty() {
            return Err(LibraryError::NoDevices {
                file: file.to_string(),
            });
        }
        Ok(library)
    }

    /// The thesis's family, Cyclone IV E.
    pub fn cyclone_iv_e() -> Self {
        // The embedded file is checked by a unit test, so this cannot fail at run time
        // unless the build itself is broken.
        Self::from_toml(CYCLONE_IV_E, "cyclone_iv_e.toml")
            .unwrap_or_else(|e| unreachable!("embedded library is invalid: {e}"))
    }

    /// Every embedded family.
    pub fn embedded() -> Vec<Self> {
        let mut out = vec![Self::cyclone_iv_e()];
        if let Ok(v) = Self::from_toml(CYCLONE_V, "cyclone_v.toml") {
            out.push(v);
        }
        if let Ok(v) = Self::from_toml(ARRIA_10, "arria_10.toml") {
            out.push(v);
        }
        out
    }

    /// The row of `op`.
    pub fn op(&self, op: OpKind) -> &OpSpec {
        // Presence of every key is checked in `from_toml`.
        &self.ops[op.key()]
    }

    /// The glue blocks, by key.
    pub fn glue(&self) -> impl Iterator<Item = (&str, &GlueSpec)> {
        self.glue.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// Cost of a delay line of `bits` wide and `cycles` long under this library's rule:
    /// short lines in registers (one LE each), long ones in memory.
    pub fn delay_line(&self, bits: u64, cycles: u64) -> Resources {
        if cycles == 0 || bits == 0 {
            Resources::default()
        } else if cycles >= u64::from(self.memory_delay_min_cycles) {
            Resources {
                mem_bits: bits * cycles,
                ..Resources::default()
            }
        } else {
            Resources {
                le: bits * cycles,
                regs: bits * cycles,
                ..Resources::default()
            }
        }
    }
}

/// Finds a device by name (case-insensitive) in any embedded family; the error lists
/// the known devices.
pub fn find_device(name: &str) -> Result<(Library, DeviceSpec), LibraryError> {
    Library::embedded()
        .into_iter()
        .find_map(|lib| {
            let device = lib
                .devices
                .iter()
                .find(|d| d.name.eq_ignore_ascii_case(name))
                .cloned();
            device.map(|d| (lib, d))
        })
        .ok_or_else(|| LibraryError::UnknownDevice {
            name: name.to_string(),
            known: device_names().join(", "),
        })
}

/// The name of the device the hardware commands use by default: the one the Cyclone
/// IV E library marks `validated` (the thesis's board), read from its TOML, the one
/// place that says which device the thesis measured on.
pub fn default_device_name() -> String {
    Library::cyclone_iv_e()
        .validated_device()
        .map_or_else(String::new, |d| d.name.clone())
}

/// Names of every embedded device, for error messages and `--help`.
pub fn device_names() -> Vec<String> {
    Library::embedded()
        .iter()
        .flat_map(|lib| lib.devices.iter().map(|d| d.name.clone()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_libraries_parse_and_carry_table_7() {
        let lib = Library::cyclone_iv_e();
        assert!(lib.validated);
        // Table 7, IP rows, as printed in the thesis, except the divider's and the
        // inverse square root's latencies: the RTL's pipelined recurrences (issue 38).
        let add = lib.op(OpKind::AddSub);
        assert_eq!(
            (add.latency, add.resources.le, add.resources.mult),
            (7, 906, 0)
        );
        let mul = lib.op(OpKind::Multiply);
        assert_eq!(
            (mul.latency, mul.resources.regs, mul.resources.mult),
            (5, 218, 7)
        );
        let div = lib.op(OpKind::Divide);
        assert_eq!(
            (div.latency, div.resources.mem_bits, div.resources.mult),
            (15, 4608, 16)
        );
        assert_eq!(lib.op(OpKind::InvSqrt).latency, 28);
        assert_eq!(lib.op(OpKind::Sqrt).resources.comb, 826);
        let ep4 = &lib.devices[0];
        assert_eq!(
            (ep4.le, ep4.mult, ep4.mem_bits, ep4.plls),
            (114_480, 532, 3_981_312, 4)
        );
        let v = Library::from_toml(CYCLONE_V, "cyclone_v.toml").unwrap();
        assert!(!v.validated && v.devices.iter().all(|d| !d.validated));
    }

    #[test]
    fn delay_lines_spill_to_memory_at_the_threshold() {
        let lib = Library::cyclone_iv_e();
        let t = u64::from(lib.memory_delay_min_cycles);
        let short = lib.delay_line(32, t - 1);
        assert_eq!(
            (short.regs, short.le, short.mem_bits),
            (32 * (t - 1), 32 * (t - 1), 0)
        );
        let long = lib.delay_line(96, t);
        assert_eq!((long.regs, long.mem_bits), (0, 96 * t));
        assert_eq!(lib.delay_line(32, 0), Resources::default());
    }

    #[test]
    fn a_library_without_an_operator_is_refused_with_its_name() {
        let text = CYCLONE_IV_E.replace("[ops.sqrt]", "[ops.not_sqrt]");
        let err = Library::from_toml(&text, "x.toml").unwrap_err().to_string();
        assert!(err.contains("x.toml") && err.contains("`sqrt`"), "{err}");
        let err = Library::from_toml("family = 3", "y.toml")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("y.toml: "), "{err}");
    }
}
