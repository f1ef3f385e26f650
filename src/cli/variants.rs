//! `rtprof variants`: every optimization variant with a one-line description, and the
//! measured accuracy of the approximating ones (sqrt error from the exhaustive scan,
//! diffuse-term error of the sqrt-free shading).

use anyhow::Result;
use serde::Serialize;
use tracer::Variant;
use tracer::variants::diffuse::{DiffuseErrors, diffuse_form_errors};
use tracer::variants::fast_sqrt::{
    BitTrickSqrt, NewtonBitTrickSqrt, SqrtError, SquareRoot, StdSqrt, TunedBitTrickSqrt,
    scan_relative_error,
};

#[derive(clap::Args, Debug)]
pub struct VariantsArgs {
    /// Print the list as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct VariantInfo {
    name: &'static str,
    description: &'static str,
    /// Whether the picture may differ from baseline's.
    changes_picture: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    sqrt_max_rel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sqrt_mean_rel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    diffuse_errors: Option<DiffuseErrors>,
}

/// The exhaustive scan of the square root a variant uses, if it changes it.
fn sqrt_scan(variant: Variant) -> Option<SqrtError> {
    match variant {
        Variant::FastSqrt => Some(scan_relative_error(BitTrickSqrt::sqrt)),
        Variant::FastSqrtTuned => Some(scan_relative_error(TunedBitTrickSqrt::sqrt)),
        Variant::FastSqrtNewton => Some(scan_relative_error(NewtonBitTrickSqrt::sqrt)),
        _ => None,
    }
}

pub fn run(args: &VariantsArgs) -> Result<()> {
    let infos: Vec<VariantInfo> = Variant::ALL
        .iter()
        .map(|&v| {
            let scan = sqrt_scan(v);
            VariantInfo {
                name: v.name(),
                description: v.description(),
                changes_picture: v.changes_picture(),
                sqrt_max_rel_error: scan.map(|s| s.max_rel_error),
                sqrt_mean_rel_error: scan.map(|s| s.mean_rel_error),
                diffuse_errors: (v == Variant::NoRsqrtShading).then(|| diffuse_form_errors(400)),
            }
        })
        .collect();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&infos)?);
        return Ok(());
    }
    let width = infos.iter().map(|i| i.name.len()).max().unwrap_or(8);
    for info in &infos {
        println!("{:<width$}  {}", info.name, info.description);
        if let (Some(max), Some(mean)) = (info.sqrt_max_rel_error, info.sqrt_mean_rel_error) {
            println!(
                "{:<width$}  relative error over every f32 in [1, 4): max {:.4} %, mean {:.4} %",
                "",
                max * 100.0,
                mean * 100.0
            );
        }
        if let Some(e) = &info.diffuse_errors {
            println!(
                "{:<width$}  vs Lambert: squared form max |error| {:.1e}; the thesis's linear form max {:.3} (at cos θ = {:.2}), mean {:.3}",
                "",
                e.squared_max_abs,
                e.thesis_linear_max_abs,
                e.thesis_linear_worst_cos,
                e.thesis_linear_mean_abs
            );
        }
    }
    let std = scan_relative_error(StdSqrt::sqrt);
    println!(
        "\nstd sqrt for reference: max relative error {:.1e}. The thesis states 3 % for fast-sqrt; the scan above is the measured figure.",
        std.max_rel_error
    );
    Ok(())
}
