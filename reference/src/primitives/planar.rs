//! Polygons: the plane of the first three vertices, then the even-odd rule.
//!
//! The plane normal is `n = normalize((V₁ - V₀) × (V₂ - V₀))` and the ray meets the plane
//! at `t = -((O - V₀)·n) / (d·n)`. Whether the hit point lies inside the outline is
//! decided in the plane: the vertices and the point are projected by dropping the
//! coordinate of the normal's largest component (exact: no rounding), taken relative
//! to the point, and a ray from the point along +u toggles `inside` at every edge it
//! crosses (W. R. Franklin's PNPOLY). An edge counts when its end points lie on
//! opposite sides of the line `v = 0` with `v > 0` on one side (half-open), so a vertex
//! on the line counts once or not at all, and concave outlines work too.

use crate::ray::{Hit, Ray};
use glam::DVec3;

/// A planar outline (a polygon, or the flat part of a patch).
#[derive(Clone, Debug, PartialEq)]
pub struct Planar {
    pub vertices: Vec<DVec3>,
    /// The unit front normal `(V₁ - V₀) × (V₂ - V₀)`, normalized.
    pub normal: DVec3,
    /// The two coordinates kept by the projection.
    axes: [usize; 2],
}

impl Planar {
    /// The outline of `vertices` (at least three, the first three not collinear: the
    /// parser checked both). A degenerate outline gets a NaN normal and is never hit.
    pub fn new(vertices: Vec<DVec3>) -> Self {
        let normal = match vertices.as_slice() {
            [v0, v1, v2, ..] => (*v1 - *v0).cross(*v2 - *v0).normalize(),
            _ => DVec3::NAN,
        };
        let a = normal.abs();
        let dropped = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let axes = match dropped {
            0 => [1, 2],
            1 => [0, 2],
            _ => [0, 1],
        };
        Self {
            vertices,
            normal,
            axes,
        }
    }

    /// The distance to the outline in `(t_min, t_max)`.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let v0 = *self.vertices.first()?;
        // Parallel rays give ±inf or NaN, rejected by the interval test.
        let t = -(ray.origin - v0).dot(self.normal) / ray.dir.dot(self.normal);
        if !(t > t_min && t < t_max) {
            return None;
        }
        self.contains(ray.at(t)).then_some(Hit::at(t))
    }

    /// Whether the point `p` of the plane lies inside the outline (even-odd rule).
    pub fn contains(&self, p: DVec3) -> bool {
        let [u, v] = self.axes;
        let project = |q: DVec3| (q[u] - p[u], q[v] - p[v]);
        let Some(&last) = self.vertices.last() else {
            return false;
        };
        let mut inside = false;
        let (mut uj, mut vj) = project(last);
        for &vertex in &self.vertices {
            let (ui, vi) = project(vertex);
            // The edge straddles v = 0, and crosses it at u > 0 (to the point's right).
            if (vi > 0.0) != (vj > 0.0) && 0.0 < (uj - ui) * (0.0 - vi) / (vj - vi) + ui {
                inside = !inside;
            }
            (uj, vj) = (ui, vi);
        }
        inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::toward(DVec3::from_array(o), DVec3::from_array(d))
    }

    #[test]
    fn triangle_hit_distance_normal_and_misses() {
        // Triangle in z = 2, counter-clockwise from +z: normal +z.
        let tri = Planar::new(vec![v(0.0, 0.0, 2.0), v(4.0, 0.0, 2.0), v(0.0, 4.0, 2.0)]);
        assert_eq!(tri.normal, v(0.0, 0.0, 1.0));
        let down = |x, y| ray([x, y, 7.0], [0.0, 0.0, -1.0]);
        assert_eq!(
            tri.intersect(&down(1.0, 1.0), 0.0, f64::INFINITY),
            Some(Hit::at(5.0))
        );
        // Outside the hypotenuse x + y = 4, and beyond t_max.
        assert_eq!(tri.intersect(&down(2.5, 2.5), 0.0, f64::INFINITY), None);
        assert_eq!(tri.intersect(&down(1.0, 1.0), 0.0, 4.0), None);
        // Parallel to the plane.
        let flat = ray([1.0, 1.0, 2.0], [1.0, 0.0, 0.0]);
        assert_eq!(tri.intersect(&flat, 0.0, f64::INFINITY), None);
        // From behind the front face: the same point, t = 3.
        let up = ray([1.0, 1.0, -1.0], [0.0, 0.0, 1.0]);
        assert_eq!(tri.intersect(&up, 0.0, f64::INFINITY), Some(Hit::at(3.0)));
    }

    #[test]
    fn concave_outline_by_the_even_odd_rule() {
        // A U shape in the x-z plane (y = 0, normal along y): the notch 1 < x < 2,
        // z > 1 is outside.
        let u = Planar::new(vec![
            v(0.0, 0.0, 0.0),
            v(0.0, 0.0, 3.0),
            v(1.0, 0.0, 3.0),
            v(1.0, 0.0, 1.0),
            v(2.0, 0.0, 1.0),
            v(2.0, 0.0, 3.0),
            v(3.0, 0.0, 3.0),
            v(3.0, 0.0, 0.0),
        ]);
        assert!(u.normal.y.abs() == 1.0);
        for (x, z, inside) in [
            (0.5, 2.5, true),
            (1.5, 2.5, false),
            (2.5, 2.5, true),
            (1.5, 0.5, true),
            (3.5, 0.5, false),
            // On the line of the vertices at z = 1, inside and in the notch's mouth.
            (0.5, 1.0, true),
            (1.5, 1.0 + 1e-12, false),
        ] {
            assert_eq!(u.contains(v(x, 0.0, z)), inside, "({x}, {z})");
        }
    }
}
