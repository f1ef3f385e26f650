//! Tones: the one place that decides how good or bad a value looks.
//!
//! A renderer maps each [`Tone`] to one colour (the HTML in its style sheet, the PDF in
//! its template); which tone a value gets is decided only here.

use crate::results::{Band, Verdict};
use serde::Serialize;

/// How a cell, tile or note reads: four steps from good to bad, plus neutral and muted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Tone {
    #[default]
    Neutral,
    /// Within the best band, fits, faster.
    Good,
    /// One step off (visually similar, a model error under 15 %, an empty section).
    Fair,
    /// Two steps off (notable changes, a model error under 50 %).
    Warning,
    /// Different, does not fit, slower, failed.
    Bad,
    /// Nothing to judge (a reference row, a value that is not there).
    Muted,
}

impl Tone {
    /// Every tone, for legends and tests.
    pub const ALL: [Tone; 6] = [
        Tone::Neutral,
        Tone::Good,
        Tone::Fair,
        Tone::Warning,
        Tone::Bad,
        Tone::Muted,
    ];

    /// The tone of the thesis's RMS band (table 2): identical good, similar fair,
    /// notable changes a warning, different bad.
    pub fn of_band(band: Band) -> Tone {
        match band {
            Band::VisuallyIdentical => Tone::Good,
            Band::Similar => Tone::Fair,
            Band::NotableChanges => Tone::Warning,
            Band::Different => Tone::Bad,
        }
    }

    /// The tone of a model's signed error against the thesis, in %: under 5 good, under
    /// 15 fair, under 50 a warning, else bad; muted without an error.
    pub fn of_error(error_pct: Option<f64>) -> Tone {
        match error_pct.map(f64::abs) {
            Some(e) if e.is_finite() && e < 5.0 => Tone::Good,
            Some(e) if e.is_finite() && e < 15.0 => Tone::Fair,
            Some(e) if e.is_finite() && e < 50.0 => Tone::Warning,
            Some(e) if e.is_finite() => Tone::Bad,
            _ => Tone::Muted,
        }
    }

    /// The legend of [`Tone::of_error`]: each step's tone and words.
    pub const ERROR_LEGEND: [(Tone, &'static str); 5] = [
        (Tone::Good, "< 5 %"),
        (Tone::Fair, "< 15 %"),
        (Tone::Warning, "< 50 %"),
        (Tone::Bad, "≥ 50 %"),
        (Tone::Muted, "no error (thesis 0)"),
    ];

    /// A verdict of the one rule (`analysis::verdict`): faster good, slower bad, within
    /// noise neutral — never coloured as a change.
    pub fn of_verdict(verdict: Verdict) -> Tone {
        match verdict {
            Verdict::Faster => Tone::Good,
            Verdict::Slower => Tone::Bad,
            Verdict::WithinNoise => Tone::Neutral,
        }
    }

    /// Yes is good, no is bad.
    pub fn of_yes(yes: bool) -> Tone {
        if yes { Tone::Good } else { Tone::Bad }
    }

    /// A count against the reference's: fewer is good, more is bad, the same muted.
    pub fn of_count(new: u64, reference: u64) -> Tone {
        match new.cmp(&reference) {
            std::cmp::Ordering::Less => Tone::Good,
            std::cmp::Ordering::Equal => Tone::Muted,
            std::cmp::Ordering::Greater => Tone::Bad,
        }
    }

    /// The tone's name, as the template and the style sheet know it.
    /// How bad a tone is: 0 for good, neutral and muted, then fair, warning, bad.
    pub fn severity(self) -> u8 {
        match self {
            Tone::Good | Tone::Neutral | Tone::Muted => 0,
            Tone::Fair => 1,
            Tone::Warning => 2,
            Tone::Bad => 3,
        }
    }

    /// The worse of two tones (see [`Tone::severity`]; the first on a tie).
    pub fn worse(self, other: Tone) -> Tone {
        if other.severity() > self.severity() {
            other
        } else {
            self
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Tone::Neutral => "neutral",
            Tone::Good => "good",
            Tone::Fair => "fair",
            Tone::Warning => "warning",
            Tone::Bad => "bad",
            Tone::Muted => "muted",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_band_has_its_own_tone() {
        // RMS 5, 30, 60, 100: one of each band (thresholds 15, 50, 85).
        let tones: Vec<Tone> = [5.0, 30.0, 60.0, 100.0]
            .map(|rms| Tone::of_band(Band::of(rms)))
            .to_vec();
        assert_eq!(tones, [Tone::Good, Tone::Fair, Tone::Warning, Tone::Bad]);
    }

    #[test]
    fn errors_verdicts_and_counts() {
        assert_eq!(Tone::of_error(Some(-4.9)), Tone::Good);
        assert_eq!(Tone::of_error(Some(5.0)), Tone::Fair);
        assert_eq!(Tone::of_error(Some(-14.9)), Tone::Fair);
        assert_eq!(Tone::of_error(Some(49.0)), Tone::Warning);
        assert_eq!(Tone::of_error(Some(154.2)), Tone::Bad);
        assert_eq!(Tone::of_error(Some(f64::NAN)), Tone::Muted);
        assert_eq!(Tone::of_error(None), Tone::Muted);
        assert_eq!(Tone::of_verdict(Verdict::Faster), Tone::Good);
        assert_eq!(Tone::of_verdict(Verdict::Slower), Tone::Bad);
        assert_eq!(Tone::of_verdict(Verdict::WithinNoise), Tone::Neutral);
        assert_eq!(Tone::of_count(3, 4), Tone::Good);
        assert_eq!(Tone::of_count(4, 4), Tone::Muted);
        assert_eq!(Tone::of_count(5, 4), Tone::Bad);
    }
}
