//! C's printf conversions the gprof-format texts are written in (`%W.Ws`, `%g`), shared
//! by the flat profile ([`super::flat`]) and the call graph ([`super::gprof`]).

/// C's `%W.Ws` (right-aligned) or `%-W.Ws` (left-aligned): cut and padded to `width`.
pub(crate) fn c_field(text: &str, width: usize, left: bool) -> String {
    let cut: String = text.chars().take(width).collect();
    if left {
        format!("{cut:<width$}")
    } else {
        format!("{cut:>width$}")
    }
}

/// C's `%g`: six significant digits, trailing zeros dropped, exponent form for
/// exponents below -4 or from 6 on.
pub fn format_g(value: f64) -> String {
    if value.is_nan() {
        return "nan".to_owned();
    }
    if value.is_infinite() {
        return if value > 0.0 { "inf" } else { "-inf" }.to_owned();
    }
    if value == 0.0 {
        return if value.is_sign_negative() { "-0" } else { "0" }.to_owned();
    }
    // Rounded to six significant digits first: the rounding can change the exponent.
    let scientific = format!("{value:.5e}");
    let Some((mantissa, exponent)) = scientific.split_once('e') else {
        return scientific;
    };
    let Ok(exponent) = exponent.parse::<i32>() else {
        return scientific;
    };
    if (-4..6).contains(&exponent) {
        let decimals = usize::try_from(5 - exponent).unwrap_or(0);
        without_trailing_zeros(&format!("{value:.decimals$}")).to_owned()
    } else {
        let sign = if exponent < 0 { '-' } else { '+' };
        format!(
            "{}e{sign}{:02}",
            without_trailing_zeros(mantissa),
            exponent.unsigned_abs()
        )
    }
}

fn without_trailing_zeros(number: &str) -> &str {
    if number.contains('.') {
        number.trim_end_matches('0').trim_end_matches('.')
    } else {
        number
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn g_format_matches_c() {
        assert_eq!(format_g(0.001), "0.001");
        assert_eq!(format_g(0.01), "0.01");
        assert_eq!(format_g(0.0100001), "0.0100001");
        assert_eq!(format_g(1e-05), "1e-05");
        assert_eq!(format_g(0.0001), "0.0001");
        assert_eq!(format_g(2.5), "2.5");
        assert_eq!(format_g(100000.0), "100000");
        assert_eq!(format_g(1e6), "1e+06");
        assert_eq!(format_g(999999.5), "1e+06"); // rounding moves the exponent
        assert_eq!(format_g(123456789.0), "1.23457e+08");
        assert_eq!(format_g(0.0), "0");
        assert_eq!(format_g(f64::NAN), "nan");
    }
}
