//! Linear RGB colour. Colour arithmetic is not counted: the thesis's table counts
//! geometric vector operations, and the hardware shades in grayscale.

use std::ops::{Add, AddAssign, Mul};

/// A linear RGB triple, nominally in [0, 1] per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Rgb {
    pub r: f32,
    pub g: f32,
    pub b: f32,
}

impl Rgb {
    /// Black.
    pub const BLACK: Self = Self::gray(0.0);
    /// White.
    pub const WHITE: Self = Self::gray(1.0);

    /// Builds a colour from its channels.
    pub const fn new(r: f32, g: f32, b: f32) -> Self {
        Self { r, g, b }
    }

    /// A gray with all three channels equal to `v`.
    pub const fn gray(v: f32) -> Self {
        Self { r: v, g: v, b: v }
    }

    /// Rec. 601 luma, the gray value of a colour.
    pub fn luminance(self) -> f32 {
        0.299 * self.r + 0.587 * self.g + 0.114 * self.b
    }

    /// Whether every channel is finite.
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }

    /// The channel values as 8-bit, clamped to [0, 1] and rounded.
    pub fn to_rgb8(self) -> [u8; 3] {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        [q(self.r), q(self.g), q(self.b)]
    }
}

impl Add for Rgb {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl Mul for Rgb {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl Mul<f32> for Rgb {
    type Output = Self;
    fn mul(self, s: f32) -> Self {
        Self::new(self.r * s, self.g * s, self.b * s)
    }
}
