//! Counts and images do not depend on the thread count, nor on whether we count.

mod common;

use common::{load_spd, options, render_counted};
use tracer::{BruteForce, Count, NoCount, Sampling, VariantSet, render_variant};

#[test]
fn rings_is_identical_on_one_and_two_threads() {
    let scene = load_spd("rings");
    let opts = options(16, 12, Sampling::SpdCorners);
    let one = render_counted(&scene, &opts, 1);
    let two = render_counted(&scene, &opts, 2);
    assert_eq!(one.frame.to_rgb8(), two.frame.to_rgb8());
    assert_eq!(
        one.frame.pixels, two.frame.pixels,
        "float framebuffers must match bit for bit"
    );
    assert_eq!(one.counts(), two.counts());
}

#[test]
fn counting_does_not_change_the_image() {
    let scene = load_spd("teapot");
    let opts = options(12, 12, Sampling::PixelCenters);
    let counted = render_counted(&scene, &opts, 2);
    let accel = BruteForce::new(&scene);
    let plain = tracer::render::<NoCount, _>(
        &scene,
        &accel,
        &opts,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counted.frame.pixels, plain.frame.pixels);
    assert_eq!(counted.rays, plain.rays, "ray counts are kept by both");
    assert!(plain.counts().is_none());
}

/// Every SPD scene, with the brute-force baseline and the BVH, on 1, 2 and 8 worker
/// threads: the float framebuffers must match bit for bit and every count (operations,
/// tests, rays, accelerator visits) must be equal. No count is allowed to vary: each
/// worker counts into its own counter and the totals are sums of integers.
#[test]
fn every_spd_scene_gives_the_same_image_and_counts_on_1_2_and_8_threads() {
    let mut names: Vec<String> = std::fs::read_dir(common::spd_dir())
        .unwrap_or_else(|e| panic!("{e}"))
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "nff"))
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    assert_eq!(names.len(), 12, "{names:?}");
    for name in &names {
        let scene = load_spd(name);
        for (variant, (width, height)) in [("baseline", (6, 4)), ("bvh", (12, 9))] {
            let variants = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
            let opts = options(width, height, Sampling::SpdCorners);
            let runs: Vec<_> = [1, 2, 8]
                .into_iter()
                .map(|threads| {
                    let pool = rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .unwrap_or_else(|e| panic!("{e}"));
                    pool.install(|| render_variant::<Count>(&scene, &opts, &variants, &|_| {}))
                        .unwrap_or_else(|e| panic!("{name}/{variant}: {e}"))
                        .rendered
                })
                .collect();
            for (threads, run) in [2, 8].into_iter().zip(&runs[1..]) {
                assert!(
                    run.frame.pixels == runs[0].frame.pixels,
                    "{name}/{variant}: the image on {threads} threads differs from 1 thread"
                );
                assert_eq!(
                    run.counts(),
                    runs[0].counts(),
                    "{name}/{variant}: counts on {threads} threads differ from 1 thread"
                );
                assert_eq!(run.rays, runs[0].rays, "{name}/{variant}: ray counts");
            }
        }
    }
}

/// Outside any rayon pool the renderer traces on the calling thread (it starts no
/// global pool), and gives the image and counts a pool of two gives.
#[test]
fn outside_a_pool_the_rows_run_on_the_calling_thread_with_the_same_result() {
    let scene = load_spd("rings");
    let opts = options(16, 12, Sampling::SpdCorners);
    let variants = VariantSet::parse("bvh").unwrap_or_else(|e| panic!("{e}"));
    let threads = std::sync::Mutex::new(std::collections::HashSet::new());
    let note_thread = |_| {
        let mut seen = threads.lock().unwrap_or_else(|e| panic!("{e}"));
        seen.insert(std::thread::current().id());
    };
    assert!(rayon::current_thread_index().is_none());
    let here = render_variant::<Count>(&scene, &opts, &variants, &note_thread)
        .unwrap_or_else(|e| panic!("{e}"))
        .rendered;
    let seen = threads.into_inner().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        seen,
        std::collections::HashSet::from([std::thread::current().id()]),
        "rows traced on other threads"
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let pooled = pool
        .install(|| render_variant::<Count>(&scene, &opts, &variants, &|_| {}))
        .unwrap_or_else(|e| panic!("{e}"))
        .rendered;
    assert!(here.frame.pixels == pooled.frame.pixels);
    assert_eq!(here.counts(), pooled.counts());
    assert_eq!(here.rays, pooled.rays);
}
