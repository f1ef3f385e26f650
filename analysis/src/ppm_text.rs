//! Method 2 of the thesis: histograms taken from the plain-text PPM (P3) form of a
//! render, plus writing and parsing that form.

use std::ops::RangeInclusive;

use serde::{Deserialize, Serialize};

use crate::error::MetricsError;
use crate::image_metrics::{RgbImage, gray_histogram};

/// Largest image `parse_p3` accepts (64 Mi pixels), checked before allocating.
pub const MAX_P3_PIXELS: u64 = 64 * 1024 * 1024;

/// The Netpbm spec asks plain-format lines to stay within 70 characters.
const MAX_LINE: usize = 70;

/// Per-channel and gray (Rec. 601 luma) histograms, 256 bins each.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct P3Histograms {
    pub red: Vec<u64>,
    pub green: Vec<u64>,
    pub blue: Vec<u64>,
    pub gray: Vec<u64>,
}

/// Writes `img` as plain PPM with maxval 255.
pub fn to_p3(img: &RgbImage) -> String {
    let mut text = format!("P3\n{} {}\n255\n", img.width, img.height);
    let mut line_len = 0;
    for value in &img.data {
        let token = value.to_string();
        if line_len > 0 && line_len + 1 + token.len() > MAX_LINE {
            text.push('\n');
            line_len = 0;
        }
        if line_len > 0 {
            text.push(' ');
            line_len += 1;
        }
        text.push_str(&token);
        line_len += token.len();
    }
    text.push('\n');
    text
}

/// Parses plain PPM. `#` starts a comment up to the end of the line; samples are
/// rescaled from `0..=maxval` to `0..=255`, rounding to nearest.
pub fn parse_p3(text: &str) -> Result<RgbImage, MetricsError> {
    let end_line = text.lines().count().max(1);
    let mut tokens = text.lines().enumerate().flat_map(|(index, line)| {
        let without_comment = line.split('#').next().unwrap_or("");
        without_comment
            .split_whitespace()
            .map(move |token| (index + 1, token))
    });
    match tokens.next() {
        Some((_, "P3")) => {}
        Some((line, other)) => {
            return Err(p3_error(
                line,
                format!("expected magic number P3, found {other:?}"),
            ));
        }
        None => return Err(p3_error(1, "empty input, expected magic number P3".into())),
    }
    let mut header = |what: &str, range: RangeInclusive<u64>| match tokens.next() {
        Some((line, token)) => parse_in(line, token, what, range),
        None => Err(p3_error(end_line, format!("input ends before the {what}"))),
    };
    let width = header("width", 0..=u64::from(u32::MAX))?;
    let height = header("height", 0..=u64::from(u32::MAX))?;
    let maxval = header("maxval", 1..=65535)?;

    // Both factors are below 2^32, so the product cannot overflow.
    if width * height > MAX_P3_PIXELS {
        return Err(MetricsError::TooLarge {
            width,
            height,
            limit: MAX_P3_PIXELS,
        });
    }
    let expected = 3 * width * height;
    // Every sample takes at least two bytes of text, which bounds a lying header.
    let mut data = Vec::with_capacity((expected as usize).min(text.len() / 2));
    for read in 0..expected {
        let Some((line, token)) = tokens.next() else {
            return Err(p3_error(
                end_line,
                format!("expected {expected} samples, found only {read}"),
            ));
        };
        let value = parse_in(line, token, "sample", 0..=maxval)?;
        // value <= maxval, so the rounded quotient is at most 255.
        data.push(((value * 255 + maxval / 2) / maxval) as u8);
    }
    if let Some((line, token)) = tokens.next() {
        return Err(p3_error(
            line,
            format!("more than {expected} samples, unexpected {token:?}"),
        ));
    }
    // Width and height are at most 64 Mi here, so they fit in u32.
    RgbImage::new(width as u32, height as u32, data)
}

/// Red, green, blue and gray histograms of the samples in a plain PPM text.
pub fn p3_histograms(text: &str) -> Result<P3Histograms, MetricsError> {
    let img = parse_p3(text)?;
    let mut channels = [vec![0u64; 256], vec![0u64; 256], vec![0u64; 256]];
    for pixel in img.data.chunks_exact(3) {
        for (bins, &value) in channels.iter_mut().zip(pixel) {
            bins[usize::from(value)] += 1;
        }
    }
    let [red, green, blue] = channels;
    Ok(P3Histograms {
        red,
        green,
        blue,
        gray: gray_histogram(&img).to_vec(),
    })
}

fn parse_in(
    line: usize,
    token: &str,
    what: &str,
    range: RangeInclusive<u64>,
) -> Result<u64, MetricsError> {
    match token.parse::<u64>() {
        Ok(n) if range.contains(&n) => Ok(n),
        _ => Err(p3_error(
            line,
            format!(
                "{what} must be an integer in {}..={}, found {token:?}",
                range.start(),
                range.end()
            ),
        )),
    }
}

fn p3_error(line: usize, problem: String) -> MetricsError {
    MetricsError::P3 { line, problem }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_image() -> RgbImage {
        let data = (0..30u32 * 7 * 3).map(|i| (i * 37 % 256) as u8).collect();
        RgbImage::new(30, 7, data).expect("valid image")
    }

    fn error_line(result: Result<RgbImage, MetricsError>) -> usize {
        match result {
            Err(MetricsError::P3 { line, .. }) => line,
            other => panic!("expected a P3 error, got {other:?}"),
        }
    }

    #[test]
    fn round_trip_is_identity_and_lines_are_short() {
        let img = sample_image();
        let text = to_p3(&img);
        assert!(text.starts_with("P3\n30 7\n255\n"));
        assert!(text.lines().all(|l| l.len() <= MAX_LINE));
        assert_eq!(parse_p3(&text).expect("parse"), img);
    }

    #[test]
    fn text_histograms_equal_binary_histograms() {
        let img = sample_image();
        let h = p3_histograms(&to_p3(&img)).expect("parse");
        assert_eq!(h.gray, gray_histogram(&img).to_vec());
        let pixels = img.pixel_count();
        for (channel, bins) in [&h.red, &h.green, &h.blue].into_iter().enumerate() {
            assert_eq!(bins.iter().sum::<u64>(), pixels);
            let count_of_7 = img
                .data
                .iter()
                .skip(channel)
                .step_by(3)
                .filter(|&&v| v == 7);
            assert_eq!(bins[7], count_of_7.count() as u64);
        }
    }

    #[test]
    fn comments_whitespace_and_maxval_are_handled() {
        // maxval 15: samples scale by 255/15 = 17 exactly.
        let text = "P3 # magic\n# a comment line\n2\t1\r\n15\n0 1 2#trailing\n  15 14 3\n";
        let img = parse_p3(text).expect("parse");
        assert_eq!((img.width, img.height), (2, 1));
        assert_eq!(img.data, vec![0, 17, 34, 255, 238, 51]);
        let h = p3_histograms(text).expect("parse");
        assert_eq!(
            (h.red[0], h.red[255], h.green[238], h.blue[51]),
            (1, 1, 1, 1)
        );
    }

    #[test]
    fn errors_carry_line_numbers() {
        assert_eq!(error_line(parse_p3("P6\n1 1\n255\n0 0 0\n")), 1);
        assert_eq!(error_line(parse_p3("P3\n1 1\n255\n0 x 0\n")), 4);
        assert_eq!(error_line(parse_p3("P3\n1 1\n255\n0 0 256\n")), 4);
        assert_eq!(error_line(parse_p3("P3\n1 1\n0\n0 0 0\n")), 3);
        assert_eq!(error_line(parse_p3("P3\n1 1\n65536\n0 0 0\n")), 3);
        // Too few values: reported at the last line; too many: at the extra value.
        assert_eq!(error_line(parse_p3("P3\n1 1\n255\n0 0\n")), 4);
        assert_eq!(error_line(parse_p3("P3\n1 1\n255\n0 0 0\n\n9\n")), 6);
        assert_eq!(error_line(parse_p3("")), 1);
        assert_eq!(error_line(parse_p3("P3\n# only a comment\n")), 2);
    }

    #[test]
    fn oversized_and_empty_headers_are_refused_before_reading_samples() {
        let huge = parse_p3("P3\n65536 65536\n255\n0 0 0\n");
        assert!(matches!(huge, Err(MetricsError::TooLarge { .. })));
        let empty = parse_p3("P3\n0 5\n255\n");
        assert!(matches!(empty, Err(MetricsError::Empty { .. })));
    }
}
