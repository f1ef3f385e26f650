//! Polygonal patch: a polygon whose shading normal interpolates its vertex normals.
//!
//! The hit point is located in the fan triangles `(V₀, Vᵢ, Vᵢ₊₁)`; in the first one
//! that holds it, its barycentric weights come from signed areas measured along the
//! plane normal, `w₁ = ((P - V₀) × e₂)·n / (e₁ × e₂)·n` and
//! `w₂ = (e₁ × (P - V₀))·n / (e₁ × e₂)·n`, `w₀ = 1 - w₁ - w₂` (with `e₁ = Vᵢ - V₀`,
//! `e₂ = Vᵢ₊₁ - V₀`), and the normal is `normalize(w₀ N₀ + w₁ Nᵢ + w₂ Nᵢ₊₁)`. As in the
//! tracer, a triangle holds the point when every weight is at least -1e-4 (a point on
//! a shared edge belongs to the first triangle), and the plane normal stands in where
//! no triangle holds the point or the weighted sum vanishes.

use super::planar::Planar;
use glam::DVec3;

/// How far outside a fan triangle (in barycentric weight) a point may lie and still be
/// shaded from it: the tracer's rule.
const SLACK: f64 = -1e-4;

/// A smooth-shaded planar patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub outline: Planar,
    /// Unit vertex normals, one per vertex.
    pub normals: Vec<DVec3>,
}

impl Patch {
    /// A patch from its outline and its vertex normals as written (any length; each is
    /// normalized here, in f64).
    pub fn new(outline: Planar, written_normals: &[DVec3]) -> Self {
        Self {
            outline,
            normals: written_normals.iter().map(|n| n.normalize()).collect(),
        }
    }

    /// The interpolated unit shading normal at the point `p` of the plane.
    pub fn shading_normal(&self, p: DVec3) -> DVec3 {
        let plane = self.outline.normal;
        let vertices = &self.outline.vertices;
        let Some(&v0) = vertices.first() else {
            return plane;
        };
        let w = p - v0;
        for i in 1..vertices.len().saturating_sub(1) {
            let (e1, e2) = (vertices[i] - v0, vertices[i + 1] - v0);
            let area = e1.cross(e2).dot(plane);
            if area == 0.0 {
                continue;
            }
            let w1 = w.cross(e2).dot(plane) / area;
            let w2 = e1.cross(w).dot(plane) / area;
            let w0 = 1.0 - w1 - w2;
            if w0 >= SLACK && w1 >= SLACK && w2 >= SLACK {
                let (Some(n0), Some(n1), Some(n2)) = (
                    self.normals.first(),
                    self.normals.get(i),
                    self.normals.get(i + 1),
                ) else {
                    return plane;
                };
                let sum = w0 * *n0 + w1 * *n1 + w2 * *n2;
                return if sum.length_squared() > 1e-12 {
                    sum.normalize()
                } else {
                    plane
                };
            }
        }
        plane
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn normal_interpolation_matches_hand_computed_weights() {
        // Unit right triangle in z = 0 with normals +z, +x, +y at its corners: at
        // (0.25, 0.5) the weights are w₁ = 0.25 (x), w₂ = 0.5 (y), w₀ = 0.25, so the
        // normal is (0.25, 0.5, 0.25) normalized.
        let patch = Patch::new(
            Planar::new(vec![v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)]),
            &[v(0.0, 0.0, 2.0), v(3.0, 0.0, 0.0), v(0.0, 0.5, 0.0)],
        );
        let n = patch.shading_normal(v(0.25, 0.5, 0.0));
        let want = v(0.25, 0.5, 0.25) / (0.25f64 * 0.25 + 0.25 + 0.25 * 0.25).sqrt();
        assert!((n - want).length() < 1e-15, "{n} vs {want}");
        // At a vertex the normal is that vertex's.
        assert!((patch.shading_normal(v(1.0, 0.0, 0.0)) - v(1.0, 0.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn quad_uses_its_second_fan_triangle_and_falls_back_to_the_plane() {
        // Square (0,0)-(2,0)-(2,2)-(0,2) in z = 0: (1.5, 1.8) lies in the second fan
        // triangle (V₀, V₂, V₃), weights w₀ = 0.1, w₂ = 0.75, w₃ = 0.15.
        let square = vec![
            v(0.0, 0.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(2.0, 2.0, 0.0),
            v(0.0, 2.0, 0.0),
        ];
        let normals = [
            v(0.0, 0.0, 1.0),
            v(0.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
        ];
        let patch = Patch::new(Planar::new(square.clone()), &normals);
        let n = patch.shading_normal(v(1.5, 1.8, 0.0));
        let want = v(0.75, 0.15, 0.1).normalize();
        assert!((n - want).length() < 1e-14, "{n} vs {want}");
        // Outside every fan triangle: the plane normal.
        assert_eq!(patch.shading_normal(v(3.0, 3.0, 0.0)), v(0.0, 0.0, 1.0));
        // Opposite normals that cancel at the midpoint: the plane normal.
        let flat = [
            v(1.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(-1.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
        ];
        let patch = Patch::new(Planar::new(square), &flat);
        let mid = patch.shading_normal(v(1.0, 1.0, 0.0));
        assert_eq!(mid, v(0.0, 0.0, 1.0));
    }
}
