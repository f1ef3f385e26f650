//! Bars: where the bars of a category stand, drawing them, and the horizontal bar chart
//! of named values with their labels (the profile's charts).

use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::Chart;
use super::frame::{DrawResult, Failure, Plot, Series, render};
use super::marks::Place;
use super::scale::{Axis, Ticks, X_ROOM, log_range};
use super::style::{TICK_PX, VALUE_PX, WIDTH, font, widest};

/// How `groups` bars share a category's slot: together `span` wide (in category units,
/// centred on the category), `gap` apart.
#[derive(Clone, Copy, Debug)]
pub(super) struct Slots {
    pub groups: usize,
    pub span: f64,
    pub gap: f64,
}

impl Slots {
    /// One bar per category, `span` wide.
    pub(super) const fn single(span: f64) -> Self {
        Slots {
            groups: 1,
            span,
            gap: 0.0,
        }
    }

    /// The width of one bar.
    pub(super) fn width(self) -> f64 {
        let groups = self.groups.max(1) as f64;
        (self.span - self.gap * (groups - 1.0)) / groups
    }

    /// Where bar `group` of category `category` starts and ends.
    pub(super) fn extent(self, category: usize, group: usize) -> (f64, f64) {
        let start = category as f64 - self.span / 2.0 + group as f64 * (self.width() + self.gap);
        (start, start + self.width())
    }

    /// The middle of bar `group` of category `category`.
    pub(super) fn centre(self, category: usize, group: usize) -> f64 {
        let (a, b) = self.extent(category, group);
        (a + b) / 2.0
    }
}

impl<'r, 'b, X, Y> Plot<'r, 'b, X, Y>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    /// Vertical bars of bar `group` in `slots`, one per (category, value), rising from
    /// `base`; the returned annotation can key them in the legend.
    pub(super) fn columns(
        &mut self,
        slots: Slots,
        group: usize,
        values: impl IntoIterator<Item = (usize, f64)>,
        base: f64,
        colour: RGBColor,
    ) -> Result<&mut Series<'r, 'b>, Failure> {
        Ok(self.chart.draw_series(values.into_iter().map(|(i, v)| {
            let (x0, x1) = slots.extent(i, group);
            Rectangle::new([(x0, base), (x1, v)], colour.filled())
        }))?)
    }

    /// Horizontal bars of `rows`, the first at the top, from `base` to each value (to
    /// `base` when the value is not a number beyond it), with the value's text at the
    /// bar's end and the row's label left of the axis.
    fn rows(&mut self, rows: &[Row], base: f64, colour: RGBColor) -> DrawResult {
        let n = rows.len();
        let y_of = |i: usize| (n - 1 - i) as f64;
        let end = |r: &Row| {
            if r.value.is_finite() && r.value > base {
                r.value
            } else {
                base
            }
        };
        let half = ROW_SLOTS.width() / 2.0;
        self.chart
            .draw_series(rows.iter().enumerate().map(|(i, r)| {
                let y = y_of(i);
                Rectangle::new([(base, y - half), (end(r), y + half)], colour.filled())
            }))?;
        for (i, r) in rows.iter().enumerate() {
            self.text(&r.text, (end(r), y_of(i)), Place::Right, BLACK)?;
        }
        let style = TextStyle::from(font(TICK_PX)).pos(Pos::new(HPos::Right, VPos::Center));
        for (i, r) in rows.iter().enumerate() {
            let (px, py) = self.at(base, y_of(i));
            self.root
                .draw(&Text::new(r.label.clone(), (px - 6, py), style.clone()))?;
        }
        Ok(())
    }
}

/// One row of a horizontal bar chart: its label, value and the text at the bar's end.
pub(super) struct Row {
    pub label: String,
    pub value: f64,
    pub text: String,
}

/// A horizontal bar chart of named values, one row per name from the top, on a log or
/// linear value axis.
pub(super) struct HorizontalBars {
    pub id: &'static str,
    pub title: String,
    pub caption: String,
    pub axis_title: &'static str,
    pub rows: Vec<Row>,
    pub log: bool,
    pub colour: RGBColor,
}

const ROW_SLOTS: Slots = Slots::single(0.7);

pub(super) fn horizontal_bars(spec: HorizontalBars) -> Chart {
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
    let label_width = widest(rows.iter().map(|r| r.label.as_str()), TICK_PX);
    let value_width = widest(rows.iter().map(|r| r.text.as_str()), VALUE_PX);
    let height = (90 + 26 * n as u32 + 50).max(220);
    let rows_axis = || Axis::categories(n, "", (label_width + 14.0) as u32);
    render(id, title, caption, (WIDTH, height), move |canvas| {
        if log {
            let (lo, hi) = log_range(rows.iter().map(|r| r.value)).unwrap_or((1.0, 10.0));
            // One more decade on the right for the value labels.
            let x = Axis::log((lo, hi * 10.0), "", None, axis_title, X_ROOM);
            canvas.plot(x, rows_axis())?.rows(&rows, lo, colour)
        } else {
            let max = rows
                .iter()
                .map(|r| r.value)
                .filter(|v| v.is_finite())
                .fold(0.0, f64::max);
            let max = if max > 0.0 { max } else { 1.0 };
            // Room on the right for the value labels.
            let plot_width = f64::from(WIDTH) - label_width - 60.0;
            let room = (value_width + 10.0) / plot_width.max(100.0);
            let x = Axis::linear(
                0.0,
                max / (1.0 - room.min(0.6)),
                Ticks::Numbers,
                axis_title,
                X_ROOM,
            );
            canvas.plot(x, rows_axis())?.rows(&rows, 0.0, colour)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_of_a_slot_share_its_span_evenly_and_centred() {
        let pair = Slots {
            groups: 2,
            span: 0.76,
            gap: 0.04,
        };
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        let (a0, a1) = pair.extent(3, 0);
        let (b0, b1) = pair.extent(3, 1);
        assert!(close(a0, 2.62) && close(a1, 2.98), "{a0} {a1}");
        assert!(close(b0, 3.02) && close(b1, 3.38), "{b0} {b1}");
        assert!(close(pair.centre(0, 0), -0.2));
        let four = Slots {
            groups: 4,
            span: 0.7,
            gap: 0.02,
        };
        assert!(close(four.width(), 0.16));
        assert!(close(four.centre(1, 0) + four.centre(1, 3), 2.0));
    }
}
