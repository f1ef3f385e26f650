//! The tracer's 3-vector.
//!
//! `Vec3` wraps glam's SIMD-friendly `Vec3A` but deliberately implements no
//! arithmetic operators: every dot product, subtraction, addition, cross product,
//! scaling and normalization must go through a [`Counter`](crate::Counter), so the
//! operation counts are exact by construction rather than by discipline. Only
//! construction, component access and sign flips (free in hardware, and not
//! counted by the thesis) are offered here.

use glam::Vec3A;

/// A 3-vector of `f32` with no uncounted arithmetic.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct Vec3(pub(crate) Vec3A);

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Self = Self(Vec3A::ZERO);

    /// Builds a vector from its components.
    #[inline(always)]
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self(Vec3A::new(x, y, z))
    }

    /// Builds a vector from an array `[x, y, z]`.
    #[inline(always)]
    pub const fn from_array(a: [f32; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// The components as an array `[x, y, z]`.
    #[inline(always)]
    pub fn to_array(self) -> [f32; 3] {
        self.0.to_array()
    }

    /// The x component.
    #[inline(always)]
    pub fn x(self) -> f32 {
        self.0.x
    }

    /// The y component.
    #[inline(always)]
    pub fn y(self) -> f32 {
        self.0.y
    }

    /// The z component.
    #[inline(always)]
    pub fn z(self) -> f32 {
        self.0.z
    }

    /// Component `axis` (0 = x, 1 = y, 2 = z).
    #[inline(always)]
    pub fn axis(self, axis: usize) -> f32 {
        self.0[axis]
    }

    /// The vector with every sign flipped (uncounted: a sign-bit flip).
    #[inline(always)]
    pub fn flipped(self) -> Self {
        Self(-self.0)
    }

    /// Whether every component is finite (neither NaN nor infinite).
    #[inline]
    pub fn is_finite(self) -> bool {
        self.0.is_finite()
    }

    /// The largest absolute component, used to scale epsilons to a point's magnitude.
    #[inline(always)]
    pub fn max_abs(self) -> f32 {
        self.0.abs().max_element()
    }

    /// The index (0, 1, 2) of the component with the largest absolute value.
    pub fn dominant_axis(self) -> usize {
        let a = self.0.abs();
        if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        }
    }
}

impl From<[f32; 3]> for Vec3 {
    fn from(a: [f32; 3]) -> Self {
        Self::from_array(a)
    }
}
