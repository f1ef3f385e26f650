//! How much of a recording could be named and placed, per module (the executable and
//! each shared library, by the module of each sample's innermost frame): samples with
//! no symbol, samples with no call stack, and what to do about each.

use serde::{Deserialize, Serialize};

/// Shares below this (percent of a module's samples) get no advice: a few samples in
/// a prologue or a stripped helper are normal.
const ADVICE_FROM_PERCENT: f64 = 10.0;
/// Modules with less than this share of all samples get no advice: what they lack
/// cannot change the profile.
const ADVICE_FROM_MODULE_PERCENT: f64 = 1.0;
/// The module of samples taken in the kernel.
pub const KERNEL: &str = "[kernel]";

/// One module's share of the samples and of the unnamed ones.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModuleCoverage {
    /// The file name (`libc.so.6`), or `[kernel]`, `[vdso]`, `[unmapped]`.
    pub module: String,
    /// The full path perf recorded.
    pub path: String,
    /// Samples whose innermost frame is in this module.
    pub samples: u64,
    /// Of those, samples whose innermost address no symbol names.
    pub no_symbol: u64,
    /// Of those, samples without callers: the unwinder found none.
    pub no_stack: u64,
    /// Of those, samples whose stack was cut short: the unwinder stopped on an error
    /// (the copied stack ended, under `--call-graph dwarf`) or at an address in no
    /// mapped file (a frame pointer that was not one). Their callers are partly known.
    pub cut_short: u64,
    /// What would name or place them, when their share is large.
    pub advice: Vec<String>,
}

impl ModuleCoverage {
    pub fn new(module: &str, path: &str) -> Self {
        ModuleCoverage {
            module: module.to_string(),
            path: path.to_string(),
            samples: 0,
            no_symbol: 0,
            no_stack: 0,
            cut_short: 0,
            advice: Vec::new(),
        }
    }

    /// Percent of this module's samples.
    pub fn percent(&self, n: u64) -> f64 {
        100.0 * n as f64 / self.samples.max(1) as f64
    }

    /// Sets [`ModuleCoverage::advice`] from the shares (`total`: all samples).
    pub fn advise(&mut self, dwarf: bool, total: u64) {
        self.advice.clear();
        let share = 100.0 * self.samples as f64 / total.max(1) as f64;
        if self.module == KERNEL || share < ADVICE_FROM_MODULE_PERCENT {
            return;
        }
        if self.percent(self.no_symbol) >= ADVICE_FROM_PERCENT {
            self.advice.push(
                "no symbols: build it with -g (C, C++) or debug info (Rust: debug = \"limited\" in the profile), and do not strip it; \
                 for a system library, install its debug package (-dbgsym; read from /usr/lib/debug/.build-id)"
                    .to_string(),
            );
        }
        if self.percent(self.no_stack + self.cut_short) >= ADVICE_FROM_PERCENT {
            self.advice.push(if dwarf {
                "call stacks missing or cut short even with --call-graph dwarf: the file has no .eh_frame unwind tables, or the stack was deeper than the 32 KiB perf copies; build with frame pointers and record with --call-graph fp".to_string()
            } else {
                "call stacks missing or cut short: build it with -fno-omit-frame-pointer (C, C++) or RUSTFLAGS=\"-C force-frame-pointers=yes\" (Rust), or record with --call-graph dwarf".to_string()
            });
        }
    }
}

/// The file name of a path (`/usr/lib/libm.so.6` → `libm.so.6`); `[vdso]` as it is.
pub fn module_name(path: &str) -> &str {
    path.rsplit('/')
        .next()
        .filter(|s| !s.is_empty())
        .unwrap_or(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advice_follows_the_shares() {
        let mut m = ModuleCoverage::new("libt.so", "/usr/lib/libt.so");
        m.samples = 100;
        m.no_symbol = 60;
        m.no_stack = 5;
        m.advise(false, 1000);
        assert_eq!(m.advice.len(), 1);
        assert!(m.advice[0].contains("-g"), "{:?}", m.advice);
        m.no_stack = 30;
        m.advise(false, 1000);
        assert!(m.advice[1].contains("-fno-omit-frame-pointer"));
        assert!(m.advice[1].contains("force-frame-pointers=yes"));
        assert!(m.advice[1].contains("--call-graph dwarf"));
        let mut k = ModuleCoverage::new(KERNEL, KERNEL);
        k.samples = 10;
        k.no_symbol = 10;
        k.advise(false, 10);
        assert!(k.advice.is_empty());
        m.advise(false, 100_000);
        assert!(m.advice.is_empty(), "0.1 % of the samples: no advice");
    }

    #[test]
    fn module_names_are_file_names() {
        assert_eq!(
            module_name("/usr/lib/x86_64-linux-gnu/libc.so.6"),
            "libc.so.6"
        );
        assert_eq!(module_name("[vdso]"), "[vdso]");
    }
}
