//! Rays and hit records.

use crate::counter::Counter;
use crate::vec3::Vec3;

/// A ray `X = origin + t dir`; `dir` has unit length.
///
/// `FROM_EYE` marks the eye rays of the `bounded` variant: they start at the observer,
/// whose offset from every primitive (`eye - C`, the `Voc` of the tests) was computed
/// once when the scene was prepared, so their tests need no subtraction (thesis 8.3.2,
/// "observer at the origin"). Every other ray is a plain `Ray`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<const FROM_EYE: bool = false> {
    pub origin: Vec3,
    pub dir: Vec3,
}

impl<const FROM_EYE: bool> Ray<FROM_EYE> {
    /// `origin - point` (the `Voc` of every test): one counted `sub`, or, for eye rays
    /// of a prepared scene, the primitive's precomputed `eye_offset`.
    #[inline(always)]
    pub fn offset_from<C: Counter>(&self, point: Vec3, eye_offset: Vec3, c: &mut C) -> Vec3 {
        if FROM_EYE {
            eye_offset
        } else {
            c.sub(self.origin, point)
        }
    }

    /// The same ray without the origin marker.
    #[inline(always)]
    pub fn plain(&self) -> Ray {
        Ray {
            origin: self.origin,
            dir: self.dir,
        }
    }
}

/// The kind of a primitive, used to find it again after the closest-hit search. The
/// declaration order is brute force's test order, which breaks ties (see [`HitBound`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PrimKind {
    Sphere,
    Cylinder,
    Cone,
    Polygon,
    Patch,
}

/// A reference to one primitive of a [`Scene`](crate::Scene), ordered as brute force
/// tests them: by kind, then index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PrimRef {
    pub kind: PrimKind,
    pub index: u32,
}

/// The closest intersection found for a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Which primitive was hit.
    pub prim: PrimRef,
    /// Test-specific value kept for the hit body: the axial coordinate `m` for
    /// cylinders and cones, unused (0) otherwise.
    pub aux: f32,
}

/// What a new hit must beat to become a query's closest: come nearer than `t`, or at
/// exactly `t` belong to a primitive before `prim` in scene order. Brute force keeps the
/// first of equal hits, so with this order every accelerator, whatever order its
/// traversal meets primitives in, returns the same hit where two surfaces meet (a gear's
/// face and a tooth's side along their shared edge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitBound {
    /// The distance to beat.
    pub t: f32,
    /// The primitive found at `t`, if any: `None` for a query's reach, which no hit at
    /// exactly that distance beats.
    pub prim: Option<PrimRef>,
}

impl HitBound {
    /// A query's reach: hits must come nearer than `t`.
    #[inline(always)]
    pub fn reach(t: f32) -> Self {
        Self { t, prim: None }
    }

    /// The bound a hit sets.
    #[inline(always)]
    pub fn of(hit: &Hit) -> Self {
        Self {
            t: hit.t,
            prim: Some(hit.prim),
        }
    }

    /// Whether a hit of `prim` at `t` beats this bound.
    #[inline(always)]
    pub fn admits(&self, t: f32, prim: PrimRef) -> bool {
        t < self.t || (t == self.t && self.prim.is_some_and(|p| prim < p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tie_goes_to_the_primitive_brute_force_tests_first() {
        let at = |kind, index| PrimRef { kind, index };
        let polygon_3 = at(PrimKind::Polygon, 3);
        let found = HitBound::of(&Hit {
            t: 2.0,
            prim: polygon_3,
            aux: 0.0,
        });
        assert!(found.admits(1.5, at(PrimKind::Patch, 9)), "nearer wins");
        assert!(!found.admits(2.5, at(PrimKind::Sphere, 0)), "farther loses");
        // Brute force tests spheres, cylinders, cones, polygons, patches, each by index.
        assert!(found.admits(2.0, at(PrimKind::Polygon, 2)));
        assert!(found.admits(2.0, at(PrimKind::Cone, 7)));
        assert!(
            !found.admits(2.0, polygon_3),
            "the same primitive is no better"
        );
        assert!(!found.admits(2.0, at(PrimKind::Polygon, 4)));
        assert!(!found.admits(2.0, at(PrimKind::Patch, 0)));
        // A query's reach is open: nothing at exactly that distance is inside it.
        assert!(!HitBound::reach(2.0).admits(2.0, at(PrimKind::Sphere, 0)));
        assert!(HitBound::reach(f32::INFINITY).admits(1e30, polygon_3));
    }
}
