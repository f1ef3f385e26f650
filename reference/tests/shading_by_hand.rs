//! The reference's Whitted shading against values computed by hand: the centre pixel of
//! a 3×3 view straight at a square, lit from the side.

use tracer::{RenderOptions, Rgb, Sampling, ShadingMode};

/// A grey square in z = 0 facing the eye at z = -5, a white light at (3, 0, -4) (5 from
/// the square's centre, cos θ = 0.8), a blue-ish background; `extra` adds primitives.
fn scene(extra: &str) -> tracer::Scene {
    let text = format!(
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 10\nhither 0\nresolution 3 3\n\
         b 0.1 0.2 0.3\nl 3 0 -4 1 1 1\nf 0.5 0.5 0.5 0.8 0.2 10 0 1\n\
         p 4\n-2 -2 0\n2 -2 0\n2 2 0\n-2 2 0\n{extra}"
    );
    tracer::parse_nff(&text, "hand.nff").unwrap_or_else(|e| panic!("{e}"))
}

fn centre(scene: &tracer::Scene, mode: ShadingMode, depth: u32) -> Rgb {
    let mut options = RenderOptions::new(3, 3, Sampling::PixelCenters, mode);
    options.max_depth = depth;
    let frame = reference::render(scene, &options, &|_| {}).unwrap_or_else(|e| panic!("{e}"));
    frame.pixels[4]
}

fn close(got: Rgb, want: [f64; 3]) -> bool {
    [got.r, got.g, got.b]
        .iter()
        .zip(want)
        .all(|(&g, w)| (f64::from(g) - w).abs() < 1e-6)
}

#[test]
fn ambient_lambert_highlight_and_reflected_background() {
    // Ambient 0.1 × Kd × colour = 0.04; Lambert colour × light × Kd × cos θ = 0.32;
    // highlight Ks × (R·L)^shine with R = (0, 0, -1), L = (0.6, 0, -0.8): 0.2 × 0.8¹⁰;
    // the reflection ray sees the background: + Ks × (0.1, 0.2, 0.3).
    let lit = 0.04 + 0.32 + 0.2 * 0.8f64.powi(10);
    let got = centre(&scene(""), ShadingMode::Color, 5);
    assert!(close(got, [lit + 0.02, lit + 0.04, lit + 0.06]), "{got:?}");
    // Depth 1: no reflection ray.
    let got = centre(&scene(""), ShadingMode::Color, 1);
    assert!(close(got, [lit; 3]), "{got:?}");
    // Gray: Rec. 601 luma of the colour.
    let luma = lit + 0.299 * 0.02 + 0.587 * 0.04 + 0.114 * 0.06;
    let got = centre(&scene(""), ShadingMode::Gray, 5);
    assert!(close(got, [luma; 3]), "{got:?}");
    // Diffuse only: N·L with the polygon's own normal, not turned toward the viewer.
    // Wound counter-clockwise seen from +z, it points away from eye and light: N·L =
    // -0.8 < 0 shows the background's luma.
    let got = centre(&scene(""), ShadingMode::DiffuseOnly, 5);
    assert!(
        close(got, [0.299 * 0.1 + 0.587 * 0.2 + 0.114 * 0.3; 3]),
        "{got:?}"
    );
}

#[test]
fn a_blocker_on_the_way_to_the_light_leaves_ambient_and_reflection() {
    // A sphere of radius 0.5 at (1.5, 0, -2), halfway to the light, off the eye ray and
    // the reflected ray.
    let got = centre(&scene("s 1.5 0 -2 0.5\n"), ShadingMode::Color, 5);
    assert!(close(got, [0.06, 0.08, 0.10]), "{got:?}");
}

#[test]
fn a_clear_transmitter_in_front_passes_the_picture_through() {
    // A transmitting square (Kd = Ks = 0, T = 1, ior 1) at z = -1: its own terms are
    // zero and the refracted ray goes straight on (relative index 1) to the grey square.
    // There the shadow ray passes z = -1 at x = 0.75, inside the transmitter, which
    // blocks it (any primitive blocks a shadow ray); the reflected ray passes back
    // through the transmitter to the background: ambient + Ks × background.
    let glass = "f 1 1 1 0 0 1 1 1\np 4\n-2 -2 -1\n2 -2 -1\n2 2 -1\n-2 2 -1\n";
    let got = centre(&scene(glass), ShadingMode::Color, 5);
    assert!(close(got, [0.06, 0.08, 0.10]), "{got:?}");
}
