//! Counts and images do not depend on the thread count, nor on whether we count.

mod common;

use common::{load_spd, options, render_counted};
use tracer::{BruteForce, NoCount, Sampling};

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
    let plain = tracer::render::<NoCount, _>(&scene, &accel, &opts, &|_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counted.frame.pixels, plain.frame.pixels);
    assert_eq!(counted.rays, plain.rays, "ray counts are kept by both");
    assert!(plain.counts().is_none());
}
