//! The thesis's verbal bands for an RMS difference on the 0-255 scale.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How different two images look, judged from their RMS difference.
///
/// Serialized in snake case: `"visually_identical"`, `"similar"`, `"notable_changes"`,
/// `"different"`; [`Band::name`] gives the human wording.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Band {
    /// RMS in [0, 15).
    VisuallyIdentical,
    /// RMS in [15, 50).
    Similar,
    /// RMS in [50, 85).
    NotableChanges,
    /// RMS >= 85.
    Different,
}

impl Band {
    /// The bands from the most alike to the least.
    pub const ALL: [Band; 4] = [
        Band::VisuallyIdentical,
        Band::Similar,
        Band::NotableChanges,
        Band::Different,
    ];

    /// The RMS where the next band starts (the thesis's table 2); `None` for
    /// `Different`, which has no upper edge.
    pub fn upper_edge(self) -> Option<f64> {
        match self {
            Band::VisuallyIdentical => Some(15.0),
            Band::Similar => Some(50.0),
            Band::NotableChanges => Some(85.0),
            Band::Different => None,
        }
    }

    /// Each band includes its lower edge. A NaN RMS cannot be called alike, so it is
    /// `Different`.
    pub fn of(rms: f64) -> Band {
        Band::ALL
            .into_iter()
            .find(|b| b.upper_edge().is_none_or(|edge| rms < edge))
            .unwrap_or(Band::Different)
    }

    pub fn name(self) -> &'static str {
        match self {
            Band::VisuallyIdentical => "visually identical",
            Band::Similar => "similar",
            Band::NotableChanges => "notable changes",
            Band::Different => "different",
        }
    }
}

impl std::fmt::Display for Band {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_edges_belong_to_the_upper_band() {
        assert_eq!(Band::of(0.0), Band::VisuallyIdentical);
        assert_eq!(Band::of(14.999), Band::VisuallyIdentical);
        assert_eq!(Band::of(15.0), Band::Similar);
        assert_eq!(Band::of(49.999), Band::Similar);
        assert_eq!(Band::of(50.0), Band::NotableChanges);
        assert_eq!(Band::of(84.999), Band::NotableChanges);
        assert_eq!(Band::of(85.0), Band::Different);
        assert_eq!(Band::of(255.0), Band::Different);
        assert_eq!(Band::of(f64::NAN), Band::Different);
    }

    #[test]
    fn names_and_json_forms() {
        assert_eq!(Band::NotableChanges.name(), "notable changes");
        assert_eq!(Band::VisuallyIdentical.to_string(), "visually identical");
        let json = serde_json::to_string(&Band::VisuallyIdentical).expect("serialize");
        assert_eq!(json, "\"visually_identical\"");
        let back: Band = serde_json::from_str("\"notable_changes\"").expect("deserialize");
        assert_eq!(back, Band::NotableChanges);
    }
}
