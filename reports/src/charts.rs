//! The report's charts, as standalone SVG strings drawn with `plotters` (SVG backend).
//!
//! The SVG backend writes text as SVG `<text>` elements, so no font files are needed:
//! the viewer (browser, typst) picks the font. Every chart has a title inside the SVG,
//! axis titles with units, and category labels drawn by this module (rotated when they
//! would not fit side by side), so long names never overlap. Function names are
//! shortened to their last two `::` segments.
//!
//! | id | data | thesis |
//! |---|---|---|
//! | `calls` | `profile.baseline.flat[].calls` | fig. 51 |
//! | `self-seconds` | `profile.baseline.flat[].self_seconds` | fig. 52 |
//! | `quality-speed` | every scene × variant: `speedup`, `quality.rms` | — |
//! | `sw-hw-times` | `scenes[].hardware`: `software_seconds`, `seconds` | fig. 49 |
//! | `hw-speedup` | `scenes[].hardware.speedup` | fig. 50 |
//! | `time-vs-primitives` | baseline `samples` of the `balls`/`cylinder`/`both` scenes, hardware `seconds` | fig. 47, 48 |
//! | `device-utilization` | `hardware.devices` | — |
//! | `histogram` | `histogram` of baseline and the variant with the largest RMS | fig. 35-37 |
//!
//! A chart whose data is missing is left out of [`all`]; a chart that fails to draw is
//! replaced by a small SVG that says so.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::results::{Band, Results, SceneFamily, SceneResult, VariantName, VariantResult};

/// One chart: a stable id (for anchors and file names), a title, a caption saying what
/// it shows and where the thesis has it, and the SVG document.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    pub id: &'static str,
    pub title: String,
    pub caption: String,
    pub svg: String,
}

/// A chart that could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    #[error("chart '{chart}' could not be drawn: {message}")]
    Draw {
        chart: &'static str,
        message: String,
    },
}

/// Every chart the data allows, in report order.
pub fn all(results: &Results) -> Vec<Chart> {
    [
        calls_chart(results),
        self_seconds_chart(results),
        quality_speed_chart(results),
        sw_hw_times_chart(results),
        hw_speedup_chart(results),
        time_vs_primitives_chart(results),
        device_utilization_chart(results),
        histogram_chart(results),
    ]
    .into_iter()
    .flatten()
    .collect()
}

type DrawResult = Result<(), Box<dyn std::error::Error>>;
type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Default chart size, pixels.
const WIDTH: u32 = 800;
const HEIGHT: u32 = 420;

/// Text sizes in CSS pixels.
const TITLE_PX: f64 = 16.0;
const AXIS_TITLE_PX: f64 = 13.0;
const TICK_PX: f64 = 12.0;
const VALUE_PX: f64 = 11.0;

/// Colour-blind-safe palette (Okabe-Ito, without the yellow that vanishes on white).
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(120, 120, 120),
];
const INK: RGBColor = RGBColor(40, 40, 40);
const BASELINE_INK: RGBColor = RGBColor(30, 30, 30);

/// A font of `px` CSS pixels. Plotters' SVG backend writes `font-size = size / 1.24`.
fn font(px: f64) -> FontDesc<'static> {
    ("sans-serif", px * 1.24).into_font()
}

/// The mesh's lines: faint, so the data stands out.
fn grid_style() -> ShapeStyle {
    RGBColor(0, 0, 0).mix(0.1).stroke_width(1)
}

/// A label for a log axis: only at mantissas 1, 2 and 5, so labels never crowd.
fn log_label(v: f64, suffix: &str) -> String {
    if !finite_positive(v) {
        return String::new();
    }
    let mantissa = v / 10f64.powf(v.log10().floor());
    if [1.0, 2.0, 5.0, 10.0]
        .iter()
        .any(|m| (mantissa - m).abs() < 0.01)
    {
        format!("{}{suffix}", format_number(v))
    } else {
        String::new()
    }
}

/// A log-axis label formatter for one mesh: [`log_label`], blank for a value already
/// labelled. Plotters' log axis emits each decade twice (as the ninth light point of
/// one decade and the bold point of the next), which drew "10" twice, over itself.
fn log_labeller(suffix: &'static str) -> impl Fn(&f64) -> String {
    let seen = std::cell::RefCell::new(Vec::<f64>::new());
    move |v: &f64| {
        let mut seen = seen.borrow_mut();
        if seen.iter().any(|s| (s - v).abs() <= 1e-9 * v.abs()) {
            return String::new();
        }
        seen.push(*v);
        log_label(*v, suffix)
    }
}

/// Rough width of `text` at `px` (sans-serif averages about 0.55 em per character).
fn text_width(text: &str, px: f64) -> f64 {
    text.chars().count() as f64 * px * 0.6
}

/// The last two `::` segments of a function name, without generic arguments, at most
/// 36 characters.
pub fn short_name(name: &str) -> String {
    let mut plain = String::new();
    let mut depth = 0usize;
    for c in name.chars() {
        match c {
            '<' => depth += 1,
            '>' => depth = depth.saturating_sub(1),
            _ if depth == 0 => plain.push(c),
            _ => {}
        }
    }
    let segments: Vec<&str> = plain.split("::").filter(|s| !s.is_empty()).collect();
    let short = if segments.len() >= 2 {
        segments[segments.len() - 2..].join("::")
    } else if segments.is_empty() {
        name.to_string()
    } else {
        segments[0].to_string()
    };
    truncate(&short, 36)
}

fn truncate(text: &str, max_chars: usize) -> String {
    if text.chars().count() <= max_chars {
        text.to_string()
    } else {
        let mut t: String = text.chars().take(max_chars.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

/// A number for an axis or a bar: 3 significant digits, SI suffix for large counts.
pub fn format_number(v: f64) -> String {
    if !v.is_finite() {
        return "–".to_string();
    }
    let a = v.abs();
    if a == 0.0 {
        "0".to_string()
    } else if a >= 1e9 {
        format!("{}G", trim(v / 1e9))
    } else if a >= 1e6 {
        format!("{}M", trim(v / 1e6))
    } else if a >= 1e4 {
        format!("{}k", trim(v / 1e3))
    } else if a < 1e-3 {
        format!("{v:.0e}")
    } else {
        trim(v)
    }
}

/// Up to 3 significant digits without trailing zeros.
fn trim(v: f64) -> String {
    let a = v.abs();
    let decimals = if a >= 100.0 {
        0
    } else if a >= 10.0 {
        1
    } else if a >= 1.0 {
        2
    } else if a >= 0.1 {
        3
    } else if a >= 0.01 {
        4
    } else {
        5
    };
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Lower and upper decade around positive `values` (for log axes).
fn log_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.into_iter().filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() || !hi.is_finite() {
        return None;
    }
    let lo = 10f64.powf(lo.log10().floor());
    let mut hi = 10f64.powf(hi.log10().ceil());
    if hi <= lo {
        hi = lo * 10.0;
    }
    Some((lo, hi))
}

/// A log range hugging positive `values` (a factor of 1.5 each side), so the data
/// fills the plot; the 1-2-5 labels of [`log_label`] mark it.
fn tight_log_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.into_iter().filter(|v| finite_positive(*v)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo.is_finite() && hi.is_finite()).then(|| (lo / 1.5, hi * 1.5))
}

/// The thesis's bands with their RMS ranges: "below 15 visually identical, 15-50
/// similar, …" (from `analysis::Band`, where the edges live).
fn band_legend() -> String {
    let mut parts = Vec::new();
    let mut low: Option<f64> = None;
    for band in Band::ALL {
        let range = match (low, band.upper_edge()) {
            (None, Some(high)) => format!("below {high}"),
            (Some(low), Some(high)) => format!("{low}-{high}"),
            (Some(low), None) => format!("{low} and above"),
            (None, None) => String::new(),
        };
        parts.push(format!("{range} {}", band.name()));
        low = band.upper_edge();
    }
    parts.join(", ")
}

fn finite_positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// Draws the chart with `draw` into an SVG of `size`; a drawing error gives an SVG that
/// says what failed.
fn render(
    id: &'static str,
    title: String,
    caption: String,
    size: (u32, u32),
    draw: impl FnOnce(&Root<'_>) -> DrawResult,
) -> Chart {
    let mut svg = String::new();
    let outcome = {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let drawn = root
            .fill(&WHITE)
            .map_err(Into::into)
            .and_then(|()| draw(&root))
            .and_then(|()| root.present().map_err(Into::into));
        drawn.map_err(|e| e.to_string())
    };
    let svg = match outcome {
        Ok(()) => svg,
        Err(message) => failed_svg(&ChartError::Draw { chart: id, message }.to_string()),
    };
    Chart {
        id,
        title,
        caption,
        svg,
    }
}

/// A small SVG carrying an error message.
fn failed_svg(message: &str) -> String {
    let escaped = message
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    format!(
        "<svg width=\"{WIDTH}\" height=\"60\" viewBox=\"0 0 {WIDTH} 60\" xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"{WIDTH}\" height=\"60\" fill=\"#fff4f4\"/><text x=\"10\" y=\"35\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#a00\">{escaped}</text></svg>"
    )
}

/// Category labels under the x axis at backend `positions` (the axis points), rotated
/// to read upwards when `rotate`.
fn draw_x_labels(
    root: &Root<'_>,
    positions: &[(i32, i32)],
    labels: &[String],
    rotate: bool,
) -> DrawResult {
    for (&(x, y), label) in positions.iter().zip(labels) {
        if rotate {
            let style = TextStyle::from(font(TICK_PX))
                .transform(FontTransform::Rotate270)
                .pos(Pos::new(HPos::Right, VPos::Center));
            root.draw(&Text::new(label.clone(), (x, y + 6), style))?;
        } else {
            let style = TextStyle::from(font(TICK_PX)).pos(Pos::new(HPos::Center, VPos::Top));
            root.draw(&Text::new(label.clone(), (x, y + 6), style))?;
        }
    }
    Ok(())
}

/// Category labels left of the y axis at backend `positions`.
fn draw_y_labels(root: &Root<'_>, positions: &[(i32, i32)], labels: &[String]) -> DrawResult {
    for (&(x, y), label) in positions.iter().zip(labels) {
        let style = TextStyle::from(font(TICK_PX)).pos(Pos::new(HPos::Right, VPos::Center));
        root.draw(&Text::new(label.clone(), (x - 6, y), style))?;
    }
    Ok(())
}

/// Whether `n` labels need rotating in `plot_width` pixels, and the label area height.
fn x_label_layout(labels: &[String], plot_width: f64) -> (bool, u32) {
    let widest = labels
        .iter()
        .map(|l| text_width(l, TICK_PX))
        .fold(0.0, f64::max);
    let slot = plot_width / labels.len().max(1) as f64;
    if widest + 8.0 > slot {
        (true, (widest + 14.0 + AXIS_TITLE_PX * 2.0).ceil() as u32)
    } else {
        (false, (TICK_PX + 14.0 + AXIS_TITLE_PX * 2.0).ceil() as u32)
    }
}

/// The colour of a variant: its place among the run's variants (baseline is dark).
fn variant_colour(results: &Results, variant: &str) -> RGBColor {
    if variant == VariantName::reference().as_str() {
        return BASELINE_INK;
    }
    let others: Vec<&VariantName> = results
        .suite
        .variants
        .iter()
        .filter(|v| !v.is_reference())
        .collect();
    let index = others
        .iter()
        .position(|v| v.as_str() == variant)
        .unwrap_or_else(|| {
            // A variant outside the suite's list: a stable colour from its name.
            variant.bytes().map(usize::from).sum::<usize>()
        });
    PALETTE[index % PALETTE.len()]
}

/// A horizontal bar chart of named values (one row per name, largest first).
struct HorizontalBars {
    id: &'static str,
    title: String,
    caption: String,
    axis_title: String,
    rows: Vec<(String, f64, String)>,
    log: bool,
    colour: RGBColor,
}

fn horizontal_bars(spec: HorizontalBars) -> Chart {
    let HorizontalBars {
        id,
        title,
        caption,
        axis_title,
        rows,
        log,
        colour,
    } = spec;
    let n = rows.len();
    let label_width = rows
        .iter()
        .map(|(l, _, _)| text_width(l, TICK_PX))
        .fold(0.0, f64::max);
    let height = (90 + 26 * n as u32 + 50).max(220);
    let title_for_svg = title.clone();
    render(id, title, caption, (WIDTH, height), move |root| {
        let values = rows.iter().map(|(_, v, _)| *v);
        let y_range = -0.5..(n as f64 - 0.5);
        let y_of = |i: usize| (n - 1 - i) as f64;
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(&title_for_svg, font(TITLE_PX))
            .margin(12)
            .margin_right(24)
            .x_label_area_size((TICK_PX + 14.0 + AXIS_TITLE_PX * 2.0) as u32)
            .y_label_area_size((label_width + 14.0) as u32);
        let widest_value = rows
            .iter()
            .map(|(_, _, t)| text_width(t, VALUE_PX))
            .fold(0.0, f64::max);
        if log {
            let (lo, hi) = log_range(values).unwrap_or((1.0, 10.0));
            // One more decade on the right for the value labels.
            let hi = hi * 10.0;
            let mut chart = builder.build_cartesian_2d((lo..hi).log_scale(), y_range)?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_y_mesh()
                .y_labels(0)
                .x_label_formatter(&log_labeller(""))
                .x_label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc(axis_title.as_str())
                .draw()?;
            chart.draw_series(rows.iter().enumerate().map(|(i, (_, v, _))| {
                let y = y_of(i);
                let v = if finite_positive(*v) { *v } else { lo };
                Rectangle::new([(lo, y - 0.35), (v, y + 0.35)], colour.filled())
            }))?;
            for (i, (_, v, text)) in rows.iter().enumerate() {
                let v = if finite_positive(*v) { *v } else { lo };
                let (px, py) = chart.backend_coord(&(v, y_of(i)));
                let style = TextStyle::from(font(VALUE_PX)).pos(Pos::new(HPos::Left, VPos::Center));
                root.draw(&Text::new(text.clone(), (px + 4, py), style))?;
            }
            let positions: Vec<(i32, i32)> = (0..n)
                .map(|i| chart.backend_coord(&(lo, y_of(i))))
                .collect();
            let labels: Vec<String> = rows.iter().map(|(l, _, _)| l.clone()).collect();
            draw_y_labels(root, &positions, &labels)?;
        } else {
            let max = rows
                .iter()
                .map(|(_, v, _)| *v)
                .filter(|v| v.is_finite())
                .fold(0.0, f64::max);
            let max = if max > 0.0 { max } else { 1.0 };
            // Room on the right for the value labels.
            let plot_width = f64::from(WIDTH) - label_width - 60.0;
            let room = (widest_value + 10.0) / plot_width.max(100.0);
            let hi = max / (1.0 - room.min(0.6));
            let mut chart = builder.build_cartesian_2d(0.0..hi, y_range)?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_y_mesh()
                .y_labels(0)
                .x_label_formatter(&|v| format_number(*v))
                .x_label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc(axis_title.as_str())
                .draw()?;
            chart.draw_series(rows.iter().enumerate().map(|(i, (_, v, _))| {
                let y = y_of(i);
                let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
                Rectangle::new([(0.0, y - 0.35), (v, y + 0.35)], colour.filled())
            }))?;
            for (i, (_, v, text)) in rows.iter().enumerate() {
                let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
                let (px, py) = chart.backend_coord(&(v, y_of(i)));
                let style = TextStyle::from(font(VALUE_PX)).pos(Pos::new(HPos::Left, VPos::Center));
                root.draw(&Text::new(text.clone(), (px + 4, py), style))?;
            }
            let positions: Vec<(i32, i32)> = (0..n)
                .map(|i| chart.backend_coord(&(0.0, y_of(i))))
                .collect();
            let labels: Vec<String> = rows.iter().map(|(l, _, _)| l.clone()).collect();
            draw_y_labels(root, &positions, &labels)?;
        }
        Ok(())
    })
}

/// Calls per function from the flat profile, log scale (thesis fig. 51).
pub fn calls_chart(results: &Results) -> Option<Chart> {
    let profile = results.profile.as_ref()?;
    let mut rows: Vec<(String, f64, String)> = profile
        .baseline
        .flat
        .iter()
        .filter_map(|r| {
            let calls = r.calls.filter(|c| *c > 0)?;
            Some((
                short_name(&r.name),
                calls as f64,
                format_number(calls as f64),
            ))
        })
        .collect();
    if rows.is_empty() {
        return None;
    }
    rows.sort_by(|a, b| b.1.total_cmp(&a.1));
    rows.truncate(20);
    Some(horizontal_bars(HorizontalBars {
        id: "calls",
        title: format!(
            "Calls per function ({}, {})",
            profile.scene, profile.baseline.variant
        ),
        caption: format!(
            "Thesis fig. 51. Exact calls of the profiled functions of {} at {}x{} ({}), counted by the instrumented tracer; log scale.",
            profile.scene, profile.width, profile.height, profile.baseline.variant
        ),
        axis_title: "calls per render (log scale)".to_string(),
        rows,
        log: true,
        colour: PALETTE[0],
    }))
}

/// Self seconds per function from the flat profile (thesis fig. 52).
pub fn self_seconds_chart(results: &Results) -> Option<Chart> {
    let profile = results.profile.as_ref()?;
    let mut rows: Vec<(String, f64, String)> = profile
        .baseline
        .flat
        .iter()
        .filter(|r| r.self_seconds.is_finite() && r.self_seconds > 0.0)
        .map(|r| {
            (
                short_name(&r.name),
                r.self_seconds,
                format!("{} s ({:.1} %)", format_number(r.self_seconds), r.percent),
            )
        })
        .collect();
    if rows.is_empty() {
        return None;
    }
    rows.sort_by(|a, b| b.1.total_cmp(&a.1));
    rows.truncate(15);
    Some(horizontal_bars(HorizontalBars {
        id: "self-seconds",
        title: format!(
            "Self time per function ({}, {})",
            profile.scene, profile.baseline.variant
        ),
        caption: format!(
            "Thesis fig. 52. Seconds spent in each function itself (not its callees), from {} samples at {} s each; the 15 largest.",
            profile.baseline.samples,
            format_number(profile.baseline.seconds_per_sample)
        ),
        axis_title: "self time (s)".to_string(),
        rows,
        log: false,
        colour: PALETTE[3],
    }))
}

/// Speed-up against image error, one point per scene × variant.
pub fn quality_speed_chart(results: &Results) -> Option<Chart> {
    let mut points: Vec<(&str, f64, f64)> = Vec::new();
    for scene in &results.scenes {
        for v in &scene.variants {
            if let Some(q) = &v.quality
                && finite_positive(v.speedup.unwrap_or(f64::NAN))
                && q.rms.is_finite()
                && q.rms >= 0.0
            {
                points.push((v.variant.as_str(), v.speedup.unwrap_or(f64::NAN), q.rms));
            }
        }
    }
    if points.is_empty() {
        return None;
    }
    let mut variants: Vec<&str> = Vec::new();
    for (v, _, _) in &points {
        if !variants.contains(v) {
            variants.push(v);
        }
    }
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let (lo, hi) = (lo.min(1.0) * 0.8, hi.max(1.0) * 1.25);
    let rms_max = points.iter().map(|p| p.2).fold(20.0, f64::max) * 1.12;
    let title = "Image error against speed-up".to_string();
    let title_svg = title.clone();
    Some(render(
        "quality-speed",
        title,
        format!(
            "One point per scene and variant: speed-up over baseline (log scale) against the RMS error of the image; dashed lines are the thesis's bands (table 2: {}).",
            band_legend()
        ),
        (WIDTH, HEIGHT),
        move |root| {
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(24)
                .x_label_area_size(46)
                .y_label_area_size(56)
                .build_cartesian_2d((lo..hi).log_scale(), 0.0..rms_max)?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .x_label_formatter(&log_labeller("×"))
                .x_labels(30)
                .y_label_formatter(&|v| format_number(*v))
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("speed-up over baseline (×, log scale)")
                .y_desc("RMS error against baseline (gray levels)")
                .draw()?;
            for band in Band::ALL {
                let Some(limit) = band.upper_edge() else {
                    continue;
                };
                let name = band.name();
                if limit < rms_max {
                    chart.draw_series(DashedLineSeries::new(
                        [(lo, limit), (hi, limit)],
                        6,
                        4,
                        RGBColor(150, 150, 150).stroke_width(1),
                    ))?;
                    let (px, py) = chart.backend_coord(&(lo, limit));
                    let style = TextStyle::from(font(VALUE_PX))
                        .color(&RGBColor(110, 110, 110))
                        .pos(Pos::new(HPos::Left, VPos::Top));
                    root.draw(&Text::new(format!("{name} below"), (px + 4, py + 3), style))?;
                }
            }
            chart.draw_series(DashedLineSeries::new(
                [(1.0, 0.0), (1.0, rms_max)],
                3,
                3,
                RGBColor(150, 150, 150).stroke_width(1),
            ))?;
            for variant in &variants {
                let colour = variant_colour(results, variant);
                chart
                    .draw_series(
                        points
                            .iter()
                            .filter(|p| p.0 == *variant)
                            .map(|p| Circle::new((p.1, p.2), 5, colour.mix(0.85).filled())),
                    )?
                    .label(*variant)
                    .legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .label_font(font(TICK_PX))
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(180, 180, 180))
                .draw()?;
            Ok(())
        },
    ))
}

/// Scenes with a hardware result, in run order.
fn hardware_scenes(results: &Results) -> Vec<&SceneResult> {
    results
        .scenes
        .iter()
        .filter(|s| {
            s.hardware.as_ref().is_some_and(|h| {
                finite_positive(h.seconds) && finite_positive(h.software_seconds.median)
            })
        })
        .collect()
}

/// Software against hardware frame time per scene, grouped bars, log y (thesis fig. 49).
pub fn sw_hw_times_chart(results: &Results) -> Option<Chart> {
    let scenes = hardware_scenes(results);
    if scenes.is_empty() {
        return None;
    }
    let labels: Vec<String> = scenes.iter().map(|s| truncate(&s.name, 24)).collect();
    let (rotate, label_area) = x_label_layout(&labels, f64::from(WIDTH) - 100.0);
    let values: Vec<f64> = scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref())
        .flat_map(|h| [h.seconds, h.software_seconds.low, h.software_seconds.high])
        .collect();
    let (lo, hi) = tight_log_range(values)?;
    // Room above the bars for the legend.
    let hi = hi * 3.0;
    let title = "Software and hardware frame time per scene".to_string();
    let title_svg = title.clone();
    let height = HEIGHT + label_area.saturating_sub(60);
    Some(render(
        "sw-hw-times",
        title,
        "Thesis fig. 49. Software: median time of the baseline diffuse-only gray render with its 95 % interval; hardware: the model's frame time at 50 MHz (eq. 49). Log scale.".to_string(),
        (WIDTH, height),
        move |root| {
            let n = scenes.len();
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(24)
                .x_label_area_size(label_area)
                .y_label_area_size(64)
                .build_cartesian_2d(-0.5..(n as f64 - 0.5), (lo..hi).log_scale())?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_x_mesh()
                .x_labels(0)
                .y_label_formatter(&log_labeller(""))
                .y_labels(30)
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("scene")
                .y_desc("frame time (s, log scale)")
                .draw()?;
            let sw_colour = PALETTE[0];
            let hw_colour = PALETTE[1];
            let hardware: Vec<_> = scenes.iter().filter_map(|s| s.hardware.as_ref()).collect();
            chart
                .draw_series(hardware.iter().enumerate().map(|(i, h)| {
                    let x = i as f64;
                    Rectangle::new([(x - 0.38, lo), (x - 0.02, h.software_seconds.median)], sw_colour.filled())
                }))?
                .label("software (baseline, diffuse gray)")
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], sw_colour.filled()));
            chart.draw_series(hardware.iter().enumerate().flat_map(|(i, h)| {
                let x = i as f64 - 0.2;
                let (l, u) = (h.software_seconds.low, h.software_seconds.high);
                let ok = finite_positive(l) && finite_positive(u);
                let style = INK.stroke_width(1);
                ok.then(|| {
                    [
                        PathElement::new(vec![(x, l), (x, u)], style),
                        PathElement::new(vec![(x - 0.06, l), (x + 0.06, l)], style),
                        PathElement::new(vec![(x - 0.06, u), (x + 0.06, u)], style),
                    ]
                })
                .into_iter()
                .flatten()
            }))?;
            chart
                .draw_series(hardware.iter().enumerate().map(|(i, h)| {
                    let x = i as f64;
                    Rectangle::new([(x + 0.02, lo), (x + 0.38, h.seconds)], hw_colour.filled())
                }))?
                .label("hardware model (50 MHz)")
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], hw_colour.filled()));
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .label_font(font(TICK_PX))
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(180, 180, 180))
                .draw()?;
            let positions: Vec<(i32, i32)> = (0..n).map(|i| chart.backend_coord(&(i as f64, lo))).collect();
            draw_x_labels(root, &positions, &labels, rotate)?;
            Ok(())
        },
    ))
}

/// Hardware speed-up over software per scene (thesis fig. 50).
pub fn hw_speedup_chart(results: &Results) -> Option<Chart> {
    let scenes: Vec<&SceneResult> = hardware_scenes(results)
        .into_iter()
        .filter(|s| s.hardware.as_ref().is_some_and(|h| h.speedup.is_finite()))
        .collect();
    if scenes.is_empty() {
        return None;
    }
    let speedups: Vec<f64> = scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref().map(|h| h.speedup.max(0.0)))
        .collect();
    let labels: Vec<String> = scenes.iter().map(|s| truncate(&s.name, 24)).collect();
    let (rotate, label_area) = x_label_layout(&labels, f64::from(WIDTH) - 100.0);
    let max = speedups.iter().copied().fold(1.0, f64::max) * 1.18;
    let title = "Hardware speed-up over software per scene".to_string();
    let title_svg = title.clone();
    let height = HEIGHT + label_area.saturating_sub(60);
    Some(render(
        "hw-speedup",
        title,
        "Thesis fig. 50 (the thesis found 4.6 to 18). Software median time / hardware model frame time; above the dashed line the hardware is faster.".to_string(),
        (WIDTH, height),
        move |root| {
            let n = scenes.len();
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(24)
                .x_label_area_size(label_area)
                .y_label_area_size(56)
                .build_cartesian_2d(-0.5..(n as f64 - 0.5), 0.0..max)?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_x_mesh()
                .x_labels(0)
                .y_label_formatter(&|v| format_number(*v))
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("scene")
                .y_desc("hardware speed-up (×)")
                .draw()?;
            chart.draw_series(speedups.iter().enumerate().map(|(i, s)| {
                let x = i as f64;
                Rectangle::new([(x - 0.32, 0.0), (x + 0.32, *s)], PALETTE[2].filled())
            }))?;
            chart.draw_series(DashedLineSeries::new(
                [(-0.5, 1.0), (n as f64 - 0.5, 1.0)],
                6,
                4,
                PALETTE[3].stroke_width(2),
            ))?;
            let (px, py) = chart.backend_coord(&(-0.5, 1.0));
            let style = TextStyle::from(font(VALUE_PX)).color(&PALETTE[3]).pos(Pos::new(HPos::Left, VPos::Bottom));
            root.draw(&Text::new("break-even (1×)", (px + 4, py - 3), style))?;
            if n <= 30 {
                let values: Vec<String> = speedups.iter().map(|s| format!("{}×", format_number(*s))).collect();
                // Side by side when every value fits its bar's slot, else reading upwards.
                let slot = f64::from(chart.plotting_area().dim_in_pixel().0) / n as f64;
                let upright = values.iter().all(|v| text_width(v, VALUE_PX) + 4.0 <= slot);
                for (i, (s, value)) in speedups.iter().zip(values).enumerate() {
                    let (px, py) = chart.backend_coord(&(i as f64, *s));
                    let style = if upright {
                        TextStyle::from(font(VALUE_PX)).pos(Pos::new(HPos::Center, VPos::Bottom))
                    } else {
                        TextStyle::from(font(VALUE_PX))
                            .transform(FontTransform::Rotate270)
                            .pos(Pos::new(HPos::Left, VPos::Center))
                    };
                    root.draw(&Text::new(value, (px, py - 3), style))?;
                }
            }
            let positions: Vec<(i32, i32)> = (0..n).map(|i| chart.backend_coord(&(i as f64, 0.0))).collect();
            draw_x_labels(root, &positions, &labels, rotate)?;
            Ok(())
        },
    ))
}

/// Box-plot statistics with Tukey whiskers (the farthest sample within 1.5 IQR).
struct BoxStats {
    low_whisker: f64,
    q1: f64,
    median: f64,
    q3: f64,
    high_whisker: f64,
    outliers: Vec<f64>,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.len() == 1 {
        return sorted[0];
    }
    let rank = p * (sorted.len() - 1) as f64;
    let below = rank.floor() as usize;
    let above = (below + 1).min(sorted.len() - 1);
    sorted[below] + (sorted[above] - sorted[below]) * (rank - below as f64)
}

fn box_stats(samples: &[f64]) -> Option<BoxStats> {
    let mut s: Vec<f64> = samples
        .iter()
        .copied()
        .filter(|v| finite_positive(*v))
        .collect();
    if s.is_empty() {
        return None;
    }
    s.sort_by(f64::total_cmp);
    let (q1, median, q3) = (
        percentile(&s, 0.25),
        percentile(&s, 0.5),
        percentile(&s, 0.75),
    );
    let iqr = q3 - q1;
    let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
    let inside: Vec<f64> = s
        .iter()
        .copied()
        .filter(|v| *v >= lo_fence && *v <= hi_fence)
        .collect();
    Some(BoxStats {
        low_whisker: inside.first().copied().unwrap_or(q1),
        q1,
        median,
        q3,
        high_whisker: inside.last().copied().unwrap_or(q3),
        outliers: s
            .into_iter()
            .filter(|v| *v < lo_fence || *v > hi_fence)
            .collect(),
    })
}

/// Baseline render time against primitive count, box plots per test-bench family, with
/// the hardware model's time (thesis fig. 47, 48).
pub fn time_vs_primitives_chart(results: &Results) -> Option<Chart> {
    const FAMILIES: [SceneFamily; 3] = SceneFamily::TEST_BENCHES;
    let mut boxes: Vec<(usize, u64, BoxStats)> = Vec::new();
    for (f, family) in FAMILIES.iter().enumerate() {
        for count in 1..=7u64 {
            let samples: Vec<f64> = results
                .scenes
                .iter()
                .filter(|s| s.family == *family && s.primitives == count)
                .filter_map(|s| results.baseline(s))
                .flat_map(|b| {
                    if b.samples.is_empty() {
                        vec![b.time.median]
                    } else {
                        b.samples.clone()
                    }
                })
                .collect();
            if let Some(stats) = box_stats(&samples) {
                boxes.push((f, count, stats));
            }
        }
    }
    if boxes.is_empty() {
        return None;
    }
    let mut hardware: Vec<(u64, f64)> = results
        .scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref())
        .filter(|h| (1..=7).contains(&h.primitives) && finite_positive(h.seconds))
        .map(|h| (h.primitives, h.seconds))
        .collect();
    hardware.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    hardware.dedup_by_key(|h| h.0);
    let values = boxes
        .iter()
        .flat_map(|(_, _, b)| {
            let mut v = vec![b.low_whisker, b.high_whisker];
            v.extend(b.outliers.iter().copied());
            v
        })
        .chain(hardware.iter().map(|h| h.1));
    let (lo, hi) = tight_log_range(values)?;
    // Room above the boxes for the legend.
    let hi = hi * 4.0;
    let title = "Render time against primitive count".to_string();
    let title_svg = title.clone();
    Some(render(
        "time-vs-primitives",
        title,
        "Thesis fig. 47, 48. Boxes: the timed repeats of the baseline render of the test-bench scenes (balls: spheres, cylinder: cylinders, both: mixed), quartiles and whiskers at 1.5 IQR; line: the hardware model's frame time, which depends on the count only (eq. 49). Log scale.".to_string(),
        (WIDTH, HEIGHT),
        move |root| {
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(24)
                .x_label_area_size((TICK_PX + 14.0 + AXIS_TITLE_PX * 2.0) as u32)
                .y_label_area_size(64)
                .build_cartesian_2d(0.5..7.5, (lo..hi).log_scale())?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_x_mesh()
                .x_labels(0)
                .y_label_formatter(&log_labeller(""))
                .y_labels(30)
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("primitives in the scene")
                .y_desc("render time (s, log scale)")
                .draw()?;
            for (f, family) in FAMILIES.iter().enumerate() {
                let colour = PALETTE[f];
                let offset = (f as f64 - 1.0) * 0.27;
                let mine: Vec<&(usize, u64, BoxStats)> = boxes.iter().filter(|b| b.0 == f).collect();
                if mine.is_empty() {
                    continue;
                }
                chart
                    .draw_series(mine.iter().map(|(_, count, b)| {
                        let x = *count as f64 + offset;
                        Rectangle::new([(x - 0.11, b.q1), (x + 0.11, b.q3)], colour.mix(0.35).filled())
                    }))?
                    .label(family.name())
                    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], colour.filled()));
                chart.draw_series(mine.iter().flat_map(|(_, count, b)| {
                    let x = *count as f64 + offset;
                    let style = colour.stroke_width(2);
                    let thin = colour.stroke_width(1);
                    [
                        PathElement::new(vec![(x - 0.11, b.q1), (x + 0.11, b.q1), (x + 0.11, b.q3), (x - 0.11, b.q3), (x - 0.11, b.q1)], thin),
                        PathElement::new(vec![(x - 0.11, b.median), (x + 0.11, b.median)], style),
                        PathElement::new(vec![(x, b.q3), (x, b.high_whisker)], thin),
                        PathElement::new(vec![(x, b.q1), (x, b.low_whisker)], thin),
                        PathElement::new(vec![(x - 0.06, b.high_whisker), (x + 0.06, b.high_whisker)], thin),
                        PathElement::new(vec![(x - 0.06, b.low_whisker), (x + 0.06, b.low_whisker)], thin),
                    ]
                }))?;
                chart.draw_series(mine.iter().flat_map(|(_, count, b)| {
                    let x = *count as f64 + offset;
                    b.outliers.iter().map(move |v| Circle::new((x, *v), 3, colour.stroke_width(1)))
                }))?;
            }
            if !hardware.is_empty() {
                let ink = INK;
                chart
                    .draw_series(DashedLineSeries::new(
                        hardware.iter().map(|(n, s)| (*n as f64, *s)),
                        6,
                        4,
                        ink.stroke_width(2),
                    ))?
                    .label("hardware model (eq. 49)")
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 14, y)], ink.stroke_width(2)));
                chart.draw_series(hardware.iter().map(|(n, s)| Circle::new((*n as f64, *s), 3, ink.filled())))?;
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .label_font(font(TICK_PX))
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(180, 180, 180))
                .draw()?;
            let labels: Vec<String> = (1..=7).map(|n| n.to_string()).collect();
            let positions: Vec<(i32, i32)> = (1..=7).map(|n| chart.backend_coord(&(f64::from(n), lo))).collect();
            draw_x_labels(root, &positions, &labels, false)?;
            Ok(())
        },
    ))
}

/// Device utilization of the thesis design: LEs, multipliers, memory and PLLs in % of
/// each device, with the 100 % line.
pub fn device_utilization_chart(results: &Results) -> Option<Chart> {
    let hardware = results.hardware.as_ref()?;
    if hardware.devices.is_empty() {
        return None;
    }
    let pct = |used: u64, capacity: u64| {
        if capacity == 0 {
            0.0
        } else {
            used as f64 / capacity as f64 * 100.0
        }
    };
    let groups: Vec<(String, [f64; 4])> = hardware
        .devices
        .iter()
        .map(|d| {
            let name = if d.validated {
                d.device.clone()
            } else {
                format!("{} (unvalidated)", d.device)
            };
            (
                name,
                [
                    pct(d.le, d.le_capacity),
                    pct(d.mult + d.soft_mult_elements, d.mult_capacity),
                    pct(d.mem_bits, d.mem_capacity),
                    pct(u64::from(d.plls), u64::from(d.pll_capacity)),
                ],
            )
        })
        .collect();
    let max = groups
        .iter()
        .flat_map(|g| g.1)
        .filter(|v| v.is_finite())
        .fold(100.0, f64::max)
        * 1.4;
    let labels: Vec<String> = groups.iter().map(|g| truncate(&g.0, 32)).collect();
    let title = format!(
        "Device utilization of the thesis design ({})",
        hardware.family
    );
    let title_svg = title.clone();
    Some(render(
        "device-utilization",
        title,
        "Share of each device's logic elements, 9-bit multipliers (demand, counting those the fitter builds in logic), memory bits and PLLs; above the dashed 100 % line the resource runs out.".to_string(),
        (WIDTH, HEIGHT),
        move |root| {
            let n = groups.len();
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(24)
                .x_label_area_size((TICK_PX + 14.0 + AXIS_TITLE_PX * 2.0) as u32)
                .y_label_area_size(56)
                .build_cartesian_2d(-0.5..(n as f64 - 0.5), 0.0..max)?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .disable_x_mesh()
                .x_labels(0)
                .y_label_formatter(&|v| format!("{v:.0}"))
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("device")
                .y_desc("utilization (% of the device)")
                .draw()?;
            let resources = ["logic elements", "9-bit multipliers", "memory bits", "PLLs"];
            for (r, resource) in resources.iter().enumerate() {
                let colour = PALETTE[r];
                let offset = -0.36 + 0.18 * r as f64;
                chart
                    .draw_series(groups.iter().enumerate().map(|(i, g)| {
                        let x = i as f64 + offset;
                        let v = if g.1[r].is_finite() { g.1[r] } else { 0.0 };
                        Rectangle::new([(x, 0.0), (x + 0.16, v)], colour.filled())
                    }))?
                    .label(*resource)
                    .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], colour.filled()));
                for (i, g) in groups.iter().enumerate() {
                    let v = if g.1[r].is_finite() { g.1[r] } else { 0.0 };
                    let (px, py) = chart.backend_coord(&(i as f64 + offset + 0.08, v));
                    let style = TextStyle::from(font(VALUE_PX)).pos(Pos::new(HPos::Center, VPos::Bottom));
                    root.draw(&Text::new(format!("{v:.0} %"), (px, py - 2), style))?;
                }
            }
            chart.draw_series(DashedLineSeries::new(
                [(-0.5, 100.0), (n as f64 - 0.5, 100.0)],
                6,
                4,
                RGBColor(200, 0, 0).stroke_width(2),
            ))?;
            let (px, py) = chart.backend_coord(&(-0.5, 100.0));
            let style = TextStyle::from(font(VALUE_PX))
                .color(&RGBColor(200, 0, 0))
                .pos(Pos::new(HPos::Left, VPos::Bottom));
            root.draw(&Text::new("device capacity (100 %)", (px + 4, py - 3), style))?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .label_font(font(TICK_PX))
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(180, 180, 180))
                .draw()?;
            let positions: Vec<(i32, i32)> = (0..n).map(|i| chart.backend_coord(&(i as f64, 0.0))).collect();
            draw_x_labels(root, &positions, &labels, false)?;
            Ok(())
        },
    ))
}

/// The histogram chart of [`all`]: the scene and variant with the largest RMS error.
pub fn histogram_chart(results: &Results) -> Option<Chart> {
    let (scene, variant) = results
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().map(move |v| (s, v)))
        .filter(|(_, v)| {
            v.quality.as_ref().is_some_and(|q| q.rms.is_finite()) && v.histogram.len() == 256
        })
        .max_by(|a, b| {
            let rms = |v: &VariantResult| v.quality.as_ref().map_or(0.0, |q| q.rms);
            rms(a.1).total_cmp(&rms(b.1))
        })?;
    let baseline = results.baseline(scene)?;
    let mut chart = gray_histograms(results, scene, &[baseline, variant], (WIDTH, HEIGHT))?;
    chart.id = "histogram";
    chart.caption = format!(
        "Thesis fig. 35-37. Gray-level histograms of {} rendered by baseline and by {} (the largest RMS error of the run, {:.1}); log scale, empty bins drawn at the bottom.",
        scene.name,
        variant.variant,
        variant.quality.as_ref().map_or(0.0, |q| q.rms)
    );
    Some(chart)
}

/// Gray histograms of one scene: baseline and every variant whose histogram differs
/// from it (for the image grid).
pub fn scene_histograms(results: &Results, scene: &SceneResult) -> Option<Chart> {
    let baseline = results.baseline(scene)?;
    let mut shown = vec![baseline];
    shown.extend(scene.variants.iter().filter(|v| {
        !v.variant.is_reference() && v.histogram.len() == 256 && v.histogram != baseline.histogram
    }));
    let hidden: Vec<&str> = scene
        .variants
        .iter()
        .filter(|v| !v.variant.is_reference() && !shown.iter().any(|s| s.variant == v.variant))
        .map(|v| v.variant.as_str())
        .collect();
    let mut chart = gray_histograms(results, scene, &shown, (640, 300))?;
    chart.caption = if !hidden.is_empty() {
        format!(
            "Gray-level histograms of {}; not drawn, because their histogram equals baseline's: {}.",
            scene.name,
            hidden.join(", ")
        )
    } else {
        format!("Gray-level histograms of {}.", scene.name)
    };
    Some(chart)
}

/// One histogram's step line: variant, colour, points.
type HistogramLine = (String, RGBColor, Vec<(f64, f64)>);

/// Step lines of 256-bin gray histograms, log y.
fn gray_histograms(
    results: &Results,
    scene: &SceneResult,
    variants: &[&VariantResult],
    size: (u32, u32),
) -> Option<Chart> {
    let variants: Vec<&VariantResult> = variants
        .iter()
        .copied()
        .filter(|v| v.histogram.len() == 256)
        .collect();
    let max = variants
        .iter()
        .flat_map(|v| v.histogram.iter().copied())
        .max()
        .filter(|m| *m > 0)?;
    let hi = 10f64.powf((max as f64).log10().ceil()).max(10.0);
    let lo = 0.8;
    let title = format!("Gray histograms of {}", scene.name);
    let title_svg = title.clone();
    let series: Vec<HistogramLine> = variants
        .iter()
        .map(|v| {
            let mut points = Vec::with_capacity(512);
            for (bin, count) in v.histogram.iter().enumerate() {
                let y = (*count as f64).max(lo);
                points.push((bin as f64, y));
                points.push((bin as f64 + 1.0, y));
            }
            (
                v.variant.to_string(),
                variant_colour(results, &v.variant),
                points,
            )
        })
        .collect();
    Some(render(
        "scene-histogram",
        title,
        String::new(),
        size,
        move |root| {
            let mut chart = ChartBuilder::on(root)
                .caption(&title_svg, font(TITLE_PX))
                .margin(12)
                .margin_right(20)
                .x_label_area_size(46)
                .y_label_area_size(56)
                .build_cartesian_2d(0.0..256.0, (lo..hi).log_scale())?;
            chart
                .configure_mesh()
                .max_light_lines(0)
                .bold_line_style(grid_style())
                .x_label_formatter(&|v| format!("{v:.0}"))
                .y_label_formatter(&log_labeller(""))
                .label_style(font(TICK_PX))
                .axis_desc_style(font(AXIS_TITLE_PX))
                .x_desc("gray level (0-255)")
                .y_desc("pixels (log scale)")
                .draw()?;
            for (name, colour, points) in &series {
                let colour = *colour;
                let width = if name == "baseline" { 2 } else { 1 };
                chart
                    .draw_series(LineSeries::new(
                        points.iter().copied(),
                        colour.stroke_width(width),
                    ))?
                    .label(name.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 14, y)], colour.stroke_width(2))
                    });
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .label_font(font(TICK_PX))
                .background_style(WHITE.mix(0.9))
                .border_style(RGBColor(180, 180, 180))
                .draw()?;
            Ok(())
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::sample_results;

    fn chart<'a>(charts: &'a [Chart], id: &str) -> &'a Chart {
        charts
            .iter()
            .find(|c| c.id == id)
            .unwrap_or_else(|| panic!("no chart {id}"))
    }

    #[test]
    fn every_chart_of_the_sample_is_svg_with_its_axis_titles() {
        let charts = all(&sample_results());
        let expected: [(&str, &[&str]); 8] = [
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
                ],
            ),
            (
                "histogram",
                &["gray level (0-255)", "pixels (log scale)", "baseline"],
            ),
        ];
        assert_eq!(charts.len(), expected.len());
        for (id, texts) in expected {
            let c = chart(&charts, id);
            assert!(
                c.svg.starts_with("<svg"),
                "{id}: {}",
                &c.svg[..c.svg.len().min(80)]
            );
            assert!(c.svg.trim_end().ends_with("</svg>"), "{id}");
            assert!(!c.svg.contains("could not be drawn"), "{id}: {}", c.svg);
            assert!(!c.title.is_empty() && !c.caption.is_empty(), "{id}");
            for text in texts {
                assert!(c.svg.contains(text), "{id} lacks '{text}'");
            }
        }
    }

    #[test]
    fn empty_results_give_no_charts_and_bad_numbers_do_not_panic() {
        let mut r = sample_results();
        r.scenes.clear();
        r.profile = None;
        r.hardware = None;
        assert!(all(&r).is_empty());

        let mut r = sample_results();
        for s in &mut r.scenes {
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
        if let Some(p) = &mut r.profile {
            for row in &mut p.baseline.flat {
                row.self_seconds = f64::NAN;
                row.calls = Some(0);
            }
        }
        if let Some(h) = &mut r.hardware {
            for d in &mut h.devices {
                d.le_capacity = 0;
            }
        }
        let charts = all(&r);
        for c in &charts {
            assert!(c.svg.starts_with("<svg"), "{}", c.id);
        }
    }

    #[test]
    fn names_are_shortened_to_two_segments() {
        assert_eq!(
            short_name("tracer::primitives::sphere::Sphere::intersect"),
            "Sphere::intersect"
        );
        assert_eq!(
            short_name("tracer::render::render::{{closure}}"),
            "render::{{closure}}"
        );
        assert_eq!(short_name("main"), "main");
        assert_eq!(
            short_name("<tracer::accel::bvh::Bvh as tracer::accel::Intersector>::occluded"),
            "occluded"
        );
        assert_eq!(format_number(4_223_520_000.0), "4.22G");
        assert_eq!(format_number(0.0184), "0.0184");
        assert_eq!(format_number(f64::NAN), "–");
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
}
