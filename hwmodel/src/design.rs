//! A hardware design: the thesis's, or a what-if derived from it.

use serde::{Deserialize, Serialize};

/// The choices that change the pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Design {
    /// Parallel intersection units (each with its own minimum-distance block, joined by
    /// a tree of comparators).
    pub units: u32,
    /// Square root by the bit trick `i = (i + 0x3F800000) >> 1` (thesis 8.3.1): one
    /// integer adder, 1 cycle, instead of the 16-cycle IP core.
    pub fast_sqrt: bool,
    /// Orthographic primary rays (thesis 8.3.2): a moving origin and one direction,
    /// no normalize.
    pub ortho: bool,
    /// Shading without the inverse square root (thesis 8.3.4): a light at infinity;
    /// spheres by the squared distance to their brightest point, cylinders by the
    /// normal scaled by 1/r (|N| = r on both surfaces), precomputed per primitive.
    pub no_rsqrt_shading: bool,
    /// Bits per pixel in the frame buffer (the thesis: 8, gray; 24 did not fit).
    pub frame_bits_per_pixel: u32,
}

impl Default for Design {
    fn default() -> Self {
        Self::thesis()
    }
}

impl Design {
    /// The design the thesis built.
    pub const fn thesis() -> Self {
        Self {
            units: 1,
            fast_sqrt: false,
            ortho: false,
            no_rsqrt_shading: false,
            frame_bits_per_pixel: 8,
        }
    }

    /// True for the thesis's own design.
    pub fn is_thesis(&self) -> bool {
        *self == Self::thesis()
    }

    /// Words per primitive in the scene memory: 8 floats and a type word, plus the
    /// precomputed shading terms of `no_rsqrt_shading` (brightest point M, 1/(2r²), 1/r).
    pub fn words_per_primitive(&self) -> u64 {
        if self.no_rsqrt_shading { 9 + 5 } else { 9 }
    }

    /// A short name for tables: "thesis" or the changes, e.g. "fast-sqrt+K=4".
    pub fn label(&self) -> String {
        let mut parts = Vec::new();
        if self.fast_sqrt {
            parts.push("fast-sqrt".to_string());
        }
        if self.ortho {
            parts.push("ortho".to_string());
        }
        if self.no_rsqrt_shading {
            parts.push("no-rsqrt-shading".to_string());
        }
        if self.units != 1 {
            parts.push(format!("K={}", self.units));
        }
        if self.frame_bits_per_pixel != 8 {
            parts.push(format!("{}-bit frame", self.frame_bits_per_pixel));
        }
        if parts.is_empty() {
            "thesis".to_string()
        } else {
            parts.join("+")
        }
    }
}
