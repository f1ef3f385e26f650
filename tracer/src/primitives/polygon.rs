//! Planar polygon: the plane test, then the crossing test (thesis ch. 1.3).

use super::{GeometryError, PlanarOutline};
use crate::counter::{Counter, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// A flat-shaded planar polygon.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    pub outline: PlanarOutline,
    pub material: u32,
}

impl Polygon {
    /// Builds a polygon from its vertices (counter-clockwise seen from the front).
    pub fn new(vertices: Vec<Vec3>, material: u32) -> Result<Self, GeometryError> {
        Ok(Self {
            outline: PlanarOutline::new(vertices)?,
            material,
        })
    }

    /// Distance to the polygon in `(t_min, t_max)`. Counts the plane test (one `sub`,
    /// two `dot`) and, when the plane is hit, the hit point (one `scale`, one `add`).
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<f32> {
        c.tally(Stat::PolygonTest);
        let t = self.outline.intersect(ray, t_min, t_max, c)?;
        c.tally(Stat::PolygonHit);
        Some(t)
    }

    /// The front-face normal (unit).
    #[inline]
    pub fn normal(&self) -> Vec3 {
        self.outline.normal
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, NoCount};

    #[test]
    fn triangle_hit_and_miss_with_counts() {
        let tri = Polygon::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(0.0, 4.0, 0.0),
            ],
            0,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let down = |x: f32, y: f32| -> Ray {
            Ray {
                origin: Vec3::new(x, y, 3.0),
                dir: Vec3::new(0.0, 0.0, -1.0),
            }
        };
        let mut c = Count::default();
        assert_eq!(
            tri.intersect(&down(1.0, 1.0), 0.0, 100.0, &mut c),
            Some(3.0)
        );
        assert_eq!(
            tri.intersect(&down(3.0, 3.0), 0.0, 100.0, &mut c),
            None,
            "beyond the hypotenuse"
        );
        assert_eq!((c.get(Stat::PolygonTest), c.get(Stat::PolygonHit)), (2, 1));
        assert_eq!((c.get(Stat::PlaneTest), c.get(Stat::PlaneHit)), (2, 2));
        assert_eq!(
            (
                c.get(Stat::Sub),
                c.get(Stat::Dot),
                c.get(Stat::Scale),
                c.get(Stat::Add)
            ),
            (2, 4, 2, 2)
        );
        // From below, the back face is hit too: sidedness is decided by the shader.
        let up: Ray = Ray {
            origin: Vec3::new(1.0, 1.0, -2.0),
            dir: Vec3::new(0.0, 0.0, 1.0),
        };
        assert_eq!(tri.intersect(&up, 0.0, 100.0, &mut NoCount), Some(2.0));
    }
}
