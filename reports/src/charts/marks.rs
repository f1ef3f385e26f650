//! What charts draw on a plot besides their data: texts placed at a data point (values,
//! notes), dashed reference lines, whiskers and legend keys.

use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::frame::{DrawResult, Failure, Plot, Series};
use super::style::{VALUE_PX, font};

/// Where a text stands relative to its point.
#[derive(Clone, Copy, Debug)]
pub(super) enum Place {
    /// To the right, vertically centred (values at the end of horizontal bars).
    Right,
    /// Above, centred (values on top of vertical bars).
    Above,
    /// Above, reading upwards (values of narrow vertical bars).
    AboveUpwards,
    /// Above and to the right, left-aligned (the note of a reference line).
    AboveRight,
    /// Below and to the right, left-aligned (the note of a guide line).
    BelowRight,
    /// Above and to the left, right-aligned (the note of a rising line, on its empty
    /// side).
    AboveLeft,
}

impl Place {
    /// The text's anchor, rotation and offset from the point, pixels.
    fn layout(self) -> (Pos, bool, (i32, i32)) {
        match self {
            Place::Right => (Pos::new(HPos::Left, VPos::Center), false, (4, 0)),
            Place::Above => (Pos::new(HPos::Center, VPos::Bottom), false, (0, -3)),
            Place::AboveUpwards => (Pos::new(HPos::Left, VPos::Center), true, (0, -3)),
            Place::AboveRight => (Pos::new(HPos::Left, VPos::Bottom), false, (4, -3)),
            Place::BelowRight => (Pos::new(HPos::Left, VPos::Top), false, (4, 3)),
            Place::AboveLeft => (Pos::new(HPos::Right, VPos::Bottom), false, (-4, -3)),
        }
    }
}

/// A key in the legend: the mark that stands for a series.
#[derive(Clone, Copy, Debug)]
pub(super) enum Key {
    Box(RGBColor),
    Line(RGBColor),
    Dot(RGBColor),
}

/// A dashed straight line: colour, width, dash and gap (pixels).
#[derive(Clone, Copy, Debug)]
pub(super) struct Dashed {
    pub colour: RGBColor,
    pub width: u32,
    pub dash: u32,
    pub gap: u32,
}

/// A vertical line at `x` from `y0` to `y1` (a whisker).
pub(super) fn stem(x: f64, (y0, y1): (f64, f64), style: ShapeStyle) -> PathElement<(f64, f64)> {
    PathElement::new(vec![(x, y0), (x, y1)], style)
}

/// The short horizontal cap of a whisker at (`x`, `y`).
pub(super) fn cap(x: f64, y: f64, style: ShapeStyle) -> PathElement<(f64, f64)> {
    PathElement::new(vec![(x - 0.06, y), (x + 0.06, y)], style)
}

/// Gives the series just drawn its legend entry.
pub(super) fn keyed(anno: &mut Series<'_, '_>, name: &str, key: Key) {
    anno.label(name);
    match key {
        Key::Box(c) => {
            anno.legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], c.filled()))
        }
        Key::Line(c) => anno
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 14, y)], c.stroke_width(2))),
        Key::Dot(c) => anno.legend(move |(x, y)| Circle::new((x + 8, y), 5, c.filled())),
    };
}

impl<'r, 'b, X, Y> Plot<'r, 'b, X, Y>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    /// Writes `text` at data point (`x`, `y`), placed by `place`, in `colour`.
    pub(super) fn text(
        &self,
        text: &str,
        (x, y): (f64, f64),
        place: Place,
        colour: RGBColor,
    ) -> DrawResult {
        let (pos, upwards, (dx, dy)) = place.layout();
        let mut style = TextStyle::from(font(VALUE_PX)).color(&colour).pos(pos);
        if upwards {
            style = style.transform(FontTransform::Rotate270);
        }
        let (px, py) = self.at(x, y);
        self.root
            .draw(&Text::new(text.to_string(), (px + dx, py + dy), style))?;
        Ok(())
    }

    /// A dashed line through `points`; the returned annotation can key it in the legend.
    pub(super) fn dashed<I>(
        &mut self,
        points: I,
        line: Dashed,
    ) -> Result<&mut Series<'r, 'b>, Failure>
    where
        I: IntoIterator<Item = (f64, f64)>,
        I::IntoIter: Clone,
    {
        let style = line.colour.stroke_width(line.width);
        Ok(self
            .chart
            .draw_series(DashedLineSeries::new(points, line.dash, line.gap, style))?)
    }

    /// A dashed horizontal line at `y` across the plot with `note` above its left end.
    pub(super) fn reference_line(&mut self, y: f64, line: Dashed, note: &str) -> DrawResult {
        let (x0, x1) = (self.chart.x_range().start, self.chart.x_range().end);
        self.dashed([(x0, y), (x1, y)], line)?;
        self.text(note, (x0, y), Place::AboveRight, line.colour)
    }
}
