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

/// The kind of a primitive, used to find it again after the closest-hit search.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PrimKind {
    Sphere,
    Cylinder,
    Cone,
    Polygon,
    Patch,
}

/// A reference to one primitive of a [`Scene`](crate::Scene).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
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
