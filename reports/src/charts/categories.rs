//! Charts over named categories along x (scenes, devices, primitive counts): the
//! category axis, its labels under the plot (rotated when they would not fit side by
//! side) and the chart height that leaves room for them.

use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::Chart;
use super::frame::{DrawResult, Plot, render};
use super::scale::{Axis, Ticks};
use super::style::{AXIS_TITLE_PX, HEIGHT, TICK_PX, WIDTH, font, widest};

/// The categories along a plot's x axis: their labels, standing at x = `first`,
/// `first` + 1, …, the axis title, whether the labels read upwards and the room they
/// take under the plot.
pub(super) struct Categories {
    labels: Vec<String>,
    first: f64,
    title: &'static str,
    rotate: bool,
    room: u32,
}

impl Categories {
    /// `labels` at x = `first`, `first` + 1, …, rotated when the widest does not fit its
    /// share of the chart's width.
    pub(super) fn fitted(labels: Vec<String>, first: f64, title: &'static str) -> Self {
        let widest = widest(labels.iter().map(String::as_str), TICK_PX);
        let slot = (f64::from(WIDTH) - 100.0) / labels.len().max(1) as f64;
        let rotate = widest + 8.0 > slot;
        let text = if rotate { widest } else { TICK_PX };
        Categories {
            room: (text + 14.0 + AXIS_TITLE_PX * 2.0).ceil() as u32,
            labels,
            first,
            title,
            rotate,
        }
    }

    /// The x axis: one unit per category, half a unit beyond the first and the last.
    fn axis(&self) -> Axis<'static, RangedCoordf64> {
        let start = self.first - 0.5;
        let end = start + self.labels.len() as f64;
        Axis::linear(start, end, Ticks::Categories, self.title, self.room)
    }
}

/// A chart of `categories` against the value axis `y`: `draw` draws the data (and the
/// legend) on the plot, then the category labels go under it. The chart is as tall as
/// the labels need.
pub(super) fn category_chart<Y>(
    (id, title, caption): (&'static str, String, String),
    categories: Categories,
    y: Axis<'static, Y>,
    draw: impl FnOnce(&mut Plot<'_, '_, RangedCoordf64, Y>) -> DrawResult,
) -> Chart
where
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let size = (WIDTH, HEIGHT + categories.room.saturating_sub(60));
    render(id, title, caption, size, move |canvas| {
        let mut plot = canvas.plot(categories.axis(), y)?;
        draw(&mut plot)?;
        plot.category_labels(&categories)
    })
}

impl<X, Y> Plot<'_, '_, X, Y>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    /// The labels of `categories` under the plot, reading upwards when rotated.
    fn category_labels(&self, categories: &Categories) -> DrawResult {
        let (pos, transform) = if categories.rotate {
            (
                Pos::new(HPos::Right, VPos::Center),
                FontTransform::Rotate270,
            )
        } else {
            (Pos::new(HPos::Center, VPos::Top), FontTransform::None)
        };
        let style = TextStyle::from(font(TICK_PX)).pos(pos).transform(transform);
        let bottom = self.chart.y_range().start;
        for (i, label) in categories.labels.iter().enumerate() {
            let (px, py) = self.at(categories.first + i as f64, bottom);
            self.root
                .draw(&Text::new(label.clone(), (px, py + 6), style.clone()))?;
        }
        Ok(())
    }
}
