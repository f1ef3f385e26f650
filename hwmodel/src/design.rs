//! A hardware design: the thesis's, or a what-if derived from it.

use serde::{Deserialize, Serialize};

/// How the minimum-distance block compares a primitive's distance with the kept one,
/// which sets how often the pipeline can take a primitive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MinDistance {
    /// The thesis's floating-point compare (ALTFP_COMPARE, 3 cycles): the next
    /// distance may be compared only when the previous one is kept, so each primitive
    /// is held 3 cycles and the intersection unit idles two cycles in three.
    #[default]
    FloatCompare,
    /// Distances compared as integers: non-negative IEEE floats order as their bit
    /// patterns, so a 31-bit magnitude compare decides within the register's cycle and
    /// the block takes one primitive a cycle. (Three pixels interleaved in the thesis's
    /// block reach the same rate with three kept registers; not modelled.)
    IntegerCompare,
}

impl MinDistance {
    /// Cycles each primitive is held: the pipeline's cycles per primitive per unit.
    pub fn cycles_per_primitive(self) -> u32 {
        match self {
            MinDistance::FloatCompare => 3,
            MinDistance::IntegerCompare => 1,
        }
    }
}

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
    /// The minimum-distance compare, and with it the primitive rate.
    #[serde(default)]
    pub min_distance: MinDistance,
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
            min_distance: MinDistance::FloatCompare,
        }
    }

    /// Cycles a primitive is held in each intersection unit (3 as the thesis, 1 with
    /// the integer compare).
    pub fn cycles_per_primitive(&self) -> u32 {
        self.min_distance.cycles_per_primitive()
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
        if self.min_distance == MinDistance::IntegerCompare {
            parts.push("int-compare".to_string());
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
