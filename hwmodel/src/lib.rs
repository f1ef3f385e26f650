//! `hwmodel`: a latency and resource model of the thesis's pipelined FPGA ray caster
//! (Cyclone IV EP4CE115, IEEE-754 single-precision IP cores), with a functional
//! emulator of the image it shows and an export of its scene memory.
//!
//! Stages, each its own module, joined by plain data:
//! - [`library`]: the operator library of a device family, read from TOML
//!   (`data/*.toml`: the thesis's table 7 IP-core rows plus the documented assumptions);
//! - [`graph`]: dataflow graphs of operators, ASAP scheduling (latency = critical
//!   path) and delay-balancing registers (resources = operators + balancing);
//! - [`composites`]: dot product, vector × scalar, vector add/sub, normalize;
//! - [`blocks`]: the thesis's blocks (primary ray, intersection test, minimum distance,
//!   shading) built from those, for a [`design::Design`] (the thesis's or a what-if);
//! - [`device`]: devices and fit (utilization, the multiplier rule, the largest K);
//! - [`frame_timing`]: frame timing (one pixel every 3·⌈n/K⌉ cycles plus the fill);
//! - [`optimizations`]: the thesis's optimizations costed in cycles and resources;
//! - [`table`]: the model next to the thesis's tables 7 and 8 with percentage errors;
//! - [`hw_scene`], [`emulator`], [`mif`]: the scene as the hardware holds it, the image
//!   it computes, and its Memory Initialization File;
//! - [`graph_eval`]: the block graphs evaluated on values, the picture they compute
//!   (checked against the emulator; the reference for the generated RTL);
//! - [`what_if`]: the design and device a command chooses (with the `clap` feature,
//!   the `rtprof hw` flags);
//! - [`float_policy`]: the arithmetic of the RTL's floating-point operators (rounding,
//!   flushed subnormals, NaN), which the emulator computes in.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod blocks;
pub mod composites;
pub mod design;
pub mod device;
pub mod emulator;
pub mod float_policy;
pub mod frame_timing;
pub mod graph;
pub mod graph_eval;
pub mod hw_scene;
pub mod library;
pub mod memory;
pub mod mif;
pub mod optimizations;
pub mod sweep;
pub mod table;
pub mod what_if;
