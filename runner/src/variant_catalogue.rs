//! The variant catalogue of `rtprof variants`: every optimization variant with its
//! one-line description, and the measured accuracy of the approximating ones (the
//! exhaustive sqrt error scan, the diffuse-term error of the sqrt-free shading).

use serde::Serialize;
use tracer::Variant;
use tracer::variants::diffuse::{DiffuseErrors, diffuse_form_errors};
use tracer::variants::fast_sqrt::{
    BitTrickSqrt, NewtonBitTrickSqrt, SqrtError, SquareRoot, StdSqrt, TunedBitTrickSqrt,
    scan_relative_error,
};

/// One variant's entry.
#[derive(Serialize)]
pub struct VariantInfo {
    pub name: &'static str,
    pub description: &'static str,
    /// Whether the picture may differ from baseline's.
    pub changes_picture: bool,
    /// Whether this build can run it (`embree` needs the `embree` feature).
    pub available: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sqrt_max_rel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sqrt_mean_rel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diffuse_errors: Option<DiffuseErrors>,
}

/// The exhaustive scan of the square root a variant uses, if it changes it.
pub fn sqrt_scan(variant: Variant) -> Option<SqrtError> {
    match variant {
        Variant::FastSqrt => Some(scan_relative_error(BitTrickSqrt::sqrt)),
        Variant::FastSqrtTuned => Some(scan_relative_error(TunedBitTrickSqrt::sqrt)),
        Variant::FastSqrtNewton => Some(scan_relative_error(NewtonBitTrickSqrt::sqrt)),
        _ => None,
    }
}

/// Every variant, and the std sqrt's scan for reference.
pub struct Catalogue {
    pub variants: Vec<VariantInfo>,
    pub std_sqrt: SqrtError,
}

/// Describes and measures every variant (the sqrt scans take a moment).
pub fn catalogue() -> Catalogue {
    let variants = Variant::ALL
        .iter()
        .map(|&v| {
            let scan = sqrt_scan(v);
            VariantInfo {
                name: v.name(),
                description: v.description(),
                changes_picture: v.changes_picture(),
                available: v.available(),
                sqrt_max_rel_error: scan.map(|s| s.max_rel_error),
                sqrt_mean_rel_error: scan.map(|s| s.mean_rel_error),
                diffuse_errors: (v == Variant::NoRsqrtShading).then(|| diffuse_form_errors(400)),
            }
        })
        .collect();
    Catalogue {
        variants,
        std_sqrt: scan_relative_error(StdSqrt::sqrt),
    }
}

impl Catalogue {
    /// The listing the command prints.
    pub fn to_text(&self) -> String {
        let infos = &self.variants;
        let mut out = String::new();
        let width = infos.iter().map(|i| i.name.len()).max().unwrap_or(8);
        for info in infos {
            let absent = if info.available {
                ""
            } else {
                " [not in this build]"
            };
            out += &format!("{:<width$}  {}{absent}\n", info.name, info.description);
            if let (Some(max), Some(mean)) = (info.sqrt_max_rel_error, info.sqrt_mean_rel_error) {
                out += &format!(
                    "{:<width$}  relative error over every f32 in [1, 4): max {:.4} %, mean {:.4} %\n",
                    "",
                    max * 100.0,
                    mean * 100.0
                );
            }
            if let Some(e) = &info.diffuse_errors {
                out += &format!(
                    "{:<width$}  vs Lambert: squared form max |error| {:.1e}; the thesis's linear form max {:.3} (at cos θ = {:.2}), mean {:.3}\n",
                    "",
                    e.squared_max_abs,
                    e.thesis_linear_max_abs,
                    e.thesis_linear_worst_cos,
                    e.thesis_linear_mean_abs
                );
            }
        }
        let std = &self.std_sqrt;
        out += &format!(
            "\nstd sqrt for reference: max relative error {:.1e}. The thesis states 3 % for fast-sqrt; the scan above is the measured figure.\n",
            std.max_rel_error
        );
        out
    }
}
