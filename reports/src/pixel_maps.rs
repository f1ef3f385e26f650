//! Per-pixel counter maps as false-colour PNGs with a legend, so that a reader sees
//! where in the picture the work goes (which pixels visit the most tree nodes, trace
//! the most rays) and how much, without other tools; and, for the report, a row of
//! maps of one counter (one per variant) on one shared colour scale with its values
//! beside them ([`shared_scale_row`]), so that the same colour is the same value in
//! every map of the row.
//!
//! Each value goes linearly from the legend's `[min, max]` onto matplotlib's viridis
//! scale: perceptually uniform (equal steps look equal), still ordered in grey and for
//! most colour-blind readers. Values outside the range are clamped; a value that is not
//! a number is grey ([`NO_DATA`]). The map is enlarged by a whole factor, nearest
//! neighbour, so one sample stays one sharp square. A band below names the counter and
//! its unit and shows the scale with its end values, in the public-domain 8x8 bitmap
//! font of `font8x8` (text in a PNG without a font rasteriser or font file).

use crate::format;
use crate::markup::escape;
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

/// Glyphs are this many font pixels wide and high.
const GLYPH: u32 = 8;
/// The legend is drawn enlarged by one whole step per this many pixels of the
/// picture's width (font pixels, gaps and bar alike): the page shows a map in a column
/// of about 300 px, so a 384 px picture (enlarged twice) keeps its text about 12 px
/// high there, a 640 px one (three times) about 11 px, where the font at its own size
/// shrank to 4 to 6 px, too small to read.
const LEGEND_SCALE_WIDTH: u32 = 192;
/// Space between the title line and the unit line.
const LINE_GAP: u32 = 2;
/// Space left and right of the legend's text and colour bar.
const MARGIN: u32 = 8;
/// Space above the title, between title and bar, and below the labels.
const GAP: u32 = 6;
/// Space between the colour bar and its labels.
const LABEL_GAP: u32 = 4;
const BAR_HEIGHT: u32 = 12;

/// Height of the legend band below the map at its own size (in font pixels): title
/// line, unit line, colour bar, value labels.
const LEGEND_UNITS: u32 =
    GAP + GLYPH + LINE_GAP + GLYPH + GAP + BAR_HEIGHT + LABEL_GAP + GLYPH + GAP;

/// How much the legend of a picture `width` pixels wide is enlarged.
fn legend_scale(width: u32) -> u32 {
    (width / LEGEND_SCALE_WIDTH).max(1)
}

/// Height of the legend band below a map in a picture `width` pixels wide.
pub fn legend_height(width: u32) -> u32 {
    LEGEND_UNITS * legend_scale(width)
}

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
    let width = map_width.max(MIN_WIDTH);
    (width, map_height.saturating_add(legend_height(width)))
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
    let k = legend_scale(width);
    let (margin, glyph) = (MARGIN * k, GLYPH * k);
    let inner_width = width.saturating_sub(2 * margin);
    let chars_across = (inner_width / glyph) as usize;

    // The title (the counter's key) on its line, its unit on the next.
    let title_y = top + GAP * k;
    draw_text(
        image,
        (margin, title_y, k),
        &fit(&legend.title, chars_across),
        TEXT,
    );
    let unit_y = title_y + (GLYPH + LINE_GAP) * k;
    draw_text(
        image,
        (margin, unit_y, k),
        &fit(&legend.unit, chars_across),
        TEXT,
    );

    let bar_y = unit_y + (GLYPH + GAP) * k;
    let bar_last = inner_width.saturating_sub(1).max(1);
    for offset in 0..inner_width {
        let colour = viridis(offset as f64 / bar_last as f64);
        fill(image, margin + offset, bar_y, 1, BAR_HEIGHT * k, colour);
    }

    // Each label gets half the width, less one character to keep them apart.
    let label_chars = (chars_across / 2).saturating_sub(1);
    let labels_y = bar_y + (BAR_HEIGHT + LABEL_GAP) * k;
    let min_label = fit(&value_label(legend.min), label_chars);
    draw_text(image, (margin, labels_y, k), &min_label, TEXT);
    let max_label = fit(&value_label(legend.max), label_chars);
    let max_label_width = max_label.chars().count() as u32 * glyph;
    let max_label_x = (margin + inner_width).saturating_sub(max_label_width);
    draw_text(image, (max_label_x, labels_y, k), &max_label, TEXT);
}

/// The least and the greatest value that is a number across `maps`: the one scale
/// that a row of maps of the same counter shares. `None` when no map has a number.
pub fn shared_range<'v>(maps: impl IntoIterator<Item = &'v [f64]>) -> Option<(f64, f64)> {
    let (lo, hi) = maps
        .into_iter()
        .flatten()
        .filter(|v| !v.is_nan())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    (lo <= hi).then_some((lo, hi))
}

/// The false-colour picture of a `columns` x `rows` map alone, without a legend, on
/// the scale from `min` to `max`, enlarged as [`false_colour`] enlarges (each sample a
/// square), so that a renderer that smooths pictures still shows sharp samples.
pub fn map_picture(values: &[f64], columns: u32, rows: u32, (min, max): (f64, f64)) -> RgbImage {
    let factor = scale_factor(columns, rows);
    let mut image = RgbImage::from_pixel(columns * factor, rows * factor, NO_DATA);
    let pixels = (0..rows).flat_map(|row| (0..columns).map(move |column| (column, row)));
    for ((column, row), index) in pixels.zip(0usize..) {
        let colour = values
            .get(index)
            .map_or(NO_DATA, |&value| colour_of(value, min, max));
        fill(
            &mut image,
            column * factor,
            row * factor,
            factor,
            factor,
            colour,
        );
    }
    image
}

/// One map of a [`shared_scale_row`]: the name above it (the variant), its values row
/// by row, and a note below it (its own mean and maximum, written by the caller).
#[derive(Clone, Debug)]
pub struct RowMap<'v> {
    pub name: String,
    pub values: &'v [f64],
    pub note: String,
}

/// A map's width in a row, pixels (a tall map is narrower: no map is taller than
/// [`ROW_MAP_MAX_HEIGHT`]).
const ROW_MAP_WIDTH: f64 = 240.0;
const ROW_MAP_MAX_HEIGHT: f64 = 240.0;
/// Space between two maps, and between the last map and the colour bar.
const ROW_GAP: f64 = 16.0;
/// Text sizes of the row's names, notes and scale labels (CSS pixels).
const ROW_TEXT_PX: f64 = 13.0;
const ROW_NOTE_PX: f64 = 11.0;
/// The colour bar's width and the room right of it for its values.
const BAR_WIDTH: f64 = 14.0;
/// Rough advance of one character of the row's sans-serif text, in ems.
const CHAR_EM: f64 = 0.6;

/// A row of maps of one counter, side by side, drawn on one colour scale from
/// `scale.min` to `scale.max` (usually [`shared_range`] of the maps), with one colour
/// bar right of the maps, outside them: the scale's unit above it, its values beside
/// it (written by `label`). An SVG (the maps embedded as PNG) and its size in pixels.
pub fn shared_scale_row(
    maps: &[RowMap<'_>],
    (columns, rows): (u32, u32),
    scale: &Legend,
    label: &dyn Fn(f64) -> String,
) -> (String, (u32, u32)) {
    let aspect = f64::from(rows.max(1)) / f64::from(columns.max(1));
    let (map_width, map_height) = if ROW_MAP_WIDTH * aspect > ROW_MAP_MAX_HEIGHT {
        (ROW_MAP_MAX_HEIGHT / aspect, ROW_MAP_MAX_HEIGHT)
    } else {
        (ROW_MAP_WIDTH, ROW_MAP_WIDTH * aspect)
    };
    let name_height = ROW_TEXT_PX + 8.0;
    let note_height = ROW_NOTE_PX + 8.0;
    let top = name_height;
    // Counts get whole ticks: a map of levels 1 to 3 is marked 1, 2, 3, not 1.5.
    let whole = maps
        .iter()
        .flat_map(|m| m.values)
        .all(|v| v.fract() == 0.0 || v.is_nan());
    let ticks = scale_ticks(scale.min, scale.max, map_height, whole);
    let labels: Vec<(f64, String)> = ticks.iter().map(|&v| (v, label(v))).collect();
    let label_width = labels
        .iter()
        .map(|(_, text)| text.chars().count() as f64 * ROW_NOTE_PX * CHAR_EM)
        .fold(0.0, f64::max);
    let unit_width = scale.unit.chars().count() as f64 * ROW_NOTE_PX * CHAR_EM;
    let count = maps.len().max(1) as f64;
    let bar_left = count * map_width + (count - 1.0) * ROW_GAP + ROW_GAP + 4.0;
    let width = (bar_left + BAR_WIDTH + 6.0 + label_width)
        .max(bar_left + unit_width)
        .ceil()
        + 4.0;
    let height = (top + map_height + note_height).ceil();
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"sans-serif\"><rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>"
    );
    let range = (scale.min, scale.max);
    for (i, map) in maps.iter().enumerate() {
        let x = i as f64 * (map_width + ROW_GAP);
        let centre = x + map_width / 2.0;
        svg += &format!(
            "<text x=\"{centre:.1}\" y=\"{:.1}\" font-size=\"{ROW_TEXT_PX}\" text-anchor=\"middle\" fill=\"#282828\">{}</text>",
            ROW_TEXT_PX,
            escape(&map.name)
        );
        let picture = map_picture(map.values, columns, rows, range);
        svg += &format!(
            "<image x=\"{x:.1}\" y=\"{top:.1}\" width=\"{map_width:.1}\" height=\"{map_height:.1}\" preserveAspectRatio=\"none\" image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{}\"/>",
            crate::markup::base64(&png_bytes(&picture))
        );
        svg += &format!(
            "<text x=\"{centre:.1}\" y=\"{:.1}\" font-size=\"{ROW_NOTE_PX}\" text-anchor=\"middle\" fill=\"#444444\">{}</text>",
            top + map_height + ROW_NOTE_PX + 4.0,
            escape(&map.note)
        );
    }
    // The colour bar: the scale's top (max) at the maps' top, its bottom (min) at
    // their bottom, in one-pixel bands.
    let steps = map_height.ceil().max(1.0) as usize;
    for step in 0..steps {
        let y = top + step as f64 * map_height / steps as f64;
        let position = 1.0 - (step as f64 + 0.5) / steps as f64;
        let Rgb([r, g, b]) = viridis(position);
        svg += &format!(
            "<rect x=\"{bar_left:.1}\" y=\"{y:.2}\" width=\"{BAR_WIDTH}\" height=\"{:.2}\" fill=\"rgb({r},{g},{b})\"/>",
            map_height / steps as f64 + 0.05
        );
    }
    svg += &format!(
        "<rect x=\"{bar_left:.1}\" y=\"{top:.1}\" width=\"{BAR_WIDTH}\" height=\"{map_height:.1}\" fill=\"none\" stroke=\"#888888\" stroke-width=\"0.5\"/>"
    );
    svg += &format!(
        "<text x=\"{bar_left:.1}\" y=\"{:.1}\" font-size=\"{ROW_NOTE_PX}\" fill=\"#282828\">{}</text>",
        ROW_NOTE_PX,
        escape(&scale.unit)
    );
    for (value, text) in &labels {
        let y = top + map_height * (1.0 - bar_position(*value, scale.min, scale.max));
        let right = bar_left + BAR_WIDTH;
        svg += &format!(
            "<line x1=\"{right:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#282828\" stroke-width=\"1\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"{ROW_NOTE_PX}\" fill=\"#282828\">{}</text>",
            right + 3.0,
            right + 5.0,
            y + ROW_NOTE_PX * 0.35,
            escape(text)
        );
    }
    svg += "</svg>";
    (svg, (width as u32, height as u32))
}

/// Where `value` stands on the bar from `min` (0) to `max` (1); the bottom when the
/// range is empty.
fn bar_position(value: f64, min: f64, max: f64) -> f64 {
    scale_position(value, min, max).unwrap_or(0.0)
}

/// The values the colour bar marks: both ends, and the round values between them (1,
/// 2 or 5 times a power of ten apart, about five in all; at least 1 apart when `whole`)
/// that stand clear of the ends on a bar `height` pixels tall.
fn scale_ticks(min: f64, max: f64, height: f64, whole: bool) -> Vec<f64> {
    if !(min.is_finite() && max.is_finite()) || max <= min {
        return if min.is_finite() {
            vec![min]
        } else {
            Vec::new()
        };
    }
    let span = max - min;
    let rough = span / 4.0;
    let decade = 10f64.powf(rough.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|s| *s >= rough)
        .unwrap_or(10.0 * decade);
    let step = if whole { step.max(1.0) } else { step };
    // Two labels closer than this many pixels would overlap.
    let clearance = span * (ROW_NOTE_PX + 2.0) / height.max(1.0);
    let mut ticks = vec![min];
    // Whole multiples of the step, each computed afresh (no sum drifting off 600).
    let first = (min / step).ceil() as i64;
    for k in first.. {
        let value = k as f64 * step;
        if value >= max {
            break;
        }
        if value - min >= clearance && max - value >= clearance {
            ticks.push(value);
        }
    }
    ticks.push(max);
    ticks
}

/// `picture` as PNG bytes (empty if encoding fails, which an in-memory RGB picture
/// does not).
fn png_bytes(picture: &RgbImage) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    match picture.write_to(&mut out, image::ImageFormat::Png) {
        Ok(()) => out.into_inner(),
        Err(_) => Vec::new(),
    }
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
fn draw_text(image: &mut RgbImage, (x, y, k): (u32, u32, u32), text: &str, colour: Rgb<u8>) {
    let step = GLYPH.saturating_mul(k);
    for (index, c) in text.chars().enumerate() {
        let glyph_x = x.saturating_add((index as u32).saturating_mul(step));
        for (row, bits) in (0u32..).zip(glyph(c)) {
            for column in 0..GLYPH {
                if bits & (1 << column) != 0 {
                    let (px, py) = (glyph_x + column * k, y.saturating_add(row * k));
                    // Each font pixel a k x k square (clipped to the picture).
                    let (w, h) = (
                        k.min(image.width().saturating_sub(px)),
                        k.min(image.height().saturating_sub(py)),
                    );
                    fill(image, px, py, w, h, colour);
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
        assert_eq!(image.height(), 8 * 24 + legend_height(384));
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
        // A 384 px picture draws its legend twice its own size: 16 px glyphs, readable
        // at the 300 px the page shows it (a 12 px font there).
        let k = 2;
        assert_eq!(legend_scale(384), k);
        assert_eq!(image.height(), band_top + LEGEND_UNITS * k);
        let (gap, glyph, margin) = (GAP * k, GLYPH * k, MARGIN * k);
        // The title line: text between the top gap and the unit line.
        let title_rows = band_top + gap..band_top + gap + glyph;
        let dark_in_title = title_rows
            .clone()
            .flat_map(|y| (0..384).map(move |x| (x, y)))
            .filter(|&(x, y)| is_dark(image.get_pixel(x, y)))
            .count();
        assert!(
            dark_in_title > 50 * k as usize,
            "{dark_in_title} dark pixels"
        );
        // The title row starts white at the left edge (the margin).
        assert_eq!(*image.get_pixel(0, title_rows.start), WHITE);

        let bar_top = title_rows.end + LINE_GAP * k + glyph + gap;
        let bar_middle = bar_top + BAR_HEIGHT * k / 2;
        assert_eq!(*image.get_pixel(margin, bar_middle), LOW);
        assert_eq!(*image.get_pixel(384 - margin - 1, bar_middle), HIGH);
        assert_eq!(*image.get_pixel(0, bar_middle), WHITE, "left margin");

        // The labels: "0" at the left, "127" ending at the right margin.
        let labels = bar_top + (BAR_HEIGHT + LABEL_GAP) * k..image.height();
        let dark_at = |xs: std::ops::Range<u32>| {
            labels
                .clone()
                .any(|y| xs.clone().any(|x| is_dark(image.get_pixel(x, y))))
        };
        assert!(dark_at(margin..margin + glyph), "min label");
        assert!(dark_at(384 - margin - glyph..384 - margin), "max label");
        assert!(!dark_at(150..234), "nothing between the labels");
        // A wider picture enlarges it more: 640 px, three times.
        assert_eq!(legend_scale(640), 3);
        assert_eq!(legend_height(640), LEGEND_UNITS * 3);
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
        assert_eq!((empty.width(), empty.height()), (384, legend_height(384)));
    }

    #[test]
    fn pixels_without_a_value_are_grey_and_extra_values_ignored() {
        // Three values for a 2 x 2 map: the last pixel has none.
        let image = false_colour(&[0.0, 1.0, 1.0], 2, 2, &legend(0.0, 1.0));
        assert_eq!(
            (image.width(), image.height()),
            (384, 384 + legend_height(384))
        );
        assert_eq!(*image.get_pixel(0, 0), LOW);
        assert_eq!(*image.get_pixel(383, 0), HIGH);
        assert_eq!(*image.get_pixel(383, 383), NO_DATA);
        // Five values for the same map: the fifth is not drawn anywhere.
        let extra = false_colour(&[0.0, 1.0, 1.0, 0.0, 0.5], 2, 2, &legend(0.0, 1.0));
        assert_eq!(*extra.get_pixel(383, 383), LOW);
        // No values and no size.
        let empty = false_colour(&[], 0, 3, &legend(0.0, 1.0));
        assert_eq!(
            (empty.width(), empty.height()),
            (384, 3 + legend_height(384))
        );
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
        draw_text(&mut image, (0, 0, 1), "{", TEXT);
        assert_eq!(glyph('{')[3], 0x07);
        assert_eq!(*image.get_pixel(0, 3), TEXT);
        assert_eq!(*image.get_pixel(2, 3), TEXT);
        assert_eq!(*image.get_pixel(7, 3), WHITE);
    }

    /// The bytes of standard base64 (RFC 4648, padded).
    fn unbase64(text: &str) -> Vec<u8> {
        const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = Vec::new();
        let (mut bits, mut held) = (0u32, 0u32);
        for c in text.bytes().filter(|&c| c != b'=') {
            let six = ALPHABET.iter().position(|&a| a == c).expect("base64") as u32;
            bits = (bits << 6) | six;
            held += 6;
            if held >= 8 {
                held -= 8;
                out.push((bits >> held) as u8);
            }
        }
        out
    }

    /// The PNG pictures a row's SVG embeds, decoded, in order.
    fn embedded_pictures(svg: &str) -> Vec<RgbImage> {
        svg.split("href=\"data:image/png;base64,")
            .skip(1)
            .map(|rest| {
                let data = rest.split('"').next().expect("closing quote");
                image::load_from_memory_with_format(&unbase64(data), image::ImageFormat::Png)
                    .expect("a PNG")
                    .to_rgb8()
            })
            .collect()
    }

    #[test]
    fn maps_of_a_row_draw_the_same_value_in_the_same_colour() {
        // Two 2 x 2 maps: the first reaches 10, the second 20; both hold a 5.
        let first = [0.0, 5.0, 10.0, 10.0];
        let second = [0.0, 5.0, 20.0, 15.0];
        let range = shared_range([&first[..], &second[..]]).expect("a range");
        assert_eq!(range, (0.0, 20.0));
        let maps = [
            RowMap {
                name: "baseline".to_string(),
                values: &first,
                note: "max 10".to_string(),
            },
            RowMap {
                name: "simd".to_string(),
                values: &second,
                note: "max 20".to_string(),
            },
        ];
        let (svg, (width, height)) =
            shared_scale_row(&maps, (2, 2), &legend(range.0, range.1), &|v| {
                format::fixed(v, 0)
            });
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>"));
        assert!(width > 2 * 240 && height > 240, "{width} x {height}");
        let pictures = embedded_pictures(&svg);
        assert_eq!(pictures.len(), 2);
        // A 2 x 2 map is enlarged 192 times: sample (column, row) is the square at
        // (192 column, 192 row).
        let at = |p: &RgbImage, column: u32, row: u32| *p.get_pixel(192 * column, 192 * row);
        // 5 is a quarter of the way up the shared scale in both maps.
        let quarter = viridis(0.25);
        assert_eq!(at(&pictures[0], 1, 0), quarter);
        assert_eq!(at(&pictures[1], 1, 0), quarter);
        // The first map's maximum (10) is the middle of the scale, not its top: only
        // the second map's 20 takes the high colour.
        assert_eq!(at(&pictures[0], 0, 1), viridis(0.5));
        assert_ne!(at(&pictures[0], 0, 1), HIGH);
        assert_eq!(at(&pictures[1], 0, 1), HIGH);
        assert_eq!(at(&pictures[0], 0, 0), LOW);
        // One colour bar, with the scale's ends and round values between them.
        for label in [
            "\">0<",
            "\">5<",
            "\">10<",
            "\">15<",
            "\">20<",
            ">nodes per sample<",
        ] {
            assert!(svg.contains(label), "{label} not in the scale");
        }
        assert!(svg.contains(">baseline<") && svg.contains(">max 20<"));
    }

    #[test]
    fn the_shared_range_skips_nan_and_needs_a_number() {
        assert_eq!(
            shared_range([&[3.0, f64::NAN][..], &[-1.0, 2.0][..]]),
            Some((-1.0, 3.0))
        );
        assert_eq!(shared_range([&[f64::NAN][..], &[][..]]), None);
    }

    #[test]
    fn the_colour_bar_marks_its_ends_and_round_values_clear_of_them() {
        // 701 over 4 is about 175: steps of 200; 600 is 101 below the top, clear of
        // it on a 240-pixel bar (a label needs 13 pixels, 38 of the scale).
        assert_eq!(
            scale_ticks(0.0, 701.0, 240.0, true),
            [0.0, 200.0, 400.0, 600.0, 701.0]
        );
        // 1 to 5 levels: steps of 1.
        assert_eq!(
            scale_ticks(1.0, 5.0, 240.0, true),
            [1.0, 2.0, 3.0, 4.0, 5.0]
        );
        // 1 to 3: steps of 0.5, unless the values are counts.
        assert_eq!(
            scale_ticks(1.0, 3.0, 240.0, false),
            [1.0, 1.5, 2.0, 2.5, 3.0]
        );
        assert_eq!(scale_ticks(1.0, 3.0, 240.0, true), [1.0, 2.0, 3.0]);
        // A round value too close to an end is left out: on a 50-pixel bar a label
        // needs 1.35 of the scale, and 4 is 1.2 below 5.2.
        assert_eq!(scale_ticks(0.0, 5.2, 50.0, false), [0.0, 2.0, 5.2]);
        assert_eq!(scale_ticks(3.0, 3.0, 240.0, true), [3.0]);
        assert!(scale_ticks(f64::NAN, 1.0, 240.0, true).is_empty());
    }
}
