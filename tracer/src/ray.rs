//! Rays and hit records.

use crate::vec3::Vec3;

/// A ray `X = origin + t dir`; `dir` has unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
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
