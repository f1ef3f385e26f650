//! A render stops when its stop flag is set: checked before each sample row, it skips
//! the rows not yet started and returns `RenderError::Cancelled`, never a partial frame.
//! The tests count traced rows through the progress callback (called once per finished
//! row), not the clock.

mod common;

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use common::{load_spd, options};
use tracer::{
    Count, NoCount, RenderError, Sampling, VariantSet, render_variant, render_variant_until,
};

fn set(name: &str) -> VariantSet {
    VariantSet::parse(name).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_flag_set_before_the_start_traces_no_row() {
    let scene = load_spd("balls");
    let opts = options(16, 12, Sampling::PixelCenters);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let stop = AtomicBool::new(true);
    for variant in ["baseline", "bvh", "bvh+simd+packets"] {
        let rows = AtomicU64::new(0);
        let out = pool.install(|| {
            render_variant_until::<Count>(
                &scene,
                &opts,
                &set(variant),
                &|n| {
                    rows.fetch_add(n, Ordering::SeqCst);
                },
                &stop,
            )
        });
        assert!(matches!(out, Err(RenderError::Cancelled)), "{variant}");
        assert_eq!(rows.load(Ordering::SeqCst), 0, "{variant}");
    }
}

#[test]
fn a_flag_set_after_row_k_stops_the_render_after_k_rows() {
    // One thread outside any pool: the rows run in order, so the flag set by the
    // progress callback after row K is seen by row K + 1, which is not traced.
    const K: u64 = 3;
    let scene = load_spd("rings");
    let opts = options(20, 15, Sampling::SpdCorners);
    for variant in ["baseline", "bvh+simd+packets", "pixel-avg"] {
        let stop = AtomicBool::new(false);
        let rows = AtomicU64::new(0);
        let out = render_variant_until::<NoCount>(
            &scene,
            &opts,
            &set(variant),
            &|n| {
                if rows.fetch_add(n, Ordering::SeqCst) + n == K {
                    stop.store(true, Ordering::SeqCst);
                }
            },
            &stop,
        );
        assert!(matches!(out, Err(RenderError::Cancelled)), "{variant}");
        assert_eq!(rows.load(Ordering::SeqCst), K, "{variant}");
        assert!(K < opts.sample_rows());
    }
    let message = RenderError::Cancelled.to_string();
    assert!(message.starts_with("cancelled"), "{message}");
}

#[test]
fn a_flag_never_set_changes_neither_image_nor_counts() {
    let scene = load_spd("teapot");
    let opts = options(12, 9, Sampling::PixelCenters);
    let stop = AtomicBool::new(false);
    for variant in ["baseline", "bvh"] {
        let plain = render_variant::<Count>(&scene, &opts, &set(variant), &|_| {})
            .unwrap_or_else(|e| panic!("{e}"));
        let watched = render_variant_until::<Count>(&scene, &opts, &set(variant), &|_| {}, &stop)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(plain.rendered.frame, watched.rendered.frame, "{variant}");
        assert_eq!(
            plain.rendered.counts(),
            watched.rendered.counts(),
            "{variant}"
        );
    }
}
