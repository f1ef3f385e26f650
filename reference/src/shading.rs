//! Whitted shading in f64 by the tracer's rules (README, "SPD rules as implemented"),
//! every query answered by the [`crate::bvh`] (which only culls) or, on request, by a
//! brute-force walk over all primitives ([`Walk`]): the same hits either way.
//!
//! Colour = ambient + Σ over lights reached by a shadow ray of (Lambert + Phong
//! highlight) + Ks × reflected + T × refracted, to the maximum depth with the eye ray at
//! depth 1. The readings the rules leave open are the tracer's:
//! - surfaces are two-sided and shaded with the normal turned toward the incoming ray
//!   (a patch's interpolated normal is kept in the hemisphere of that geometric normal);
//!   a negative radius makes a quadric inside-only (in its intersection test);
//! - ambient `0.1 × Kd × colour`; no shadow ray toward a light the normal faces away
//!   from; a shadow ray starts at the lifted point and reaches the light's distance from
//!   the hit point; any primitive blocks it;
//! - secondary rays start `1e-4 × (1 + max |coordinate|)` off the surface along the
//!   facing geometric normal (reflection and shadow rays above it, refraction below);
//! - every hit on a reflective (Ks > 0) or transmitting (T > 0) surface below the
//!   maximum depth spawns a reflection ray; a transmitter also a refraction ray (relative
//!   index 1/ior entering the front face, ior leaving) unless total internal reflection,
//!   where the reflection ray carries the transmitted weight too;
//! - the highlight is `Ks × light × (R·L)^shine` with R the mirrored view direction;
//! - a secondary ray that hits nothing sees the background colour; an eye ray that hits
//!   nothing the background in the mode's colours; gray is the Rec. 601 luma.
//!
//! `ShadingMode::DiffuseOnly` is the thesis hardware's: the Lambert term of the first
//! light with the primitive's own normal (not turned toward the viewer), gray, the
//! background where it is negative, nothing else.

use crate::bvh::Bvh;
use crate::primitives::Shape;
use crate::ray::{Hit, Ray};
use crate::scene::{Material, Object, RefScene};
use glam::DVec3;
use tracer::ShadingMode;

/// Ambient intensity (the tracer's rule: NFF gives none).
pub const AMBIENT: f64 = 0.1;

/// Secondary rays start this far, relative to the hit point's magnitude, off the
/// surface (the tracer's rule).
pub const OFFSET_SCALE: f64 = 1e-4;

/// A colour as an (r, g, b) vector.
pub type Color = DVec3;

/// Rec. 601 luma.
pub fn luminance(c: Color) -> f64 {
    0.299 * c.x + 0.587 * c.y + 0.114 * c.z
}

/// How queries find the primitives a ray meets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Walk {
    /// Through the f64 bounding volume hierarchy (the default).
    Bvh,
    /// Every primitive, in scene order: the definition the hierarchy is tested against.
    BruteForce,
}

/// Traces rays through a scene.
pub struct Shader<'s> {
    scene: &'s RefScene,
    mode: ShadingMode,
    max_depth: u32,
    /// `None`: the brute-force walk.
    bvh: Option<Bvh>,
}

/// A hit's surface as shading sees it.
struct Surface {
    point: DVec3,
    /// Shading normal, on the incoming ray's side.
    normal: DVec3,
    /// Geometric normal, on the incoming ray's side.
    facing: DVec3,
    /// Whether the ray met the side the primitive's normal points to.
    front: bool,
    material: Material,
}

impl<'s> Shader<'s> {
    pub fn new(scene: &'s RefScene, mode: ShadingMode, max_depth: u32, walk: Walk) -> Self {
        Self {
            scene,
            mode,
            max_depth,
            bvh: (walk == Walk::Bvh).then(|| Bvh::build(&scene.objects)),
        }
    }

    /// The closest primitive hit by `ray` at `t > 0` (ties: the first in scene order).
    pub fn closest(&self, ray: &Ray) -> Option<(&'s Object, Hit)> {
        if let Some(bvh) = &self.bvh {
            return bvh.closest(&self.scene.objects, ray);
        }
        let mut best: Option<(&'s Object, Hit)> = None;
        let mut reach = f64::INFINITY;
        for object in &self.scene.objects {
            if let Some(hit) = object.shape.intersect(ray, 0.0, reach) {
                reach = hit.t;
                best = Some((object, hit));
            }
        }
        best
    }

    /// Whether any primitive lies on `ray` at `0 < t < reach`.
    pub fn occluded(&self, ray: &Ray, reach: f64) -> bool {
        if let Some(bvh) = &self.bvh {
            return bvh.occluded(&self.scene.objects, ray, reach);
        }
        self.scene
            .objects
            .iter()
            .any(|o| o.shape.intersect(ray, 0.0, reach).is_some())
    }

    /// The background in the mode's colours (eye rays).
    fn background(&self) -> Color {
        match self.mode {
            ShadingMode::Color => self.scene.background,
            ShadingMode::Gray | ShadingMode::DiffuseOnly => {
                DVec3::splat(luminance(self.scene.background))
            }
        }
    }

    /// The value of one eye ray.
    pub fn primary(&self, ray: &Ray) -> Color {
        let Some((object, hit)) = self.closest(ray) else {
            return self.background();
        };
        match self.mode {
            ShadingMode::Color => self.shade(ray, object, &hit, 1),
            ShadingMode::Gray => DVec3::splat(luminance(self.shade(ray, object, &hit, 1))),
            ShadingMode::DiffuseOnly => self
                .diffuse_only(ray, object, &hit)
                .unwrap_or_else(|| self.background()),
        }
    }

    /// The colour seen along a secondary ray at tree depth `depth`.
    fn trace(&self, ray: &Ray, depth: u32) -> Color {
        match self.closest(ray) {
            Some((object, hit)) => self.shade(ray, object, &hit, depth),
            None => self.scene.background,
        }
    }

    /// The thesis hardware's value of a hit; `None` shows the background.
    fn diffuse_only(&self, ray: &Ray, object: &Object, hit: &Hit) -> Option<Color> {
        let light = self.scene.lights.first()?;
        let (normal, _) = object.shape.normals(ray, hit);
        let to_light = (light.position - ray.at(hit.t)).normalize();
        let lambert = normal.dot(to_light);
        (lambert >= 0.0).then(|| DVec3::splat(lambert))
    }

    fn surface(&self, ray: &Ray, object: &Object, hit: &Hit) -> Surface {
        let point = ray.at(hit.t);
        let (mut normal, mut facing) = object.shape.normals(ray, hit);
        // No orientation where none is defined (a cone's tip): shade as facing the ray.
        if !facing.is_finite() || !normal.is_finite() {
            facing = -ray.dir;
            normal = facing;
        }
        let front = facing.dot(ray.dir) < 0.0;
        if !front {
            facing = -facing;
        }
        if matches!(object.shape, Shape::Patch(_)) {
            if normal.dot(facing) < 0.0 {
                normal = -normal;
            }
        } else {
            normal = facing;
        }
        Surface {
            point,
            normal,
            facing,
            front,
            material: object.material,
        }
    }

    fn shade(&self, ray: &Ray, object: &Object, hit: &Hit, depth: u32) -> Color {
        let s = self.surface(ray, object, hit);
        let m = s.material;
        let mut color = m.color * (AMBIENT * m.kd);
        let offset = OFFSET_SCALE * (1.0 + s.point.abs().max_element());
        let lift = s.facing * offset;
        let above = s.point + lift;
        let reflective = m.ks > 0.0 || m.t > 0.0;
        let mirror = reflective.then(|| reflect(ray.dir, s.normal));
        for light in &self.scene.lights {
            let to_light = light.position - s.point;
            let n_dot = s.normal.dot(to_light);
            if !(n_dot > 0.0) {
                continue;
            }
            let distance = to_light.length();
            let l = to_light / distance;
            let shadow = Ray {
                origin: above,
                dir: l,
            };
            if self.occluded(&shadow, distance) {
                continue;
            }
            color += m.color * light.color * (m.kd * n_dot / distance);
            if let (Some(mirror), true) = (mirror, m.ks > 0.0) {
                let cos_alpha = mirror.dot(l);
                if cos_alpha > 0.0 {
                    color += light.color * (m.ks * cos_alpha.min(1.0).powf(m.shine));
                }
            }
        }
        if depth < self.max_depth && reflective {
            let mut reflect_weight = m.ks;
            if m.t > 0.0 {
                let eta = if s.front { 1.0 / m.ior } else { m.ior };
                match refract(ray.dir, s.normal, eta) {
                    Some(dir) => {
                        let below = Ray {
                            origin: s.point - lift,
                            dir,
                        };
                        color += self.trace(&below, depth + 1) * m.t;
                    }
                    None => reflect_weight += m.t,
                }
            }
            if let Some(dir) = mirror {
                let reflected = Ray { origin: above, dir };
                color += self.trace(&reflected, depth + 1) * reflect_weight;
            }
        }
        color
    }
}

/// The mirror direction of `dir` about the unit `normal`: `D - 2 (D·N) N`.
pub fn reflect(dir: DVec3, normal: DVec3) -> DVec3 {
    dir - 2.0 * dir.dot(normal) * normal
}

/// The refracted direction by Snell's law for the relative index `eta = n₁ / n₂`, with
/// `normal` on the incoming side; `None` on total internal reflection.
pub fn refract(dir: DVec3, normal: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -dir.dot(normal);
    let sin_t_sq = eta * eta * (1.0 - cos_i * cos_i);
    if sin_t_sq > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin_t_sq).sqrt();
    Some(eta * dir + (eta * cos_i - cos_t) * normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snell_at_45_degrees_into_glass_and_total_internal_reflection_out_of_it() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let n = DVec3::Y;
        let into = refract(DVec3::new(h, -h, 0.0), n, 1.0 / 1.5).unwrap_or(DVec3::NAN);
        // sin t = sin 45° / 1.5.
        let sin_t = h / 1.5;
        let want = DVec3::new(sin_t, -(1.0 - sin_t * sin_t).sqrt(), 0.0);
        assert!((into - want).length() < 1e-15, "{into}");
        // Out of glass at 45°: beyond the critical angle asin(1/1.5) = 41.8°.
        assert_eq!(refract(DVec3::new(h, -h, 0.0), n, 1.5), None);
        // At 30° it passes: sin t = 0.75.
        let out = refract(DVec3::new(0.5, -(0.75f64).sqrt(), 0.0), n, 1.5);
        let out = out.unwrap_or(DVec3::NAN);
        assert!((out - DVec3::new(0.75, -(1.0f64 - 0.5625).sqrt(), 0.0)).length() < 1e-15);
    }

    #[test]
    fn reflection_mirrors_about_the_normal() {
        assert_eq!(
            reflect(DVec3::new(1.0, -1.0, 0.0), DVec3::Y),
            DVec3::new(1.0, 1.0, 0.0)
        );
    }
}
