//! The roofline chart (Williams, Waterman and Patterson, 2009; drawn as Intel Advisor
//! draws its roofs): every render as a point of attained GFLOP/s against arithmetic
//! intensity (flops per byte read), log-log, under the machine's measured roofs: two
//! compute roofs (the SIMD peak and the scalar peak) and two bandwidth roofs (L1, which
//! bounds the cache-aware bytes, and DRAM). A point is held to the compute roof of its
//! code: filled for a variant that tests primitives in SIMD lanes, hollow for scalar
//! code. One colour per variant; the scenes share the plot, so a variant's cloud shows
//! how its intensity and speed move with the scene.
//!
//! Every roof is labelled at its right end, outside the data: the compute roofs (and a
//! bandwidth roof that leaves the plot through its right edge) in a margin right of
//! the plot; a bandwidth roof that ends on the SIMD peak just above that peak, where no
//! point lies. The legend stands below the plot.

use std::cell::Cell;

use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::Chart;
use super::data::{RooflinePoint, machine_peak, roofline_points, variant_name, variant_place};
use super::frame::{DrawResult, Plot, render};
use super::marks::Dashed;
use super::scale::{Axis, log_range, tight_log_range};
use super::style::{HEIGHT, INK, TICK_PX, VALUE_PX, WIDTH, font, text_width, variant_colour};
use crate::format;
use crate::results::{CodeKind, MachinePeak, Results, VariantResult};

/// DRAM's roof: a second, dashed ink, so that it reads as the lesser limit.
const DRAM: RGBColor = RGBColor(110, 110, 110);
/// The scalar compute roof: the compute roofs' ink, lighter.
const SCALAR: RGBColor = RGBColor(90, 90, 150);

/// Pixels right of the plot for the roofs' labels.
const LABEL_MARGIN: u32 = 118;
/// Height of one line of a roof's label.
const LINE_PX: i32 = 14;
/// Height of one row of the legend below the plot.
const LEGEND_ROW: u32 = 20;
/// The y axis' room (tick labels and title) left of the plot.
const Y_ROOM: u32 = 56;
/// The page's margin around the plot (see [`super::frame::Canvas::plot`]).
const PAGE_MARGIN: u32 = 12;

/// Where the chart puts its data: the axes' ranges and the plot's pixel edges, so a
/// test can tell where a point must be drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct RooflineScale {
    /// Flop/byte at the left and right edges.
    pub intensity: (f64, f64),
    /// GFLOP/s at the bottom and top edges.
    pub gflops: (f64, f64),
    /// Pixel columns of the left and right edges.
    pub columns: (f64, f64),
    /// Pixel rows of the top and bottom edges.
    pub rows: (f64, f64),
}

/// Attained GFLOP/s against arithmetic intensity for every render with a roofline
/// point, under the roofs when the run measured the machine's peaks.
pub fn roofline_chart(results: &Results) -> Option<Chart> {
    roofline_with_scale(results).map(|(chart, _)| chart)
}

/// A roof's label at the right edge: its pixel row, two lines and its ink.
struct EdgeLabel {
    row: i32,
    lines: [String; 2],
    colour: RGBColor,
}

/// [`roofline_chart`] and the scale it was drawn at.
pub(super) fn roofline_with_scale(results: &Results) -> Option<(Chart, RooflineScale)> {
    let points = roofline_points(results);
    if points.is_empty() {
        return None;
    }
    let peak = machine_peak(results).cloned();
    // The SIMD roof's bend in view (where it meets the L1 roof), so that the L1 slope
    // shows; the scalar roof's bend may lie left of the data (it then starts at the
    // left edge), DRAM's right of it (its slope leaves through the right edge,
    // labelled there).
    let ridges: Vec<f64> = peak.iter().map(|p| p.ridge(CodeKind::Simd)).collect();
    // Each axis from the decade below the data (plotters labels a log axis from its
    // first power of ten on) to just past the data and the roofs' bends.
    let span = |values: Vec<f64>| -> Option<(f64, f64)> {
        let (lo, _) = log_range(values.iter().copied())?;
        let (_, hi) = tight_log_range(values)?;
        Some((lo, hi))
    };
    let (x_lo, x_hi) = span(points.iter().map(|p| p.intensity).chain(ridges).collect())?;
    // Twice the SIMD peak: room above the top roof for the labels of the bandwidth
    // roofs that end on it.
    let top = peak.as_ref().map(|p| p.peak_gflops * 2.0);
    let (y_lo, y_hi) = span(points.iter().map(|p| p.gflops).chain(top).collect())?;
    let mut series: Vec<&VariantResult> = Vec::new();
    for p in &points {
        if !series
            .iter()
            .any(|s| variant_name(s) == variant_name(p.variant))
        {
            series.push(p.variant);
        }
    }
    let size = (WIDTH + LABEL_MARGIN, HEIGHT + 40);
    let legend = legend_layout(&series, size.0);
    let legend_height = legend.rows * LEGEND_ROW + 6;
    let size = (size.0, size.1 + legend_height);
    let caption = caption(peak.as_ref(), &points);
    let scale = Cell::new(RooflineScale::default());
    let drawn = &scale;
    let chart = render(
        "roofline",
        "Roofline: attained GFLOP/s against arithmetic intensity".to_string(),
        caption,
        size,
        move |canvas| {
            let x = Axis::log(
                (x_lo, x_hi),
                "",
                Some(30),
                "arithmetic intensity (flop/byte, log scale)",
                46,
            );
            let y = Axis::log(
                (y_lo, y_hi),
                "",
                Some(30),
                "attained GFLOP/s (log scale)",
                Y_ROOM,
            );
            let mut plot =
                canvas.plot_with_room(x, y, (LABEL_MARGIN, PAGE_MARGIN + legend_height))?;
            let (columns, rows) = plot.chart.plotting_area().get_pixel_range();
            drawn.set(RooflineScale {
                intensity: (x_lo, x_hi),
                gflops: (y_lo, y_hi),
                columns: (f64::from(columns.start), f64::from(columns.end - 1)),
                rows: (f64::from(rows.start), f64::from(rows.end - 1)),
            });
            if let Some(peak) = &peak {
                draw_roofs(&mut plot, peak, y_lo)?;
            }
            for first in &series {
                let colour = variant_colour(variant_place(results, first));
                let name = variant_name(first);
                let mine = points.iter().filter(|p| variant_name(p.variant) == name);
                plot.chart.draw_series(
                    mine.map(|p: &RooflinePoint| marker(p.code, (p.intensity, p.gflops), colour)),
                )?;
            }
            draw_legend(&plot, results, &legend, rows.end + 46)
        },
    );
    Some((chart, scale.get()))
}

/// A point's mark: filled for SIMD code, a ring for scalar code.
fn marker<C>(code: CodeKind, at: C, colour: RGBColor) -> Circle<C, i32> {
    match code {
        CodeKind::Simd => Circle::new(at, 4, colour.mix(0.85).filled()),
        CodeKind::Scalar => Circle::new(at, 4, colour.stroke_width(2)),
    }
}

/// The caption: what a point is, which roofs are drawn and which one holds a point.
fn caption(peak: Option<&MachinePeak>, points: &[RooflinePoint<'_>]) -> String {
    let mut text = "One point per scene and variant: the counted floating-point operations over the median tracing time, against the flops per byte the render asks of the memory system, wherever they are found (the cache-aware roofline).".to_string();
    let Some(peak) = peak else {
        text += " The machine's peaks were not measured in this run: no roofs.";
        return text;
    };
    let kinds = |kind: CodeKind| -> Vec<String> {
        let mut names: Vec<String> = Vec::new();
        for p in points.iter().filter(|p| p.code == kind) {
            let name = variant_name(p.variant).to_string();
            if !names.contains(&name) {
                names.push(name);
            }
        }
        names
    };
    let (simd, scalar) = (kinds(CodeKind::Simd), kinds(CodeKind::Scalar));
    let l1 = peak.cache_bandwidth_gbs > 0.0;
    text += if l1 {
        " Solid roofs: the L1 bandwidth (STREAM triad within the cache) times the intensity, up to the compute peaks, each measured on the timed renders' threads; dashed: the DRAM bandwidth's slope, which a point above it beat by reading from the caches."
    } else {
        " Solid roofs: the DRAM bandwidth (STREAM triad) times the intensity, up to the compute peaks (this file has no L1 bandwidth, so DRAM's is the bandwidth roof)."
    };
    match peak.scalar_peak() {
        Some(_) => {
            text += " Filled points are SIMD code, held to the SIMD peak";
            if !simd.is_empty() {
                text += &format!(" ({})", format::join_list(&simd));
            }
            text += "; rings are scalar code, held to the scalar peak";
            if !scalar.is_empty() {
                text += &format!(" ({})", format::join_list(&scalar));
            }
            text += ".";
        }
        None => {
            text += " This file has no scalar peak (measured since the roofline's scalar roof was added): only the SIMD compute roof is drawn, and every point, scalar code (rings) as well as SIMD code (filled), is set against it.";
        }
    }
    text
}

/// The roofs: the L1 slope up to the SIMD peak and that peak to the right edge (one
/// line, the SIMD roofline), the scalar peak from where it meets the L1 slope, and
/// DRAM's slope dashed up to the SIMD peak or the right edge, each labelled at its
/// right end.
fn draw_roofs<X, Y>(plot: &mut Plot<'_, '_, X, Y>, peak: &MachinePeak, y_lo: f64) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let (x_lo, x_hi) = (plot.chart.x_range().start, plot.chart.x_range().end);
    let bandwidth = peak.roof_bandwidth_gbs();
    let ridge = peak.ridge(CodeKind::Simd);
    let simd = peak.peak_gflops;
    // A sloped roof enters the plot at its left edge or through its floor.
    let entry = |gbs: f64| x_lo.max(y_lo / gbs);
    let start = entry(bandwidth);
    plot.chart.draw_series(LineSeries::new(
        [(start, bandwidth * start), (ridge, simd), (x_hi, simd)],
        INK.stroke_width(2),
    ))?;
    let mut edge = vec![EdgeLabel {
        row: plot.at(x_hi, simd).1,
        lines: [
            "SIMD peak".to_string(),
            format!("{} GFLOP/s", format::significant(simd)),
        ],
        colour: INK,
    }];
    if let Some(scalar) = peak.scalar_peak().filter(|s| *s < simd) {
        let from = peak.ridge(CodeKind::Scalar).max(x_lo);
        plot.chart.draw_series(LineSeries::new(
            [(from, scalar), (x_hi, scalar)],
            SCALAR.stroke_width(2),
        ))?;
        edge.push(EdgeLabel {
            row: plot.at(x_hi, scalar).1,
            lines: [
                "scalar peak".to_string(),
                format!("{} GFLOP/s", format::significant(scalar)),
            ],
            colour: SCALAR,
        });
    }
    let level = if peak.cache_bandwidth_gbs > 0.0 {
        "L1"
    } else {
        "DRAM"
    };
    let bandwidth_text = |gbs: f64| format!("{} GB/s", format::significant(gbs));
    // Labels above the SIMD peak, right-aligned at the slope's end; a second one
    // that would run into the first goes a line higher.
    let mut above: Vec<(i32, i32)> = Vec::new();
    let mut label_above = |plot: &Plot<'_, '_, X, Y>, x: f64, text: &str, colour| {
        let (px, py) = plot.at(x, simd);
        let width = text_width(text, VALUE_PX) as i32;
        let mut raise = 0;
        while above
            .iter()
            .any(|&(right, r)| r == raise && (right - px).abs() < width + 8)
        {
            raise += 1;
        }
        above.push((px, raise));
        draw_text(
            plot,
            text,
            (px - 4, py - 3 - raise * LINE_PX),
            Pos::new(HPos::Right, VPos::Bottom),
            colour,
        )
    };
    label_above(
        plot,
        ridge,
        &format!("{level} {}", bandwidth_text(bandwidth)),
        INK,
    )?;
    if peak.cache_bandwidth_gbs > 0.0 && peak.bandwidth_gbs < bandwidth {
        // DRAM's slope up to where it meets the SIMD peak: a render above it read
        // most of its records from the caches.
        let dram = peak.bandwidth_gbs;
        let from = entry(dram);
        let to = (simd / dram).min(x_hi);
        plot.dashed(
            [(from, dram * from), (to, dram * to)],
            Dashed {
                colour: DRAM,
                width: 2,
                dash: 6,
                gap: 4,
            },
        )?;
        let text = format!("DRAM {}", bandwidth_text(dram));
        if to < x_hi {
            label_above(plot, to, &text, DRAM)?;
        } else {
            edge.push(EdgeLabel {
                row: plot.at(x_hi, dram * x_hi).1,
                lines: ["DRAM".to_string(), bandwidth_text(dram)],
                colour: DRAM,
            });
        }
    }
    draw_edge_labels(plot, edge)
}

/// The labels right of the plot, each centred on its roof's row, pushed apart where
/// two would overlap.
fn draw_edge_labels<X, Y>(plot: &Plot<'_, '_, X, Y>, mut labels: Vec<EdgeLabel>) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let (columns, _) = plot.chart.plotting_area().get_pixel_range();
    let left = columns.end + 6;
    labels.sort_by_key(|l| l.row);
    // Two lines a label: its top is a line above its roof.
    let mut next_top = i32::MIN;
    for label in &labels {
        let top = (label.row - LINE_PX).max(next_top);
        for (i, line) in (0i32..).zip(&label.lines) {
            draw_text(
                plot,
                line,
                (left, top + i * LINE_PX),
                Pos::new(HPos::Left, VPos::Top),
                label.colour,
            )?;
        }
        plot.root.draw(&PathElement::new(
            vec![(columns.end, label.row), (left - 2, label.row)],
            label.colour.stroke_width(1),
        ))?;
        next_top = top + 2 * LINE_PX + 2;
    }
    Ok(())
}

fn draw_text<X, Y>(
    plot: &Plot<'_, '_, X, Y>,
    text: &str,
    at: (i32, i32),
    pos: Pos,
    colour: RGBColor,
) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let style = TextStyle::from(font(VALUE_PX)).color(&colour).pos(pos);
    plot.root.draw(&Text::new(text.to_string(), at, style))?;
    Ok(())
}

/// The legend's entries in rows below the plot: each variant's name, where it goes.
struct LegendLayout<'r> {
    /// Variant, column offset from the plot's left edge, row.
    entries: Vec<(&'r VariantResult, u32, u32)>,
    rows: u32,
}

/// Lays the variants' keys out left to right below the plot, wrapping at its width.
fn legend_layout<'r>(series: &[&'r VariantResult], chart_width: u32) -> LegendLayout<'r> {
    let width = chart_width.saturating_sub(2 * PAGE_MARGIN + Y_ROOM + LABEL_MARGIN);
    let (mut column, mut row) = (0u32, 0u32);
    let mut entries = Vec::new();
    for v in series {
        let entry = 18 + text_width(variant_name(v), TICK_PX).ceil() as u32 + 16;
        if column > 0 && column + entry > width {
            column = 0;
            row += 1;
        }
        entries.push((*v, column, row));
        column += entry;
    }
    LegendLayout {
        entries,
        rows: row + u32::from(!series.is_empty()),
    }
}

/// The legend below the plot from pixel row `top`: a mark in each variant's colour
/// (filled for SIMD code, a ring for scalar code) and its name.
fn draw_legend<X, Y>(
    plot: &Plot<'_, '_, X, Y>,
    results: &Results,
    legend: &LegendLayout<'_>,
    top: i32,
) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let (columns, _) = plot.chart.plotting_area().get_pixel_range();
    for (v, column, row) in &legend.entries {
        let colour = variant_colour(variant_place(results, v));
        let x = columns.start + *column as i32;
        let y = top + (*row * LEGEND_ROW) as i32 + LEGEND_ROW as i32 / 2;
        let code = CodeKind::of_variant(&v.variant);
        plot.root.draw(&marker(code, (x + 6, y), colour))?;
        let style = TextStyle::from(font(TICK_PX))
            .color(&INK)
            .pos(Pos::new(HPos::Left, VPos::Center));
        plot.root
            .draw(&Text::new(variant_name(v).to_string(), (x + 16, y), style))?;
    }
    Ok(())
}
