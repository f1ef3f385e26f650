//! The hardware emulator against hand-computed pixels, against the software's
//! diffuse-only render of the test bench (RMS), and the scene conversion's refusals.

// Expected values are computed here by hand, outside the counting layer.
#![allow(clippy::disallowed_methods)]

use hwmodel::emulator::{HwImage, render};
use hwmodel::hw_scene::{HwKind, HwScene, HwSceneError};
use std::path::Path;
use tracer::{BruteForce, NoCount, RenderOptions, Sampling, ShadingMode};

fn parse(text: &str) -> tracer::Scene {
    tracer::parse_nff(text, "test.nff").unwrap_or_else(|e| panic!("{e}"))
}

fn hw(text: &str) -> HwScene {
    HwScene::from_scene(&parse(text)).unwrap_or_else(|e| panic!("{e}"))
}

/// Eye at z = -5 looking +z, 30° vertical angle, gray 0.2 background, light at
/// (4, 0, -4), then `body`.
fn scene_text(body: &str) -> String {
    format!(
        "b 0.2 0.2 0.2\nv\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0.01\n\
         resolution 31 21\nl 4 0 -4\nf 1 1 1 1 0 1 0 1\n{body}"
    )
}

fn gray(image: &HwImage, column: u32, row: u32) -> u8 {
    image
        .gray_at(column, row)
        .unwrap_or_else(|| panic!("({column}, {row}) is outside the image"))
}

/// Hand Lambert value shared by the two one-primitive scenes: the centre ray meets
/// the surface at P = (0, 0, -1) with outward normal N = (0, 0, -1); the light at
/// (4, 0, -4) gives L = (4, 0, -3)/5, so N·L = 3/5 and the gray is 0.6 × 255 = 153.
/// The background 0.2 gray (luma 0.2) is 0.2 × 255 = 51.
const CENTRE_GRAY: u8 = 153;
const BACKGROUND_GRAY: u8 = 51;

#[test]
fn one_sphere_centre_pixel_is_the_hand_computed_lambert_value() {
    let scene = hw(&scene_text("s 0 0 0 1\n"));
    assert_eq!(scene.primitive_count(), 1);
    assert_eq!(scene.primitives[0].kind, HwKind::Sphere);
    // 31 x 21: the middle pixel (15, 10) looks straight down the axis.
    let image = render(&scene, 31, 21);
    assert_eq!(
        (image.width, image.height, image.pixels.len()),
        (31, 21, 651)
    );
    assert_eq!(gray(&image, 15, 10), CENTRE_GRAY);
    // The sphere subtends asin(1/5) = 11.5° around the axis; the corner pixel looks
    // atan(√(15² + 10²) · 2 tan 15° / 20) = 25.8° off it.
    for (column, row) in [(0, 0), (30, 0), (0, 20), (30, 20)] {
        assert_eq!(gray(&image, column, row), BACKGROUND_GRAY);
    }
    // Image right is normalize(forward × up) = (0, 0, 1) × (0, 1, 0) = (-1, 0, 0), so
    // the light at x = +4 is on the image's left: the left half is the brighter one.
    assert!(gray(&image, 12, 10) > gray(&image, 18, 10));
}

#[test]
fn one_cylinder_centre_pixel_uses_the_radial_normal() {
    // Axis along y from -1 to 1, radius 1: the centre ray meets the wall at (0, 0, -1),
    // m = 1, radial normal (0, 0, -1): the same Lambert value as the sphere's.
    let scene = hw(&scene_text("c\n0 -1 0 1\n0 1 0 1\n"));
    assert_eq!(scene.primitives[0].kind, HwKind::Cylinder);
    assert_eq!(scene.primitives[0].m_max, 2.0);
    let image = render(&scene, 31, 21);
    assert_eq!(gray(&image, 15, 10), CENTRE_GRAY);
    assert_eq!(gray(&image, 0, 0), BACKGROUND_GRAY);
    // Row 0 looks up at tan 15° = 0.268: it meets the wall plane z = -1 (4 units
    // away) at y = 1.07, above the top (m = 2.07 > m max = 2), and the far wall higher.
    assert_eq!(gray(&image, 15, 0), BACKGROUND_GRAY);
}

#[test]
fn light_behind_the_surface_shows_the_background() {
    // Light behind the sphere: N·L < 0 on the whole visible cap.
    let text = scene_text("s 0 0 0 1\n").replace("l 4 0 -4", "l 0 0 10");
    let image = render(&hw(&text), 31, 21);
    assert_eq!(gray(&image, 15, 10), BACKGROUND_GRAY);
}

fn rms(a: &[u8], b: &[u8]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2))
        .sum();
    (sum / a.len().max(1) as f64).sqrt()
}

/// The software's `--diffuse-only` render as 8-bit gray (the red channel of its
/// 8-bit RGB: the three are equal in gray modes).
fn software_gray(scene: &tracer::Scene, width: u32, height: u32) -> Vec<u8> {
    let options = RenderOptions::new(
        width,
        height,
        Sampling::PixelCenters,
        ShadingMode::DiffuseOnly,
    );
    let rendered = tracer::render::<NoCount, _>(
        scene,
        &BruteForce::new(scene),
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"));
    rendered
        .frame
        .to_rgb8()
        .iter()
        .step_by(3)
        .copied()
        .collect()
}

#[test]
fn test_bench_matches_the_software_diffuse_only_render() {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/"));
    let (width, height) = (160, 120);
    let mut measured = Vec::new();
    for family in ["balls", "cylinder", "both"] {
        for n in 1..=7 {
            let path = dir.join(format!("{family}{n}.nff"));
            if !path.exists() {
                continue;
            }
            let scene = tracer::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
            let hw_scene =
                HwScene::from_scene(&scene).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let emulated = render(&hw_scene, width, height);
            let software = software_gray(&scene, width, height);
            assert_eq!(emulated.pixels.len(), software.len());
            let differing = emulated
                .pixels
                .iter()
                .zip(&software)
                .filter(|(a, b)| a != b)
                .count();
            let value = rms(&emulated.pixels, &software);
            eprintln!(
                "{family}{n}: RMS {value:.3}, {differing} of {} pixels differ",
                software.len()
            );
            measured.push((format!("{family}{n}"), value));
        }
    }
    assert!(
        measured.len() >= 21,
        "expected the 21 test-bench scenes in {}, found {}",
        dir.display(),
        measured.len()
    );
    for (name, value) in &measured {
        assert!(*value <= 15.0, "{name}: RMS {value:.2} > 15");
    }
}

#[test]
fn unsupported_primitives_are_refused_with_a_count() {
    let text = scene_text(
        "s 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\np 3\n0 0 1\n1 0 1\n0 1 1\n\
         c\n0 0 0 1\n0 1 0 0.5\n",
    );
    let err = HwScene::from_scene(&parse(&text)).err();
    let message = err.map(|e| e.to_string()).unwrap_or_default();
    assert!(message.contains("2 polygons"), "{message}");
    assert!(message.contains("1 cone"), "{message}");
    assert!(message.contains("spheres and cylinders"), "{message}");

    let inside = scene_text("s 0 0 0 -1\n");
    let message = HwScene::from_scene(&parse(&inside))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        message.contains("1 inside-only sphere (negative radius)"),
        "{message}"
    );
}

#[test]
fn scene_without_light_is_refused() {
    let text = scene_text("s 0 0 0 1\n").replace("l 4 0 -4\n", "");
    assert_eq!(
        HwScene::from_scene(&parse(&text)),
        Err(HwSceneError::NoLight)
    );
}

#[test]
fn open_cylinder_end_shows_the_background_where_the_software_shows_the_inner_wall() {
    // Eye at (0, 4, -3) looking at (0, 0, 1) on the far wall of an open cylinder around
    // the y axis (y from -1 to 1, radius 1). The centre ray P(s) = (0, 4 - 4s, -3 + 4s)
    // crosses the near wall's surface z = -1 at s = 1/2, y = 2: m = 3 > m max = 2,
    // so the smaller root fails the body test and the hardware reports a miss; the
    // far wall z = 1 is met at s = 1, y = 0 (m = 1), which the software shows. Its
    // outward normal (0, 0, 1) faces the light at (0, 0, 10) squarely: N·L = 1, 255.
    let text = "b 0.2 0.2 0.2\nv\nfrom 0 4 -3\nat 0 0 1\nup 0 1 0\nangle 30\nhither 0.01\n\
                resolution 31 21\nl 0 0 10\nc\n0 -1 0 1\n0 1 0 1\n";
    let scene = parse(text);
    let emulated = render(&hw(text), 31, 21);
    assert_eq!(gray(&emulated, 15, 10), BACKGROUND_GRAY);
    let software = software_gray(&scene, 31, 21);
    assert_eq!(software[10 * 31 + 15], 255);
}
