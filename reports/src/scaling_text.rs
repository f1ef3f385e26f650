//! The growth study ([`results::scaling::ScalingStudy`]) as tables and their plain
//! forms: aligned text for a terminal, Markdown, and CSV of plain numbers. The chart is
//! [`crate::charts::scaling_chart`].

use crate::document::{Cell, Column, Table, Tone};
use crate::format;
use crate::results::scaling::{ScalingFit, ScalingPoint, ScalingStudy};
use crate::table_format::Exports;
use crate::text;

/// Every point: measured ones with their counts, extrapolated ones marked.
pub fn points_table(study: &ScalingStudy) -> Table {
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::number("primitives"),
        Column::text("accelerator"),
        Column::number("time per ray"),
        Column::number("tests per ray"),
        Column::number("nodes per ray"),
        Column::number("build"),
        Column::number("structure"),
        Column::number("bytes per primitive"),
    ]);
    for p in &study.points {
        let optional = |v: Option<f64>, cell: fn(f64) -> Cell| v.map_or_else(Cell::dash, cell);
        let time = Cell::number(format::seconds(p.seconds_per_ray), p.seconds_per_ray);
        let time = if p.measured {
            time
        } else {
            time.detail("extrapolated").tone(Tone::Muted)
        };
        t.rows.push(vec![
            Cell::text(format!("spd:{}:{}", p.family, p.size_factor)),
            Cell::count(p.primitives),
            Cell::text(&p.accelerator),
            time,
            optional(p.tests_per_ray, |v| Cell::number(format::significant(v), v)),
            // No structure, no nodes: a dash rather than a zero that reads as measured.
            optional(p.nodes_per_ray.filter(|n| *n > 0.0), |v| {
                Cell::number(format::significant(v), v)
            }),
            optional(p.build_seconds, |v| Cell::number(format::seconds(v), v)),
            match p.accelerator_bytes {
                Some(b) => Cell::number(format::bytes(b), b as f64),
                None => Cell::dash(),
            },
            match p.accelerator_bytes {
                Some(b) if b > 0 => {
                    let per = b as f64 / p.primitives.max(1) as f64;
                    Cell::number(format::fixed(per, 1), per)
                }
                _ => Cell::dash(),
            },
        ]);
    }
    t
}

/// The fitted exponents: time per ray ∝ primitives^exponent.
pub fn fits_table(study: &ScalingStudy) -> Table {
    let mut t = Table::new(vec![
        Column::text("family"),
        Column::text("accelerator"),
        Column::number("time exponent").detail("per ray ∝ N^b"),
        Column::number("tests exponent"),
        Column::number("measured points"),
    ]);
    for f in &study.fits {
        t.rows.push(vec![
            Cell::text(&f.family),
            Cell::text(&f.accelerator),
            Cell::number(format::fixed(f.exponent, 2), f.exponent),
            f.tests_exponent
                .map_or_else(Cell::dash, |e| Cell::number(format::fixed(e, 2), e)),
            Cell::count(u64::from(f.points)),
        ]);
    }
    t
}

/// Growth of time per ray of `accelerator` on `family` between the measured points
/// nearest `from` and `to` primitives: (primitives, primitives, factor).
pub fn growth(
    study: &ScalingStudy,
    family: &str,
    accelerator: &str,
    from: u64,
    to: u64,
) -> Option<(u64, u64, f64)> {
    let measured: Vec<&ScalingPoint> = study
        .points
        .iter()
        .filter(|p| p.family == family && p.accelerator == accelerator && p.measured)
        .collect();
    let nearest = |n: u64| {
        measured.iter().min_by(|a, b| {
            let d = |p: &ScalingPoint| ((p.primitives as f64).ln() - (n as f64).ln()).abs();
            d(a).total_cmp(&d(b))
        })
    };
    let (a, b) = (nearest(from)?, nearest(to)?);
    (a.primitives < b.primitives).then(|| {
        (
            a.primitives,
            b.primitives,
            b.seconds_per_ray / a.seconds_per_ray,
        )
    })
}

/// How each measured point was timed: "median of 3" or "median of at least 3 renders,
/// more until 250 ms of tracing".
pub fn timing_text(study: &ScalingStudy) -> String {
    if study.min_seconds > 0.0 {
        format!(
            "median of at least {} render{}, more until {} of tracing",
            study.repeats,
            if study.repeats == 1 { "" } else { "s" },
            format::seconds(study.min_seconds)
        )
    } else {
        format!("median of {}", study.repeats)
    }
}

/// The headline: each family's bvh growth over its measured range.
pub fn headline(study: &ScalingStudy) -> String {
    let mut lines = format!(
        "growth study: {} points ({} measured) at {}, {} thread{}, {}\n",
        study.points.len(),
        study.points.iter().filter(|p| p.measured).count(),
        format::size(study.width, study.height),
        study.threads,
        if study.threads == 1 { "" } else { "s" },
        timing_text(study)
    );
    let families: Vec<&str> =
        study
            .fits
            .iter()
            .map(|f| f.family.as_str())
            .fold(Vec::new(), |mut v, f| {
                if !v.contains(&f) {
                    v.push(f);
                }
                v
            });
    for family in families {
        let fits: Vec<&ScalingFit> = study.fits.iter().filter(|f| f.family == family).collect();
        let exponents: Vec<String> = fits
            .iter()
            .map(|f| format!("{} {}", f.accelerator, format::fixed(f.exponent, 2)))
            .collect();
        let bvh = growth(study, family, "bvh", 1_000, u64::MAX / 2)
            .map(|(a, b, g)| {
                format!(
                    "; bvh time per ray ×{} from {} to {} primitives",
                    format::fixed(g, 2),
                    format::count(a),
                    format::count(b)
                )
            })
            .unwrap_or_default();
        lines += &format!("  {family}: exponents {}{bvh}\n", exponents.join(", "));
    }
    lines
}

pub fn to_text(study: &ScalingStudy) -> String {
    format!(
        "{}\n{}\n{}",
        headline(study),
        text::table(&points_table(study)),
        text::table(&fits_table(study))
    )
}

pub fn to_markdown(study: &ScalingStudy) -> String {
    format!(
        "{}\n{}\n{}",
        headline(study),
        text::markdown(&points_table(study)),
        text::markdown(&fits_table(study))
    )
}

/// Plain numbers, one row per point.
pub fn to_csv(study: &ScalingStudy) -> String {
    let header = [
        "family",
        "size_factor",
        "primitives",
        "accelerator",
        "measured",
        "rays",
        "seconds_per_ray",
        "tests_per_ray",
        "nodes_per_ray",
        "build_seconds",
        "accelerator_bytes",
        "scene_bytes",
    ];
    let rows: Vec<Vec<String>> = study
        .points
        .iter()
        .map(|p| {
            vec![
                p.family.clone(),
                p.size_factor.to_string(),
                p.primitives.to_string(),
                p.accelerator.clone(),
                p.measured.to_string(),
                p.rays.map(|r| r.to_string()).unwrap_or_default(),
                text::csv_number(Some(p.seconds_per_ray)),
                text::csv_number(p.tests_per_ray),
                text::csv_number(p.nodes_per_ray),
                text::csv_number(p.build_seconds),
                p.accelerator_bytes
                    .map(|b| b.to_string())
                    .unwrap_or_default(),
                p.scene_bytes.to_string(),
            ]
        })
        .collect();
    text::csv(&header, &rows)
}

impl Exports for ScalingStudy {
    fn to_text(&self) -> String {
        to_text(self)
    }
    fn to_markdown(&self) -> String {
        to_markdown(self)
    }
    fn to_csv(&self) -> String {
        to_csv(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::scaling::SCALING_SCHEMA;

    fn point(
        primitives: u64,
        accelerator: &str,
        seconds_per_ray: f64,
        measured: bool,
    ) -> ScalingPoint {
        ScalingPoint {
            family: "balls".into(),
            size_factor: 0,
            primitives,
            accelerator: accelerator.into(),
            measured,
            rays: None,
            seconds_per_ray,
            tests_per_ray: None,
            nodes_per_ray: None,
            build_seconds: None,
            accelerator_bytes: Some(0),
            scene_bytes: 0,
        }
    }

    fn study(points: Vec<ScalingPoint>) -> ScalingStudy {
        ScalingStudy {
            schema: SCALING_SCHEMA.into(),
            created: String::new(),
            command: String::new(),
            machine: results::Machine {
                cpu_model: "test".into(),
                cores: 2,
                os: "test".into(),
                hostname: "test".into(),
            },
            build: results::Build {
                rtprof_version: "0".into(),
                rustc: "rustc".into(),
                git_commit: "none".into(),
                profile: "test".into(),
            },
            threads: 2,
            width: 8,
            height: 8,
            repeats: 1,
            min_seconds: 0.0,
            budget_seconds: 1.0,
            fits: vec![ScalingFit {
                family: "balls".into(),
                accelerator: "bvh".into(),
                exponent: 0.2,
                coefficient: 1.0,
                tests_exponent: None,
                points: 3,
            }],
            points,
        }
    }

    #[test]
    fn the_headline_says_how_each_point_was_timed() {
        let mut s = study(Vec::new());
        assert_eq!(timing_text(&s), "median of 1");
        s.repeats = 3;
        s.min_seconds = 0.25;
        assert_eq!(
            timing_text(&s),
            "median of at least 3 renders, more until 250 ms of tracing"
        );
        assert!(headline(&s).contains(", median of at least 3 renders,"));
    }

    #[test]
    fn growth_runs_between_the_measured_points_nearest_the_bounds() {
        let s = study(vec![
            point(10, "bvh", 50e-9, true),
            point(821, "bvh", 100e-9, true),
            point(597_872, "bvh", 280e-9, true),
            // Extrapolated points never bound a growth.
            point(5_000_000, "bvh", 1e-6, false),
        ]);
        let (from, to, factor) = growth(&s, "balls", "bvh", 1_000, u64::MAX / 2).unwrap();
        assert_eq!((from, to), (821, 597_872));
        assert!((factor - 2.8).abs() < 1e-9, "{factor}");
        assert!(headline(&s).contains("bvh time per ray ×2.80 from 821 to 597,872 primitives"));
        assert_eq!(growth(&s, "balls", "simd", 1_000, 1_000_000), None);
    }

    #[test]
    fn extrapolated_points_are_marked_and_csv_keeps_every_point() {
        let s = study(vec![
            point(10, "baseline", 1e-8, true),
            point(1_000, "baseline", 1e-6, false),
        ]);
        let text = to_text(&s);
        assert!(text.contains("extrapolated"), "{text}");
        let csv = to_csv(&s);
        assert_eq!(csv.lines().count(), 3);
        assert!(
            csv.lines().nth(2).unwrap_or_default().contains(",false,"),
            "{csv}"
        );
    }
}
