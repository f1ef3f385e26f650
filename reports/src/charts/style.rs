//! The charts' look: size, text sizes, fonts, colours and the grid.

use plotters::prelude::*;

/// Default chart size, pixels.
pub(super) const WIDTH: u32 = 800;
pub(super) const HEIGHT: u32 = 420;

/// Text sizes in CSS pixels.
pub(super) const TITLE_PX: f64 = 16.0;
pub(super) const AXIS_TITLE_PX: f64 = 13.0;
pub(super) const TICK_PX: f64 = 12.0;
pub(super) const VALUE_PX: f64 = 11.0;

/// Series colours: first the colour-blind-safe Okabe-Ito set (without the yellow that
/// vanishes on white), then darker, distinct hues, so that a suite's dozen variants
/// (the default runs ten) never share a colour in one chart.
pub(super) const PALETTE: [RGBColor; 12] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(120, 120, 120),
    RGBColor(102, 61, 170),
    RGBColor(140, 140, 0),
    RGBColor(0, 90, 90),
    RGBColor(160, 40, 70),
    RGBColor(110, 70, 20),
];
pub(super) const INK: RGBColor = RGBColor(40, 40, 40);
pub(super) const BASELINE_INK: RGBColor = RGBColor(30, 30, 30);
/// Reference lines that mark a limit the data must not cross (device capacity).
pub(super) const ALARM: RGBColor = RGBColor(200, 0, 0);
/// Guide lines behind the data (bands, break-even of the scatter).
pub(super) const GUIDE: RGBColor = RGBColor(150, 150, 150);
/// Text of the guide lines.
pub(super) const GUIDE_TEXT: RGBColor = RGBColor(110, 110, 110);
/// The legend's frame.
pub(super) const LEGEND_BORDER: RGBColor = RGBColor(180, 180, 180);

/// A font of `px` CSS pixels. Plotters' SVG backend writes `font-size = size / 1.24`.
pub(super) fn font(px: f64) -> FontDesc<'static> {
    ("sans-serif", px * 1.24).into_font()
}

/// The mesh's lines: faint, so the data stands out.
pub(super) fn grid_style() -> ShapeStyle {
    RGBColor(0, 0, 0).mix(0.1).stroke_width(1)
}

/// Rough width of `text` at `px` (sans-serif averages about 0.55 em per character; 0.6
/// leaves a margin).
pub(super) fn text_width(text: &str, px: f64) -> f64 {
    text.chars().count() as f64 * px * 0.6
}

/// The widest of `texts` at `px`.
pub(super) fn widest<'t>(texts: impl IntoIterator<Item = &'t str>, px: f64) -> f64 {
    texts
        .into_iter()
        .map(|t| text_width(t, px))
        .fold(0.0, f64::max)
}

/// The colour of a variant from its place among the run's other variants (`None` for
/// the reference, which is dark).
pub(super) fn variant_colour(place: Option<usize>) -> RGBColor {
    match place {
        None => BASELINE_INK,
        Some(i) => PALETTE[i % PALETTE.len()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_colours_are_distinct_and_none_is_the_reference_ink() {
        for (i, a) in PALETTE.iter().enumerate() {
            assert_ne!(*a, BASELINE_INK);
            for b in &PALETTE[i + 1..] {
                // At least 60 apart in the sum of channel differences: tellable apart.
                let d =
                    a.0.abs_diff(b.0) as u32 + a.1.abs_diff(b.1) as u32 + a.2.abs_diff(b.2) as u32;
                assert!(d >= 60, "{a:?} and {b:?}");
            }
        }
    }
}
