//! Instruction counts of the `sqrt` and `intersect` kernels and of a small whole frame
//! per variant, under valgrind (gungraun runs each benchmark once under callgrind and
//! counts only the benchmark function).
//!
//! Unlike wall time these counts are the same on every run, whatever else the machine
//! is doing, so they can gate a change on a noisy machine. They are not time: a bit
//! trick can execute more instructions than `sqrtss` and still finish sooner, because
//! it has no long-latency divider step and vectorizes; the report shows both columns.
//!
//! Each `sqrt` and `intersect` benchmark does exactly the work of the criterion
//! benchmark of the same id in the `groups` target (same 4096 inputs, same primitives
//! and rays), so the counts sit beside criterion's estimates. The `frame_*` benchmarks
//! render [`benches::frame::INSTRUCTION_SCENES`] at 32x24 with each variant, structure
//! build included, on the calling thread (a render outside any rayon pool runs its rows
//! there, where callgrind counts them): `frame/rings/simd` is the SIMD lanes of spheres
//! and cylinders, `frame/teapot/bvh-simd-packets` the packets over triangle lanes. The
//! repository's performance baseline (`benches/baseline.json`) gates them all. The id mapping: a function `intersect_sphere` with
//! bench id `hit` is criterion's `intersect/sphere/hit` (the function name's first
//! `_` separates the group; further `_` become `-`); `sqrt` with `fast_sqrt_tuned` is
//! `sqrt/fast-sqrt-tuned`.
//!
//! Run with `scripts/instruction-counts.sh` (installs valgrind and the matching
//! `gungraun-runner`), or `cargo bench -p benches --features instructions --bench
//! instructions` when both are present.

use benches::frame::{instruction_options, render, spd_scene};
use benches::intersect::{Primitives, Rays, primitives, rays};
use benches::sqrt::{classic_inverse_sqrt, classic_inverse_sqrt_newton, inputs, std_inverse_sqrt};
use gungraun::{LibraryBenchmarkConfig, library_benchmark, library_benchmark_group, main};
use std::hint::black_box;
use tracer::variants::fast_sqrt::{
    BitTrickSqrt, NewtonBitTrickSqrt, SquareRoot, StdSqrt, TunedBitTrickSqrt,
};
use tracer::{NoCount, Ray, RenderOptions, Scene, VariantSet};

/// The root every `sqrt` benchmark maps over the inputs; one enum so that each arm
/// is its own inlined loop, as each criterion closure is.
#[derive(Clone, Copy)]
enum Root {
    Std,
    FastSqrt,
    FastSqrtTuned,
    FastSqrtNewton,
    InverseStd,
    InverseClassic,
    InverseClassicNewton,
}

#[inline(always)]
fn map_into(inputs: &[f32], out: &mut [f32], f: impl Fn(f32) -> f32) {
    for (o, &x) in out.iter_mut().zip(inputs) {
        *o = f(x);
    }
}

/// The inputs and an output array, built outside the measured function. The inputs
/// are leaked and the output returned, so that freeing them is not counted either.
fn sqrt_setup(root: Root) -> (Root, &'static [f32], Vec<f32>) {
    let inputs: &'static [f32] = inputs().leak();
    (root, inputs, vec![0.0; inputs.len()])
}

#[library_benchmark]
#[bench::std(setup = sqrt_setup, args = (Root::Std))]
#[bench::fast_sqrt(setup = sqrt_setup, args = (Root::FastSqrt))]
#[bench::fast_sqrt_tuned(setup = sqrt_setup, args = (Root::FastSqrtTuned))]
#[bench::fast_sqrt_newton(setup = sqrt_setup, args = (Root::FastSqrtNewton))]
#[bench::inverse_std(setup = sqrt_setup, args = (Root::InverseStd))]
#[bench::inverse_classic(setup = sqrt_setup, args = (Root::InverseClassic))]
#[bench::inverse_classic_newton(setup = sqrt_setup, args = (Root::InverseClassicNewton))]
fn sqrt((root, inputs, mut out): (Root, &'static [f32], Vec<f32>)) -> Vec<f32> {
    let inputs = black_box(inputs);
    match black_box(root) {
        Root::Std => map_into(inputs, &mut out, StdSqrt::sqrt),
        Root::FastSqrt => map_into(inputs, &mut out, BitTrickSqrt::sqrt),
        Root::FastSqrtTuned => map_into(inputs, &mut out, TunedBitTrickSqrt::sqrt),
        Root::FastSqrtNewton => map_into(inputs, &mut out, NewtonBitTrickSqrt::sqrt),
        Root::InverseStd => map_into(inputs, &mut out, std_inverse_sqrt),
        Root::InverseClassic => map_into(inputs, &mut out, classic_inverse_sqrt),
        Root::InverseClassicNewton => map_into(inputs, &mut out, classic_inverse_sqrt_newton),
    }
    out
}

/// Which ray of a primitive's pair.
#[derive(Clone, Copy)]
enum Case {
    Hit,
    Miss,
}

/// The primitives and the chosen ray, built outside the measured function. The
/// primitives are leaked: dropping them inside the benchmark would count hundreds of
/// instructions of `free` against a test of a few dozen.
fn intersect_setup(kind: &str, case: Case) -> (&'static Primitives, Ray) {
    let r: Rays = rays();
    let pair = match kind {
        "sphere" => r.sphere,
        "cylinder" => r.cylinder,
        "cone" => r.cone,
        "polygon" => r.polygon,
        "patch" => r.patch,
        "plane" => r.plane,
        other => panic!("no rays for primitive '{other}'"),
    };
    let ray = match case {
        Case::Hit => pair.hit,
        Case::Miss => pair.miss,
    };
    (Box::leak(Box::new(primitives())), ray)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("sphere", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("sphere", Case::Miss))]
fn intersect_sphere((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.sphere).intersect(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("cylinder", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("cylinder", Case::Miss))]
fn intersect_cylinder((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.cylinder)
        .intersect(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
        .map(|hit| hit.0)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("cone", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("cone", Case::Miss))]
fn intersect_cone((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.cone)
        .intersect(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
        .map(|hit| hit.0)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("polygon", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("polygon", Case::Miss))]
fn intersect_polygon((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.polygon).intersect(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("patch", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("patch", Case::Miss))]
fn intersect_patch((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.patch).intersect(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
}

#[library_benchmark]
#[bench::hit(setup = intersect_setup, args = ("plane", Case::Hit))]
#[bench::miss(setup = intersect_setup, args = ("plane", Case::Miss))]
fn intersect_plane((p, ray): (&'static Primitives, Ray)) -> Option<f32> {
    black_box(&p.plane).intersect_plane(black_box(&ray), 0.0, f32::INFINITY, &mut NoCount)
}

/// A scene of [`benches::frame::INSTRUCTION_SCENES`], the frame's options and the
/// variants, built outside the measured function (the scene leaked, as the primitives
/// above).
fn frame_setup(
    (scene, size_factor): (&str, u32),
    variant: &str,
) -> (&'static Scene, RenderOptions, VariantSet) {
    let variants = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
    let scene: &'static Scene = Box::leak(Box::new(spd_scene(scene, size_factor)));
    (scene, instruction_options(), variants)
}

#[library_benchmark]
#[bench::baseline(setup = frame_setup, args = (("rings", 2), "baseline"))]
#[bench::simd(setup = frame_setup, args = (("rings", 2), "simd"))]
#[bench::bvh(setup = frame_setup, args = (("rings", 2), "bvh"))]
#[bench::bvh_simd(setup = frame_setup, args = (("rings", 2), "bvh+simd"))]
#[bench::bvh_simd_packets(setup = frame_setup, args = (("rings", 2), "bvh+simd+packets"))]
#[bench::bounded(setup = frame_setup, args = (("rings", 2), "bounded"))]
#[bench::fast_sqrt(setup = frame_setup, args = (("rings", 2), "fast-sqrt"))]
#[bench::ortho(setup = frame_setup, args = (("rings", 2), "ortho"))]
#[bench::no_rsqrt_shading(setup = frame_setup, args = (("rings", 2), "no-rsqrt-shading"))]
#[bench::pixel_avg(setup = frame_setup, args = (("rings", 2), "pixel-avg"))]
fn frame_rings((scene, options, variants): (&'static Scene, RenderOptions, VariantSet)) -> u64 {
    render::<NoCount>(black_box(scene), &options, &variants)
}

#[library_benchmark]
#[bench::baseline(setup = frame_setup, args = (("teapot", 2), "baseline"))]
#[bench::simd(setup = frame_setup, args = (("teapot", 2), "simd"))]
#[bench::bvh(setup = frame_setup, args = (("teapot", 2), "bvh"))]
#[bench::bvh_simd(setup = frame_setup, args = (("teapot", 2), "bvh+simd"))]
#[bench::bvh_simd_packets(setup = frame_setup, args = (("teapot", 2), "bvh+simd+packets"))]
fn frame_teapot((scene, options, variants): (&'static Scene, RenderOptions, VariantSet)) -> u64 {
    render::<NoCount>(black_box(scene), &options, &variants)
}

library_benchmark_group!(
    name = square_roots;
    benchmarks = sqrt
);

library_benchmark_group!(
    name = frames;
    benchmarks = frame_rings, frame_teapot
);

library_benchmark_group!(
    name = ray_primitive_tests;
    benchmarks =
        intersect_sphere,
        intersect_cylinder,
        intersect_cone,
        intersect_polygon,
        intersect_patch,
        intersect_plane
);

main!(
    config = LibraryBenchmarkConfig::default();
    library_benchmark_groups = square_roots, ray_primitive_tests, frames
);
