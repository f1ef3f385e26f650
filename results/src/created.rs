//! The `created` field's form: seconds since the epoch as RFC 3339 UTC.

/// Seconds since the epoch as RFC 3339 UTC, to the second (`2026-11-21T00:00:00Z`).
pub fn rfc3339_utc(secs: u64) -> String {
    let seconds = i64::try_from(secs).unwrap_or(i64::MAX);
    // Past the year 9999 RFC 3339 has no form: the latest instant it has.
    let time = time::OffsetDateTime::from_unix_timestamp(seconds)
        .unwrap_or(time::macros::datetime!(9999-12-31 23:59:59 UTC));
    let format =
        time::macros::format_description!("[year]-[month]-[day]T[hour]:[minute]:[second]Z");
    time.format(format).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rfc3339_matches_known_instants() {
        assert_eq!(rfc3339_utc(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC (a leap day) = 951827696.
        assert_eq!(rfc3339_utc(951_827_696), "2000-02-29T12:34:56Z");
        // 2026-11-21 00:00:00 UTC = 1795219200.
        assert_eq!(rfc3339_utc(1_795_219_200), "2026-11-21T00:00:00Z");
    }
}
