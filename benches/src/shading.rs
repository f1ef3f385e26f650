//! Group `shading`: the diffuse term of a sphere at 1024 fixed surface points, three
//! ways (variant `no-rsqrt-shading`, thesis 8.3.4):
//! - `lambert`: `max(0, N·L)` with `N = normalize(P - C)` and `L = normalize(light - P)`
//!   (two normalizations, each a square root and a division: the baseline);
//! - `thesis-linear`: [`thesis_linear_diffuse`] of `|P - M|`, with `M` the sphere's
//!   brightest point precomputed once (no normalization, but still one square root for
//!   the distance);
//! - `squared`: [`squared_diffuse`] of `|P - M|²` (no normalization, no square root).
//!
//! Vector maths goes through [`NoCount`], as in the uncounted renderer.

use criterion::{Criterion, Throughput};
use std::hint::black_box;
use tracer::variants::diffuse::{squared_diffuse, thesis_linear_diffuse};
use tracer::{Counter, NoCount, Vec3};

/// Number of surface points every benchmark of the group shades.
pub const POINT_COUNT: usize = 1024;

/// A sphere, a point light and points on the sphere's surface.
pub struct LitSphere {
    pub center: Vec3,
    pub radius: f32,
    pub light: Vec3,
    /// `center + radius · normalize(light - center)`: where the diffuse term peaks.
    pub peak: Vec3,
    pub points: Vec<Vec3>,
}

/// A sphere of radius 1.5 lit from 20 radii away, and [`POINT_COUNT`] points spread
/// evenly over its surface (a Fibonacci spiral: both the lit and the unlit side).
pub fn lit_sphere() -> LitSphere {
    let c = &mut NoCount;
    let center = Vec3::new(0.5, -1.0, 2.0);
    let radius = 1.5f32;
    let light = Vec3::new(20.0, 25.0, -10.0);
    let to_light = c.sub(light, center);
    let toward = c.normalize(to_light);
    let lift = c.scale(toward, radius);
    let peak = c.add(center, lift);
    let golden_angle = std::f32::consts::PI * (3.0 - c.sqrt(5.0));
    let points = (0..POINT_COUNT)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / POINT_COUNT as f32;
            let ring = c.sqrt((1.0 - z * z).max(0.0));
            let azimuth = golden_angle * i as f32;
            let normal = Vec3::new(ring * azimuth.cos(), ring * azimuth.sin(), z);
            let offset = c.scale(normal, radius);
            c.add(center, offset)
        })
        .collect();
    LitSphere {
        center,
        radius,
        light,
        peak,
        points,
    }
}

impl LitSphere {
    /// Lambert with both vectors normalized.
    #[inline(always)]
    pub fn lambert(&self, point: Vec3) -> f32 {
        let c = &mut NoCount;
        let radial = c.sub(point, self.center);
        let normal = c.normalize(radial);
        let to_light = c.sub(self.light, point);
        let light_dir = c.normalize(to_light);
        c.dot(normal, light_dir).max(0.0)
    }

    /// The thesis's linear form of the distance to the peak.
    #[inline(always)]
    pub fn thesis_linear(&self, point: Vec3) -> f32 {
        let c = &mut NoCount;
        let from_peak = c.sub(point, self.peak);
        let distance_sq = c.dot(from_peak, from_peak);
        thesis_linear_diffuse(c.sqrt(distance_sq), self.radius)
    }

    /// The squared form of the distance to the peak.
    #[inline(always)]
    pub fn squared(&self, point: Vec3) -> f32 {
        let c = &mut NoCount;
        let from_peak = c.sub(point, self.peak);
        let distance_sq = c.dot(from_peak, from_peak);
        squared_diffuse(distance_sq, self.radius).max(0.0)
    }
}

/// One way of computing the diffuse term of a surface point.
pub type DiffuseTerm = fn(&LitSphere, Vec3) -> f32;

/// The `shading` group.
pub fn bench_shading(c: &mut Criterion) {
    let sphere = lit_sphere();
    let mut out = vec![0.0f32; sphere.points.len()];
    let mut group = c.benchmark_group("shading");
    group.throughput(Throughput::Elements(sphere.points.len() as u64));
    let forms: [(&str, DiffuseTerm); 3] = [
        ("lambert", LitSphere::lambert),
        ("thesis-linear", LitSphere::thesis_linear),
        ("squared", LitSphere::squared),
    ];
    for (name, form) in forms {
        group.bench_function(name, |b| {
            b.iter(|| {
                let sphere = black_box(&sphere);
                for (o, &p) in out.iter_mut().zip(&sphere.points) {
                    *o = form(sphere, p);
                }
                black_box(&mut out);
            })
        });
    }
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_points_lie_on_the_sphere_and_the_forms_agree_where_they_should() {
        let s = lit_sphere();
        let c = &mut NoCount;
        let mut lit = 0;
        for &p in &s.points {
            let r = c.sub(p, s.center);
            assert!((c.dot(r, r) - s.radius * s.radius).abs() < 1e-4);
            let (lambert, squared) = (s.lambert(p), s.squared(p));
            // The light is far but not at infinity: the squared form is close to Lambert.
            assert!((lambert - squared).abs() < 0.1, "{lambert} vs {squared}");
            assert!((0.0..=1.0).contains(&s.thesis_linear(p)));
            lit += usize::from(lambert > 0.0);
        }
        assert!(lit > POINT_COUNT / 3 && lit < 2 * POINT_COUNT / 3, "{lit}");
        assert!((s.lambert(s.peak) - 1.0).abs() < 1e-3);
    }
}
