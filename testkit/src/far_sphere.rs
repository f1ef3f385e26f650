//! The far-sphere scenes of issue 35: one diffuse sphere of radius `r` straight ahead,
//! [`DISTANCE`] from the eye, 64×64, the field of view fitted so that the view's
//! half-width at the sphere's distance is [`HALF_WIDTH_IN_RADII`] radii (the sphere's
//! angular radius about 1/1.25 of the half-angle). Every radius gives nearly the same
//! picture, so a renderer that is right draws the same pixels for each; an f32
//! `b² - c` discriminant cancels as `r` shrinks. [`expected_hits`] counts the pixel
//! centres whose ray meets the sphere in closed form, independently of any renderer.
//!
//! The light sits at the eye, so every visible point faces it (the diffuse-only
//! shading shows the background where N·L < 0) and the background is black: the pixels
//! a renderer draws are those that differ from black.

use tracer::{NffError, Scene, parse_nff};

/// Distance from the eye to the sphere's centre.
pub const DISTANCE: f64 = 1000.0;

/// Image width and height.
pub const SIZE: u32 = 64;

/// The radii of the table.
pub const RADII: [f64; 5] = [1.0, 0.3, 0.1, 0.03, 0.01];

/// The view's half-width at the sphere's distance, in radii: `tan(angle/2) = 1.25 r / D`.
pub const HALF_WIDTH_IN_RADII: f64 = 1.25;

/// The NFF angle (degrees, centre of the top sample row to centre of the bottom one)
/// that fits the view to a sphere of `radius`.
pub fn angle_deg(radius: f64) -> f64 {
    2.0 * (HALF_WIDTH_IN_RADII * radius / DISTANCE)
        .atan()
        .to_degrees()
}

/// The scene as NFF text: eye at the origin looking down +z, the sphere at z = D.
pub fn nff(radius: f64) -> String {
    format!(
        "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle {angle}\nhither 0.001\nresolution {SIZE} {SIZE}\n\
         b 0 0 0\nl 0 0 0\nf 1 1 1 1 0 1 0 1\ns 0 0 {DISTANCE} {radius}\n",
        angle = angle_deg(radius),
    )
}

/// The parsed scene.
pub fn scene(radius: f64) -> Result<Scene, NffError> {
    parse_nff(&nff(radius), &format!("far-sphere-r{radius}.nff"))
}

/// Which of the scene's W×H pixel centres (row-major, row 0 at the top) see the
/// sphere, computed in f64 from the parsed numbers (the f32 angle and radius the
/// renderers get): the ray through the centre at offset `(x, y)` samples from the
/// middle makes the angle θ with the view axis where `tan θ = pitch √(x² + y²)`,
/// `pitch = 2 tan(angle/2) / (H - 1)`, and meets a sphere of radius `r` centred on the
/// axis at distance `D` when `sin θ < r / D`, i.e. `tan² θ < r² / (D² - r²)` (a tangent
/// ray is no hit). An error unless the scene is one sphere centred on the view axis,
/// in front of the eye, which it does not contain.
pub fn expected_mask(scene: &Scene) -> Result<Vec<bool>, String> {
    let [sphere] = scene.spheres.as_slice() else {
        return Err("expected exactly one sphere".into());
    };
    let v = &scene.view;
    let f64s = |a: [f32; 3]| a.map(f64::from);
    let (eye, at, centre) = (
        f64s(v.from.to_array()),
        f64s(v.at.to_array()),
        f64s(sphere.center.to_array()),
    );
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (axis, to_centre) = (sub(at, eye), sub(centre, eye));
    let (aa, cc, ac) = (
        dot(axis, axis),
        dot(to_centre, to_centre),
        dot(axis, to_centre),
    );
    // sin² of the angle between the view axis and the centre's direction (Lagrange).
    // (Written so that NaN fails too.)
    let (ahead, on_axis) = (ac > 0.0, aa * cc - ac * ac <= 1e-18 * aa * cc);
    if !(ahead && on_axis) {
        return Err("the sphere is not centred on the view axis in front of the eye".into());
    }
    let r = f64::from(sphere.radius.abs());
    let outside = cc > r * r;
    if !outside {
        return Err("the eye is inside the sphere".into());
    }
    let limit = r * r / (cc - r * r);
    let (w, h) = (v.width, v.height);
    let pitch = 2.0 * (f64::from(v.angle_deg).to_radians() / 2.0).tan() / f64::from(h.max(2) - 1);
    Ok((0..h)
        .flat_map(|row| (0..w).map(move |column| (column, row)))
        .map(|(column, row)| {
            let x = f64::from(column) - f64::from(w - 1) / 2.0;
            let y = f64::from(h - 1) / 2.0 - f64::from(row);
            pitch * pitch * (x * x + y * y) < limit
        })
        .collect())
}

/// How many pixel centres see the sphere ([`expected_mask`]).
pub fn expected_hits(scene: &Scene) -> Result<u64, String> {
    Ok(expected_mask(scene)?.into_iter().filter(|&hit| hit).count() as u64)
}

/// Which pixels of a rendered frame differ from the black background (row-major).
pub fn drawn_mask(frame: &tracer::Frame) -> Vec<bool> {
    frame
        .pixels
        .iter()
        .map(|p| *p != tracer::Rgb::BLACK)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_radius_covers_the_same_1992_pixel_centres() {
        // With tan(angle/2) = 1.25 r / D the disc's radius on the sample grid is
        // 31.5 / 1.25 = 25.2 samples (up to r²/D² ≈ 1e-6): the centres (i + ½, j + ½)
        // with (2i+1)² + (2j+1)² < 4 × 25.2² = 2540.16, whose sums of two odd squares
        // are ≡ 2 (mod 8) and so never within 1.6 of the bound: 1,992 of them,
        // counted here from the lattice alone.
        let mut lattice = 0;
        for a in (-63i64..=63).step_by(2) {
            for b in (-63i64..=63).step_by(2) {
                if a * a + b * b < 2540 {
                    lattice += 1;
                }
            }
        }
        assert_eq!(lattice, 1992);
        for r in RADII {
            let scene = scene(r).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(expected_hits(&scene), Ok(1992), "r = {r}");
        }
    }

    #[test]
    fn a_scene_that_is_not_one_sphere_on_the_axis_is_refused() {
        let mut s = scene(1.0).unwrap_or_else(|e| panic!("{e}"));
        s.spheres[0].center = tracer::Vec3::new(5.0, 0.0, 1000.0);
        assert!(expected_hits(&s).is_err());
        s.spheres.clear();
        assert!(expected_hits(&s).is_err());
    }
}
