//! The diffuse forms of the `no-rsqrt-shading` variant (thesis 8.3.4).
//!
//! [`DiffuseForm::Squared`] replaces the Lambert term of spheres by
//! `cos θ = 1 - |I - M|² / 2r²`, with `M = C + r L̂` the sphere's brightest point for
//! the direction `L̂` from its centre to the light (precomputed once per sphere and
//! light, [`SpherePeaks`]): no normalization and no square root. It equals Lambert for
//! a light at infinity and differs for near point lights. The thesis's own form,
//! `1 - |I - M| / (r√2)`, is [`thesis_linear_diffuse`]; it is not Lambert (see its
//! doc). In full Whitted shading the shadow ray and the highlight still need the unit
//! light vector, so the saving shows in diffuse-only shading.

use crate::counter::{Counter, NoCount};
use crate::ray::{Hit, PrimKind};
use crate::scene::Scene;
use crate::vec3::Vec3;

/// How the diffuse term of spheres is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DiffuseForm {
    /// `N·L` with both vectors of unit length (baseline).
    #[default]
    Lambert,
    /// `1 - |I - M|² / 2r²` (variant `no-rsqrt-shading`).
    Squared,
}

/// The thesis's sqrt-free diffuse term in its intended reading (8.3.4): with
/// `d = |I - M|`, `1 - d / (r√2)` where `d < r√2`, else 0 (the thesis's pseudo-code has
/// the comparison inverted). In terms of `cos θ = N·L̂` it is `1 - sqrt(1 - cos θ)`, not
/// Lambert: it falls short of `cos θ` by up to 0.25 (at `cos θ = 0.75`).
pub fn thesis_linear_diffuse(distance_to_peak: f32, radius: f32) -> f32 {
    let limit = radius.abs() * std::f32::consts::SQRT_2;
    if distance_to_peak < limit {
        1.0 - distance_to_peak / limit
    } else {
        0.0
    }
}

/// The exact sqrt-free form: `1 - d² / 2r²` = `cos θ` for a light at infinity.
pub fn squared_diffuse(distance_to_peak_sq: f32, radius: f32) -> f32 {
    1.0 - distance_to_peak_sq / (2.0 * radius * radius)
}

/// How far the sqrt-free diffuse forms are from Lambert, over a sphere lit by a light
/// at infinity (where the squared form is exact).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DiffuseErrors {
    /// The thesis's `1 - d/(r√2)`: largest and mean absolute difference from `max(0, N·L)`.
    pub thesis_linear_max_abs: f32,
    pub thesis_linear_mean_abs: f32,
    /// `cos θ` at the worst point of the linear form.
    pub thesis_linear_worst_cos: f32,
    /// `1 - d²/2r²`: largest and mean absolute difference (rounding only).
    pub squared_max_abs: f32,
    pub squared_mean_abs: f32,
    /// Points measured.
    pub samples: u32,
}

/// Measures both sqrt-free forms against Lambert at `n × 2n` points spread over a
/// sphere (latitude-longitude grid) with the light along an oblique axis. Geometry is
/// computed with vectors, independently of the `cos θ` algebra the forms rely on.
pub fn diffuse_form_errors(n: u32) -> DiffuseErrors {
    let c = &mut NoCount;
    let centre = Vec3::new(1.0, -2.0, 0.5);
    let radius = 1.75f32;
    let light = c.normalize(Vec3::new(0.3, 0.8, -0.5));
    let lift = c.scale(light, radius);
    let peak = c.add(centre, lift);
    let mut e = DiffuseErrors {
        thesis_linear_max_abs: 0.0,
        thesis_linear_mean_abs: 0.0,
        thesis_linear_worst_cos: 0.0,
        squared_max_abs: 0.0,
        squared_mean_abs: 0.0,
        samples: 0,
    };
    let (mut linear_sum, mut squared_sum) = (0.0f64, 0.0f64);
    for i in 0..n {
        let polar = std::f32::consts::PI * (i as f32 + 0.5) / n as f32;
        for j in 0..2 * n {
            let azimuth = std::f32::consts::PI * j as f32 / n as f32;
            let normal = Vec3::new(
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            );
            let offset = c.scale(normal, radius);
            let point = c.add(centre, offset);
            let lambert = c.dot(normal, light).max(0.0);
            let from_peak = c.sub(point, peak);
            let d_sq = c.dot(from_peak, from_peak);
            let linear = thesis_linear_diffuse(c.sqrt(d_sq), radius);
            let squared = squared_diffuse(d_sq, radius).max(0.0);
            let linear_err = (linear - lambert).abs();
            let squared_err = (squared - lambert).abs();
            if linear_err > e.thesis_linear_max_abs {
                e.thesis_linear_max_abs = linear_err;
                e.thesis_linear_worst_cos = lambert;
            }
            e.squared_max_abs = e.squared_max_abs.max(squared_err);
            linear_sum += f64::from(linear_err);
            squared_sum += f64::from(squared_err);
            e.samples += 1;
        }
    }
    let count = f64::from(e.samples.max(1));
    e.thesis_linear_mean_abs = (linear_sum / count) as f32;
    e.squared_mean_abs = (squared_sum / count) as f32;
    e
}

/// The squared form's preprocessing: each sphere's brightest point `M = C + r L̂` per
/// light, computed once, uncounted.
#[derive(Clone, Debug)]
pub struct SpherePeaks {
    /// `peaks[sphere * lights + light]`.
    peaks: Vec<Vec3>,
    lights: usize,
}

impl SpherePeaks {
    /// The peaks of every sphere of `scene` for every light.
    pub fn new(scene: &Scene) -> Self {
        let c = &mut NoCount;
        let mut peaks = Vec::with_capacity(scene.spheres.len() * scene.lights.len());
        for sphere in &scene.spheres {
            for light in &scene.lights {
                let to_light = c.sub(light.position, sphere.center);
                let peak = if c.dot(to_light, to_light) > 0.0 {
                    let toward = c.normalize(to_light);
                    let lift = c.scale(toward, sphere.radius.abs());
                    c.add(sphere.center, lift)
                } else {
                    // A light at the centre lights nothing from outside.
                    sphere.center
                };
                peaks.push(peak);
            }
        }
        Self {
            peaks,
            lights: scene.lights.len(),
        }
    }

    /// `cos θ` by the squared form at `point` of the hit sphere for light `light`
    /// (`scene` is the one the peaks were made for); `None` when the hit is not on a
    /// sphere seen from outside, where Lambert applies.
    #[inline]
    pub fn cos_theta<C: Counter>(
        &self,
        scene: &Scene,
        hit: &Hit,
        point: Vec3,
        light: usize,
        c: &mut C,
    ) -> Option<f32> {
        if hit.prim.kind != PrimKind::Sphere {
            return None;
        }
        let index = hit.prim.index as usize;
        let sphere = &scene.spheres[index];
        if sphere.inside_visible() {
            return None;
        }
        let peak = self.peaks[index * self.lights + light];
        let from_peak = c.sub(point, peak);
        let distance_sq = c.dot(from_peak, from_peak);
        Some(squared_diffuse(distance_sq, sphere.radius))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, Stat};

    #[test]
    fn sqrt_free_forms_against_lambert() {
        // Squared form: exact up to rounding. Linear form: 1 - sqrt(1 - cos) vs cos,
        // worst at cos = 3/4 where it gives 1/2: error 1/4.
        let e = diffuse_form_errors(200);
        assert!(e.squared_max_abs < 1e-5, "{e:?}");
        assert!((e.thesis_linear_max_abs - 0.25).abs() < 2e-3, "{e:?}");
        assert!((e.thesis_linear_worst_cos - 0.75).abs() < 0.02, "{e:?}");
        assert_eq!(e.samples, 200 * 400);
    }

    #[test]
    fn squared_diffuse_of_a_sphere_hit_counts_no_root() {
        let scene = crate::nff::parse_nff(
            "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0\nresolution 1 1\n\
             l 0 0 -100\ns 0 0 0 2\n",
            "sq.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let peaks = SpherePeaks::new(&scene);
        let hit = Hit {
            t: 3.0,
            prim: crate::ray::PrimRef {
                kind: PrimKind::Sphere,
                index: 0,
            },
            aux: 0.0,
        };
        let mut c = Count::default();
        // The point facing the light is its brightest: cos θ = 1.
        let cos = peaks.cos_theta(&scene, &hit, Vec3::new(0.0, 0.0, -2.0), 0, &mut c);
        assert_eq!(cos, Some(1.0));
        assert_eq!(c.get(Stat::Sqrt) + c.get(Stat::Normalize), 0);
        // The silhouette (90° from the light) is dark: cos θ = 0.
        let cos = peaks.cos_theta(&scene, &hit, Vec3::new(2.0, 0.0, 0.0), 0, &mut c);
        assert!(cos.is_some_and(|v| v.abs() < 1e-6));
    }
}
