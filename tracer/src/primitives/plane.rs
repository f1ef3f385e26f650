//! The planar part shared by polygons and patches: the plane test, then the crossing
//! (Jordan curve) test after projecting onto the two axes left when the normal's
//! largest component is dropped (thesis ch. 1.3; Haines's crossings test).

use super::GeometryError;
use super::edge_slabs::EdgeSlabs;
use crate::counter::{Counter, NoCount, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// A planar outline: vertices, their plane, and their 2D projection.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarOutline {
    /// The vertices as given, counter-clockwise seen from the front.
    pub vertices: Vec<Vec3>,
    /// Unit normal from the first three vertices, `(V1 - V0) × (V2 - V0)`.
    pub normal: Vec3,
    /// The two coordinate axes kept by the projection.
    axes: [usize; 2],
    /// The vertices projected onto `axes`.
    projected: Vec<[f32; 2]>,
    /// The edges by slab of the second axis, for outlines of many vertices.
    slabs: Option<EdgeSlabs>,
    /// `eye - vertices[0]`, set by [`crate::variants::eye_space`] for the `bounded` variant.
    pub eye_offset: Vec3,
}

impl PlanarOutline {
    /// Bytes of the vertex lists on the heap.
    pub fn heap_bytes(&self) -> usize {
        self.vertices.capacity() * std::mem::size_of::<Vec3>()
            + self.projected.capacity() * std::mem::size_of::<[f32; 2]>()
            + self.slabs.as_ref().map_or(0, EdgeSlabs::heap_bytes)
    }

    /// Builds the outline; fails with fewer than three vertices or when the first three
    /// define no plane.
    pub fn new(vertices: Vec<Vec3>) -> Result<Self, GeometryError> {
        if vertices.len() < 3 {
            return Err(GeometryError::TooFewVertices(vertices.len()));
        }
        let c = &mut NoCount;
        let e1 = c.sub(vertices[1], vertices[0]);
        let e2 = c.sub(vertices[2], vertices[0]);
        let n = c.cross(e1, e2);
        let n_sq = c.dot(n, n);
        // sin² of the angle between the first two edges must exceed 1e-12: below that
        // the vertices are collinear (or coincident) within f32 precision.
        let scale = c.dot(e1, e1) * c.dot(e2, e2);
        if !(n_sq > 1e-12 * scale) || !n_sq.is_finite() {
            return Err(GeometryError::DegeneratePolygon);
        }
        let normal = c.normalize(n);
        let axes = match normal.dominant_axis() {
            0 => [1, 2],
            1 => [2, 0],
            _ => [0, 1],
        };
        let projected: Vec<[f32; 2]> = vertices
            .iter()
            .map(|v| [v.axis(axes[0]), v.axis(axes[1])])
            .collect();
        Ok(Self {
            vertices,
            normal,
            axes,
            slabs: EdgeSlabs::new(&projected),
            projected,
            eye_offset: Vec3::ZERO,
        })
    }

    /// The plane test `d = -(Voc·N) / (R·N)`, `Voc = O - V0`: the distance to the plane
    /// when inside `(t_min, t_max)`. Counts one `sub` and two `dot`.
    #[inline(always)]
    pub fn intersect_plane<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<f32> {
        c.tally(Stat::PlaneTest);
        let voc = ray.offset_from(self.vertices[0], self.eye_offset, c);
        let along = c.dot(ray.dir, self.normal);
        let offset = c.dot(voc, self.normal);
        // A ray parallel to the plane (along = 0) gives ±inf or NaN, rejected here.
        let t = -offset / along;
        if !(t > t_min && t < t_max) {
            return None;
        }
        c.tally(Stat::PlaneHit);
        Some(t)
    }

    /// The plane test, then (when the plane is hit) the hit point (one `scale`, one
    /// `add`) and the crossing test: the distance when the ray meets the outline.
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<f32> {
        let t = self.intersect_plane(ray, t_min, t_max, c)?;
        let p = self.hit_point(ray, t, c);
        self.contains(self.project(p)).then_some(t)
    }

    /// The point at distance `t` along `ray` (one `scale`, one `add`).
    #[inline(always)]
    pub fn hit_point<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t: f32,
        c: &mut C,
    ) -> Vec3 {
        let along = c.scale(ray.dir, t);
        c.add(ray.origin, along)
    }

    /// `p` projected onto the outline's two axes.
    #[inline(always)]
    pub fn project(&self, p: Vec3) -> [f32; 2] {
        [p.axis(self.axes[0]), p.axis(self.axes[1])]
    }

    /// Crossing test: whether the projected point lies inside the projected outline.
    ///
    /// A ray from the point along +u toggles `inside` at each edge it crosses. Vertices
    /// with v ≥ 0 count as above the ray (a half-open rule), so a ray through a vertex
    /// counts exactly one crossing or none, never two. Outlines of many vertices walk
    /// only the edges near the point (`EdgeSlabs`), with the same result.
    #[inline]
    pub fn contains(&self, q: [f32; 2]) -> bool {
        match &self.slabs {
            Some(slabs) => {
                let n = self.projected.len();
                let mut inside = false;
                for &i in slabs.edges_near(q[1]) {
                    let i = i as usize;
                    let (a, b) = (self.projected[(i + n - 1) % n], self.projected[i]);
                    inside ^= crosses((a[0] - q[0], a[1] - q[1]), (b[0] - q[0], b[1] - q[1]));
                }
                inside
            }
            None => self.contains_by_every_edge(q),
        }
    }

    /// The crossing test walking every edge.
    pub fn contains_by_every_edge(&self, q: [f32; 2]) -> bool {
        let Some(&last) = self.projected.last() else {
            return false;
        };
        let mut inside = false;
        let mut a = (last[0] - q[0], last[1] - q[1]);
        for p in &self.projected {
            let b = (p[0] - q[0], p[1] - q[1]);
            inside ^= crosses(a, b);
            a = b;
        }
        inside
    }

    /// Barycentric weights of `q` in the fan triangle `(0, i, i + 1)` that contains it:
    /// `(i, [w0, wi, wi+1])`, or `None` when no fan triangle does (a concave outline).
    pub fn fan_weights(&self, q: [f32; 2]) -> Option<(usize, [f32; 3])> {
        const SLACK: f32 = -1e-4;
        let cross = |a: [f32; 2], b: [f32; 2]| a[0] * b[1] - a[1] * b[0];
        let rel = |a: [f32; 2], o: [f32; 2]| [a[0] - o[0], a[1] - o[1]];
        let p0 = self.projected[0];
        for i in 1..self.projected.len() - 1 {
            let (e1, e2) = (rel(self.projected[i], p0), rel(self.projected[i + 1], p0));
            let area = cross(e1, e2);
            if area == 0.0 {
                continue;
            }
            let d = rel(q, p0);
            let w1 = cross(d, e2) / area;
            let w2 = cross(e1, d) / area;
            let w0 = 1.0 - w1 - w2;
            if w0 >= SLACK && w1 >= SLACK && w2 >= SLACK {
                return Some((i, [w0, w1, w2]));
            }
        }
        None
    }
}

/// Whether the edge from `a` to `b` (relative to the query point, as `(u, v)`) crosses
/// the ray from the point along +u. End points with v ≥ 0 count as above the ray (a
/// half-open rule), so a ray through a vertex counts exactly one crossing or none.
#[inline(always)]
fn crosses((u0, v0): (f32, f32), (u1, v1): (f32, f32)) -> bool {
    if (v0 >= 0.0) == (v1 >= 0.0) {
        return false;
    }
    let right0 = u0 >= 0.0;
    if right0 == (u1 >= 0.0) {
        right0
    } else {
        u1 - v1 * (u0 - u1) / (v0 - v1) >= 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outline(points: &[[f32; 3]]) -> PlanarOutline {
        PlanarOutline::new(points.iter().map(|&p| Vec3::from_array(p)).collect())
            .unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn plane_distance_and_parallel_rays() {
        let square = outline(&[
            [0.0, 0.0, 2.0],
            [1.0, 0.0, 2.0],
            [1.0, 1.0, 2.0],
            [0.0, 1.0, 2.0],
        ]);
        assert_eq!(square.normal.to_array(), [0.0, 0.0, 1.0]);
        let down: Ray = Ray {
            origin: Vec3::new(0.5, 0.5, 7.0),
            dir: Vec3::new(0.0, 0.0, -1.0),
        };
        assert_eq!(
            square.intersect_plane(&down, 0.0, 100.0, &mut NoCount),
            Some(5.0)
        );
        let parallel: Ray = Ray {
            origin: Vec3::new(0.5, 0.5, 7.0),
            dir: Vec3::new(1.0, 0.0, 0.0),
        };
        assert_eq!(
            square.intersect_plane(&parallel, 0.0, 100.0, &mut NoCount),
            None
        );
        let in_plane: Ray = Ray {
            origin: Vec3::new(0.5, 0.5, 2.0),
            dir: Vec3::new(1.0, 0.0, 0.0),
        };
        assert_eq!(
            square.intersect_plane(&in_plane, 0.0, 100.0, &mut NoCount),
            None,
            "0/0 is no hit"
        );
    }

    #[test]
    fn crossing_test_on_a_concave_polygon() {
        // A "U": the notch between x = 1 and x = 2 above y = 1 is outside.
        let u = outline(&[
            [0.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 3.0, 0.0],
            [2.0, 3.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
        ]);
        assert!(u.contains([0.5, 2.0]), "left arm");
        assert!(u.contains([2.5, 2.0]), "right arm");
        assert!(u.contains([1.5, 0.5]), "bottom bar");
        assert!(!u.contains([1.5, 2.0]), "notch");
        assert!(!u.contains([4.0, 0.5]), "beside");
        assert!(!u.contains([1.5, -0.5]), "below");
    }

    #[test]
    fn crossing_test_through_a_vertex_counts_once() {
        // A diamond with vertices on the axes; the +u ray from (-0.5, 0) passes exactly
        // through the right vertex (1, 0) after crossing the left edge: one crossing.
        let diamond = outline(&[
            [0.0, -1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
        ]);
        assert!(diamond.contains([-0.5, 0.0]));
        assert!(diamond.contains([0.5, 0.0]));
        // From outside on the left, the ray passes through both side vertices: zero or
        // two crossings, so outside.
        assert!(!diamond.contains([-1.5, 0.0]));
        assert!(!diamond.contains([1.5, 0.0]));
        // A ray grazing the top vertex (v = 1) from the left touches it without entering.
        assert!(!diamond.contains([-0.5, 1.0]));
    }

    #[test]
    fn degenerate_outlines_are_rejected() {
        let collinear = [
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [2.0, 2.0, 2.0],
            [0.0, 1.0, 0.0],
        ];
        let pts: Vec<Vec3> = collinear.iter().map(|&p| Vec3::from_array(p)).collect();
        assert_eq!(
            PlanarOutline::new(pts.clone()),
            Err(GeometryError::DegeneratePolygon)
        );
        assert_eq!(
            PlanarOutline::new(pts[..2].to_vec()),
            Err(GeometryError::TooFewVertices(2))
        );
        let repeated = vec![Vec3::ZERO, Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0)];
        assert_eq!(
            PlanarOutline::new(repeated),
            Err(GeometryError::DegeneratePolygon)
        );
    }

    #[test]
    fn fan_weights_reproduce_the_point() {
        let quad = outline(&[
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ]);
        let (i, w) = quad.fan_weights([0.5, 1.5]).unwrap_or((0, [f32::NAN; 3]));
        assert_eq!(i, 2, "upper-left triangle (0, 2, 3)");
        // 0.5,1.5 = w0 (0,0) + w2 (2,2) + w3 (0,2): w2 = 0.25, w3 = 0.5, w0 = 0.25.
        assert!(
            (w[0] - 0.25).abs() < 1e-6 && (w[1] - 0.25).abs() < 1e-6 && (w[2] - 0.5).abs() < 1e-6,
            "{w:?}"
        );
    }
}
