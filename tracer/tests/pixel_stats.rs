//! Per-sample records (`RenderOptions::per_sample`): on every SPD scene and for
//! baseline, simd, bvh and packets of eye rays in the wide BVH, the maps summed over the samples equal the render's own
//! counters exactly, the work outside every sample is exactly the camera's set-up, and
//! the records are the same for one and two threads.

mod common;

use common::{load_spd, options, spd_dir};
use tracer::camera::{Camera, Projection};
use tracer::{
    COUNTERS, Count, Counter, RenderOptions, SampleStats, Sampling, Scene, VariantSet,
    render_variant,
};

const SCENES: [&str; 12] = [
    "balls", "gears", "jacks", "lattice", "mount", "rings", "sample", "shells", "sombrero",
    "teapot", "tetra", "tree",
];

fn per_sample(width: u32, height: u32) -> RenderOptions {
    let mut o = options(width, height, Sampling::SpdCorners);
    o.per_sample = true;
    o
}

fn render(scene: &Scene, o: &RenderOptions, variant: &str, threads: usize) -> (Count, SampleStats) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let set = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
    let out = pool
        .install(|| render_variant::<Count>(scene, o, &set, &|_| {}))
        .unwrap_or_else(|e| panic!("{e}"));
    let samples = out.rendered.samples.unwrap_or_else(|| panic!("no samples"));
    (out.rendered.counter, samples)
}

#[test]
fn maps_sum_to_the_global_counters_on_every_spd_scene_and_accelerator() {
    assert!(spd_dir().join("balls.nff").is_file());
    for name in SCENES {
        let scene = load_spd(name);
        let o = per_sample(8, 8);
        // The one piece of work that belongs to no sample: the camera's set-up.
        let mut camera = Count::default();
        Camera::new(
            &scene.view,
            8,
            8,
            Sampling::SpdCorners,
            Projection::Perspective,
            None,
            &mut camera,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let camera = camera.totals().unwrap_or_else(|| panic!("uncounted"));
        for variant in ["baseline", "simd", "bvh", "bvh+simd+packets"] {
            let (counter, samples) = render(&scene, &o, variant, 2);
            let totals = counter.totals().unwrap_or_else(|| panic!("uncounted"));
            assert_eq!((samples.columns, samples.rows), (9, 9), "{name}");
            assert_eq!(samples.len(), 81);
            let rendered = tracer::Counts::from_parts(&totals, ray_sum(&samples));
            for def in COUNTERS {
                let map = samples
                    .map(def)
                    .unwrap_or_else(|| panic!("{}: no map", def.key));
                let sum: u64 = map.iter().sum();
                let global = (def.value)(&rendered);
                let outside = def.stat.map_or(0, |s| camera[s as usize]);
                assert_eq!(sum + outside, global, "{name} {variant} {}", def.key);
            }
            assert_eq!(
                samples.frame_level(&totals),
                Some(camera),
                "{name} {variant}"
            );
            // Every sample traced one eye ray; depth within the SPD's 5; a sample that
            // spawned secondary rays went deeper than its eye ray.
            for (i, rays) in samples.rays.iter().enumerate() {
                assert_eq!(rays.primary, 1);
                let depth = samples.depth[i];
                assert!((1..=5).contains(&depth), "{name}: depth {depth}");
                assert_eq!(
                    depth > 1,
                    rays.reflection + rays.refraction > 0,
                    "{name} sample {i}"
                );
            }
        }
    }
}

/// The ray counts of the render, from its samples (they are not in the counter).
fn ray_sum(samples: &SampleStats) -> tracer::RayCounts {
    let mut sum = tracer::RayCounts::default();
    for r in &samples.rays {
        sum.merge(r);
    }
    sum
}

#[test]
fn ray_maps_sum_to_the_renders_ray_counts() {
    let scene = load_spd("rings");
    let set = VariantSet::parse("bvh").unwrap_or_else(|e| panic!("{e}"));
    let o = per_sample(10, 6);
    let out = render_variant::<Count>(&scene, &o, &set, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
    let samples = out.rendered.samples.unwrap_or_else(|| panic!("no samples"));
    assert_eq!(ray_sum(&samples), out.rendered.rays);
    assert!(out.rendered.rays.shadow > 0 && out.rendered.rays.reflection > 0);
    let secondary: u64 = samples.secondary_rays().iter().sum();
    assert_eq!(
        secondary,
        out.rendered.rays.reflection + out.rendered.rays.refraction
    );
}

#[test]
fn records_are_the_same_for_one_and_two_threads() {
    for name in ["balls", "gears", "teapot"] {
        let scene = load_spd(name);
        let o = per_sample(12, 12);
        for variant in ["baseline", "simd", "bvh", "bvh+simd+packets"] {
            let (one_counter, one) = render(&scene, &o, variant, 1);
            let (two_counter, two) = render(&scene, &o, variant, 2);
            assert_eq!(one_counter, two_counter);
            assert_eq!(one.counts, two.counts, "{name} {variant}");
            assert_eq!(one.rays, two.rays);
            assert_eq!(one.depth, two.depth);
            assert_eq!(one.nanos.len(), two.nanos.len());
        }
    }
}

#[test]
fn uncounted_renders_keep_rays_depth_and_time_but_no_operation_maps() {
    let scene = load_spd("balls");
    let set = VariantSet::parse("bvh").unwrap_or_else(|e| panic!("{e}"));
    let o = per_sample(6, 6);
    let out = render_variant::<tracer::NoCount>(&scene, &o, &set, &|_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    let samples = out.rendered.samples.unwrap_or_else(|| panic!("no samples"));
    assert!(samples.counts.is_none());
    let dot = COUNTERS
        .iter()
        .find(|d| d.key == "ops.dot")
        .unwrap_or_else(|| panic!("no ops.dot"));
    assert!(samples.map(dot).is_none());
    let primary = COUNTERS
        .iter()
        .find(|d| d.key == "rays.primary")
        .unwrap_or_else(|| panic!("no rays.primary"));
    assert_eq!(samples.map(primary), Some(vec![1; 49]));
    // Every traced sample took some time on the clock (balls: every eye ray is traced
    // through the tree, a few hundred nanoseconds at least).
    assert!(samples.nanos.iter().any(|&t| t > 0));
    // Without the option there are no records.
    let plain = options(6, 6, Sampling::SpdCorners);
    let out =
        render_variant::<Count>(&scene, &plain, &set, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
    assert!(out.rendered.samples.is_none());
}

#[test]
fn pixel_averaging_leaves_the_filled_samples_empty() {
    let scene = load_spd("balls");
    // Packets gather the traced samples of a row; the records stay in column order.
    for variant in ["pixel-avg", "pixel-avg+bvh+simd+packets"] {
        let set = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
        let mut o = options(19, 4, Sampling::PixelCenters);
        o.per_sample = true;
        let out =
            render_variant::<Count>(&scene, &o, &set, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
        let samples = out.rendered.samples.unwrap_or_else(|| panic!("no samples"));
        for row in 0..4usize {
            for column in 0..19usize {
                let i = row * 19 + column;
                let traced = (row + column) % 2 == 0;
                assert_eq!(
                    samples.rays[i].primary,
                    u64::from(traced),
                    "{variant} {row},{column}"
                );
                assert_eq!(samples.depth[i] > 0, traced);
            }
        }
    }
}
