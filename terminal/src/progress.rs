//! Progress bars on stderr (indicatif) for the runner's long work. `RTPROF_PROGRESS`
//! says when they draw: `auto` (the default: when stderr is a terminal), `always` (into a
//! pipe or a file too, as plain lines: CI logs) or `never`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle, TermLike};
use std::io::Write;
use std::sync::Mutex;
use std::time::Duration;

/// The long help (--help) of the commands that draw progress bars: when they draw and
/// `RTPROF_PROGRESS`, which this module reads.
pub const HELP: &str = "Progress bars draw on stderr when it is a terminal (a render \
    only once it has run a second). RTPROF_PROGRESS=always draws them anyway, as plain \
    lines in a pipe or log (CI); RTPROF_PROGRESS=never turns them off; auto is the default.";

/// The environment variable that says when progress draws.
pub const VARIABLE: &str = "RTPROF_PROGRESS";

/// Draws one bar per stage; a stage of unknown length is a spinner.
#[derive(Default)]
pub struct Bars {
    bar: Mutex<Option<ProgressBar>>,
    /// The stage's last message, which a count of the work under way follows.
    message: Mutex<String>,
    /// Bars show only once their stage has run this long (a quick render shows none).
    delay: Duration,
}

impl Bars {
    /// Bars that appear only when a stage lasts longer than about a second.
    pub fn delayed() -> Self {
        let delay = Duration::from_secs(1);
        Bars {
            delay,
            ..Bars::default()
        }
    }

    /// Replaces the current bar (finishing it) with `bar`, or removes it.
    fn replace(&self, bar: Option<ProgressBar>) {
        if let Ok(mut guard) = self.bar.lock()
            && let Some(old) = std::mem::replace(&mut *guard, bar)
        {
            old.finish_and_clear();
        }
    }

    fn current(&self) -> Option<ProgressBar> {
        self.bar.lock().ok().and_then(|guard| guard.clone())
    }
}

/// Where bars draw, as `RTPROF_PROGRESS` says.
fn draw_target() -> ProgressDrawTarget {
    let value = std::env::var(VARIABLE).unwrap_or_default();
    match value.as_str() {
        "never" => ProgressDrawTarget::hidden(),
        "always" => match ProgressDrawTarget::stderr() {
            // Not a terminal: one plain line per redraw, at most one a second.
            target if target.is_hidden() => {
                ProgressDrawTarget::term_like_with_hz(Box::new(PlainLines::default()), 1)
            }
            target => target,
        },
        "" | "auto" => ProgressDrawTarget::stderr(),
        other => {
            static WARNED: std::sync::Once = std::sync::Once::new();
            WARNED.call_once(|| {
                eprintln!("rtprof: warning: {VARIABLE}={other} is not always, never or auto: auto");
            });
            ProgressDrawTarget::stderr()
        }
    }
}

impl runner::Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let target = match self.delay.is_zero() {
            true => draw_target(),
            false => ProgressDrawTarget::hidden(),
        };
        let template = if total == 0 {
            "{prefix:>8} {spinner} {msg} ({elapsed} elapsed)"
        } else {
            // At most about 100 columns with a message of 40 characters.
            "{prefix:>8} [{bar:12}] {pos}/{len} {msg} ({elapsed} elapsed, {eta} remaining)"
        };
        let bar = ProgressBar::with_draw_target((total > 0).then_some(total), target);
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix(stage.to_string());
        if total == 0 {
            bar.enable_steady_tick(Duration::from_millis(120));
        }
        // The late switch to a visible target, on its own thread: only where the bar
        // could be seen at all (not in a pipe or a file by default, nor with `never`),
        // so a short render into a log starts no thread for it.
        if !self.delay.is_zero() && !draw_target().is_hidden() {
            let (late, delay) = (bar.clone(), self.delay);
            std::thread::spawn(move || {
                std::thread::sleep(delay);
                if !late.is_finished() {
                    late.set_draw_target(draw_target());
                }
            });
        }
        self.replace(Some(bar));
    }

    fn message(&self, text: &str) {
        if let Ok(mut message) = self.message.lock() {
            *message = text.to_string();
        }
        self.current()
            .inspect(|bar| bar.set_message(text.to_string()));
    }

    fn within(&self, what: &str, done: u64, total: u64) {
        let message = self.message.lock().map(|m| m.clone()).unwrap_or_default();
        let text = within_text(&message, what, done, total);
        self.current().inspect(|bar| bar.set_message(text));
    }

    fn advance(&self, steps: u64) {
        self.current().inspect(|bar| bar.inc(steps));
    }

    fn end(&self) {
        self.replace(None);
    }

    fn note(&self, text: &str) {
        match self.current() {
            Some(bar) => bar.suspend(|| eprintln!("{text}")),
            None => eprintln!("{text}"),
        }
    }
}

/// The bar's message with the count of the work under way, short enough for the
/// bar's line: "1/3 balls3: timing 3 variants (4/12)"; alone, "1,500/3,000 samples".
/// (The page, with room, says "4 of 12 timed renders".)
fn within_text(message: &str, what: &str, done: u64, total: u64) -> String {
    let count = format!(
        "{}/{}",
        reports::format::count(done.min(total)),
        reports::format::count(total)
    );
    match message.is_empty() {
        true => format!("{count} {what}"),
        false => format!("{message} ({count})"),
    }
}

/// A "terminal" that cannot move the cursor: each finished redraw becomes one line on
/// stderr (repeats and clears dropped), for logs that are not terminals.
#[derive(Debug, Default)]
struct PlainLines {
    /// (the redraw being written, the last line written)
    lines: Mutex<(String, String)>,
}

impl TermLike for PlainLines {
    fn width(&self) -> u16 {
        100
    }
    fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn write_line(&self, s: &str) -> std::io::Result<()> {
        self.write_str(s)?;
        self.flush()
    }
    fn write_str(&self, s: &str) -> std::io::Result<()> {
        if let Ok(mut lines) = self.lines.lock() {
            lines.0.push_str(s.trim_start_matches('\r'));
        }
        Ok(())
    }
    fn clear_line(&self) -> std::io::Result<()> {
        Ok(())
    }
    fn flush(&self) -> std::io::Result<()> {
        let Ok(mut lines) = self.lines.lock() else {
            return Ok(());
        };
        let line = std::mem::take(&mut lines.0).trim_end().to_string();
        if line.is_empty() || line == lines.1 {
            return Ok(());
        }
        writeln!(std::io::stderr().lock(), "{line}")?;
        lines.1 = line;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::within_text;

    #[test]
    fn the_bar_says_how_far_the_work_under_way_is() {
        assert_eq!(
            within_text("1/3 balls3: timing 3 variants", "timed renders", 4, 12),
            "1/3 balls3: timing 3 variants (4/12)"
        );
        assert_eq!(
            within_text("", "samples", 1_500, 3_000),
            "1,500/3,000 samples"
        );
        // Never more done than there is.
        assert_eq!(within_text("", "samples", 5, 3), "3/3 samples");
    }
}
