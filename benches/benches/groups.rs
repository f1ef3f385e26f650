//! The benchmark target: every group of the `benches` crate under one criterion main,
//! with the flamegraph profiler hooked in for `-- --profile-time N`.
//!
//! `cargo bench -p benches` runs them all; `-- --list` lists them; a filter such as
//! `-- accel/bvh` or `-- frame` runs a subset; `-- --quick` stops each benchmark as
//! soon as its estimate is significant.

use benches::accel::bench_accel;
use benches::camera::bench_camera;
use benches::flame_profiler::FlameProfiler;
use benches::frame::bench_frame;
use benches::intersect::bench_intersect;
use benches::shading::bench_shading;
use benches::sqrt::bench_sqrt;
use criterion::{Criterion, criterion_group, criterion_main};

criterion_group! {
    name = groups;
    config = Criterion::default().with_profiler(FlameProfiler::new(None));
    targets = bench_sqrt, bench_camera, bench_intersect, bench_shading, bench_accel, bench_frame
}
criterion_main!(groups);
