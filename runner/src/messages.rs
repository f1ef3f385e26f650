//! Error messages as rtprof prints them: one line each, so that a script's log shows
//! what was wrong. Clap's multi-line parser errors are joined whole (the missing
//! argument, the tip naming a similar command or flag), and a limit error says how to
//! raise the limit it names (rtprof: the flag, not the library's field).

/// A message on one line: the line breaks of a nested message become "; ".
pub fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Clap's rendered error on one line: its message (the items it lists on lines of their
/// own follow the colon, its tips follow "; ") and its usage with a pointer to --help.
pub fn usage_error(clap_text: &str) -> String {
    let mut message = String::new();
    let lines = clap_text.lines().take_while(|l| !l.starts_with("Usage:"));
    for line in lines.map(str::trim).filter(|l| !l.is_empty()) {
        let separator = match () {
            _ if message.is_empty() => "",
            _ if message.ends_with(':') => " ",
            _ if line.starts_with("tip:") => "; ",
            _ => ", ",
        };
        message.push_str(separator);
        message.push_str(line.trim_start_matches("error: "));
    }
    if message.is_empty() {
        message.push_str("invalid command line");
    }
    let usage = clap_text
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(|u| format!(" (usage: {u}; see --help)"))
        .unwrap_or_else(|| " (see rtprof --help)".to_string());
    message + &usage
}

/// `message` with the hint of `limit` ([`tracer::Limit::hint`]) replaced by how its
/// reader raises that limit (`--max-side` for rtprof's user): `… (raise it with
/// --max-side)`.
pub fn raise_with(message: &str, limit: tracer::Limit, how: &str) -> String {
    message.replace(&limit.hint(), &format!("(raise it with {how})"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clap_errors_keep_the_missing_argument_and_the_tip() {
        let missing = "error: the following required arguments were not provided:\n  <A>\n  <B>\n\n\
                       Usage: rtprof x <A> <B>\n\nFor more information, try '--help'.\n";
        assert_eq!(
            usage_error(missing),
            "the following required arguments were not provided: <A>, <B> \
             (usage: rtprof x <A> <B>; see --help)"
        );
        let tip = "error: unrecognized subcommand 'rendr'\n\n  tip: a similar subcommand exists: 'render'\n";
        assert_eq!(
            usage_error(tip),
            "unrecognized subcommand 'rendr'; tip: a similar subcommand exists: 'render' \
             (see rtprof --help)"
        );
        assert_eq!(usage_error(""), "invalid command line (see rtprof --help)");
    }

    #[test]
    fn limit_hints_name_the_way_to_raise_them() {
        let limits = tracer::Limits {
            max_side: 10,
            ..tracer::Limits::default()
        };
        let error = limits.check_size(20, 5).unwrap_err();
        assert_eq!(error.limit, Some(tracer::Limit::MaxSide));
        assert!(
            error
                .to_string()
                .ends_with("(limit tracer::Limits::max_side)"),
            "{error}"
        );
        let message = format!("scene.nff: {error}");
        assert_eq!(
            raise_with(&message, tracer::Limit::MaxSide, "--max-side"),
            "scene.nff: image size 20x5 exceeds the limit of 10 pixels per side \
             (raise it with --max-side)"
        );
        // Another limit's hint is not there to replace.
        assert_eq!(
            raise_with(&message, tracer::Limit::MaxPixels, "--x"),
            message
        );
        assert_eq!(one_line("a\n  b\n\nc"), "a; b; c");
    }
}
