//! Group `frame`: whole renders of a mid-size scene, one benchmark per variant, through
//! [`render_variant`] exactly as `rtprof render` runs them (structure build and scene
//! preparation included), on a one-thread rayon pool so the figures do not depend on
//! the machine's other load or core count.
//!
//! The scene is the sphereflake of depth 2 (91 reflective spheres, three lights, the
//! suite's `sphereflake:2`) at 160x120, full Whitted colour. Every variant renders
//! uncounted ([`NoCount`]); `baseline-counted` renders the baseline with [`Count`], so
//! `baseline-counted / baseline` is what the exact operation counters cost.

use criterion::{BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use std::hint::black_box;
use tracer::{
    Count, NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, render_variant,
};

/// Frame size of every render of the group.
pub const WIDTH: u32 = 160;
pub const HEIGHT: u32 = 120;

/// The variants rendered uncounted, by their command-line names.
pub const VARIANTS: [&str; 10] = [
    "baseline",
    "simd",
    "bvh",
    "bvh+simd",
    "bvh+simd+packets",
    "bounded",
    "fast-sqrt",
    "ortho",
    "no-rsqrt-shading",
    "pixel-avg",
];

/// The group's scene.
pub fn scene() -> Scene {
    crate::accel::sphereflake(2)
}

/// The scenes of the whole-frame instruction counts (`benches/benches/instructions.rs`),
/// by SPD name and size factor: `rings` has spheres, cylinders and a polygon (the brute
/// force and SIMD lanes of both quadric kinds), `teapot` patches (the wide BVH's
/// triangle lanes and the packets). Small, so that a frame under valgrind takes well
/// under a second.
pub const INSTRUCTION_SCENES: [(&str, u32); 2] = [("rings", 2), ("teapot", 2)];

/// Frame size of the instruction-count renders.
pub const INSTRUCTION_WIDTH: u32 = 32;
pub const INSTRUCTION_HEIGHT: u32 = 24;

/// An SPD scene at a size factor, parsed.
pub fn spd_scene(name: &str, size_factor: u32) -> Scene {
    let text = spd::generate(name, Some(size_factor)).unwrap_or_else(|e| panic!("{e}"));
    tracer::parse_nff(&text, &format!("spd:{name}:{size_factor}")).unwrap_or_else(|e| panic!("{e}"))
}

/// The render options of the instruction-count frames: full Whitted colour.
pub fn instruction_options() -> RenderOptions {
    RenderOptions::new(
        INSTRUCTION_WIDTH,
        INSTRUCTION_HEIGHT,
        Sampling::PixelCenters,
        ShadingMode::Color,
    )
}

/// The group's render options.
pub fn options() -> RenderOptions {
    RenderOptions::new(WIDTH, HEIGHT, Sampling::PixelCenters, ShadingMode::Color)
}

/// One whole render of `scene` with `variants`, counted with `C`; returns the number
/// of primary rays that hit (kept alive so the render is not optimized away).
pub fn render<C: tracer::RenderWith>(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
) -> u64 {
    render_variant::<C>(scene, options, variants, &|_| {})
        .unwrap_or_else(|e| panic!("render failed: {e}"))
        .rendered
        .rays
        .primary_hit
}

/// Registers `frame/<name>`: a render with `variants` counted with `C`, in `pool`.
fn bench_render<C: tracer::RenderWith>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    pool: &rayon::ThreadPool,
    name: &str,
    scene: &Scene,
    variants: &VariantSet,
) {
    let options = options();
    group.bench_function(name, |b| {
        pool.install(|| b.iter(|| render::<C>(black_box(scene), &options, variants)))
    });
}

/// The `frame` group.
pub fn bench_frame(c: &mut Criterion) {
    let scene = scene();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap_or_else(|e| panic!("cannot build a one-thread pool: {e}"));
    let mut group = c.benchmark_group("frame");
    group.sample_size(10);
    group.throughput(Throughput::Elements(u64::from(WIDTH * HEIGHT)));
    for name in VARIANTS {
        let variants = VariantSet::parse(name).unwrap_or_else(|e| panic!("{e}"));
        bench_render::<NoCount>(&mut group, &pool, name, &scene, &variants);
        if name == "baseline" {
            // Right after the uncounted baseline, so the two are measured under the
            // same machine load and their ratio is the counters' cost.
            bench_render::<Count>(&mut group, &pool, "baseline-counted", &scene, &variants);
        }
    }
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_variant_parses_and_the_counted_render_sees_the_same_rays() {
        for name in VARIANTS {
            assert!(VariantSet::parse(name).is_ok(), "{name}");
        }
        let scene = scene();
        let small = RenderOptions::new(32, 24, Sampling::PixelCenters, ShadingMode::Color);
        let baseline = VariantSet::default();
        let uncounted = render::<NoCount>(&scene, &small, &baseline);
        assert!(uncounted > 0);
        assert_eq!(render::<Count>(&scene, &small, &baseline), uncounted);
    }

    #[test]
    fn the_instruction_scenes_hold_the_kinds_they_are_chosen_for() {
        // rings at size factor n: n(n + 1)(2n + 1)/6 objects of 30 spheres and 30
        // cylinders, and the wall: 5 objects at n = 2. teapot: 64n² - 8n patches = 240
        // and n² = 4 checker squares.
        let rings = spd_scene("rings", 2);
        assert_eq!((rings.spheres.len(), rings.cylinders.len()), (150, 150));
        assert_eq!(rings.polygons.len(), 1);
        let teapot = spd_scene("teapot", 2);
        assert_eq!((teapot.patches.len(), teapot.polygons.len()), (240, 4));
        // Every variant renders both, uncounted and counted alike.
        for (name, factor) in INSTRUCTION_SCENES {
            let scene = spd_scene(name, factor);
            for variant in VARIANTS {
                let variants = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
                let options = instruction_options();
                assert_eq!(
                    render::<NoCount>(&scene, &options, &variants),
                    render::<Count>(&scene, &options, &variants),
                    "{name} {variant}"
                );
            }
        }
    }
}
