//! Polygonal patch: a polygon with a normal per vertex, smooth shaded by
//! interpolating the vertex normals with barycentric weights in the fan triangle
//! that contains the hit point.

use super::{GeometryError, PlanarOutline};
use crate::counter::{Counter, NoCount, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// A smooth-shaded planar patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub outline: PlanarOutline,
    /// Unit vertex normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// The vertex normals as written in the scene (any length), kept so that the scene
    /// can be written back exactly ([`crate::nff_writer`]).
    pub written_normals: Vec<Vec3>,
    pub material: u32,
}

impl Patch {
    /// Builds a patch; vertex normals are normalized and must be non-zero (the error
    /// names the first zero one).
    pub fn new(
        vertices: Vec<Vec3>,
        normals: Vec<Vec3>,
        material: u32,
    ) -> Result<Self, GeometryError> {
        if vertices.len() != normals.len() {
            return Err(GeometryError::NormalCountMismatch {
                vertices: vertices.len(),
                normals: normals.len(),
            });
        }
        let outline = PlanarOutline::new(vertices)?;
        let unit_normals = normals
            .iter()
            .enumerate()
            .map(|(i, &n)| unit_normal(n).ok_or(GeometryError::ZeroNormal(i + 1)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            outline,
            normals: unit_normals,
            written_normals: normals,
            material,
        })
    }

    /// Distance to the patch in `(t_min, t_max)`; counted like a polygon test.
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<f32> {
        c.tally(Stat::PatchTest);
        let t = self.outline.intersect(ray, t_min, t_max, c)?;
        c.tally(Stat::PatchHit);
        Some(t)
    }

    /// The interpolated shading normal at surface point `p` (unit). Falls back to the
    /// plane normal where no fan triangle holds `p` or the weighted sum vanishes.
    pub fn shading_normal<C: Counter>(&self, p: Vec3, c: &mut C) -> Vec3 {
        let Some((i, w)) = self.outline.fan_weights(self.outline.project(p)) else {
            return self.outline.normal;
        };
        let n0 = c.scale(self.normals[0], w[0]);
        let n1 = c.scale(self.normals[i], w[1]);
        let n2 = c.scale(self.normals[i + 1], w[2]);
        let sum = c.add(n0, n1);
        let sum = c.add(sum, n2);
        if c.dot(sum, sum) > 1e-12 {
            c.normalize(sum)
        } else {
            self.outline.normal
        }
    }
}

/// `n` scaled to unit length, or `None` for a zero vector. A normal whose squared
/// length underflows or overflows f32 (components below about 1e-19 or above 1e19) is
/// first divided by its largest component, so every non-zero direction is accepted.
fn unit_normal(n: Vec3) -> Option<Vec3> {
    let c = &mut NoCount;
    let len_sq = c.dot(n, n);
    if len_sq >= f32::MIN_POSITIVE && len_sq.is_finite() {
        return Some(c.normalize(n));
    }
    let largest = n.max_abs();
    if !(largest > 0.0) || !largest.is_finite() {
        return None;
    }
    // Exact division: the largest component becomes exactly ±1.
    let scaled = Vec3::from_array(n.to_array().map(|v| v / largest));
    Some(c.normalize(scaled))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_interpolation_matches_hand_computed_weights() {
        let patch = Patch::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            vec![
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            0,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        // Midpoint of edge V0-V1: weights (1/2, 1/2, 0) -> normalize((1, 0, 1)).
        let n = patch
            .shading_normal(Vec3::new(0.5, 0.0, 0.0), &mut NoCount)
            .to_array();
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert!(
            (n[0] - h).abs() < 1e-6 && n[1].abs() < 1e-6 && (n[2] - h).abs() < 1e-6,
            "{n:?}"
        );
        // At a vertex the normal is that vertex's.
        let n2 = patch
            .shading_normal(Vec3::new(0.0, 1.0, 0.0), &mut NoCount)
            .to_array();
        assert!((n2[1] - 1.0).abs() < 1e-6, "{n2:?}");
        // Centroid: (1,1,1)/sqrt3.
        let c = patch
            .shading_normal(Vec3::new(1.0 / 3.0, 1.0 / 3.0, 0.0), &mut NoCount)
            .to_array();
        let s = 1.0 / 3f32.sqrt();
        assert!(c.iter().all(|v| (v - s).abs() < 1e-5), "{c:?}");
    }

    #[test]
    fn zero_normals_and_count_mismatch_are_errors() {
        let v = vec![
            Vec3::ZERO,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let n = vec![
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 1.0),
        ];
        assert_eq!(
            Patch::new(v.clone(), n, 0),
            Err(GeometryError::ZeroNormal(2))
        );
        assert!(matches!(
            Patch::new(v, vec![Vec3::new(0.0, 0.0, 1.0)], 0),
            Err(GeometryError::NormalCountMismatch { .. })
        ));
    }
}
