//! The estimated clock of a logic depth on Cyclone IV E: one place for the delays the
//! estimate assumes.
//!
//! Rule: a path of `n` LUT levels between two registers takes
//! `register_ns + n × level_ns`, and Fmax is its inverse: 1 ns + 1.5 ns per level, so
//! 12 levels give 19 ns, 52.6 MHz, and 13 give 20.5 ns, below the thesis's 50 MHz.
//!
//! Where the figures come from: not from the device datasheet, which has none to
//! give. The Cyclone IV Device Datasheet (Cyclone IV Device Handbook vol. 3, chapter 1,
//! CYIV-53001, v2.0 of March 2016), section "Switching Characteristics" (p. 1–16 on),
//! publishes the core's limits per speed grade (clock tree, PLLs, embedded
//! multipliers, M9K memory blocks) and the periphery's, and leaves I/O timing to
//! Quartus; it has no logic-element table: no tLUT, no LE register tCO or tSU, no
//! interconnect delay per hop (they live only in Quartus's timing models). Handbooks
//! up to Cyclone II and Stratix II printed them ("LE_FF Internal Timing
//! Microparameters": Stratix II, vol. 1, table 5–37, tLUT 162 to 507 ps), which shows
//! that the LUT is the small part of a level and the routing to the next LE the rest.
//! So both constants are assumptions: 1.5 ns for one LE's LUT and its routing (issue
//! 38's estimate for the thesis's EP4CE115 class, C7/C8 grades) and 1 ns for clock to
//! output plus set-up. The measured check is a real place and route ([`super::ice40`]:
//! nextpnr-ice40's timing model of an iCE40 HX8K, a slower device), set beside this
//! estimate per operator in `docs/hardware-model.md`.

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
    source: "assumed: 1.5 ns per LUT level and its routing, 1 ns register tCO + tSU (the \
             Cyclone IV Device Datasheet, CYIV-53001, Switching Characteristics, has no LE or \
             interconnect delays; checked against nextpnr-ice40 on an iCE40 HX8K)",
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
