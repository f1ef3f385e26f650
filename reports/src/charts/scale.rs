//! Axis ranges and tick labels: what range a chart's data needs and how its ticks read.

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::{IntoLogRange, LogCoord};

use super::numbers::format_number;
use super::style::{AXIS_TITLE_PX, TICK_PX};

pub(super) fn finite_positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// The finite positive minimum and maximum of `values`, if there is one.
fn positive_extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| finite_positive(*v))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// Lower and upper decade around positive `values` (for log axes).
pub(super) fn log_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = positive_extent(values)?;
    let lo = 10f64.powf(lo.log10().floor());
    let hi = 10f64.powf(hi.log10().ceil());
    Some((lo, if hi <= lo { lo * 10.0 } else { hi }))
}

/// A log range hugging positive `values` (a factor of 1.5 each side), so the data
/// fills the plot; the 1-2-5 labels of [`log_label`] mark it.
pub(super) fn tight_log_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    positive_extent(values).map(|(lo, hi)| (lo / 1.5, hi * 1.5))
}

/// A label for a log axis: only at mantissas 1, 2 and 5, so labels never crowd.
pub(super) fn log_label(v: f64, suffix: &str) -> String {
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
pub(super) fn log_labeller(suffix: &'static str) -> impl Fn(&f64) -> String {
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

/// The room under a plot for one line of tick labels and the axis title.
pub(super) const X_ROOM: u32 = (TICK_PX + 14.0 + AXIS_TITLE_PX * 2.0) as u32;

/// How an axis is ticked and labelled.
#[derive(Clone, Copy, Debug)]
pub(super) enum Ticks {
    /// Neither ticks nor grid lines: the chart writes its category labels itself.
    Categories,
    /// Numbers by [`format_number`].
    Numbers,
    /// Whole numbers.
    Whole,
    /// The 1-2-5 labels of [`log_label`] with a unit suffix, out of `candidates`
    /// points (more candidates reach the 2 and 5 of each decade).
    Log {
        suffix: &'static str,
        candidates: Option<usize>,
    },
}

impl Ticks {
    /// The label of value `v` on this axis (not for [`Ticks::Log`], whose labeller keeps
    /// state).
    pub(super) fn plain_label(self, v: f64) -> String {
        match self {
            Ticks::Numbers => format_number(v),
            // Only the whole numbers among the ticks (a range of a few units gets ticks
            // at halves too), and 0 never as "-0".
            Ticks::Whole if (v - v.round()).abs() < 1e-9 => format!("{:.0}", v.round() + 0.0),
            Ticks::Whole => String::new(),
            Ticks::Categories | Ticks::Log { .. } => String::new(),
        }
    }
}

/// One axis of a plot: its range, how it is labelled, its title and the room for its
/// labels (pixels beside the plot: below it for x, left of it for y).
pub(super) struct Axis<'t, R> {
    pub range: R,
    pub ticks: Ticks,
    pub title: &'t str,
    pub room: u32,
}

impl<'t> Axis<'t, RangedCoordf64> {
    /// A linear axis from `lo` to `hi`.
    pub(super) fn linear(lo: f64, hi: f64, ticks: Ticks, title: &'t str, room: u32) -> Self {
        Axis {
            range: (lo..hi).into(),
            ticks,
            title,
            room,
        }
    }

    /// A category axis: `n` slots at 0, 1, …, n - 1.
    pub(super) fn categories(n: usize, title: &'t str, room: u32) -> Self {
        Axis::linear(-0.5, n as f64 - 0.5, Ticks::Categories, title, room)
    }
}

impl<'t> Axis<'t, LogCoord<f64>> {
    /// A log axis from `lo` to `hi`, labelled 1-2-5 with `suffix`.
    pub(super) fn log(
        (lo, hi): (f64, f64),
        suffix: &'static str,
        candidates: Option<usize>,
        title: &'t str,
        room: u32,
    ) -> Self {
        // A hair wider: plotters finds the first decade as 10^ceil(ln(lo) / ln(10)),
        // which for lo = 0.1 rounds to 10^0 and leaves the decade below 1 unlabelled.
        let (lo, hi) = (lo * (1.0 - 1e-9), hi * (1.0 + 1e-9));
        Axis {
            range: (lo..hi).log_scale().into(),
            ticks: Ticks::Log { suffix, candidates },
            title,
            room,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_number_ticks_label_only_whole_numbers() {
        let labels: Vec<String> = [-0.4, 0.0, 0.5, 1.0, 1.5, 12.0]
            .map(|v| Ticks::Whole.plain_label(v))
            .to_vec();
        assert_eq!(labels, ["", "0", "", "1", "", "12"]);
        assert_eq!(Ticks::Whole.plain_label(-0.0), "0");
    }

    #[test]
    fn log_ranges_span_whole_decades_or_hug_the_data() {
        assert_eq!(log_range([3.0, 40.0, f64::NAN, -1.0]), Some((1.0, 100.0)));
        assert_eq!(log_range([10.0]), Some((10.0, 100.0)));
        assert_eq!(log_range([0.0, f64::INFINITY]), None);
        assert_eq!(tight_log_range([3.0, 30.0]), Some((2.0, 45.0)));
    }

    #[test]
    fn log_labels_mark_one_two_five_once_each() {
        let label = log_labeller("×");
        let texts: Vec<String> = [1.0, 2.0, 3.0, 5.0, 10.0, 10.0, 20_000.0]
            .iter()
            .map(&label)
            .collect();
        assert_eq!(texts, ["1×", "2×", "", "5×", "10×", "", "20k×"]);
    }
}
