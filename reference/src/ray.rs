//! Rays and hits in f64.

use glam::DVec3;

/// A ray `X = origin + t dir` with `dir` of unit length (to f64 rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

impl Ray {
    /// The ray from `origin` along `dir` normalized.
    pub fn toward(origin: DVec3, dir: DVec3) -> Self {
        Self {
            origin,
            dir: dir.normalize(),
        }
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// An intersection: the distance and, for cylinders and cones, the axial coordinate
/// of the hit (distance from the base along the axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub m: f64,
}

impl Hit {
    /// A hit with no axial coordinate.
    pub fn at(t: f64) -> Self {
        Self { t, m: 0.0 }
    }
}
