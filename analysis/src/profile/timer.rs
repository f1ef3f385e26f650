//! Which timer sends the sampler's SIGPROF signals, and at what rate by default.
//!
//! - [`Timer::PerfCpuClock`]: one `perf_event_open` software cpu-clock event per thread
//!   that runs the work ([`super::perf_clock`]). It is hrtimer-driven, so it delivers
//!   the rate it is asked (thousands a CPU second), also in a VM without a PMU.
//! - [`Timer::Setitimer`]: pprof's process-wide `setitimer(ITIMER_PROF)`. It fires on
//!   the kernel's tick, so it delivers at most about the tick rate (CONFIG_HZ, 250 on
//!   many kernels) whatever it is asked.
//!
//! `RTPROF_SAMPLER=auto|perf|setitimer` ([`TimerChoice`]) picks one: `auto` (the
//! default) takes perf when every thread gets its event and setitimer otherwise.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The environment variable that forces a timer.
pub const SAMPLER_ENV: &str = "RTPROF_SAMPLER";
/// Default rate of the perf cpu-clock timer, Hz of CPU time: it delivers it.
pub const PERF_DEFAULT_FREQUENCY: i32 = 4000;
/// Default rate asked of setitimer, Hz (it delivers at most the kernel's tick rate).
pub const SETITIMER_DEFAULT_FREQUENCY: i32 = 1000;

/// The timer a sampling run used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
pub enum Timer {
    /// Per-thread `perf_event_open` software cpu-clock events (hrtimers).
    #[serde(rename = "perf cpu-clock")]
    PerfCpuClock,
    /// The process-wide `setitimer(ITIMER_PROF)` (the kernel's tick).
    #[serde(rename = "setitimer")]
    Setitimer,
}

impl Timer {
    /// The name in messages and in results.json: "perf cpu-clock", "setitimer".
    pub fn name(self) -> &'static str {
        match self {
            Timer::PerfCpuClock => "perf cpu-clock",
            Timer::Setitimer => "setitimer",
        }
    }

    /// The rate asked of this timer when the caller does not choose one.
    pub fn default_frequency(self) -> i32 {
        match self {
            Timer::PerfCpuClock => PERF_DEFAULT_FREQUENCY,
            Timer::Setitimer => SETITIMER_DEFAULT_FREQUENCY,
        }
    }
}

impl std::fmt::Display for Timer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Which timer a run may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimerChoice {
    /// perf cpu-clock when every thread of the work gets its event, else setitimer.
    #[default]
    Auto,
    /// perf cpu-clock or an error that says why not.
    Perf,
    /// setitimer, as pprof alone does.
    Setitimer,
}

/// A value of [`SAMPLER_ENV`] that names no timer.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{SAMPLER_ENV}={value:?} names no timer: use auto, perf or setitimer")]
pub struct BadTimerChoice {
    pub value: String,
}

impl TimerChoice {
    /// `auto`, `perf` or `setitimer` (any case, surrounding spaces ignored).
    pub fn parse(value: &str) -> Result<Self, BadTimerChoice> {
        match value.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(TimerChoice::Auto),
            "perf" => Ok(TimerChoice::Perf),
            "setitimer" => Ok(TimerChoice::Setitimer),
            _ => Err(BadTimerChoice {
                value: value.to_string(),
            }),
        }
    }

    /// What [`SAMPLER_ENV`] says; [`TimerChoice::Auto`] when it is unset or empty.
    pub fn from_env() -> Result<Self, BadTimerChoice> {
        TimerChoice::from_env_value(std::env::var_os(SAMPLER_ENV).as_deref())
    }

    /// What a value of [`SAMPLER_ENV`] says (`None`: unset); unset or empty is auto.
    pub fn from_env_value(value: Option<&std::ffi::OsStr>) -> Result<Self, BadTimerChoice> {
        match value.map(|v| v.to_string_lossy()) {
            None => Ok(TimerChoice::Auto),
            Some(value) if value.trim().is_empty() => Ok(TimerChoice::Auto),
            Some(value) => TimerChoice::parse(&value),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_three_choices_parse_and_junk_is_refused() {
        assert_eq!(TimerChoice::parse("auto"), Ok(TimerChoice::Auto));
        assert_eq!(TimerChoice::parse(" PERF "), Ok(TimerChoice::Perf));
        assert_eq!(TimerChoice::parse("setitimer"), Ok(TimerChoice::Setitimer));
        for junk in ["", "perf2", "itimer", "cpu-clock", "auto,perf"] {
            let error = TimerChoice::parse(junk).expect_err(junk);
            assert_eq!(error.value, junk);
            assert!(error.to_string().contains("auto, perf or setitimer"));
        }
    }

    #[test]
    fn names_round_trip_through_json() {
        for timer in [Timer::PerfCpuClock, Timer::Setitimer] {
            let json = serde_json::to_string(&timer).unwrap_or_default();
            assert_eq!(json, format!("\"{}\"", timer.name()));
            assert_eq!(serde_json::from_str::<Timer>(&json).ok(), Some(timer));
        }
    }
}
