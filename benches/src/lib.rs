//! Criterion benchmarks of the tracer's kernels, one group per module, and the
//! in-process profiler that draws a flamegraph of a benchmark.
//!
//! Run them with `cargo bench -p benches` (the `groups` bench target runs every group;
//! `-- --list` lists them, `-- sqrt` or `-- accel/bvh` filters). The groups:
//! - [`sqrt`]: square roots and inverse square roots over 4096 floats;
//! - [`camera`]: eye-ray generation for a whole 320x240 frame, per projection;
//! - [`intersect`]: one ray-primitive test, hit and miss, per primitive kind;
//! - [`shading`]: the Lambert diffuse term against the two sqrt-free forms;
//! - [`accel`]: closest-hit queries per intersection structure on growing sphereflakes;
//! - [`frame`]: whole renders per variant, plus one counted render.
//!
//! `cargo bench -p benches -- --profile-time 5 accel/bvh` runs the matching benchmarks
//! for 5 s each without measuring them, under [`flame_profiler::FlameProfiler`], which
//! writes `flamegraph.svg` and `folded.txt` into
//! `<target dir>/criterion/<group>/<benchmark>/profile/` (criterion's output directory
//! follows `CARGO_TARGET_DIR`).
//!
//! Every input is built outside the timed closures and is deterministic.

pub mod accel;
pub mod camera;
pub mod flame_profiler;
pub mod frame;
pub mod intersect;
pub mod shading;
pub mod sqrt;
