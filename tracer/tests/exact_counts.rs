//! The exact counts of a whole one-pixel render, counted by hand from the algorithm.

use tracer::{BruteForce, Count, Counts, RenderOptions, Sampling, ShadingMode, parse_nff};

#[test]
fn one_pixel_one_sphere_one_light_counts_by_hand() {
    // Eye on -z looking at a unit sphere; one light up and behind the eye. Opaque,
    // non-reflective material: no highlight, no secondary rays but the shadow ray.
    let scene = parse_nff(
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0\nresolution 1 1\n\
         l 0 5 -10\nf 1 1 1 1 0 10 0 1\ns 0 0 0 1\n",
        "one.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let opts = RenderOptions::new(1, 1, Sampling::PixelCenters, ShadingMode::Color);
    let out = tracer::render::<Count, _>(
        &scene,
        &accel,
        &opts,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let c: Counts = out.counts().unwrap_or_default();

    // Camera set-up: at - from (sub), normalize w, w × up (cross), normalize u,
    // u × w (cross), two pitch scalings.
    // Eye ray: two scale, two add, one normalize.
    // Sphere test: sub, two dot (first stage; b = -5, |Voc|² = 25, so its discriminant
    // 25 - (25 - 1) = 1 is above 25/2⁸ and kept: no second stage); sqrt (hit).
    // Hit body: point (scale + add), normal (sub + normalize), facing test (dot).
    // Shadow-ray origin offset: scale + add.
    // Light: to_light (sub), N·L (dot), |L|² (dot), sqrt, L / |L| (scale).
    // Shadow test against the sphere: the first stage only (sub, two dot: from just
    // outside (0, 0, -1) towards the light b ≈ 0.87 and |Voc|² ≈ 1, so its discriminant
    // ≈ 0.76 is kept) and sqrt (the line meets the sphere behind the ray's origin), no
    // hit.
    assert_eq!(c.ops.sub, 1 + 1 + 1 + 1 + 1);
    assert_eq!(c.ops.dot, 2 + 1 + 2 + 2);
    assert_eq!(c.ops.sqrt, 1 + 1 + 1);
    assert_eq!(c.ops.normalize, 2 + 1 + 1);
    assert_eq!(c.ops.cross, 2);
    assert_eq!(c.ops.scale, 2 + 2 + 1 + 1 + 1);
    assert_eq!(c.ops.add, 2 + 1 + 1);
    assert_eq!(c.ops.pow, 0, "Ks = 0: no highlight");
    assert_eq!(
        (
            c.calls.primary_ray_setup,
            c.calls.trace,
            c.calls.intersect,
            c.calls.shade,
            c.calls.color_contribution
        ),
        (1, 1, 2, 1, 1)
    );
    assert_eq!((c.tests.sphere.tests, c.tests.sphere.hits), (2, 1));
    assert_eq!(
        (
            c.rays.primary,
            c.rays.primary_hit,
            c.rays.shadow,
            c.rays.shadow_blocked,
            c.rays.reflection
        ),
        (1, 1, 1, 0, 0)
    );
    // The lit point faces the light: its gray is ambient 0.1 + Lambert term > 0.1.
    assert!(out.frame.pixels[0].r > 0.1);
}

#[test]
fn mirror_sphere_spawns_reflections_down_to_depth_five() {
    // Eye inside a mirror sphere (inside visible): every ray hits, and each hit spawns a
    // reflection until depth 5, so one eye ray makes exactly 4 reflection rays.
    let scene = parse_nff(
        "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 30\nhither 0\nresolution 1 1\n\
         f 1 1 1 0.5 0.5 10 0 1\ns 0 0 0 -10\n",
        "mirror.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let opts = RenderOptions::for_scene(&scene);
    let out = tracer::render::<Count, _>(
        &scene,
        &accel,
        &opts,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let c = out.counts().unwrap_or_default();
    assert_eq!(c.rays.reflection, 4);
    assert_eq!(c.calls.trace, 5);
    assert_eq!(c.calls.shade, 5);
    assert_eq!(c.rays.shadow, 0, "no lights");
}

#[test]
fn glass_slab_refracts_and_total_internal_reflection_keeps_the_reflection_ray() {
    // A transmitting square seen head-on: the eye ray spawns one reflection and one
    // refraction; each of those continues into the background.
    let scene = parse_nff(
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 10\nhither 0\nresolution 1 1\n\
         f 1 1 1 0.2 0.1 10 0.8 1.5\np 4\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n",
        "glass.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let out = tracer::render::<Count, _>(
        &scene,
        &accel,
        &RenderOptions::for_scene(&scene),
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let c = out.counts().unwrap_or_default();
    assert_eq!((c.rays.reflection, c.rays.refraction), (1, 1));
    assert_eq!(c.calls.trace, 3);
    assert_eq!(
        c.calls.shade, 1,
        "the secondary rays leave into the background"
    );
}
