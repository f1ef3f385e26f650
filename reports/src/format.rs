//! How the reports write numbers: counts, times, intervals, percentages, speed-ups and
//! per-call times, once for the HTML, the PDF and the command line.
//!
//! The rules: counts group thousands with a comma (as the thesis writes 114,480); a
//! time takes the unit (s, ms, µs, ns) that puts its value in [1, 1000) and keeps three
//! significant digits; a median next to its interval gets the decimals that show the
//! interval's width to two significant digits, in the median's unit, no more; a value
//! that is not a number prints as [`DASH`].

/// What a missing or non-finite value prints as.
pub const DASH: &str = "–";

/// A median and its interval as printed: `median` carries the unit ("1.245 ms"),
/// `interval` the bounds in the same unit and decimals ("[1.234 – 1.256]").
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EstimateText {
    pub median: String,
    pub interval: String,
}

impl EstimateText {
    /// Both on one line: "1.245 ms [1.234 – 1.256]".
    pub fn line(&self) -> String {
        if self.interval.is_empty() {
            self.median.clone()
        } else {
            format!("{} {}", self.median, self.interval)
        }
    }
}

/// An integer with commas between thousands: 1,234,567.
pub fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `v` with `decimals` decimals, or [`DASH`].
pub fn fixed(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        DASH.to_string()
    }
}

/// Decimals that give a value in [0, 1000) three significant digits (after rounding:
/// 9.996 has one decimal, as it prints 10.0).
fn three_digit_decimals(v: f64) -> usize {
    let a = v.abs();
    if a >= 99.95 {
        0
    } else if a >= 9.995 {
        1
    } else if a >= 0.0995 || a == 0.0 || !a.is_finite() {
        2
    } else {
        // Small ratios (an outside tracer hundreds of times slower) keep two
        // significant digits rather than printing as 0.00.
        ((-a.log10().floor()) as usize + 1).min(9)
    }
}

/// `v` with three significant digits (no exponent; values of 1000 and more print as
/// integers).
pub fn significant(v: f64) -> String {
    fixed(v, three_digit_decimals(v))
}

/// A non-negative quantity with three significant digits below 1000 and as a grouped
/// integer from 1000 up: "3.27", "15.6", "13,530".
pub fn quantity(v: f64) -> String {
    if v.is_finite() && v.abs() >= 999.5 {
        let n = count(v.abs().round() as u64);
        if v < 0.0 { format!("-{n}") } else { n }
    } else {
        significant(v)
    }
}

/// The unit a time of `s` seconds is printed in: its name and the factor from seconds.
/// Values that round up to the next unit take it (999.96 µs is "1.00 ms").
pub fn time_unit(s: f64) -> (&'static str, f64) {
    let a = s.abs();
    if a == 0.0 || a >= 0.9995 || !a.is_finite() {
        ("s", 1.0)
    } else if a >= 0.9995e-3 {
        ("ms", 1e3)
    } else if a >= 0.9995e-6 {
        ("µs", 1e6)
    } else {
        ("ns", 1e9)
    }
}

/// A time in seconds with its unit and three significant digits: "12.3 ms".
pub fn seconds(s: f64) -> String {
    if !s.is_finite() || s < 0.0 {
        return DASH.to_string();
    }
    if s == 0.0 {
        return "0 s".to_string();
    }
    let (unit, scale) = time_unit(s);
    format!("{} {unit}", significant(s * scale))
}

/// Decimals that show a width `w` (already in the printed unit) to two significant
/// digits; `None` when the width is zero or not a number.
fn width_decimals(w: f64) -> Option<usize> {
    if !(w.is_finite() && w > 0.0) {
        return None;
    }
    // Two significant digits: 0.022 -> 3 decimals, 5.1 -> 1, 12 -> 0.
    let exponent = w.log10().floor() as i64;
    Some((1 - exponent).clamp(0, 9) as usize)
}

/// A time estimate (seconds): the median in its unit, with the decimals the interval's
/// width needs, and the interval in the same unit and decimals.
pub fn estimate(median: f64, low: f64, high: f64) -> EstimateText {
    if !median.is_finite() || median < 0.0 {
        return EstimateText {
            median: DASH.to_string(),
            interval: String::new(),
        };
    }
    let (unit, scale) = time_unit(median);
    let bounds_known = low.is_finite() && high.is_finite();
    let decimals = bounds_known
        .then(|| width_decimals((high - low) * scale))
        .flatten()
        .unwrap_or_else(|| three_digit_decimals(median * scale));
    let median_text = format!("{} {unit}", fixed(median * scale, decimals));
    let interval = if bounds_known {
        format!(
            "[{} – {}]",
            fixed(low * scale, decimals),
            fixed(high * scale, decimals)
        )
    } else {
        String::new()
    };
    EstimateText {
        median: median_text,
        interval,
    }
}

/// Time per call: `total_seconds / calls` as [`seconds`]; `None` without calls.
pub fn per_call(total_seconds: f64, calls: Option<u64>) -> Option<String> {
    match calls {
        Some(c) if c > 0 && total_seconds.is_finite() && total_seconds >= 0.0 => {
            Some(seconds(total_seconds / c as f64))
        }
        _ => None,
    }
}

/// Seconds per call as a sort key (NaN without calls).
pub fn per_call_value(total_seconds: f64, calls: Option<u64>) -> f64 {
    match calls {
        Some(c) if c > 0 => total_seconds / c as f64,
        _ => f64::NAN,
    }
}

/// A percentage: "12.3 %".
pub fn percent(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$} %")
    } else {
        DASH.to_string()
    }
}

/// A signed percentage with a true minus sign: "+4.2 %", "−0.5 %" ("+0.0 %" when the
/// value rounds to zero).
pub fn signed_percent(v: f64, decimals: usize) -> String {
    if !v.is_finite() {
        return DASH.to_string();
    }
    let magnitude = format!("{:.decimals$}", v.abs());
    let negative = v < 0.0 && magnitude.chars().any(|c| c.is_ascii_digit() && c != '0');
    format!("{}{magnitude} %", if negative { '−' } else { '+' })
}

/// A signed percentage change with at least `decimals` decimals and more (up to four)
/// when a change that is not zero would print as zero: "+0.004 %", never "+0.0 %" for
/// a count that did change.
pub fn signed_change(v: f64, decimals: usize) -> String {
    if v == 0.0 {
        return signed_percent(v, decimals);
    }
    let shows = |d: usize| {
        format!("{:.d$}", v.abs())
            .chars()
            .any(|c| c.is_ascii_digit() && c != '0')
    };
    let d = (decimals..=4).find(|d| shows(*d)).unwrap_or(4);
    signed_percent(v, d)
}

/// `used` as a percentage of `capacity` (NaN without capacity).
pub fn percent_of(used: u64, capacity: u64) -> f64 {
    if capacity == 0 {
        f64::NAN
    } else {
        used as f64 / capacity as f64 * 100.0
    }
}

/// Used against available: "3,947 / 114,480 (3.4 %)".
pub fn usage(used: u64, capacity: u64) -> String {
    if capacity == 0 {
        return count(used);
    }
    format!(
        "{} / {} ({})",
        count(used),
        count(capacity),
        percent(percent_of(used, capacity), 1)
    )
}

/// A speed-up or ratio with three significant digits: "2.35×", "12.3×", "123×", "∞".
pub fn speedup(x: f64) -> String {
    if x == f64::INFINITY {
        "∞".to_string()
    } else if x.is_finite() {
        format!("{}×", significant(x))
    } else {
        DASH.to_string()
    }
}

/// A speed-up or time ratio with its interval, the decimals following the interval's
/// width as [`estimate`] does for times: "2.01× [1.98 – 2.05]"; without a usable
/// interval, [`speedup`] alone.
pub fn ratio_estimate(median: f64, low: f64, high: f64) -> EstimateText {
    if !(median.is_finite() && low.is_finite() && high.is_finite()) {
        return EstimateText {
            median: speedup(median),
            interval: String::new(),
        };
    }
    let decimals = width_decimals(high - low).unwrap_or_else(|| three_digit_decimals(median));
    EstimateText {
        median: format!("{}×", fixed(median, decimals)),
        interval: format!("[{} – {}]", fixed(low, decimals), fixed(high, decimals)),
    }
}

/// A change given as a ratio new / old with its interval, written as a signed
/// percentage whose decimals follow the interval's width: "+25 % [+20 – +31]",
/// "−8.3 % [−9.1 – −7.6]"; without an interval, one decimal.
pub fn change_estimate(ratio: f64, low: f64, high: f64) -> EstimateText {
    let pct = |r: f64| (r - 1.0) * 100.0;
    if !ratio.is_finite() {
        return EstimateText {
            median: DASH.to_string(),
            interval: String::new(),
        };
    }
    if !(low.is_finite() && high.is_finite()) {
        return EstimateText {
            median: signed_percent(pct(ratio), 1),
            interval: String::new(),
        };
    }
    let decimals = width_decimals(pct(high) - pct(low)).unwrap_or(1).min(3);
    let bound = |r: f64| {
        signed_percent(pct(r), decimals)
            .trim_end_matches(" %")
            .to_string()
    };
    EstimateText {
        median: signed_percent(pct(ratio), decimals),
        interval: format!("[{} – {}]", bound(low), bound(high)),
    }
}

/// A clock frequency: "50 MHz", "52.6 MHz".
pub fn megahertz(hz: f64) -> String {
    format!("{} MHz", trimmed(hz / 1e6))
}

/// Frames per second: "137 fps", "5.42 fps".
pub fn fps(frames_per_second: f64) -> String {
    format!("{} fps", significant(frames_per_second))
}

/// "1 sphere", "2,400 spheres" from a plural kind name.
pub fn kind_count(n: u64, kind: &str) -> String {
    if n == 1 {
        format!("1 {}", kind.strip_suffix('s').unwrap_or(kind))
    } else {
        format!("{} {kind}", count(n))
    }
}

/// A size in bytes with binary units: "512 B", "3.0 MiB".
pub fn bytes(n: u64) -> String {
    const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
    if n < 1024 {
        return format!("{n} B");
    }
    let mut value = n as f64 / 1024.0;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    format!("{value:.1} {}", UNITS[unit])
}

/// "n thing" or "n things".
pub fn plural(n: usize, thing: &str) -> String {
    format!("{n} {thing}{}", if n == 1 { "" } else { "s" })
}

/// An image size: "640×480".
pub fn size(width: u32, height: u32) -> String {
    format!("{width}×{height}")
}

/// "a", "a and b", "a, b and c".
pub fn join_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// A number with at most three significant digits and no trailing zeros: "15",
/// "0.5", "2.35" (a band's edge, a threshold).
pub fn trimmed(v: f64) -> String {
    let text = significant(v);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// An elapsed time in whole seconds, as a clock reads it: "42 s", "3 min 05 s",
/// "1 h 02 min".
pub fn elapsed(seconds: u64) -> String {
    let (h, m, s) = (seconds / 3600, seconds / 60 % 60, seconds % 60);
    if h > 0 {
        format!("{h} h {m:02} min")
    } else if m > 0 {
        format!("{m} min {s:02} s")
    } else {
        format!("{s} s")
    }
}

/// A guess of a duration, shown as one: "about 40 s", "about 2 min", "about 3 h".
pub fn rough_duration(seconds: f64) -> String {
    if !seconds.is_finite() || seconds < 0.0 {
        DASH.to_string()
    } else if seconds < 90.0 {
        format!("about {:.0} s", seconds)
    } else if seconds < 90.0 * 60.0 {
        format!("about {:.0} min", seconds / 60.0)
    } else {
        format!("about {:.0} h", seconds / 3600.0)
    }
}

/// An RFC 3339 UTC time as a reader scans it: "2026-11-27 20:11:25 UTC" (the text as
/// is when it is not of that form).
pub fn timestamp(rfc3339: &str) -> String {
    match rfc3339.strip_suffix('Z').and_then(|t| t.split_once('T')) {
        Some((date, time)) => format!("{date} {} UTC", time.split('.').next().unwrap_or(time)),
        None => rfc3339.to_string(),
    }
}

/// A PDF's length: "report.pdf: 48 pages, of which the main body (answers and
/// chapters) 16".
pub fn pdf_pages(total: usize, main_body: usize) -> String {
    format!(
        "report.pdf: {} pages, of which the main body (answers and chapters) {}",
        count(total as u64),
        count(main_body as u64)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_ratios_keep_two_significant_digits() {
        // 1.6 ms against 0.70 s: 0.0023, not 0.00.
        assert_eq!(speedup(0.0016 / 0.70), "0.0023×");
        assert_eq!(speedup(0.042), "0.042×");
        assert_eq!(speedup(0.5), "0.50×");
        assert_eq!(speedup(0.0), "0.00×");
    }

    #[test]
    fn page_helpers_write_clocks_guesses_and_edges() {
        assert_eq!(trimmed(15.0), "15");
        assert_eq!(trimmed(0.5), "0.5");
        assert_eq!(trimmed(2.345), "2.35");
        assert_eq!(trimmed(1234.0), "1234");
        assert_eq!(elapsed(42), "42 s");
        assert_eq!(elapsed(185), "3 min 05 s");
        assert_eq!(elapsed(3720), "1 h 02 min");
        assert_eq!(rough_duration(40.2), "about 40 s");
        assert_eq!(rough_duration(125.0), "about 2 min");
        assert_eq!(rough_duration(3.0 * 3600.0), "about 3 h");
        assert_eq!(timestamp("2026-11-27T20:11:25Z"), "2026-11-27 20:11:25 UTC");
        assert_eq!(timestamp("not a time"), "not a time");
    }

    #[test]
    fn counts_group_thousands_with_commas() {
        assert_eq!(count(0), "0");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_000), "1,000");
        assert_eq!(count(114_480), "114,480");
        assert_eq!(count(1_234_567), "1,234,567");
        assert_eq!(count(u64::MAX), "18,446,744,073,709,551,615");
    }

    #[test]
    fn quantities_keep_three_digits_then_group_integers() {
        assert_eq!(quantity(3.2734), "3.27");
        assert_eq!(quantity(15.59), "15.6");
        assert_eq!(quantity(999.4), "999");
        assert_eq!(quantity(999.6), "1,000");
        assert_eq!(quantity(13_530.43), "13,530");
        assert_eq!(quantity(-2_500.0), "-2,500");
    }

    #[test]
    fn times_keep_three_significant_digits_in_their_unit() {
        assert_eq!(seconds(0.0123), "12.3 ms");
        assert_eq!(seconds(3.87), "3.87 s");
        assert_eq!(seconds(2.5e-5), "25.0 µs");
        assert_eq!(seconds(4.2e-8), "42.0 ns");
        assert_eq!(seconds(123.456), "123 s");
        assert_eq!(seconds(0.0), "0 s");
        // Rounding carries into the next unit: 999.96 µs is 1.00 ms, not 1000 µs.
        assert_eq!(seconds(0.000_999_96), "1.00 ms");
        assert_eq!(seconds(0.009_996), "10.0 ms");
        assert_eq!(seconds(0.99996), "1.00 s");
        assert_eq!(seconds(f64::NAN), DASH);
        assert_eq!(seconds(-1.0), DASH);
    }

    #[test]
    fn a_median_shows_as_many_digits_as_its_interval_needs() {
        // [1.234, 1.256] ms: the width 0.022 ms needs three decimals.
        let e = estimate(1.245e-3, 1.234e-3, 1.256e-3);
        assert_eq!(e.median, "1.245 ms");
        assert_eq!(e.interval, "[1.234 – 1.256]");
        assert_eq!(e.line(), "1.245 ms [1.234 – 1.256]");
        // [12.0, 13.1] ms: width 1.1 -> one decimal.
        let e = estimate(0.0123, 0.0120, 0.0131);
        assert_eq!(e.line(), "12.3 ms [12.0 – 13.1]");
        // A wide interval: [8, 20] ms, width 12 -> no decimals; the median is not
        // printed more precisely than the interval allows.
        let e = estimate(0.0123, 0.008, 0.020);
        assert_eq!(e.line(), "12 ms [8 – 20]");
        // A very narrow one: [2.50001, 2.50003] s, width 0.000020 -> six decimals.
        let e = estimate(2.500_02, 2.500_01, 2.500_03);
        assert_eq!(e.line(), "2.500020 s [2.500010 – 2.500030]");
        // No width (one sample): three significant digits.
        let e = estimate(8.217e-6, 8.217e-6, 8.217e-6);
        assert_eq!(e.line(), "8.22 µs [8.22 – 8.22]");
        // Unknown bounds: the median alone.
        let e = estimate(0.5, f64::NAN, f64::NAN);
        assert_eq!(e.line(), "500 ms");
        assert_eq!(estimate(f64::NAN, 0.0, 1.0).line(), DASH);
    }

    #[test]
    fn per_call_times_take_the_time_unit_rule() {
        // 0.25 s over 1,000,000 calls = 250 ns.
        assert_eq!(per_call(0.25, Some(1_000_000)).as_deref(), Some("250 ns"));
        // 3 s over 2,000 calls = 1.5 ms.
        assert_eq!(per_call(3.0, Some(2_000)).as_deref(), Some("1.50 ms"));
        assert_eq!(per_call(1.0, Some(0)), None);
        assert_eq!(per_call(1.0, None), None);
        assert!(per_call_value(1.0, None).is_nan());
        assert_eq!(per_call_value(3.0, Some(2_000)), 0.0015);
    }

    #[test]
    fn percentages_ratios_and_usage() {
        assert_eq!(percent(12.345, 1), "12.3 %");
        assert_eq!(percent(f64::NAN, 1), DASH);
        assert_eq!(signed_percent(4.26, 1), "+4.3 %");
        assert_eq!(signed_percent(-0.54, 1), "−0.5 %");
        assert_eq!(signed_percent(-0.04, 1), "+0.0 %");
        assert_eq!(signed_percent(154.2, 1), "+154.2 %");
        // 491,114 against 491,113 dot products: +0.0002 %, not "+0.0 %".
        assert_eq!(
            signed_change((491_114.0 / 491_113.0 - 1.0) * 100.0, 1),
            "+0.0002 %"
        );
        assert_eq!(signed_change(-28.74, 1), "−28.7 %");
        assert_eq!(signed_change(0.0, 1), "+0.0 %");
        // Too small for four decimals: it stays at four.
        assert_eq!(signed_change(1e-9, 1), "+0.0000 %");
        assert_eq!(speedup(2.345_6), "2.35×");
        assert_eq!(speedup(12.34), "12.3×");
        assert_eq!(speedup(123.4), "123×");
        assert_eq!(speedup(f64::INFINITY), "∞");
        assert_eq!(speedup(f64::NAN), DASH);
        // 100,000 of 114,480 logic elements = 87.35 %.
        assert_eq!(usage(100_000, 114_480), "100,000 / 114,480 (87.4 %)");
        assert_eq!(usage(5, 0), "5");
        assert!(percent_of(1, 0).is_nan());
    }

    #[test]
    fn bytes_use_binary_units_with_one_decimal() {
        assert_eq!(bytes(0), "0 B");
        assert_eq!(bytes(1023), "1023 B");
        // 16 x 12 pixels of three f32: 2,304 bytes = 2.25 KiB.
        assert_eq!(bytes(2304), "2.2 KiB");
        assert_eq!(bytes(3 * 1024 * 1024), "3.0 MiB");
        assert_eq!(bytes(5 << 40), "5.0 TiB");
        assert_eq!(bytes(2048 << 40), "2048.0 TiB");
    }

    #[test]
    fn ratios_show_the_digits_their_interval_needs() {
        // Width 0.070: its two significant digits need three decimals.
        assert_eq!(
            ratio_estimate(2.013, 1.98, 2.05).line(),
            "2.013× [1.980 – 2.050]"
        );
        // Width 1.2: one decimal, not "1.013×" next to "[0.512 – 1.712]".
        assert_eq!(
            ratio_estimate(1.013, 0.512, 1.712).line(),
            "1.0× [0.5 – 1.7]"
        );
        assert_eq!(ratio_estimate(f64::NAN, 1.0, 2.0).line(), DASH);
        assert_eq!(ratio_estimate(1.5, f64::NAN, 2.0).line(), "1.50×");
    }

    #[test]
    fn changes_are_signed_percentages_as_precise_as_their_interval() {
        // [1.20, 1.31]: width 11 points, no decimals.
        assert_eq!(
            change_estimate(1.25, 1.20, 1.31).line(),
            "+25 % [+20 – +31]"
        );
        // [0.909, 0.924]: width 1.5 points, one decimal.
        assert_eq!(
            change_estimate(0.917, 0.909, 0.924).line(),
            "−8.3 % [−9.1 – −7.6]"
        );
        assert_eq!(change_estimate(1.05, f64::NAN, 1.1).line(), "+5.0 %");
        assert_eq!(change_estimate(f64::NAN, 1.0, 1.1).line(), DASH);
    }

    #[test]
    fn words() {
        assert_eq!(kind_count(1, "spheres"), "1 sphere");
        assert_eq!(kind_count(4200, "cylinders"), "4,200 cylinders");
        assert_eq!(plural(1, "scene"), "1 scene");
        assert_eq!(plural(3, "scene"), "3 scenes");
        assert_eq!(size(640, 480), "640×480");
        assert_eq!(
            join_list(&["a".into(), "b".into(), "c".into()]),
            "a, b and c"
        );
        assert_eq!(join_list(&["a".into()]), "a");
        assert_eq!(join_list(&[]), "");
    }
}
