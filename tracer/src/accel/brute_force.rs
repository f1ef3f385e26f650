//! Brute force: every query tests every primitive (the thesis's software reference and
//! the `baseline` variant). Closest-hit queries always test all primitives; occlusion
//! queries stop at the first blocker, in the fixed order spheres, cylinders, cones,
//! polygons, patches (so counts stay deterministic).

use super::Intersector;
use crate::counter::{Counter, Stat};
use crate::ray::{Hit, PrimKind, PrimRef, Ray};
use crate::scene::Scene;

/// Brute-force intersector over a scene.
#[derive(Clone, Copy, Debug)]
pub struct BruteForce<'s> {
    scene: &'s Scene,
}

impl<'s> BruteForce<'s> {
    /// Wraps a scene; there is nothing to build.
    pub fn new(scene: &'s Scene) -> Self {
        Self { scene }
    }
}

fn prim(kind: PrimKind, index: usize) -> PrimRef {
    PrimRef {
        kind,
        index: index as u32,
    }
}

impl Intersector for BruteForce<'_> {
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        self.closest(ray, t_min, c)
    }

    fn closest_hit_from_eye<C: Counter>(&self, ray: &Ray<true>, c: &mut C) -> Option<Hit> {
        self.closest(ray, 0.0, c)
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        c.tally(Stat::Intersect);
        let s = self.scene;
        s.spheres
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
            || s.cylinders
                .iter()
                .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
            || occluded_by_cones_and_planars(s, ray, t_min, t_max, c)
    }
}

/// Whether a cone, polygon or patch blocks `ray` in `(t_min, t_max)`, tested one by one
/// (shared with the SIMD intersector, whose lanes hold only spheres and cylinders).
pub(super) fn occluded_by_cones_and_planars<C: Counter>(
    s: &Scene,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    c: &mut C,
) -> bool {
    s.cones
        .iter()
        .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
        || s.polygons
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
        || s.patches
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
}

impl BruteForce<'_> {
    /// The closest hit over every primitive, kind by kind.
    #[inline(always)]
    fn closest<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        c: &mut C,
    ) -> Option<Hit> {
        c.tally(Stat::Intersect);
        let s = self.scene;
        let mut best: Option<Hit> = None;
        let mut t_max = f32::INFINITY;
        for (i, sphere) in s.spheres.iter().enumerate() {
            if let Some(t) = sphere.intersect(ray, t_min, t_max, c) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: prim(PrimKind::Sphere, i),
                    aux: 0.0,
                });
            }
        }
        for (i, cylinder) in s.cylinders.iter().enumerate() {
            if let Some((t, m)) = cylinder.intersect(ray, t_min, t_max, c) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: prim(PrimKind::Cylinder, i),
                    aux: m,
                });
            }
        }
        for (i, cone) in s.cones.iter().enumerate() {
            if let Some((t, m)) = cone.intersect(ray, t_min, t_max, c) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: prim(PrimKind::Cone, i),
                    aux: m,
                });
            }
        }
        for (i, polygon) in s.polygons.iter().enumerate() {
            if let Some(t) = polygon.intersect(ray, t_min, t_max, c) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: prim(PrimKind::Polygon, i),
                    aux: 0.0,
                });
            }
        }
        for (i, patch) in s.patches.iter().enumerate() {
            if let Some(t) = patch.intersect(ray, t_min, t_max, c) {
                t_max = t;
                best = Some(Hit {
                    t,
                    prim: prim(PrimKind::Patch, i),
                    aux: 0.0,
                });
            }
        }
        best
    }
}
