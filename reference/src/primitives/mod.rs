//! Ray-primitive intersection in f64, one primitive per file, each written from its
//! formula in a form that does not cancel for small or far objects.
//!
//! A test returns the distance (and, for cylinders and cones, the axial coordinate);
//! the normal is computed afterwards for the closest hit alone, from the ray and the
//! distance (relative to the primitive, not as the hit point less a centre).

mod cone;
mod cylinder;
mod patch;
mod planar;
mod sphere;

pub use cone::Cone;
pub use cylinder::Cylinder;
pub use patch::Patch;
pub use planar::Planar;
pub use sphere::Sphere;

use crate::ray::{Hit, Ray};
use glam::DVec3;

/// The axis of a cylinder or cone: base, unit direction toward the apex, length.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    pub base: DVec3,
    pub dir: DVec3,
    pub length: f64,
}

impl Axis {
    /// The axis from `base` to `apex` (the parser refused coincident ends).
    pub fn new(base: DVec3, apex: DVec3) -> Self {
        let span = apex - base;
        let length = span.length();
        Self {
            base,
            dir: span / length,
            length,
        }
    }

    /// A vector split into its part across the axis and its coordinate along it.
    pub fn split(&self, v: DVec3) -> (DVec3, f64) {
        let along = v.dot(self.dir);
        (v - along * self.dir, along)
    }
}

/// Any primitive of an NFF scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Cylinder(Cylinder),
    Cone(Cone),
    Polygon(Planar),
    Patch(Patch),
}

impl Shape {
    /// The first visible intersection in `(t_min, t_max)`.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_min, t_max),
            Shape::Cylinder(c) => c.intersect(ray, t_min, t_max),
            Shape::Cone(c) => c.intersect(ray, t_min, t_max),
            Shape::Polygon(p) => p.intersect(ray, t_min, t_max),
            Shape::Patch(p) => p.outline.intersect(ray, t_min, t_max),
        }
    }

    /// The primitive's own normals at `hit`: (shading normal, geometric normal). The
    /// geometric one is the visible side's (outward, inward for inside-only quadrics; a
    /// polygon's front normal); the shading one differs only for patches (interpolated).
    /// Neither is turned toward the ray here.
    pub fn normals(&self, ray: &Ray, hit: &Hit) -> (DVec3, DVec3) {
        match self {
            Shape::Sphere(s) => {
                let n = s.normal(ray, hit.t);
                (n, n)
            }
            Shape::Cylinder(c) => {
                let n = c.normal(ray, hit);
                (n, n)
            }
            Shape::Cone(c) => {
                let n = c.normal(ray, hit);
                (n, n)
            }
            Shape::Polygon(p) => (p.normal, p.normal),
            Shape::Patch(p) => (p.shading_normal(ray.at(hit.t)), p.outline.normal),
        }
    }
}
