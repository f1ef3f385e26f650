//! The estimated clock of a logic depth on Cyclone IV E: one place for the delays the
//! estimate assumes.
//!
//! Rule: a path of `n` LUT levels between two registers takes
//! `register_ns + n × level_ns`, and Fmax is its inverse.
//!
//! Where the figures come from, and how far to trust them: the Cyclone IV device
//! datasheet (Cyclone IV Device Handbook vol. 3, CYIV-53001) publishes the clock-tree,
//! PLL, multiplier and M9K limits, but no per-LUT or per-hop routing delay (those
//! live only in Quartus's timing models). The per-level figure is therefore the
//! estimate issue 38 works with — about 1.5 ns for one logic element's LUT and the
//! routing to the next, for the C8 speed grade of the thesis's EP4CE115F29C7/C8 class
//! board — and the register term (clock-to-output plus set-up) an assumed 1 ns. With
//! these, 12 levels give 19 ns, 52.6 MHz: the 12-level goal and the thesis's 50 MHz
//! agree. The measured bound is the depth itself ([`super::depth`]); real timing on
//! silicon needs a place and route (see `docs/hardware-model.md`).

use serde::Serialize;

/// The delays the estimate assumes for one device.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DelayRule {
    /// The device family.
    pub family: &'static str,
    /// One LUT level and its routing, in ns.
    pub level_ns: f64,
    /// Clock to output of the launching register plus set-up of the capturing one, ns.
    pub register_ns: f64,
    /// Where the figures come from.
    pub source: &'static str,
}

/// Cyclone IV E (the thesis's EP4CE115).
pub const CYCLONE_IV_E: DelayRule = DelayRule {
    family: "Cyclone IV E",
    level_ns: 1.5,
    register_ns: 1.0,
    source: "assumed (issue 38's estimate: ~1.5 ns per LUT and its routing; the Cyclone IV \
             device datasheet CYIV-53001 gives no per-LUT delays); register tCO + tSU 1 ns assumed",
};

/// The thesis's clock (50 MHz on the DE2-115).
pub const THESIS_CLOCK_MHZ: f64 = 50.0;

impl DelayRule {
    /// The period of a path of `levels` LUT levels, in ns.
    pub fn period_ns(&self, levels: u64) -> f64 {
        self.register_ns + levels as f64 * self.level_ns
    }

    /// The estimated Fmax of a path of `levels` LUT levels, in MHz.
    pub fn fmax_mhz(&self, levels: u64) -> f64 {
        1000.0 / self.period_ns(levels)
    }

    /// The most LUT levels a path may have to run at `mhz`.
    pub fn max_levels_at(&self, mhz: f64) -> u64 {
        let budget = 1000.0 / mhz - self.register_ns;
        if budget <= 0.0 {
            0
        } else {
            (budget / self.level_ns).floor() as u64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twelve_levels_close_the_thesis_clock_and_thirteen_do_not() {
        // 1 + 12 × 1.5 = 19 ns; 1 + 13 × 1.5 = 20.5 ns > 20 ns.
        let rule = CYCLONE_IV_E;
        assert!((rule.period_ns(12) - 19.0).abs() < 1e-9);
        assert!(rule.fmax_mhz(12) >= THESIS_CLOCK_MHZ);
        assert!(rule.fmax_mhz(13) < THESIS_CLOCK_MHZ);
        assert_eq!(rule.max_levels_at(THESIS_CLOCK_MHZ), 12);
        assert_eq!(rule.max_levels_at(2000.0), 0);
    }
}
