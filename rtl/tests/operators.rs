//! Bit-exact tests of the Verilog operators (`rtl/verilog/fp_*.v`) against their Rust
//! reference (`rtl::float_policy`), simulated with Verilator.
//!
//! For each operator: 1,000,000 seeded random inputs (uniform bit patterns mixed with
//! values drawn to hit near-equal exponents, cancellation, rounding ties, exact results
//! and the edges of the exponent range; for `fp_to_u8`, values in [-2, 300] with exact
//! halves and their neighbours) and a list of edge cases. The test writes the
//! inputs to a file, builds a Verilator model of the operator at the latency of its row
//! in hwmodel's Cyclone IV E library (wrapped in a generated `tb_top` with uniform
//! ports, driven by `rtl/verilog/tb/tb_main.cpp`, one input per clock), runs it, and
//! compares every output with the reference: identical bits, or any NaN where the
//! reference is NaN. It also checks that the results appear exactly LATENCY cycles
//! after their inputs.
//!
//! These tests need `verilator`, `g++` and `make` (`scripts/install-rtl-tools.sh`), so
//! they are ignored by default: `cargo test -p rtl -- --ignored`. Without the tools
//! they fail and say how to install them.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use hwmodel::library::Library;
use rtl::Operator;
use rtl::float_policy as fp;

/// Random inputs per operator.
const RANDOM: usize = 1_000_000;

/// The constants the `fp_const` test instantiates (selected by `c[1:0]`).
const CONSTANTS: [u32; 4] = [0x3F80_0000, 0x7FC0_0000, 0x8000_0000, 0xFF7F_FFFF];

/// Single-precision edge values (their negations are added by [`edge_values`]).
const SPECIALS: &[u32] = &[
    0x0000_0000, // +0
    0x0000_0001, // smallest subnormal
    0x0040_0000, // a middle subnormal
    0x007F_FFFF, // largest subnormal
    0x0080_0000, // smallest normal
    0x0080_0001,
    0x00FF_FFFF,
    0x0100_0000,
    0x7F7F_FFFF, // largest normal
    0x7F7F_FFFE,
    0x7F00_0000, // 2^127
    0x7E80_0000,
    0x7F80_0000, // inf
    0x7FC0_0000, // quiet NaN
    0x7F80_0001, // signalling NaN
    0x7FFF_FFFF, // NaN, all payload bits
    0x3F80_0000, // 1.0
    0x3F80_0001, // 1 + 2^-23
    0x3F7F_FFFF, // 1 - 2^-24
    0x4000_0000, // 2.0
    0x3F00_0000, // 0.5
    0x3FC0_0000, // 1.5
    0x4040_0000, // 3.0
    0x3FFF_FFFF,
    0x3380_0000, // 2^-24: half an ulp of 1.0
    0x3300_0000, // 2^-25
    0x33C0_0000, // 1.5 * 2^-24
    0x3400_0000, // 2^-23
    0x3DCC_CCCD, // 0.1
    0x3E4C_CCCD, // 0.2
    0x3E99_999A, // 0.3
    0x4049_0FDB, // pi
    0x3FB5_04F3, // sqrt(2)
    0x4B80_0000, // 2^24
    0x4B80_0001, // 2^24 + 2
    0x4B00_0000, // 2^23
    0x5F00_0000, // 2^63
    0x2000_0000, // 2^-63
    0x1F80_0000, // 2^-64
    0x3F80_0800, // 1 + 2^-12: its square is a tie
    0x3F80_1800, // 1 + 3 * 2^-12
];

/// Every special value and its negation.
fn edge_values() -> Vec<u32> {
    SPECIALS
        .iter()
        .flat_map(|&x| [x, x ^ 0x8000_0000])
        .collect()
}

/// Integers for `fp_from_int`'s edge list.
const INT_EDGES: &[i32] = &[
    0,
    1,
    -1,
    2,
    -2,
    3,
    i32::MIN,
    i32::MIN + 1,
    i32::MAX,
    i32::MAX - 63,
    i32::MAX - 64,
    i32::MAX - 127,
    (1 << 24) - 1,
    1 << 24,
    (1 << 24) + 1, // tie: to 2^24
    (1 << 24) + 3, // tie: to 2^24 + 4
    (1 << 25) + 2, // tie: to 2^25
    (1 << 25) + 6, // tie: to 2^25 + 8
    (1 << 25) + 1,
    (1 << 25) + 3,
    -(1 << 24) - 1,
    -(1 << 24) - 3,
    0x7FFF_FF80, // tie between 0x7FFFFF00 and 2^31: to 2^31
    0x7FFF_FF7F,
    0x7FFF_FFC0,
    0x00FF_FFFF,
    0x0100_0001,
    0x4000_0040,
    0x4000_00C0,
    -0x4000_00C0,
    1 << 30,
    -(1 << 30),
    640,
    480,
    1023,
];

/// One input triple: a, b and the control word c (as the testbench streams them).
type Input = [u32; 3];

/// A random float with `exp` as biased exponent, a random sign and fraction.
fn with_exp(rng: &mut fastrand::Rng, exp: u32) -> u32 {
    (rng.u32(..) & 0x8000_0000) | (exp.min(255) << 23) | fraction(rng)
}

/// A random normal number.
fn random_normal(rng: &mut fastrand::Rng) -> u32 {
    let exp = rng.u32(1..255);
    with_exp(rng, exp)
}

/// A fraction: uniformly random, or with only its high bits random (so that results
/// are exact or land on ties), or with only a few bits set.
fn fraction(rng: &mut fastrand::Rng) -> u32 {
    let f = rng.u32(..) & 0x7F_FFFF;
    match rng.u8(0..4) {
        0 | 1 => f,
        2 => f & !((1u32 << rng.u32(0..24)) - 1) & 0x7F_FFFF,
        _ => (0..rng.u32(0..4)).fold(0, |acc, _| acc | (1 << rng.u32(0..23))),
    }
}

/// A float of an integer of 1 to 25 significant bits scaled by a random power of two
/// (products and quotients of these are often exact or ties).
fn int_like(rng: &mut fastrand::Rng) -> u32 {
    let bits = rng.u32(1..=25);
    let n = rng.u32(1u32 << (bits - 1)..=((1u64 << bits) - 1) as u32);
    let lz = n.leading_zeros(); // n = 1.x * 2^(31 - lz)
    let frac = ((u64::from(n) << (lz + 1)) >> 9) as u32 & 0x7F_FFFF;
    let exp = rng.u32(60..=190);
    (rng.u32(..) & 0x8000_0000) | (exp << 23) | frac
}

/// Random inputs for a two-operand arithmetic operator (`op` selects the cases that
/// matter for it: exponent sums for products, differences for quotients).
fn binary_inputs(rng: &mut fastrand::Rng, op: Operator, n: usize) -> Vec<Input> {
    let edges = edge_values();
    (0..n)
        .map(|_| {
            let c = u32::from(rng.bool());
            let (a, b) = match rng.u8(0..10) {
                // Uniform bit patterns.
                0 | 1 => (rng.u32(..), rng.u32(..)),
                // Random normal numbers over the whole range.
                2 => (random_normal(rng), random_normal(rng)),
                // Near-equal exponents (cancellation in a difference).
                3 => {
                    let ea = rng.u32(1..255);
                    let eb = (ea as i32 + rng.i32(-3..=3)).clamp(1, 254) as u32;
                    (with_exp(rng, ea), with_exp(rng, eb))
                }
                // b = ±(a plus a few ulps): massive cancellation, exact zeros.
                4 => {
                    let a = random_normal(rng);
                    let b =
                        a.wrapping_add(rng.u32(0..5)).wrapping_sub(2) ^ (rng.u32(..) & 0x8000_0000);
                    (a, b)
                }
                // Exponent differences around the significand width: rounding ties and
                // sticky bits in alignment.
                5 => {
                    let ea = rng.u32(30..255);
                    let eb = ea - rng.u32(20..30);
                    (with_exp(rng, ea), with_exp(rng, eb))
                }
                // Integer-like values: exact products and quotients, ties in products.
                6 => (int_like(rng), int_like(rng)),
                // Results near the ends of the exponent range (flush and overflow).
                7 => {
                    let ea = rng.u32(1..255);
                    let target = if rng.bool() {
                        rng.u32(0..4)
                    } else {
                        rng.u32(251..256)
                    };
                    let eb = match op {
                        // product exponent ea + eb - 127, quotient ea - eb + 127
                        Operator::Multiply => target as i32 + 127 - ea as i32,
                        Operator::Divide => ea as i32 + 127 - target as i32,
                        _ => {
                            // sums: two numbers near the smallest normal, or the largest
                            let e = if target < 4 {
                                rng.u32(1..4)
                            } else {
                                rng.u32(252..255)
                            };
                            return [with_exp(rng, e), with_exp(rng, e), c];
                        }
                    };
                    (with_exp(rng, ea), with_exp(rng, eb.clamp(1, 254) as u32))
                }
                // Products whose 24-bit rounding is just below 2^-126 (see
                // `band_product`), or just above it.
                8 if op == Operator::Multiply => band_product(rng),
                // An edge value with a random or another edge value.
                _ => {
                    let e = edges[rng.usize(..edges.len())];
                    let other = if rng.bool() {
                        rng.u32(..)
                    } else {
                        edges[rng.usize(..edges.len())]
                    };
                    if rng.bool() { (e, other) } else { (other, e) }
                }
            };
            [a, b, c]
        })
        .collect()
}

/// A pair whose exact product lies in or near [2^-126 - 2^-150, 2^-126 - 2^-151), where
/// IEEE rounding (on the subnormal grid) gives 2^-126 but the policy flushes: the
/// significands ma, mb have a product just below 2^47, and a = ma * 2^-24,
/// b = mb * 2^-149 (random signs, and the factor 2^k moved between them).
fn band_product(rng: &mut fastrand::Rng) -> (u32, u32) {
    let ma = rng.u64((1 << 23) + 1..1 << 24);
    let target = (1u64 << 47) - (1 << 23) + rng.u64(0..(1 << 23) + (1 << 22));
    let mb = target.div_ceil(ma).clamp(1 << 23, (1 << 24) - 1);
    let k = rng.u32(0..100);
    let a = (rng.u32(..) & 0x8000_0000) | ((126 - k) << 23) | (ma as u32 & 0x7F_FFFF);
    let b = (rng.u32(..) & 0x8000_0000) | ((1 + k) << 23) | (mb as u32 & 0x7F_FFFF);
    (a, b)
}

/// Explicit two-operand edge cases: every pair of edge values (with `sub` 0 and 1 for
/// the adder), plus hand-picked ties.
fn binary_edges(op: Operator) -> Vec<Input> {
    let edges = edge_values();
    let mut out = Vec::new();
    for &a in &edges {
        for &b in &edges {
            out.push([a, b, 0]);
            if op == Operator::AddSub {
                out.push([a, b, 1]);
            }
        }
    }
    let ties: &[(u32, u32)] = &[
        (0x3F80_0000, 0x3380_0000), // 1 + 2^-24: tie, to even 1.0
        (0x3F80_0001, 0x3380_0000), // (1 + 2^-23) + 2^-24: tie, to even 1 + 2^-22
        (0x4B80_0000, 0x3F80_0000), // 2^24 + 1: tie, to 2^24
        (0x4B80_0001, 0x3F80_0000), // 2^24 + 3: tie, to 2^24 + 4
        (0x3F80_0800, 0x3F80_0800), // (1 + 2^-12)^2 = 1 + 2^-11 + 2^-24: tie
        (0x3F80_1800, 0x3F80_0800),
        (0x3E99_999A, 0x3DCC_CCCD), // 0.3 - 0.1: a tie
        (0x3F80_0000, 0x4040_0000), // 1/3
        (0x4000_0000, 0x4040_0000),
        (0x0080_0000, 0x3F00_0000), // 2^-126 * 0.5: flushed
        (0x0100_0000, 0x3F00_0000), // exactly 2^-126
    ];
    for &(a, b) in ties {
        for c in [0, 1] {
            out.push([a, b, c]);
            out.push([b, a, c]);
            out.push([a ^ 0x8000_0000, b, c]);
        }
    }
    out
}

/// Random inputs for the square root: uniform bits, positive normals, exact squares of
/// integers and their neighbours.
fn sqrt_inputs(rng: &mut fastrand::Rng, n: usize) -> Vec<Input> {
    (0..n)
        .map(|_| {
            let a = match rng.u8(0..4) {
                0 => rng.u32(..),
                1 => random_normal(rng) & 0x7FFF_FFFF,
                _ => {
                    let m = rng.u32(1..1 << 12);
                    let square = (m * m) as f32; // exact: at most 24 bits
                    // times 2^scale (an even power keeps it a square), exponent in range
                    let scale = rng.i32(-60..=50) * 2;
                    let x = (square.to_bits() as i32 + (scale << 23)) as u32;
                    x.wrapping_add(rng.u32(0..3)).wrapping_sub(1)
                }
            };
            [a, 0, 0]
        })
        .collect()
}

/// Random inputs for the reciprocal root: the square root's (uniform bits, positive
/// normals, exact squares and their neighbours), and powers of two over the whole
/// exponent range with their neighbours (exact roots of even powers, exact reciprocals).
fn inv_sqrt_inputs(rng: &mut fastrand::Rng, n: usize) -> Vec<Input> {
    let mut out = sqrt_inputs(rng, n);
    for input in &mut out {
        if rng.u8(0..4) == 0 {
            let power = rng.u32(1..255) << 23;
            input[0] = power.wrapping_add(rng.u32(0..5)).wrapping_sub(2);
        }
    }
    out
}

/// Random inputs for the float-to-byte conversion: uniform bit patterns; uniform values
/// in [-2, 300]; exact integers and halves k + 0.5 (ties, rounded away from zero) for
/// k in -3..=300, and their neighbours a few ulps away; and values with exponents
/// around the conversion's range (0.5 to 512, either sign).
fn u8_inputs(rng: &mut fastrand::Rng, n: usize) -> Vec<Input> {
    (0..n)
        .map(|_| {
            let a = match rng.u8(0..8) {
                0 => rng.u32(..),
                1..=3 => (rng.f32() * 302.0 - 2.0).to_bits(),
                4 => (rng.i32(-3..=300) as f32).to_bits(),
                5 => (rng.i32(-3..=300) as f32 + 0.5).to_bits(),
                6 => (rng.i32(-3..=300) as f32 + 0.5)
                    .to_bits()
                    .wrapping_add(rng.u32(0..7))
                    .wrapping_sub(3),
                _ => {
                    let exp = rng.u32(124..=136);
                    let sign = if rng.u8(0..8) == 0 { 0x8000_0000 } else { 0 };
                    sign | (exp << 23) | fraction(rng)
                }
            };
            [a, 0, 0]
        })
        .collect()
}

/// The float-to-byte conversion's edge list: every integer and half from -3 to 300
/// with its neighbours one ulp away, and the largest floats below the saturation and
/// rounding thresholds.
fn u8_edges() -> Vec<Input> {
    let mut out: Vec<u32> = edge_values();
    for k in -3..=300 {
        for x in [k as f32, k as f32 + 0.5] {
            let b = x.to_bits();
            out.extend([b, b.wrapping_add(1), b.wrapping_sub(1)]);
        }
    }
    out.extend([
        0x3EFF_FFFF, // just below 0.5
        0x437F_8000, // 255.5
        0x437F_7FFF, // just below 255.5
        0x437F_FFFF, // just below 256
        0x4380_0000, // 256
        0x4F00_0000, // 2^31
        0x4F80_0000, // 2^32
        0x5F80_0000, // 2^64
    ]);
    out.into_iter().map(|a| [a, 0, 0]).collect()
}

/// Random integers for the conversion: uniform, of random bit lengths, and ties (the
/// bits below the 24 kept ones exactly one half).
fn int_inputs(rng: &mut fastrand::Rng, n: usize) -> Vec<Input> {
    (0..n)
        .map(|_| {
            let x = match rng.u8(0..3) {
                0 => rng.u32(..),
                1 => rng.u32(..) >> rng.u32(0..32),
                _ => {
                    let drop = rng.u32(1..8); // bits below the 24 kept ones
                    let top = rng.u32(1 << 23..1 << 24);
                    ((top << drop) | (1 << (drop - 1))) >> rng.u32(0..2)
                }
            };
            let x = if rng.bool() { x } else { x.wrapping_neg() };
            [x, 0, 0]
        })
        .collect()
}

/// Random pairs for the comparison: uniform bits, near-equal values, equal magnitudes of
/// either sign, and edge values.
fn compare_inputs(rng: &mut fastrand::Rng, n: usize) -> Vec<Input> {
    let edges = edge_values();
    (0..n)
        .map(|_| {
            let (a, b) = match rng.u8(0..5) {
                0 | 1 => (rng.u32(..), rng.u32(..)),
                2 => {
                    let a = rng.u32(..);
                    (a, a.wrapping_add(rng.u32(0..5)).wrapping_sub(2))
                }
                3 => {
                    let a = rng.u32(..);
                    (a, a ^ (rng.u32(..) & 0x8000_0000))
                }
                _ => (
                    edges[rng.usize(..edges.len())],
                    if rng.bool() {
                        rng.u32(..)
                    } else {
                        edges[rng.usize(..edges.len())]
                    },
                ),
            };
            [a, b, 0]
        })
        .collect()
}

fn f(x: u32) -> f32 {
    f32::from_bits(x)
}

/// The reference result of `op` for one input triple, as the testbench's 32-bit `y`.
fn reference(op: Operator, [a, b, c]: Input) -> u32 {
    match op {
        Operator::AddSub if c & 1 == 1 => fp::sub(f(a), f(b)).to_bits(),
        Operator::AddSub => fp::add(f(a), f(b)).to_bits(),
        Operator::Multiply => fp::mul(f(a), f(b)).to_bits(),
        Operator::Divide => fp::div(f(a), f(b)).to_bits(),
        Operator::Sqrt => fp::sqrt(f(a)).to_bits(),
        Operator::InvSqrt => fp::inv_sqrt(f(a)).to_bits(),
        Operator::Compare => u32::from(fp::lt(f(a), f(b))),
        Operator::FromInt => fp::from_int(a as i32).to_bits(),
        Operator::ToU8 => u32::from(fp::to_u8(f(a))),
        Operator::FastSqrt => fp::fast_sqrt(f(a)).to_bits(),
        Operator::Const => CONSTANTS[(c & 3) as usize],
        Operator::Select => fp::select(c & 1 == 1, f(a), f(b)).to_bits(),
        Operator::Register => a,
    }
}

/// The test inputs of `op`: random ones first (the latency probe looks at those), then
/// the edge cases. Returns the inputs and the number of edge cases.
fn inputs(op: Operator) -> (Vec<Input>, usize) {
    let mut rng = fastrand::Rng::with_seed(0x5254_4C00 + op as u64);
    let mut cases = match op {
        Operator::AddSub | Operator::Multiply | Operator::Divide => {
            binary_inputs(&mut rng, op, RANDOM)
        }
        Operator::Sqrt => sqrt_inputs(&mut rng, RANDOM),
        Operator::InvSqrt => inv_sqrt_inputs(&mut rng, RANDOM),
        Operator::FromInt => int_inputs(&mut rng, RANDOM),
        Operator::ToU8 => u8_inputs(&mut rng, RANDOM),
        Operator::Compare => compare_inputs(&mut rng, RANDOM),
        Operator::FastSqrt | Operator::Register | Operator::Select | Operator::Const => (0..RANDOM)
            .map(|_| [rng.u32(..), rng.u32(..), rng.u32(..)])
            .collect(),
    };
    let edges: Vec<Input> = match op {
        Operator::AddSub | Operator::Multiply | Operator::Divide | Operator::Compare => {
            binary_edges(op)
        }
        Operator::FromInt => INT_EDGES.iter().map(|&x| [x as u32, 0, 0]).collect(),
        Operator::ToU8 => u8_edges(),
        Operator::Const => (0..4).map(|c| [0, 0, c]).collect(),
        Operator::Select => edge_values()
            .iter()
            .flat_map(|&x| [[x, !x, 0], [x, !x, 1]])
            .collect(),
        Operator::Sqrt | Operator::InvSqrt | Operator::FastSqrt | Operator::Register => {
            edge_values().iter().map(|&x| [x, 0, 0]).collect()
        }
    };
    let n_edges = edges.len();
    cases.extend(edges);
    (cases, n_edges)
}

/// Fails with installation instructions unless `tool` runs.
fn require(tool: &str) {
    let ok = Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "`{tool}` is not installed or does not run: the RTL tests need Verilator, g++ and \
         make. Install them with `scripts/install-rtl-tools.sh` (Debian: \
         `apt-get install verilator g++ make`), then run `cargo test -p rtl -- --ignored`."
    );
}

fn require_tools() {
    for tool in ["verilator", "g++", "make"] {
        require(tool);
    }
}

/// The generated top of the model: `op` at the library's latency behind the uniform
/// ports clk, a, b, c, y.
fn wrapper(op: Operator, lib: &Library) -> String {
    let instance = |extra: &[(&str, u32)], name: &str, ports: &[(&str, &str)]| {
        op.instance(lib, name, extra, ports)
            .unwrap_or_else(|e| panic!("{e}"))
    };
    let body = match op {
        Operator::AddSub => instance(
            &[],
            "dut",
            &[
                ("clk", "clk"),
                ("a", "a"),
                ("b", "b"),
                ("sub", "c[0]"),
                ("y", "y"),
            ],
        ),
        Operator::Multiply | Operator::Divide => instance(
            &[],
            "dut",
            &[("clk", "clk"), ("a", "a"), ("b", "b"), ("y", "y")],
        ),
        Operator::Compare => format!(
            "wire lt;\n    {}\n    assign y = {{31'd0, lt}};",
            instance(
                &[],
                "dut",
                &[("clk", "clk"), ("a", "a"), ("b", "b"), ("lt", "lt")]
            )
        ),
        Operator::Sqrt
        | Operator::InvSqrt
        | Operator::FromInt
        | Operator::FastSqrt
        | Operator::Register => instance(&[], "dut", &[("clk", "clk"), ("a", "a"), ("y", "y")]),
        Operator::ToU8 => format!(
            "wire [7:0] q;\n    {}\n    assign y = {{24'd0, q}};",
            instance(&[], "dut", &[("clk", "clk"), ("a", "a"), ("y", "q")])
        ),
        Operator::Select => instance(
            &[],
            "dut",
            &[
                ("clk", "clk"),
                ("sel", "c[0]"),
                ("a", "a"),
                ("b", "b"),
                ("y", "y"),
            ],
        ),
        Operator::Const => {
            let mut text = String::from("wire [31:0] k0, k1, k2, k3;\n");
            for (i, v) in CONSTANTS.iter().enumerate() {
                let out = format!("k{i}");
                let _ = writeln!(
                    text,
                    "    {}",
                    instance(&[("VALUE", *v)], &format!("c{i}"), &[("y", &out)])
                );
            }
            text.push_str("    assign y = c[1] ? (c[0] ? k3 : k2) : (c[0] ? k1 : k0);");
            text
        }
    };
    format!(
        "// Generated by rtl/tests/operators.rs: {} behind the testbench's ports.\n\
         /* verilator lint_off UNUSEDSIGNAL */\n\
         module tb_top (\n    input clk,\n    input [31:0] a,\n    input [31:0] b,\n    \
         input [31:0] c,\n    output [31:0] y\n);\n    {body}\nendmodule\n",
        op.module_name()
    )
}

/// Runs `cmd` and fails with its output if it does not succeed.
fn run(cmd: &mut Command, what: &str) {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run {cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Builds the Verilator model of `op` (sources written by `rtl::write_sources`) in a
/// fresh directory; returns the executable.
fn build(op: Operator, lib: &Library) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("rtl-operators")
        .join(op.module_name());
    if dir.exists() {
        fs::remove_dir_all(&dir).unwrap();
    }
    let src = dir.join("src");
    rtl::write_sources(&src).unwrap();
    fs::write(src.join("tb_top.v"), wrapper(op, lib)).unwrap();
    fs::write(
        src.join("tb_main.cpp"),
        include_str!("../verilog/tb/tb_main.cpp"),
    )
    .unwrap();
    // The pipeline's flags (rtl::sim), on one compiler, the C++ barely optimised: the
    // operator models run for a second, their build would take longer.
    let mut cmd = rtl::sim::verilator_command(&dir, "tb_top", "tb", 1);
    cmd.args(["-MAKEFLAGS", "OPT_FAST=-O1 OPT_SLOW=-O0 OPT_GLOBAL=-O1"]);
    cmd.arg(src.join("tb_top.v"));
    for file in op.files() {
        cmd.arg(src.join(file.name));
    }
    cmd.arg(src.join("tb_main.cpp"));
    run(
        &mut cmd,
        &format!("verilator build of {}", op.module_name()),
    );
    dir.join("obj").join("tb")
}

fn to_bytes(words: impl Iterator<Item = u32>) -> Vec<u8> {
    words.flat_map(u32::to_le_bytes).collect()
}

/// Builds, simulates and checks `op` against the reference.
fn check(op: Operator) {
    require_tools();
    let start = Instant::now();
    let lib = Library::cyclone_iv_e();
    let latency = op.latency(&lib) as usize;
    let (cases, n_edges) = inputs(op);
    let want: Vec<u32> = cases.iter().map(|&x| reference(op, x)).collect();

    let exe = build(op, &lib);
    let built = start.elapsed();
    let dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
    let in_path = dir.join("inputs.bin");
    let out_path = dir.join("outputs.bin");
    fs::write(&in_path, to_bytes(cases.iter().flatten().copied())).unwrap();
    // Enough extra cycles for the latency probe to look past the expected latency.
    let extra = latency + 3;
    run(
        Command::new(&exe)
            .arg(&in_path)
            .arg(&out_path)
            .arg(extra.to_string()),
        &format!("simulation of {}", op.module_name()),
    );
    let got: Vec<u32> = fs::read(&out_path)
        .unwrap()
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        .collect();
    assert_eq!(got.len(), cases.len() + extra, "output cycles");

    // Latency: of the shifts 0..=LATENCY + 3, the one at which most of the first
    // random inputs' results appear must be LATENCY, and clearly (any other shift
    // matches by chance only); the full comparison below then requires every result
    // at that shift.
    let probe = 4096.min(cases.len());
    let matches: Vec<usize> = (0..=extra)
        .map(|s| {
            (0..probe)
                .filter(|&k| fp::agrees(got[k + s], want[k]))
                .count()
        })
        .collect();
    let best = (0..=extra).max_by_key(|&s| matches[s]).unwrap_or(0);
    let runner_up = (0..=extra)
        .filter(|&s| s != latency)
        .map(|s| matches[s])
        .max()
        .unwrap_or(0);
    assert!(
        best == latency && matches[latency] > runner_up + probe / 8,
        "{}: results must appear exactly LATENCY = {latency} cycles after the inputs; \
         of the first {probe} results, this many match at shifts 0..={extra}: {matches:?}",
        op.module_name()
    );

    let mismatches: Vec<usize> = (0..cases.len())
        .filter(|&k| !fp::agrees(got[k + latency], want[k]))
        .collect();
    if !mismatches.is_empty() {
        let mut report = format!(
            "{}: {} of {} results differ from rtl::float_policy (first ones: a, b, c -> got, want):\n",
            op.module_name(),
            mismatches.len(),
            cases.len()
        );
        for &k in mismatches.iter().take(20) {
            let [a, b, c] = cases[k];
            let _ = writeln!(
                report,
                "  {a:08X} {b:08X} {c:X} -> {:08X}, want {:08X}   ({:e}, {:e} -> {:e}, want {:e})",
                got[k + latency],
                want[k],
                f(a),
                f(b),
                f(got[k + latency]),
                f(want[k])
            );
        }
        panic!("{report}");
    }
    eprintln!(
        "{}: LATENCY {latency}, {} random + {n_edges} edge cases bit-exact \
         (build {:.1} s, total {:.1} s)",
        op.module_name(),
        cases.len() - n_edges,
        built.as_secs_f64(),
        start.elapsed().as_secs_f64()
    );
}

#[test]
#[ignore = "needs verilator"]
fn fp_add_sub_is_bit_exact() {
    check(Operator::AddSub);
}

#[test]
#[ignore = "needs verilator"]
fn fp_mul_is_bit_exact() {
    // The band that only the policy's rule 2 flushes must really be exercised.
    let (cases, _) = inputs(Operator::Multiply);
    // Computed here, not with `fp::mul`, so that a reference without the rule fails the
    // comparison with the RTL instead of this count.
    let threshold = 2f64.powi(-126) - 2f64.powi(-151);
    let band = cases
        .iter()
        .filter(|&&[a, b, _]| {
            let (a, b) = (fp::flush(f(a)), fp::flush(f(b)));
            (a * b).abs() == f32::MIN_POSITIVE && (f64::from(a) * f64::from(b)).abs() < threshold
        })
        .count();
    eprintln!("fp_mul: {band} products in the flushed band below 2^-126");
    assert!(band > 1000, "only {band} products in the band");
    check(Operator::Multiply);
}

#[test]
#[ignore = "needs verilator"]
fn fp_div_is_bit_exact() {
    check(Operator::Divide);
}

#[test]
#[ignore = "needs verilator"]
fn fp_sqrt_is_bit_exact() {
    check(Operator::Sqrt);
}

#[test]
#[ignore = "needs verilator"]
fn fp_inv_sqrt_is_bit_exact() {
    check(Operator::InvSqrt);
}

#[test]
#[ignore = "needs verilator"]
fn fp_compare_is_bit_exact() {
    check(Operator::Compare);
}

#[test]
#[ignore = "needs verilator"]
fn fp_from_int_is_bit_exact() {
    check(Operator::FromInt);
}

#[test]
#[ignore = "needs verilator"]
fn fp_to_u8_is_bit_exact() {
    // The ties must really be exercised: inputs exactly halfway between two bytes.
    let (cases, _) = inputs(Operator::ToU8);
    let ties = cases
        .iter()
        .filter(|&&[a, _, _]| {
            let x = f(a);
            (0.0..255.0).contains(&x) && x.fract() == 0.5
        })
        .count();
    eprintln!("fp_to_u8: {ties} inputs exactly halfway between two bytes");
    assert!(ties > 100_000, "only {ties} ties");
    check(Operator::ToU8);
}

#[test]
#[ignore = "needs verilator"]
fn fp_fast_sqrt_is_bit_exact() {
    check(Operator::FastSqrt);
}

#[test]
#[ignore = "needs verilator"]
fn fp_const_is_bit_exact() {
    check(Operator::Const);
}

#[test]
#[ignore = "needs verilator"]
fn fp_select_is_bit_exact() {
    check(Operator::Select);
}

#[test]
#[ignore = "needs verilator"]
fn fp_register_is_bit_exact() {
    check(Operator::Register);
}

/// Every module passes Verilator's lint with all warnings on, at its library latency
/// and combinational.
#[test]
#[ignore = "needs verilator"]
fn every_module_is_lint_clean() {
    require("verilator");
    let lib = Library::cyclone_iv_e();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rtl-lint");
    let paths = rtl::write_sources(&dir).unwrap();
    assert_eq!(paths.len(), rtl::SOURCES.len());
    for op in Operator::ALL {
        let latencies = match op {
            Operator::Const => vec![None],
            _ => vec![Some(op.latency(&lib)), Some(0), Some(2)],
        };
        for latency in latencies {
            let mut cmd = Command::new("verilator");
            cmd.args(["--lint-only", "-Wall", "--top-module", op.module_name()]);
            if let Some(l) = latency {
                cmd.arg(format!("-GLATENCY={l}"));
            }
            for file in op.files() {
                cmd.arg(dir.join(file.name));
            }
            run(
                &mut cmd,
                &format!("verilator lint of {} at {latency:?}", op.module_name()),
            );
        }
    }
}
