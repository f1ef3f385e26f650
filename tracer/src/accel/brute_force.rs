//! Brute force: every query tests every primitive (the thesis's software reference and
//! the `baseline` variant). Closest-hit queries always test all primitives; occlusion
//! queries stop at the first blocker, in the fixed order spheres, cylinders, cones,
//! polygons, patches (so counts stay deterministic). Every test runs against the
//! query's reach, not the closest hit so far, and the caller keeps the closer: so a
//! test counts a hit wherever the intersection lies inside the ray's range, whatever the
//! order of the primitives in the file. Each kind's loop is that kind's
//! test phase (one phase per kind and query, not per primitive: the loop is the test
//! work, and marking it once keeps the phase recording cheap).

use super::Intersector;
use crate::counter::{Counter, Phase, Stat};
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
        ({
            let _phase = kind_phase::<C, _>(Phase::SphereTest, &s.spheres);
            s.spheres
                .iter()
                .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
        } || {
            let _phase = kind_phase::<C, _>(Phase::CylinderTest, &s.cylinders);
            s.cylinders
                .iter()
                .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
        }) || occluded_by_cones_and_planars(s, ray, t_min, t_max, c)
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
    ({
        let _phase = kind_phase::<C, _>(Phase::ConeTest, &s.cones);
        s.cones
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
    } || {
        let _phase = kind_phase::<C, _>(Phase::PolygonTest, &s.polygons);
        s.polygons
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
    } || {
        let _phase = kind_phase::<C, _>(Phase::PatchTest, &s.patches);
        s.patches
            .iter()
            .any(|p| p.intersect(ray, t_min, t_max, c).is_some())
    })
}

/// Starts the test phase of one kind's loop over `prims`. Without a primitive of the
/// kind the (empty) loop runs outside any test phase, which spares a phased render
/// up to five phases per query; the plain render does not look at `prims`.
#[inline(always)]
fn kind_phase<C: Counter, T>(phase: Phase, prims: &[T]) -> Option<C::PhaseGuard> {
    if C::PHASES && prims.is_empty() {
        None
    } else {
        Some(C::enter_phase(phase))
    }
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
        {
            let _phase = kind_phase::<C, _>(Phase::SphereTest, &s.spheres);
            for (i, sphere) in s.spheres.iter().enumerate() {
                if let Some(t) = sphere.intersect(ray, t_min, f32::INFINITY, c)
                    && t < t_max
                {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: prim(PrimKind::Sphere, i),
                        aux: 0.0,
                    });
                }
            }
        }
        {
            let _phase = kind_phase::<C, _>(Phase::CylinderTest, &s.cylinders);
            for (i, cylinder) in s.cylinders.iter().enumerate() {
                if let Some((t, m)) = cylinder.intersect(ray, t_min, f32::INFINITY, c)
                    && t < t_max
                {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: prim(PrimKind::Cylinder, i),
                        aux: m,
                    });
                }
            }
        }
        {
            let _phase = kind_phase::<C, _>(Phase::ConeTest, &s.cones);
            for (i, cone) in s.cones.iter().enumerate() {
                if let Some((t, m)) = cone.intersect(ray, t_min, f32::INFINITY, c)
                    && t < t_max
                {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: prim(PrimKind::Cone, i),
                        aux: m,
                    });
                }
            }
        }
        {
            let _phase = kind_phase::<C, _>(Phase::PolygonTest, &s.polygons);
            for (i, polygon) in s.polygons.iter().enumerate() {
                if let Some(t) = polygon.intersect(ray, t_min, f32::INFINITY, c)
                    && t < t_max
                {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: prim(PrimKind::Polygon, i),
                        aux: 0.0,
                    });
                }
            }
        }
        {
            let _phase = kind_phase::<C, _>(Phase::PatchTest, &s.patches);
            for (i, patch) in s.patches.iter().enumerate() {
                if let Some(t) = patch.intersect(ray, t_min, f32::INFINITY, c)
                    && t < t_max
                {
                    t_max = t;
                    best = Some(Hit {
                        t,
                        prim: prim(PrimKind::Patch, i),
                        aux: 0.0,
                    });
                }
            }
        }
        best
    }
}
