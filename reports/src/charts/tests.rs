//! Tests over every chart of the synthetic sample run: content, declared size, and that
//! what is drawn follows the data.

use super::*;
use crate::results::{SceneResult, VariantResult};
use testkit::sample_results;

/// Every chart the sample gives: [`all`], each scene's histograms, each variant's.
fn every_chart() -> Vec<Chart> {
    let r = sample_results();
    let mut charts = all(&r);
    for scene in &r.scenes {
        charts.extend(scene_histograms(&r, scene));
        charts.extend(bvh_histograms(scene));
        charts.extend(
            scene
                .variants
                .iter()
                .filter_map(|v| variant_histogram(scene, v)),
        );
    }
    charts
}

/// The value of attribute `name` of the SVG's root element.
fn root_attribute(svg: &str, name: &str) -> Option<String> {
    let tag = svg.split('>').next()?;
    let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
    Some(tag[start..].split('"').next()?.to_string())
}

/// The points of the first `<polygon>` of an SVG.
fn polygon_points(svg: &str) -> Vec<(f64, f64)> {
    let Some(at) = svg.find("<polygon") else {
        return Vec::new();
    };
    let points = svg[at..].split("points=\"").nth(1).unwrap_or("");
    let points = points.split('"').next().unwrap_or("");
    points
        .split_whitespace()
        .filter_map(|p| {
            let (x, y) = p.split_once(',')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect()
}

/// The value of attribute `name` of one element's text.
fn attribute(element: &str, name: &str) -> Option<f64> {
    element
        .split(&format!(" {name}=\""))
        .nth(1)?
        .split('"')
        .next()?
        .parse()
        .ok()
}

/// The points of every `<polyline>` of an SVG.
fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split("<polyline")
        .skip(1)
        .map(|p| {
            let points = p.split("points=\"").nth(1).unwrap_or("");
            points
                .split('"')
                .next()
                .unwrap_or("")
                .split_whitespace()
                .filter_map(|xy| {
                    let (x, y) = xy.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect()
        })
        .collect()
}

/// The `(x, y, width, height)` of the filled `<rect>`s of colour `fill` (as `#RRGGBB`).
fn rects(svg: &str, fill: &str) -> Vec<[f64; 4]> {
    svg.split("<rect")
        .skip(1)
        .filter(|r| r.contains(&format!("fill=\"{fill}\"")))
        .filter_map(|r| {
            let value = |k: &str| -> Option<f64> {
                r.split(&format!(" {k}=\""))
                    .nth(1)?
                    .split('"')
                    .next()?
                    .parse()
                    .ok()
            };
            Some([value("x")?, value("y")?, value("width")?, value("height")?])
        })
        .collect()
}

#[test]
fn every_chart_of_the_sample_is_svg_with_its_axis_titles() {
    let charts = all(&sample_results());
    let expected: [(&str, &[&str]); 9] = [
        (
            "calls",
            &[
                "calls per render (log scale)",
                "Sphere::intersect",
                "vec3::dot",
            ],
        ),
        ("self-seconds", &["self time (s)", "Cylinder::intersect"]),
        (
            "quality-speed",
            &[
                "speed-up over baseline",
                "RMS error against baseline",
                "fast-sqrt",
            ],
        ),
        (
            "sw-hw-times",
            &["frame time (s, log scale)", "scene", "balls4"],
        ),
        ("hw-speedup", &["hardware speed-up (×)", "break-even"]),
        (
            "time-vs-primitives",
            &[
                "primitives in the scene",
                "render time (s, log scale)",
                "cylinder",
            ],
        ),
        (
            "device-utilization",
            &[
                "utilization (% of the device)",
                "EP4CE115",
                "5CGXFC9 (unvalidated)",
                "routing headroom (85 %)",
            ],
        ),
        (
            "histogram",
            &["gray level (0-255)", "pixels (log scale)", "baseline"],
        ),
        (
            "roofline",
            &[
                "arithmetic intensity (flop/byte, log scale)",
                "attained GFLOP/s (log scale)",
                "SIMD peak",
                "149 GFLOP/s",
                "scalar peak",
                "29.7 GFLOP/s",
                "L1 190 GB/s",
                "11.8 GB/s",
                "bvh",
            ],
        ),
    ];
    let ids: Vec<&str> = charts.iter().map(|c| c.id).collect();
    assert_eq!(ids, expected.map(|e| e.0), "the charts, in report order");
    for (c, (id, texts)) in charts.iter().zip(expected) {
        assert!(
            c.svg.starts_with("<svg") && c.svg.trim_end().ends_with("</svg>"),
            "{id}"
        );
        assert!(!c.svg.contains("could not be drawn"), "{id}: {}", c.svg);
        assert!(!c.title.is_empty() && !c.caption.is_empty(), "{id}");
        assert!(c.svg.contains(&c.title), "{id}: the title is drawn");
        for text in texts {
            assert!(c.svg.contains(text), "{id} lacks '{text}'");
        }
    }
}

#[test]
fn each_chart_carries_the_size_its_svg_declares() {
    let charts = every_chart();
    assert!(charts.len() > 8, "histograms are included");
    for c in &charts {
        let declared = ["width", "height"].map(|a| root_attribute(&c.svg, a));
        let carried = [c.width, c.height].map(|v| Some(v.to_string()));
        assert_eq!(declared, carried, "{} ({})", c.id, c.title);
        let view_box = format!("0 0 {} {}", c.width, c.height);
        assert_eq!(
            root_attribute(&c.svg, "viewBox"),
            Some(view_box),
            "{}",
            c.id
        );
    }
}

#[test]
fn a_chart_that_fails_to_draw_says_so_at_its_declared_size() {
    let c = frame::render("broken", "t".into(), "c".into(), (300, 200), |_| {
        Err("no <room> & no luck".into())
    });
    assert!(
        c.svg.contains("chart 'broken' could not be drawn"),
        "{}",
        c.svg
    );
    assert!(c.svg.contains("no &lt;room&gt; &amp; no luck"), "{}", c.svg);
    let declared = ["width", "height"].map(|a| root_attribute(&c.svg, a));
    assert_eq!(declared, [c.width, c.height].map(|v| Some(v.to_string())));
}

#[test]
fn a_variant_histogram_rises_with_the_log_of_each_bin() {
    let r = sample_results();
    let scene: &SceneResult = &r.scenes[0];
    let variant = scene
        .variants
        .iter()
        .find(|v| v.histogram.len() == 256)
        .expect("a histogram");
    let c = variant_histogram(scene, variant).expect("chart");
    // The area: the bottom-left corner, two corners per bin, the bottom-right corner.
    let points = polygon_points(&c.svg);
    assert_eq!(points.len(), 2 + 2 * 256, "{}", c.svg.len());
    let bottom = points[0].1;
    let top_count = *variant.histogram.iter().max().expect("bins") as f64;
    // Height over the bottom / full height = ln(count / 0.8) / ln(max / 0.8), to a pixel.
    let full = (top_count / 0.8).ln();
    let plot_height = f64::from(c.height) - 1.0;
    for (bin, count) in variant.histogram.iter().enumerate() {
        let (left, right) = (points[1 + 2 * bin], points[2 + 2 * bin]);
        assert_eq!(left.1, right.1, "bin {bin} is flat");
        assert!(
            right.0 - left.0 <= 1.0 && left.0 <= bin as f64 + 0.5,
            "bin {bin} at {left:?}"
        );
        let expected = if *count == 0 {
            0.0
        } else {
            (*count as f64 / 0.8).ln() / full * plot_height
        };
        let drawn = bottom - left.1;
        assert!(
            (drawn - expected).abs() <= 1.0,
            "bin {bin}: {count} drawn {drawn} px, expected {expected:.1}"
        );
    }
    let empty = VariantResult {
        histogram: vec![0; 256],
        ..variant.clone()
    };
    assert!(variant_histogram(scene, &empty).is_none());
    let short = VariantResult {
        histogram: vec![5; 10],
        ..variant.clone()
    };
    assert!(variant_histogram(scene, &short).is_none());
}

#[test]
fn speed_up_bars_are_as_tall_as_their_speed_up() {
    let r = sample_results();
    let c = hw_speedup_chart(&r).expect("chart");
    // The speed-up bars are PALETTE[2], green.
    let bars = rects(&c.svg, "#009E73");
    let speedups: Vec<f64> = r
        .scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref())
        .filter(|h| h.seconds > 0.0 && h.software_seconds.median > 0.0 && h.speedup.is_finite())
        .map(|h| h.speedup)
        .collect();
    assert_eq!(bars.len(), speedups.len());
    // Pixels per unit of speed-up, from the tallest bar; every bar within a pixel of it.
    let (tallest, largest) = bars
        .iter()
        .zip(&speedups)
        .map(|(b, s)| (b[3], *s))
        .fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
    let scale = tallest / largest;
    for (bar, s) in bars.iter().zip(&speedups) {
        assert!(
            (bar[3] - s * scale).abs() <= 1.0,
            "{s}× drawn {} px",
            bar[3]
        );
    }
    // Left to right in scene order, the same width each (to a pixel of rounding).
    assert!(
        bars.windows(2)
            .all(|w| w[0][0] < w[1][0] && (w[0][2] - w[1][2]).abs() <= 1.0),
        "{bars:?}"
    );
}

#[test]
fn results_without_data_give_no_charts() {
    let nothing = Results {
        scenes: Vec::new(),
        profile: None,
        hardware: None,
        ..sample_results()
    };
    assert_eq!(all(&nothing), Vec::new());
}

#[test]
fn bad_numbers_draw_charts_without_panicking() {
    let mut bad = sample_results();
    for s in &mut bad.scenes {
        for v in &mut s.variants {
            v.speedup = None;
            v.samples = vec![f64::NAN, f64::INFINITY, -1.0];
            v.time.median = f64::NAN;
            v.histogram.clear();
        }
        if let Some(h) = &mut s.hardware {
            h.seconds = 0.0;
            h.speedup = f64::NAN;
        }
    }
    if let Some(p) = &mut bad.profile {
        for row in &mut p.baseline.flat {
            row.self_seconds = f64::NAN;
            row.calls = Some(0);
        }
    }
    if let Some(h) = &mut bad.hardware {
        for d in &mut h.devices {
            d.le_capacity = 0;
            d.mult = u64::MAX;
        }
    }
    for c in all(&bad) {
        assert!(
            c.svg.starts_with("<svg") && !c.svg.contains("could not be drawn"),
            "{}",
            c.id
        );
    }
}

#[test]
fn scene_histograms_leave_out_identical_variants() {
    let r = sample_results();
    let scene = r
        .scenes
        .iter()
        .find(|s| s.name == "balls4")
        .expect("balls4");
    let c = scene_histograms(&r, scene).expect("chart");
    assert!(c.svg.contains("ortho") && !c.svg.contains(">\nsimd\n<"));
    assert!(c.caption.contains("not drawn") && c.caption.contains("simd"));
}

/// The `<circle>`s of an SVG: centre and whether it is filled (a ring has
/// `fill="none"`).
fn circles_filled(svg: &str) -> Vec<(f64, f64, bool)> {
    svg.split("<circle")
        .skip(1)
        .filter_map(|c| {
            let element = c.split('>').next()?;
            Some((
                attribute(element, "cx")?,
                attribute(element, "cy")?,
                !element.contains("fill=\"none\""),
            ))
        })
        .collect()
}

#[test]
fn roofline_points_sit_at_their_intensity_and_speed_under_their_own_roof() {
    use crate::results::CodeKind;
    let r = sample_results();
    let peak = r.peak.clone().expect("the sample measured the peaks");
    let scalar_peak = peak.scalar_peak_gflops.expect("and the scalar peak");
    let (chart, scale) = roofline::roofline_with_scale(&r).expect("chart");
    // Pixels from the scale alone: a log axis puts ln(v) linearly between its edges,
    // and the pixel rows grow downwards.
    let along = |v: f64, (lo, hi): (f64, f64)| (v.ln() - lo.ln()) / (hi.ln() - lo.ln());
    let (left, right) = scale.columns;
    let (top, bottom) = scale.rows;
    let x_of = |intensity: f64| left + along(intensity, scale.intensity) * (right - left);
    let y_of = |gflops: f64| bottom - along(gflops, scale.gflops) * (bottom - top);
    assert!(0.0 < left && right < f64::from(chart.width), "{scale:?}");
    assert!(0.0 < top && bottom < f64::from(chart.height), "{scale:?}");
    let drawn = circles_filled(&chart.svg);
    let mut checked = 0;
    for scene in &r.scenes {
        for v in &scene.variants {
            let e = v
                .efficiency
                .as_ref()
                .expect("every sample render has a point");
            let (x, y) = (x_of(e.arithmetic_intensity), y_of(e.achieved_gflops));
            // SIMD code (simd here) filled, scalar code a ring.
            let simd = v.variant.as_str() == "simd";
            assert!(
                drawn
                    .iter()
                    .any(|c| (c.0 - x).abs() <= 1.5 && (c.1 - y).abs() <= 1.5 && c.2 == simd),
                "{} {}: no {} point at ({x:.1}, {y:.1})",
                scene.name,
                v.variant,
                if simd { "filled" } else { "ring" }
            );
            // The roof of its code over the point is higher on the page (a smaller
            // row): min(its compute peak, L1 bandwidth × intensity).
            let compute = if simd { peak.peak_gflops } else { scalar_peak };
            let roof = y_of(compute.min(peak.cache_bandwidth_gbs * e.arithmetic_intensity));
            assert!(
                roof < y - 1.0,
                "{} {}: roof {roof:.1}, point {y:.1}",
                scene.name,
                v.variant
            );
            assert_eq!(CodeKind::of_variant(&v.variant) == CodeKind::Simd, simd);
            checked += 1;
        }
    }
    assert!(checked > 50, "{checked} points");
    // The SIMD roofline bends where the L1 slope meets the SIMD peak and ends flat at
    // the right edge.
    let ridge = (
        x_of(peak.peak_gflops / peak.cache_bandwidth_gbs),
        y_of(peak.peak_gflops),
    );
    let lines = polylines(&chart.svg);
    let roof = lines
        .iter()
        .find(|line| line.len() == 3)
        .expect("the roof's polyline");
    assert!(
        (roof[1].0 - ridge.0).abs() <= 1.5 && (roof[1].1 - ridge.1).abs() <= 1.5,
        "ridge drawn at {:?}, expected {ridge:?}",
        roof[1]
    );
    assert!((roof[2].1 - roof[1].1).abs() <= 1.0 && roof[0].1 > roof[1].1);
    assert!((roof[2].0 - right).abs() <= 1.5);
    // The scalar roof: flat at the scalar peak from where it meets the L1 slope (or
    // the left edge) to the right edge.
    let scalar_row = y_of(scalar_peak);
    let from = x_of((scalar_peak / peak.cache_bandwidth_gbs).max(scale.intensity.0));
    assert!(
        lines.iter().any(|line| line.len() == 2
            && (line[0].0 - from).abs() <= 1.5
            && (line[1].0 - right).abs() <= 1.5
            && line.iter().all(|p| (p.1 - scalar_row).abs() <= 1.0)),
        "no scalar roof at row {scalar_row:.1} from column {from:.1}: {lines:?}"
    );
    // Each compute roof's label stands right of the plot.
    for label in ["SIMD peak", "scalar peak"] {
        let at = chart
            .svg
            .find(&format!(">\n{label}\n<"))
            .or_else(|| chart.svg.find(&format!(">{label}<")));
        let text = &chart.svg[..at.unwrap_or_else(|| panic!("no label {label}"))];
        let element = &text[text.rfind("<text").expect("a text element")..];
        let x = attribute(element, "x").expect("x");
        assert!(
            x > right,
            "{label} at column {x}, inside the plot (right edge {right})"
        );
    }

    // Without the peaks: the same points, no roof.
    let unmeasured = Results {
        peak: None,
        outside_profiles: Vec::new(),
        ..r.clone()
    };
    let c = roofline_chart(&unmeasured).expect("chart");
    assert!(!c.svg.contains("SIMD peak") && !c.svg.contains("scalar peak"));
    assert!(c.caption.contains("not measured"));
    // Without the scalar peak: no scalar roof, and the caption says so.
    let mut older = r.clone();
    if let Some(p) = older.peak.as_mut() {
        p.scalar_peak_gflops = None;
    }
    let c = roofline_chart(&older).expect("chart");
    assert!(c.svg.contains("SIMD peak") && !c.svg.contains("scalar peak"));
    assert!(c.caption.contains("This file has no scalar peak"));
}
