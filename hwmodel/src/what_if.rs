//! The design and device a `hw` command models, as the command line chooses them: the
//! thesis's by default, changed by what-ifs. With the `clap` feature these are also the
//! `rtprof hw` flags, declared here once beside the [`Design`] they fill.

use crate::design::{Design, MinDistance};
use crate::library::{DeviceSpec, Library, LibraryError, find_device};

// The design's changes from the thesis's, shared by every `hw` command that takes a
// design (`table`, `time`, `rtl`, `sim`, `synth`). (A plain comment: clap would take a
// doc comment as the about of every command that flattens these flags.)
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct DesignFlags {
    /// What-if: the bit-trick square root (one adder, 1 cycle) instead of the IP core.
    #[cfg_attr(feature = "clap", arg(long))]
    pub fast_sqrt: bool,
    /// What-if: orthographic primary rays (no normalize; one direction for all rays).
    #[cfg_attr(feature = "clap", arg(long))]
    pub ortho: bool,
    /// What-if: shading without the inverse square root (light at infinity).
    #[cfg_attr(feature = "clap", arg(long))]
    pub no_rsqrt_shading: bool,
    /// What-if: K parallel intersection units (each with its minimum-distance block).
    #[cfg_attr(feature = "clap", arg(long, value_name = "K", default_value_t = 1,
        value_parser = clap::value_parser!(u32).range(1..=4096)))]
    pub units: u32,
    /// What-if: the minimum distance compares distances as integers (1 cycle, one
    /// primitive a cycle) instead of the 3-cycle float compare.
    #[cfg_attr(feature = "clap", arg(long))]
    pub int_compare: bool,
}

impl Default for DesignFlags {
    /// No what-if: the thesis's design.
    fn default() -> Self {
        DesignFlags {
            fast_sqrt: false,
            ortho: false,
            no_rsqrt_shading: false,
            units: Design::thesis().units,
            int_compare: false,
        }
    }
}

impl DesignFlags {
    /// The thesis's design with these changes.
    pub fn design(&self) -> Design {
        Design {
            units: self.units,
            fast_sqrt: self.fast_sqrt,
            ortho: self.ortho,
            no_rsqrt_shading: self.no_rsqrt_shading,
            min_distance: if self.int_compare {
                MinDistance::IntegerCompare
            } else {
                MinDistance::FloatCompare
            },
            ..Design::thesis()
        }
    }
}

// Design changes and the device, for `hw table` and `hw time`.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct WhatIf {
    #[cfg_attr(feature = "clap", command(flatten))]
    pub design: DesignFlags,
    /// Device: the thesis's by default; the others are unvalidated.
    #[cfg_attr(feature = "clap", arg(long, value_name = "D",
        default_value_t = crate::library::default_device_name()))]
    pub device: String,
}

impl WhatIf {
    /// The design with its what-ifs.
    pub fn design(&self) -> Design {
        self.design.design()
    }

    /// The device by name, with the library of its family.
    pub fn device(&self) -> Result<(Library, DeviceSpec), LibraryError> {
        find_device(&self.device)
    }
}

/// A clock in MHz as the command line gives it (`--clock 50`): positive, at most 2 GHz.
pub fn parse_clock_mhz(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(mhz) if mhz.is_finite() && mhz > 0.0 && mhz <= 2000.0 => Ok(mhz),
        _ => Err(format!(
            "'{text}' is not a clock: expected MHz between 0 and 2000, e.g. 50"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_flags_is_the_thesis_design() {
        let flags = DesignFlags::default();
        assert!(flags.design().is_thesis());
        let k2 = DesignFlags {
            units: 2,
            fast_sqrt: true,
            ..flags
        };
        let d = k2.design();
        assert_eq!((d.units, d.fast_sqrt, d.ortho), (2, true, false));
        assert_eq!(
            d.frame_bits_per_pixel,
            Design::thesis().frame_bits_per_pixel
        );
        assert_eq!(d.min_distance, MinDistance::FloatCompare);
        let int = DesignFlags {
            int_compare: true,
            ..flags
        };
        assert_eq!(int.design().cycles_per_primitive(), 1);
        assert_eq!(int.design().label(), "int-compare");
    }

    #[test]
    fn clocks_are_positive_and_bounded() {
        assert_eq!(parse_clock_mhz(" 50 "), Ok(50.0));
        for bad in ["0", "-5", "2001", "nan", "inf", "fast"] {
            assert!(parse_clock_mhz(bad).is_err(), "{bad}");
        }
    }
}
