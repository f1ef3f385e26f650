//! Small, far spheres: the case where the thesis's sphere discriminant cancels.
//!
//! One sphere of radius r at distance 1000 from the eye, 64×64 eye rays through the pixel
//! centres, the field of view fitted so that the image spans ±1.25 r at the sphere. The
//! number of eye rays that hit it is worked out here in f64 from the camera's geometry
//! alone: a ray through the centre of pixel (i, j) leaves at `x = (i - 31.5) p`,
//! `y = (j - 31.5) p` on the unit-distance image plane (the NFF angle spans the centres of
//! the extreme rows, so `p = 2 tan(angle / 2) / 63`), and meets the sphere when its angle
//! to the axis is below `asin(r / D)`, i.e. when `x² + y² < r² / (D² - r²)`. Every
//! structure must draw that many pixels within 2 % (before the two-stage sphere test, the
//! f32 baseline drew 1,788, 3,668, 0, 0 and 0 of about 1,990).

use tracer::{Count, RenderOptions, Sampling, ShadingMode, VariantSet, parse_nff, render_variant};

const DISTANCE: f64 = 1000.0;
const SIDE: u32 = 64;
const RADII: [f64; 5] = [1.0, 0.3, 0.1, 0.03, 0.01];
const STRUCTURES: [&str; 5] = ["baseline", "simd", "bvh", "bvh+simd", "bvh+simd+packets"];

/// The scene's NFF text: eye at the origin looking down +z, the sphere on the axis.
fn far_sphere_nff(radius: f64) -> String {
    let angle = 2.0 * (1.25 * radius / DISTANCE).atan().to_degrees();
    format!(
        "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle {angle:.9e}\nhither 1\nresolution {SIDE} {SIDE}\n\
         b 0 0 0\nl 0 0 0\nf 1 1 1 1 0 0 0 1\ns 0 0 {DISTANCE} {radius}\n"
    )
}

/// Pixel centres whose eye ray meets the sphere, in f64, for the angle as parsed.
fn exact_drawn(angle_deg: f32, radius: f64) -> u64 {
    let pitch = 2.0 * (f64::from(angle_deg).to_radians() / 2.0).tan() / f64::from(SIDE - 1);
    let limit = radius * radius / (DISTANCE * DISTANCE - radius * radius);
    let middle = f64::from(SIDE - 1) / 2.0;
    let mut drawn = 0;
    for j in 0..SIDE {
        for i in 0..SIDE {
            let x = (f64::from(i) - middle) * pitch;
            let y = (f64::from(j) - middle) * pitch;
            drawn += u64::from(x * x + y * y < limit);
        }
    }
    drawn
}

#[test]
fn every_structure_draws_small_far_spheres_whole() {
    for radius in RADII {
        let scene =
            parse_nff(&far_sphere_nff(radius), "far-sphere.nff").unwrap_or_else(|e| panic!("{e}"));
        let exact = exact_drawn(scene.view.angle_deg, radius);
        assert!(
            (1900..2100).contains(&exact),
            "r = {radius}: the sphere should cover about π/6.25 of the frame, {exact}"
        );
        let options =
            RenderOptions::new(SIDE, SIDE, Sampling::PixelCenters, ShadingMode::DiffuseOnly);
        for structure in STRUCTURES {
            let variants = VariantSet::parse(structure).unwrap_or_else(|e| panic!("{e}"));
            let rendered = render_variant::<Count>(&scene, &options, &variants, &|_| {})
                .unwrap_or_else(|e| panic!("{structure}: {e}"))
                .rendered;
            let drawn = rendered.counts().map_or(0, |c| c.rays.primary_hit);
            let off = (drawn as f64 - exact as f64).abs() / exact as f64;
            println!("r = {radius}: {structure} draws {drawn} of {exact} pixels");
            assert!(
                off <= 0.02,
                "r = {radius}: {structure} draws {drawn} pixels, exactly {exact} are on the sphere"
            );
        }
    }
}
