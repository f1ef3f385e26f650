//! The reference's BVH only culls: every scene renders bit for bit as the brute-force
//! walk over all primitives renders it (the definition), in every shading mode and
//! sampling, including exact ties between coincident primitives (the first in scene
//! order wins in both) and rays that run along a box's face.

use std::path::PathBuf;
use tracer::{Frame, RenderOptions, Sampling, Scene, ShadingMode};

fn shared_spd(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/spd")
        .join(format!("{name}.nff"));
    tracer::load_nff(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn both_walks(scene: &Scene, options: &RenderOptions) -> (Frame, Frame) {
    let converted = reference::RefScene::new(scene);
    let walk = |walk| {
        reference::render::render_walking(&converted, options, walk, &|_| {})
            .unwrap_or_else(|e| panic!("{e}"))
    };
    (
        walk(reference::Walk::Bvh),
        walk(reference::Walk::BruteForce),
    )
}

fn assert_same(name: &str, scene: &Scene, options: &RenderOptions) {
    let (bvh, brute) = both_walks(scene, options);
    let differing = bvh
        .pixels
        .iter()
        .zip(&brute.pixels)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differing, 0, "{name}: {differing} pixels differ");
}

#[test]
fn bvh_and_brute_force_give_the_same_picture_on_every_spd_scene() {
    let names = [
        "balls", "gears", "jacks", "lattice", "mount", "rings", "sample", "shells", "sombrero",
        "teapot", "tetra", "tree",
    ];
    for name in names {
        let scene = shared_spd(name);
        let options = RenderOptions::new(24, 24, Sampling::PixelCenters, ShadingMode::Color);
        assert_same(name, &scene, &options);
    }
}

#[test]
fn bvh_and_brute_force_agree_in_every_mode_and_with_corner_rays() {
    let scene = shared_spd("tetra");
    for (sampling, mode) in [
        (Sampling::PixelCenters, ShadingMode::Gray),
        (Sampling::PixelCenters, ShadingMode::DiffuseOnly),
        (Sampling::SpdCorners, ShadingMode::Color),
    ] {
        let options = RenderOptions::new(20, 20, sampling, mode);
        assert_same(&format!("tetra {sampling:?} {mode:?}"), &scene, &options);
    }
}

#[test]
fn coincident_primitives_resolve_to_the_first_in_scene_order() {
    // Eight coincident squares facing the eye, alternating red and green, and a row of
    // cubes' faces lying in axis planes that eye rays graze: more objects than a leaf
    // holds, so the hierarchy splits them and meets them in another order than the file.
    let mut text = String::from(
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 16 16\n\
         l 0 0 -10\n",
    );
    for i in 0..8 {
        let colour = if i % 2 == 0 { "1 0 0" } else { "0 1 0" };
        text.push_str(&format!(
            "f {colour} 1 0 0 0 1\np 4\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n"
        ));
    }
    for i in 0..6 {
        let x = -1.5 + 0.5 * f64::from(i);
        text.push_str(&format!(
            "f 0 0 1 1 0 0 0 1\np 4\n{x} -2 -1\n{x} 2 -1\n{x} 2 1\n{x} -2 1\n"
        ));
    }
    let scene = tracer::parse_nff(&text, "ties.nff").unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions::new(16, 16, Sampling::PixelCenters, ShadingMode::Color);
    assert_same("ties", &scene, &options);
    // And the winner is the first square: red, not green.
    let (bvh, _) = both_walks(&scene, &options);
    let centre = bvh.pixels[8 * 16 + 8];
    assert!(centre.r > 0.0 && centre.g == 0.0, "{centre:?}");
}
