//! The `bounded` variant's scene preparation (thesis 8.3.2, "observer at the origin"):
//! once, before rendering, every primitive gets its offset from the observer,
//! `eye - C`, which is the `Voc` every eye ray's test would otherwise subtract anew.
//! Eye rays then test primitives without that subtraction, and the screen is walked
//! row by row with the row's base direction computed once (see the camera).
//!
//! This is the scene in eye-centred coordinates, a translation. It is not rotated to
//! look down an axis as the thesis's bounded scene is: any rotation rounds every
//! coordinate differently from the world-space baseline, and those last-bit
//! differences flip hit decisions at silhouettes and shadow edges (measured on
//! rings.nff at 96x96 with a full camera-space rotation: RMS 1.9 and different ray
//! counts). The offsets here are the very f32 values the baseline computes, so the
//! picture and every ray count stay the baseline's.

use crate::counter::{Counter, NoCount};
use crate::scene::Scene;

/// A copy of `scene` whose primitives carry their offset from the view's eye.
pub fn with_eye_offsets(scene: &Scene) -> Scene {
    let eye = scene.view.from;
    let c = &mut NoCount;
    let mut out = scene.clone();
    for s in &mut out.spheres {
        s.eye_offset = c.sub(eye, s.center);
    }
    for cy in &mut out.cylinders {
        cy.eye_offset = c.sub(eye, cy.base);
    }
    for co in &mut out.cones {
        co.eye_offset = c.sub(eye, co.base);
    }
    for p in &mut out.polygons {
        p.outline.eye_offset = c.sub(eye, p.outline.vertices[0]);
    }
    for p in &mut out.patches {
        p.outline.eye_offset = c.sub(eye, p.outline.vertices[0]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, Stat};
    use crate::nff::parse_nff;
    use crate::ray::Ray;
    use crate::vec3::Vec3;

    #[test]
    fn eye_rays_of_a_prepared_scene_match_plain_rays_bit_for_bit_without_a_sub() {
        let scene = parse_nff(
            "v\nfrom 0.3 -7.1 2.2\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
             s 0.1 0.2 0.3 1.7\nc\n1 1 -1 0.5\n1.2 1.1 2 0.5\np 3\n-3 -3 -1\n3 -3 -1\n0 3 -1\n",
            "eye.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let prepared = with_eye_offsets(&scene);
        let eye = scene.view.from;
        for dir in [[0.0, 1.0, -0.3], [0.14, 1.0, -0.1], [-0.4, 1.0, -0.45]] {
            let dir = NoCount.normalize(Vec3::from_array(dir));
            let plain: Ray = Ray { origin: eye, dir };
            let from_eye: Ray<true> = Ray { origin: eye, dir };
            let (mut p, mut c) = (Count::default(), Count::default());
            let a = scene.spheres[0].intersect(&plain, 0.0, f32::INFINITY, &mut p);
            let b = prepared.spheres[0].intersect(&from_eye, 0.0, f32::INFINITY, &mut c);
            assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits));
            let a = scene.cylinders[0].intersect(&plain, 0.0, f32::INFINITY, &mut p);
            let b = prepared.cylinders[0].intersect(&from_eye, 0.0, f32::INFINITY, &mut c);
            assert_eq!(a, b);
            let a = scene.polygons[0].intersect(&plain, 0.0, f32::INFINITY, &mut p);
            let b = prepared.polygons[0].intersect(&from_eye, 0.0, f32::INFINITY, &mut c);
            assert_eq!(a, b);
            // Eye rays skip the O - C of each of the three tests, and nothing else (the
            // sphere's second stage subtracts the centre's offset along the ray).
            assert_eq!(
                p.get(Stat::Sub) - c.get(Stat::Sub),
                3,
                "eye rays skip O - C"
            );
            assert_eq!(p.get(Stat::Dot), c.get(Stat::Dot));
        }
    }
}
