//! Per-pixel counter maps as false-colour PNGs with a legend, so that a reader sees
//! where in the picture the work goes (which pixels visit the most tree nodes, trace
//! the most rays) and how much, without other tools.
//!
//! Each value goes linearly from the legend's `[min, max]` onto matplotlib's viridis
//! scale: perceptually uniform (equal steps look equal), still ordered in grey and for
//! most colour-blind readers. Values outside the range are clamped; a value that is not
//! a number is grey ([`NO_DATA`]). The map is enlarged by a whole factor, nearest
//! neighbour, so one sample stays one sharp square. A band below names the counter and
//! its unit and shows the scale with its end values, in the public-domain 8x8 bitmap
//! font of `font8x8` (text in a PNG without a font rasteriser or font file).

use crate::format;
use image::{Rgb, RgbImage};

/// What a map shows and the range of its colour scale.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The counter, e.g. `accel.nodes_visited`.
    pub title: String,
    /// What one value counts, e.g. `nodes per sample` (empty: no unit shown).
    pub unit: String,
    /// The value drawn in the scale's low colour; lower values are clamped to it.
    pub min: f64,
    /// The value drawn in the scale's high colour; higher values are clamped to it.
    pub max: f64,
}

/// The colour of a pixel whose value is not a number, or missing.
pub const NO_DATA: Rgb<u8> = Rgb([128, 128, 128]);

/// Maps narrower than this are enlarged to at least this width (unless that would
/// make them taller than [`MAX_SIDE`]), and the picture is never narrower: the legend
/// needs the room.
pub const MIN_WIDTH: u32 = 384;

/// Enlarging stops before either side of the map passes this many pixels (a map
/// already larger is drawn at one pixel per value).
pub const MAX_SIDE: u32 = 1024;

/// Key colours of matplotlib's viridis colour map (the 256-entry `_viridis_data` of
/// matplotlib's lib/matplotlib/_cm_listed.py, released CC0), sampled at 0, 0.1, ..., 1
/// and rounded to 8-bit sRGB. Linear interpolation between 11 keys stays within a few
/// levels of the full table, which a legend-read map does not need.
const VIRIDIS: [[u8; 3]; 11] = [
    [68, 1, 84],
    [72, 37, 117],
    [65, 68, 135],
    [52, 95, 141],
    [42, 120, 142],
    [33, 144, 140],
    [34, 168, 132],
    [67, 191, 113],
    [122, 209, 81],
    [188, 223, 39],
    [253, 231, 37],
];

const WHITE: Rgb<u8> = Rgb([255, 255, 255]);
const TEXT: Rgb<u8> = Rgb([0, 0, 0]);

/// Glyphs are this many pixels wide and high.
const GLYPH: u32 = 8;
/// Space left and right of the legend's text and colour bar.
const MARGIN: u32 = 8;
/// Space above the title, between title and bar, and below the labels.
const GAP: u32 = 6;
/// Space between the colour bar and its labels.
const LABEL_GAP: u32 = 4;
const BAR_HEIGHT: u32 = 12;

/// Height of the legend band below the map: title line, colour bar, value labels.
pub const LEGEND_HEIGHT: u32 = GAP + GLYPH + GAP + BAR_HEIGHT + LABEL_GAP + GLYPH + GAP;

/// The false-colour picture of a `columns` x `rows` map whose `values` are given row
/// by row, with its legend band below.
///
/// `values` should hold `columns * rows` values; pixels past its end are drawn as
/// [`NO_DATA`] and values past the last pixel are ignored (a picture with a visible
/// hole rather than a panic). The map is enlarged by the smallest whole factor that
/// makes it [`MIN_WIDTH`] wide, unless that would take a side past [`MAX_SIDE`]. If
/// the scale's range is empty or not finite (`max == min`, a NaN bound) every value
/// that is a number takes the low colour.
pub fn false_colour(values: &[f64], columns: u32, rows: u32, legend: &Legend) -> RgbImage {
    let factor = scale_factor(columns, rows);
    // No overflow: a factor above 1 keeps each side within MAX_SIDE.
    let (map_width, map_height) = (columns * factor, rows * factor);
    let (width, height) = picture_size(columns, rows);
    let mut image = RgbImage::from_pixel(width, height, WHITE);

    // A map narrower than the legend sits in the middle.
    let left = (width - map_width) / 2;
    let pixels = (0..rows).flat_map(|row| (0..columns).map(move |column| (column, row)));
    for ((column, row), index) in pixels.zip(0usize..) {
        let colour = values
            .get(index)
            .map_or(NO_DATA, |&value| colour_of(value, legend.min, legend.max));
        fill(
            &mut image,
            left + column * factor,
            row * factor,
            factor,
            factor,
            colour,
        );
    }
    draw_legend(&mut image, map_height, legend);
    image
}

/// The size in pixels of [`false_colour`]'s picture of a `columns` x `rows` map, its
/// legend included (what a report needs to lay the picture out before reading it).
pub fn picture_size(columns: u32, rows: u32) -> (u32, u32) {
    let factor = scale_factor(columns, rows);
    let (map_width, map_height) = (columns * factor, rows * factor);
    (
        map_width.max(MIN_WIDTH),
        map_height.saturating_add(LEGEND_HEIGHT),
    )
}

/// The whole enlargement of a `columns` x `rows` map (see [`false_colour`]).
fn scale_factor(columns: u32, rows: u32) -> u32 {
    if columns == 0 || columns >= MIN_WIDTH {
        return 1;
    }
    let to_min_width = MIN_WIDTH.div_ceil(columns);
    // Reaching MIN_WIDTH alone never passes MAX_SIDE across (ceil(384 / c) * c < 768);
    // the bound matters for a tall, narrow map, which would become a tower.
    let within_max_side = (MAX_SIDE / columns).min(MAX_SIDE / rows.max(1));
    to_min_width.min(within_max_side).max(1)
}

/// Where `value` lies on the scale from `min` (0) to `max` (1), clamped; `None` when it
/// is not a number.
fn scale_position(value: f64, min: f64, max: f64) -> Option<f64> {
    if value.is_nan() {
        return None;
    }
    let span = max - min;
    if span == 0.0 || !span.is_finite() {
        return Some(0.0);
    }
    // min and span are finite here, so an infinite value gives an infinite position
    // (never NaN), which the clamp takes to an end.
    Some(((value - min) / span).clamp(0.0, 1.0))
}

/// The colour of `value` on the scale from `min` to `max`.
fn colour_of(value: f64, min: f64, max: f64) -> Rgb<u8> {
    scale_position(value, min, max).map_or(NO_DATA, viridis)
}

/// The viridis colour at `position` in [0, 1], interpolated between the key colours.
fn viridis(position: f64) -> Rgb<u8> {
    let last = VIRIDIS.len() - 1;
    let scaled = position.clamp(0.0, 1.0) * last as f64;
    // At position 1 the segment is the last one, at its end.
    let segment = (scaled.floor() as usize).min(last - 1);
    let along = scaled - segment as f64;
    let (from, to) = (VIRIDIS[segment], VIRIDIS[segment + 1]);
    Rgb(std::array::from_fn(|channel| {
        let (a, b) = (from[channel] as f64, to[channel] as f64);
        (a + (b - a) * along).round() as u8
    }))
}

/// Fills the `width` x `height` rectangle at (`x`, `y`), clipped to the image.
fn fill(image: &mut RgbImage, x: u32, y: u32, width: u32, height: u32, colour: Rgb<u8>) {
    let x_end = x.saturating_add(width).min(image.width());
    let y_end = y.saturating_add(height).min(image.height());
    for py in y..y_end {
        for px in x..x_end {
            image.put_pixel(px, py, colour);
        }
    }
}

/// Draws the legend band that starts at row `top`: the title and unit, the colour bar
/// across the width, and the scale's end values under its ends.
fn draw_legend(image: &mut RgbImage, top: u32, legend: &Legend) {
    let width = image.width();
    let inner_width = width.saturating_sub(2 * MARGIN);
    let chars_across = (inner_width / GLYPH) as usize;

    let title_y = top + GAP;
    let title = if legend.unit.is_empty() {
        legend.title.clone()
    } else {
        format!("{} ({})", legend.title, legend.unit)
    };
    draw_text(image, MARGIN, title_y, &fit(&title, chars_across), TEXT);

    let bar_y = title_y + GLYPH + GAP;
    let bar_last = inner_width.saturating_sub(1).max(1);
    for offset in 0..inner_width {
        let colour = viridis(offset as f64 / bar_last as f64);
        fill(image, MARGIN + offset, bar_y, 1, BAR_HEIGHT, colour);
    }

    // Each label gets half the width, less one character to keep them apart.
    let label_chars = (chars_across / 2).saturating_sub(1);
    let labels_y = bar_y + BAR_HEIGHT + LABEL_GAP;
    let min_label = fit(&value_label(legend.min), label_chars);
    draw_text(image, MARGIN, labels_y, &min_label, TEXT);
    let max_label = fit(&value_label(legend.max), label_chars);
    let max_label_width = max_label.chars().count() as u32 * GLYPH;
    let max_label_x = (MARGIN + inner_width).saturating_sub(max_label_width);
    draw_text(image, max_label_x, labels_y, &max_label, TEXT);
}

/// `text` cut to `max_chars` characters, ending in "..." when cut.
fn fit(text: &str, max_chars: usize) -> String {
    const ELLIPSIS: &str = "...";
    if text.chars().count() <= max_chars {
        return text.to_string();
    }
    if max_chars < ELLIPSIS.len() {
        return ELLIPSIS[..max_chars].to_string();
    }
    let kept: String = text.chars().take(max_chars - ELLIPSIS.len()).collect();
    kept + ELLIPSIS
}

/// A scale end as the legend prints it: an integer without decimals (thousands
/// grouped, as the reports write counts), otherwise three significant digits.
fn value_label(value: f64) -> String {
    // Below 1e18 an integral f64 converts to u64 exactly.
    if value.fract() == 0.0 && value.abs() < 1e18 {
        let magnitude = format::count(value.abs() as u64);
        return if value < 0.0 {
            format!("-{magnitude}")
        } else {
            magnitude
        };
    }
    // The decimal exponent after rounding to three digits (0.09996 is 0.100, e-1).
    let exponent = format!("{value:.2e}")
        .rsplit_once('e')
        .and_then(|(_, exponent)| exponent.parse::<i32>().ok());
    match exponent {
        // format::significant keeps three significant digits from 1 up; below 1 it
        // stops at two decimals, so smaller values take the decimals they need here.
        Some(exponent) if exponent < 0 => format::fixed(value, (2 - exponent) as usize),
        // Also infinities and NaN, which print as format::DASH.
        _ => format::significant(value),
    }
}

/// The 8x8 glyph of `c`: ASCII and Latin-1 from the font; dashes as '-', anything else
/// as '?'. Each byte is a row from the top, bit 0 its leftmost pixel.
fn glyph(c: char) -> [u8; 8] {
    use font8x8::legacy::{BASIC_LEGACY, LATIN_LEGACY};
    let code = c as usize;
    match code {
        0..=0x7f => BASIC_LEGACY[code],
        0xa0..=0xff => LATIN_LEGACY[code - 0xa0],
        // En dash (format::DASH), em dash, minus sign.
        0x2013 | 0x2014 | 0x2212 => BASIC_LEGACY[b'-' as usize],
        _ => BASIC_LEGACY[b'?' as usize],
    }
}

/// Draws `text` with its top-left corner at (`x`, `y`), clipped to the image.
fn draw_text(image: &mut RgbImage, x: u32, y: u32, text: &str, colour: Rgb<u8>) {
    for (index, c) in text.chars().enumerate() {
        let glyph_x = x.saturating_add((index as u32).saturating_mul(GLYPH));
        for (row, bits) in (0u32..).zip(glyph(c)) {
            for column in 0..GLYPH {
                if bits & (1 << column) != 0 {
                    let (px, py) = (glyph_x.saturating_add(column), y.saturating_add(row));
                    if px < image.width() && py < image.height() {
                        image.put_pixel(px, py, colour);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Viridis at 0 and at 1 (matplotlib's first and last table entries in 8 bits).
    const LOW: Rgb<u8> = Rgb([68, 1, 84]);
    const HIGH: Rgb<u8> = Rgb([253, 231, 37]);

    fn legend(min: f64, max: f64) -> Legend {
        Legend {
            title: "accel.nodes_visited".to_string(),
            unit: "nodes per sample".to_string(),
            min,
            max,
        }
    }

    /// A 16 x 8 map rising from 0 at the top-left to 127 at the bottom-right.
    fn ramp_16x8() -> Vec<f64> {
        (0..16 * 8).map(f64::from).collect()
    }

    fn is_dark(p: &Rgb<u8>) -> bool {
        p.0.iter().all(|&channel| channel < 64)
    }

    #[test]
    fn a_16x8_map_is_enlarged_24_times_to_384_wide() {
        let image = false_colour(&ramp_16x8(), 16, 8, &legend(0.0, 127.0));
        assert_eq!(image.width(), 384);
        assert_eq!(image.height(), 8 * 24 + LEGEND_HEIGHT);
        // Each value is one 24 x 24 square: the square's corners agree.
        assert_eq!(image.get_pixel(24, 0), image.get_pixel(47, 23));
        assert_ne!(image.get_pixel(23, 0), image.get_pixel(24, 0));
    }

    #[test]
    fn the_picture_size_is_known_before_drawing() {
        // Small (enlarged), narrower than the legend, tall and the SPD's corner grid.
        for (columns, rows) in [(16, 8), (3, 40), (40, 600), (513, 513), (320, 240)] {
            let values = vec![1.0; (columns * rows) as usize];
            let image = false_colour(&values, columns, rows, &legend(0.0, 2.0));
            assert_eq!(
                picture_size(columns, rows),
                (image.width(), image.height()),
                "{columns}x{rows}"
            );
        }
    }

    #[test]
    fn enlargement_reaches_384_wide_and_stays_within_1024() {
        assert_eq!(scale_factor(16, 8), 24);
        assert_eq!(
            scale_factor(100, 75),
            4,
            "400 wide, the first whole factor past 384"
        );
        assert_eq!(scale_factor(384, 384), 1);
        assert_eq!(
            scale_factor(2000, 10),
            1,
            "wider than 1024 already: not shrunk"
        );
        assert_eq!(scale_factor(1, 1), 384);
        assert_eq!(
            scale_factor(1, 600),
            1,
            "a column stays a column, not a tower"
        );
        assert_eq!(scale_factor(0, 0), 1);
    }

    #[test]
    fn the_scale_ends_get_viridis_first_and_last_colours() {
        let image = false_colour(&ramp_16x8(), 16, 8, &legend(0.0, 127.0));
        assert_eq!(*image.get_pixel(0, 0), LOW, "value 0 = min");
        assert_eq!(*image.get_pixel(383, 191), HIGH, "value 127 = max");
    }

    #[test]
    fn values_between_key_colours_are_interpolated() {
        // 13 of [0, 100] is 0.13: 30% of the way from the key at 0.1 (72, 37, 117) to
        // the key at 0.2 (65, 68, 135): 69.9, 46.3, 122.4.
        assert_eq!(colour_of(13.0, 0.0, 100.0), Rgb([70, 46, 122]));
        // The middle is the key at 0.5.
        assert_eq!(colour_of(50.0, 0.0, 100.0), Rgb([33, 144, 140]));
    }

    #[test]
    fn values_outside_the_range_are_clamped_and_nan_is_grey() {
        assert_eq!(colour_of(-5.0, 0.0, 10.0), LOW);
        assert_eq!(colour_of(1e300, 0.0, 10.0), HIGH);
        assert_eq!(colour_of(f64::INFINITY, 0.0, 10.0), HIGH);
        assert_eq!(colour_of(f64::NAN, 0.0, 10.0), Rgb([128, 128, 128]));

        let mut values = vec![1.0; 4];
        values[0] = f64::NAN;
        let image = false_colour(&values, 2, 2, &legend(0.0, 1.0));
        assert_eq!(*image.get_pixel(0, 0), Rgb([128, 128, 128]));
        assert_eq!(*image.get_pixel(255, 255), HIGH);
    }

    #[test]
    fn an_empty_range_draws_everything_in_the_low_colour() {
        let image = false_colour(&[3.0, 4.0, 5.0, 3.0], 2, 2, &legend(3.0, 3.0));
        assert_eq!(*image.get_pixel(0, 0), LOW);
        assert_eq!(*image.get_pixel(255, 255), LOW);
        assert_eq!(colour_of(1.0, f64::NAN, 2.0), LOW);
        assert_eq!(colour_of(f64::NAN, 3.0, 3.0), NO_DATA);
    }

    #[test]
    fn the_legend_has_a_title_and_a_colour_bar_from_low_to_high() {
        let image = false_colour(&ramp_16x8(), 16, 8, &legend(0.0, 127.0));
        let band_top = 192;
        // The title line: text between the top gap and the bar.
        let title_rows = band_top + GAP..band_top + GAP + GLYPH;
        let dark_in_title = title_rows
            .clone()
            .flat_map(|y| (0..384).map(move |x| (x, y)))
            .filter(|&(x, y)| is_dark(image.get_pixel(x, y)))
            .count();
        assert!(dark_in_title > 50, "{dark_in_title} dark pixels");
        // The title row starts white at the left edge (the margin).
        assert_eq!(*image.get_pixel(0, title_rows.start), WHITE);

        let bar_middle = band_top + GAP + GLYPH + GAP + BAR_HEIGHT / 2;
        assert_eq!(*image.get_pixel(MARGIN, bar_middle), LOW);
        assert_eq!(*image.get_pixel(384 - MARGIN - 1, bar_middle), HIGH);
        assert_eq!(*image.get_pixel(0, bar_middle), WHITE, "left margin");

        // The labels: "0" at the left, "127" ending at the right margin.
        let labels = bar_middle + BAR_HEIGHT / 2 + LABEL_GAP..image.height();
        let dark_at = |xs: std::ops::Range<u32>| {
            labels
                .clone()
                .any(|y| xs.clone().any(|x| is_dark(image.get_pixel(x, y))))
        };
        assert!(dark_at(MARGIN..MARGIN + GLYPH), "min label");
        assert!(dark_at(384 - MARGIN - GLYPH..384 - MARGIN), "max label");
        assert!(!dark_at(150..234), "nothing between the labels");
    }

    #[test]
    fn text_too_long_for_the_width_is_cut_with_dots() {
        assert_eq!(fit("accel.nodes_visited", 30), "accel.nodes_visited");
        assert_eq!(fit("abcdefghij", 6), "abc...");
        assert_eq!(fit("abcdefghij", 2), "..");
        assert_eq!(fit("abcdefghij", 0), "");
        let long = Legend {
            title: "x".repeat(500),
            unit: "µs per sample – ∞".repeat(20),
            min: -1e300,
            max: f64::NAN,
        };
        let image = false_colour(&[1.0], 1, 1, &long);
        assert_eq!(image.width(), 384);
        // A map of nothing still gets its legend.
        let empty = false_colour(&[], 0, 0, &long);
        assert_eq!((empty.width(), empty.height()), (384, LEGEND_HEIGHT));
    }

    #[test]
    fn pixels_without_a_value_are_grey_and_extra_values_ignored() {
        // Three values for a 2 x 2 map: the last pixel has none.
        let image = false_colour(&[0.0, 1.0, 1.0], 2, 2, &legend(0.0, 1.0));
        assert_eq!((image.width(), image.height()), (384, 384 + LEGEND_HEIGHT));
        assert_eq!(*image.get_pixel(0, 0), LOW);
        assert_eq!(*image.get_pixel(383, 0), HIGH);
        assert_eq!(*image.get_pixel(383, 383), NO_DATA);
        // Five values for the same map: the fifth is not drawn anywhere.
        let extra = false_colour(&[0.0, 1.0, 1.0, 0.0, 0.5], 2, 2, &legend(0.0, 1.0));
        assert_eq!(*extra.get_pixel(383, 383), LOW);
        // No values and no size.
        let empty = false_colour(&[], 0, 3, &legend(0.0, 1.0));
        assert_eq!((empty.width(), empty.height()), (384, 3 + LEGEND_HEIGHT));
    }

    #[test]
    fn labels_print_integers_whole_and_fractions_with_three_digits() {
        assert_eq!(value_label(0.0), "0");
        assert_eq!(value_label(127.0), "127");
        assert_eq!(value_label(1_234_567.0), "1,234,567");
        assert_eq!(value_label(-42.0), "-42");
        assert_eq!(value_label(4.56789), "4.57");
        assert_eq!(value_label(12.345), "12.3");
        assert_eq!(value_label(0.123456), "0.123");
        assert_eq!(value_label(0.0012345), "0.00123");
        assert_eq!(value_label(0.099996), "0.100");
        assert_eq!(value_label(f64::NAN), format::DASH);
    }

    #[test]
    fn glyphs_come_from_the_font_with_bit_0_leftmost() {
        assert_eq!(glyph('1'), font8x8::legacy::BASIC_LEGACY[b'1' as usize]);
        assert_eq!(glyph('–'), glyph('-'));
        assert_eq!(glyph('∞'), glyph('?'));
        // '{' points left at its middle: row 3 is 0x07, bits 0-2, so the leftmost
        // three pixels are drawn there and the right side is empty.
        let mut image = RgbImage::from_pixel(8, 8, WHITE);
        draw_text(&mut image, 0, 0, "{", TEXT);
        assert_eq!(glyph('{')[3], 0x07);
        assert_eq!(*image.get_pixel(0, 3), TEXT);
        assert_eq!(*image.get_pixel(2, 3), TEXT);
        assert_eq!(*image.get_pixel(7, 3), WHITE);
    }
}
