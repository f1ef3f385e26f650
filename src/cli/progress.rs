//! Progress bars on stderr (indicatif) for the runner's long work.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::Mutex;

/// Draws one bar per stage; a stage of unknown length is a spinner.
#[derive(Default)]
pub struct Bars {
    bar: Mutex<Option<ProgressBar>>,
}

impl Bars {
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

impl runner::Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let (bar, template) = if total == 0 {
            let bar = ProgressBar::new_spinner();
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
            (bar, "{prefix:>10} {spinner} {msg} ({elapsed})")
        } else {
            let template = "{prefix:>10} [{bar:30}] {pos}/{len} {msg} ({elapsed})";
            (ProgressBar::new(total), template)
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix(stage.to_string());
        self.replace(Some(bar));
    }

    fn message(&self, text: &str) {
        self.current()
            .inspect(|bar| bar.set_message(text.to_string()));
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
