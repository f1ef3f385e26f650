//! What a `perf.data` says about how it was recorded — its sampling event and rate,
//! perf's command line, the program sampled, the time its samples span — and how
//! much CPU time its samples stand for, from the most honest source the recording
//! offers ([`CpuTimeSource`]). `rtprof record` measures the program's CPU time itself
//! (`wait4`); a recording made elsewhere ([`super::read_perf_data`] for `rtprof record
//! --import`) has only what is in the file.

use linux_perf_data::linux_perf_event_reader::{
    HardwareEventId, PerfEventType, SamplingPolicy, SoftwareCounterType,
};
use linux_perf_data::{AttributeDescription, Endianness};
use serde::{Deserialize, Serialize};

/// Where the CPU seconds of a recording come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CpuTimeSource {
    /// The samples' periods added up: under `cpu-clock` or `task-clock` each sample's
    /// period is the nanoseconds of CPU time since the thread's previous sample.
    Periods,
    /// Samples over the asked frequency: the event counts something else (`cycles`),
    /// and the kernel adjusts its period to give that many samples per second of
    /// running; an estimate.
    Frequency,
    /// The wall time from the first sample to the last: the event counts something
    /// else at a fixed period, so the samples give no CPU time; one thread's at most.
    Span,
}

impl CpuTimeSource {
    /// How the seconds were found, for a reader.
    pub fn describe(self) -> &'static str {
        match self {
            CpuTimeSource::Periods => "the samples' periods (cpu-clock: nanoseconds of CPU time)",
            CpuTimeSource::Frequency => {
                "samples / the asked frequency (the event's periods are not time): an estimate"
            }
            CpuTimeSource::Span => {
                "the wall time from the first sample to the last (the event's periods are not time, and its rate is fixed): not CPU time"
            }
        }
    }
}

/// How a recording was made.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RecordingInfo {
    /// The sampling event as perf named it (`cpu-clock:u`, `cycles:P`), or its kind.
    pub event: String,
    /// The event's periods are nanoseconds of CPU time (`cpu-clock`, `task-clock`).
    pub clock: bool,
    /// Samples per second asked (`-F`), when the rate was a frequency.
    pub frequency: Option<u64>,
    /// Events per sample (`-c`), when the rate was a fixed period.
    pub period: Option<u64>,
    /// perf's own command line, from the file's header.
    pub perf_command: Vec<String>,
    /// The name (`comm`) of the process with the most samples: the program.
    pub program: Option<String>,
    /// Seconds from the first sample to the last (0 without timestamps).
    pub span_seconds: f64,
    /// Samples of other sampling events in the file, left out (one event is read).
    pub other_event_samples: u64,
}

impl RecordingInfo {
    /// The event of `attribute` described.
    pub fn of_event(attribute: &AttributeDescription) -> RecordingInfo {
        let attr = &attribute.attr;
        let clock = matches!(
            attr.type_,
            PerfEventType::Software(SoftwareCounterType::CpuClock | SoftwareCounterType::TaskClock)
        );
        let kind = match attr.type_ {
            PerfEventType::Software(SoftwareCounterType::CpuClock) => "cpu-clock",
            PerfEventType::Software(SoftwareCounterType::TaskClock) => "task-clock",
            PerfEventType::Hardware(HardwareEventId::CpuCycles, _) => "cycles",
            PerfEventType::Hardware(HardwareEventId::Instructions, _) => "instructions",
            PerfEventType::Hardware(..) => "a hardware event",
            PerfEventType::Software(_) => "a software event",
            _ => "an event",
        };
        let (frequency, period) = match attr.sampling_policy {
            SamplingPolicy::Frequency(f) => (Some(f), None),
            SamplingPolicy::Period(p) => (None, Some(p.get())),
            SamplingPolicy::NoSampling => (None, None),
        };
        RecordingInfo {
            event: attribute.name.clone().unwrap_or_else(|| kind.to_string()),
            clock,
            frequency,
            period,
            ..RecordingInfo::default()
        }
    }

    /// CPU seconds of `samples` samples whose periods add up to `periods`, and where
    /// that figure comes from.
    pub fn cpu_seconds(&self, samples: u64, periods: u64) -> (f64, CpuTimeSource) {
        if self.clock {
            return (periods as f64 * 1e-9, CpuTimeSource::Periods);
        }
        match self.frequency.filter(|&f| f > 0) {
            Some(f) => (samples as f64 / f as f64, CpuTimeSource::Frequency),
            None => (self.span_seconds, CpuTimeSource::Span),
        }
    }
}

/// Whether `attribute` samples (a `dummy` event only carries side-band records).
pub fn samples_anything(attribute: &AttributeDescription) -> bool {
    !matches!(
        attribute.attr.type_,
        PerfEventType::Software(SoftwareCounterType::Dummy)
    ) && !matches!(attribute.attr.sampling_policy, SamplingPolicy::NoSampling)
}

/// perf's `HEADER_CMDLINE` section: a count, then per argument its length and bytes
/// (NUL-padded). Read here, bounded by the section, rather than by the reader, which
/// reserves room for as many arguments as the count says.
pub fn command_line(section: &[u8], endian: Endianness) -> Vec<String> {
    let u32_at = |at: usize| -> Option<usize> {
        let raw: [u8; 4] = section.get(at..at + 4)?.try_into().ok()?;
        let value = match endian {
            Endianness::LittleEndian => u32::from_le_bytes(raw),
            Endianness::BigEndian => u32::from_be_bytes(raw),
        };
        usize::try_from(value).ok()
    };
    let mut words = Vec::new();
    let Some(count) = u32_at(0) else {
        return words;
    };
    let mut at = 4;
    for _ in 0..count {
        let Some(length) = u32_at(at) else { break };
        let Some(raw) = at
            .checked_add(4 + length)
            .and_then(|end| section.get(at + 4..end))
        else {
            break;
        };
        let text = raw.split(|&b| b == 0).next().unwrap_or_default();
        words.push(String::from_utf8_lossy(text).into_owned());
        at += 4 + length;
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info(clock: bool, frequency: Option<u64>, span: f64) -> RecordingInfo {
        RecordingInfo {
            clock,
            frequency,
            span_seconds: span,
            ..RecordingInfo::default()
        }
    }

    #[test]
    fn cpu_time_comes_from_periods_only_for_a_clock_event() {
        // 4,000 samples whose cpu-clock periods add up to 1.002 s
        let (s, from) = info(true, Some(4000), 3.0).cpu_seconds(4000, 1_002_000_000);
        assert!((s - 1.002).abs() < 1e-9 && from == CpuTimeSource::Periods);
        // cycles at -F 4000: the periods are cycles, samples / F is the estimate
        let (s, from) = info(false, Some(4000), 3.0).cpu_seconds(2000, 7_000_000_000);
        assert!((s - 0.5).abs() < 1e-9 && from == CpuTimeSource::Frequency);
        let (s, from) = info(false, None, 3.0).cpu_seconds(2000, 7_000_000_000);
        assert!((s - 3.0).abs() < 1e-9 && from == CpuTimeSource::Span);
    }

    #[test]
    fn the_command_line_is_read_within_its_section() {
        let mut section = 3u32.to_le_bytes().to_vec();
        for word in ["perf", "record", "-g"] {
            let mut padded = word.as_bytes().to_vec();
            padded.resize(8, 0);
            section.extend_from_slice(&8u32.to_le_bytes());
            section.extend_from_slice(&padded);
        }
        assert_eq!(
            command_line(&section, Endianness::LittleEndian),
            ["perf", "record", "-g"]
        );
        // A count far beyond the bytes: what is there, no more.
        section[..4].copy_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(command_line(&section, Endianness::LittleEndian).len(), 3);
        assert!(command_line(&[1, 2], Endianness::LittleEndian).is_empty());
    }
}
