//! The scaffolding every chart shares: the SVG backend and its white page, the failure
//! SVG, the title, the plot area with its two axes and grid, and the legend.
//!
//! A chart function hands [`render`] its id, texts and size and a drawing closure; the
//! closure gets a [`Canvas`] and asks it for a [`Plot`] with two [`Axis`]es, then draws
//! its data with the plot's helpers (here, in `marks.rs` and `bars.rs`); a chart over
//! categories goes through `categories.rs`, which does this for it.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::prelude::*;

use super::scale::{Axis, Ticks, log_labeller};
use super::style::{AXIS_TITLE_PX, LEGEND_BORDER, TICK_PX, TITLE_PX, WIDTH, font, grid_style};
use super::{Chart, ChartError};

pub(super) type Failure = Box<dyn std::error::Error>;
pub(super) type DrawResult = Result<(), Failure>;
/// A drawn series, to be keyed in the legend.
pub(super) type Series<'r, 'b> = plotters::chart::SeriesAnno<'r, SVGBackend<'b>>;
pub(super) type Root<'b> = DrawingArea<SVGBackend<'b>, Shift>;

/// Where a chart's drawing goes: the whole SVG page and the chart's title.
pub(super) struct Canvas<'r, 'b> {
    pub root: &'r Root<'b>,
    title: &'r str,
}

/// A plot area with its axes drawn, in data coordinates `X` × `Y`, and the page around
/// it for labels drawn outside the plot.
pub(super) struct Plot<'r, 'b, X: Ranged, Y: Ranged> {
    pub chart: ChartContext<'r, SVGBackend<'b>, Cartesian2d<X, Y>>,
    pub root: &'r Root<'b>,
}

/// Draws a chart with `draw` into an SVG of `size`; a drawing error gives an SVG that
/// says what failed. The chart's size is the SVG's own.
pub(super) fn render(
    id: &'static str,
    title: String,
    caption: String,
    size: (u32, u32),
    draw: impl FnOnce(&Canvas<'_, '_>) -> DrawResult,
) -> Chart {
    let mut svg = String::new();
    let outcome = {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let canvas = Canvas {
            root: &root,
            title: &title,
        };
        root.fill(&WHITE)
            .map_err(Into::into)
            .and_then(|()| draw(&canvas))
            .and_then(|()| root.present().map_err(Into::into))
            .map_err(|e| e.to_string())
    };
    let (svg, (width, height)) = match outcome {
        Ok(()) => (svg, size),
        Err(message) => failed_svg(&ChartError::Draw { chart: id, message }.to_string()),
    };
    Chart {
        id,
        title,
        caption,
        svg,
        width,
        height,
    }
}

/// A small SVG carrying an error message, and its size.
fn failed_svg(message: &str) -> (String, (u32, u32)) {
    const HEIGHT: u32 = 60;
    let escaped = message
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    let svg = format!(
        "<svg width=\"{WIDTH}\" height=\"{HEIGHT}\" viewBox=\"0 0 {WIDTH} {HEIGHT}\" xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"{WIDTH}\" height=\"{HEIGHT}\" fill=\"#fff4f4\"/><text x=\"10\" y=\"35\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#a00\">{escaped}</text></svg>"
    );
    (svg, (WIDTH, HEIGHT))
}

impl<'r, 'b> Canvas<'r, 'b> {
    /// The titled plot area of the page with axes `x` and `y`, their grid, tick labels
    /// and titles drawn.
    pub(super) fn plot<X, Y>(
        &self,
        x: Axis<'_, X>,
        y: Axis<'_, Y>,
    ) -> Result<Plot<'r, 'b, X, Y>, Failure>
    where
        X: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        self.plot_with_room(x, y, (24, 12))
    }

    /// [`Canvas::plot`] leaving `right` pixels of the page right of the plot and
    /// `bottom` below its axis title, for labels and a legend drawn outside the plot.
    pub(super) fn plot_with_room<X, Y>(
        &self,
        x: Axis<'_, X>,
        y: Axis<'_, Y>,
        (right, bottom): (u32, u32),
    ) -> Result<Plot<'r, 'b, X, Y>, Failure>
    where
        X: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(self.root)
            .caption(self.title, font(TITLE_PX))
            .margin(12)
            .margin_right(right)
            .margin_bottom(bottom)
            .x_label_area_size(x.room)
            .y_label_area_size(y.room)
            .build_cartesian_2d(x.range, y.range)?;
        draw_mesh(&mut chart, (x.ticks, x.title), (y.ticks, y.title))?;
        Ok(Plot {
            chart,
            root: self.root,
        })
    }

    /// Panels side by side, one per title, each drawn by `draw` (its index and a
    /// canvas of its own, titled) on an equal share of the page.
    pub(super) fn panels(
        &self,
        titles: &[String],
        mut draw: impl FnMut(usize, &Canvas<'_, 'b>) -> DrawResult,
    ) -> DrawResult {
        let areas = self.root.split_evenly((1, titles.len().max(1)));
        for (i, (area, title)) in areas.iter().zip(titles).enumerate() {
            draw(i, &Canvas { root: area, title })?;
        }
        Ok(())
    }

    /// The whole page as a plot without title, axes or margins (for small multiples).
    pub(super) fn bare_plot<XR, YR>(
        &self,
        x: XR,
        y: YR,
    ) -> Result<Plot<'r, 'b, XR::CoordDescType, YR::CoordDescType>, Failure>
    where
        XR: AsRangedCoord<Value = f64>,
        YR: AsRangedCoord<Value = f64>,
    {
        let chart = ChartBuilder::on(self.root).build_cartesian_2d(x, y)?;
        Ok(Plot {
            chart,
            root: self.root,
        })
    }
}

/// The grid (bold lines only), tick labels and axis titles of a plot.
fn draw_mesh<X, Y>(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
    (x_ticks, x_title): (Ticks, &str),
    (y_ticks, y_title): (Ticks, &str),
) -> DrawResult
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let x_label = labeller(x_ticks);
    let y_label = labeller(y_ticks);
    let mut mesh = chart.configure_mesh();
    mesh.max_light_lines(0)
        .bold_line_style(grid_style())
        .x_label_formatter(&*x_label)
        .y_label_formatter(&*y_label)
        .label_style(font(TICK_PX))
        .axis_desc_style(font(AXIS_TITLE_PX));
    // An empty title would still be written, as an empty text element.
    if !x_title.is_empty() {
        mesh.x_desc(x_title);
    }
    if !y_title.is_empty() {
        mesh.y_desc(y_title);
    }
    match x_ticks {
        Ticks::Categories => {
            mesh.disable_x_mesh().x_labels(0);
        }
        Ticks::Log {
            candidates: Some(n),
            ..
        } => {
            mesh.x_labels(n);
        }
        _ => {}
    }
    match y_ticks {
        Ticks::Categories => {
            mesh.disable_y_mesh().y_labels(0);
        }
        Ticks::Log {
            candidates: Some(n),
            ..
        } => {
            mesh.y_labels(n);
        }
        _ => {}
    }
    mesh.draw()?;
    Ok(())
}

/// The tick label formatter of one axis.
fn labeller(ticks: Ticks) -> Box<dyn Fn(&f64) -> String> {
    match ticks {
        Ticks::Log { suffix, .. } => Box::new(log_labeller(suffix)),
        plain => Box::new(move |v: &f64| plain.plain_label(*v)),
    }
}

impl<X, Y> Plot<'_, '_, X, Y>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    /// The page coordinates of data point (`x`, `y`).
    pub(super) fn at(&self, x: f64, y: f64) -> (i32, i32) {
        self.chart.backend_coord(&(x, y))
    }

    /// The legend of the labelled series, framed, in `corner`.
    pub(super) fn legend(&mut self, corner: SeriesLabelPosition) -> DrawResult {
        self.chart
            .configure_series_labels()
            .position(corner)
            .label_font(font(TICK_PX))
            .background_style(WHITE.mix(0.9))
            .border_style(LEGEND_BORDER)
            .draw()?;
        Ok(())
    }
}
