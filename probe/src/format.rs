//! The probe's output file: its one home, the writer's lines and the reader.
//!
//! Text, one record a line, fields separated by one space, a name always last (so it
//! may hold spaces). The C header writes the same lines (`rtprof.h`, `rtprof_i_write`);
//! this module's tests read the header's output too.
//!
//! ```text
//! rtprof.probe 1
//! writer c                       the probe that wrote it: c or rust
//! pid 4242
//! reason exit                    or: reason signal 15 (SIGINT, SIGTERM)
//! threads 8                      threads that used the probe
//! period_ns 1000000              phase sampling period of a thread's CPU time; 0 = none
//! samples 2104                   phase samples taken, all threads
//! cpu_ns 2103559000              CPU time of the sampled threads while sampled
//! unbalanced 0                   phase ends that did not match the innermost phase
//! counter 307200 rays.primary    a standard counter (every one is written)
//! user_counter 12 bvh refits     a user counter that was declared or counted
//! outside 3                      samples outside any phase
//! phase 1510 1800 sphere test    a standard phase: self samples, total samples, name
//! user_phase 0 2 setup           a user phase
//! end
//! ```
//!
//! The reader refuses anything else with the line and byte offset of the fault: a
//! file cut short (no `end`), unknown records, numbers out of range, repeated keys, and
//! sample counts that do not add up (outside + the phases' self samples = samples).

use std::fmt;

/// The first line of a probe file: the format and its version.
pub const FORMAT_LINE: &str = "rtprof.probe 1";

/// The environment variable that turns the probe on: the file to write.
pub const ENV_FILE: &str = "RTPROF_PROBE_FILE";

/// The environment variable with the phase sampling rate per CPU second of a thread
/// (default 1000; 0 = counters only).
pub const ENV_HZ: &str = "RTPROF_PROBE_HZ";

/// The largest file the reader accepts (a real one is a few kilobytes).
pub const MAX_FILE_BYTES: usize = 1 << 20;

/// Longest name of a counter or phase.
pub const MAX_NAME_BYTES: usize = 255;

/// Why the writer wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reason {
    /// The process exited (or the program flushed).
    Exit,
    /// The process was stopped by this signal (2 SIGINT, 15 SIGTERM).
    Signal(u32),
}

/// A counter's total.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CounterTotal {
    /// The counter table's key (`rays.primary`) or the user's name.
    pub name: String,
    /// Summed over all threads.
    pub value: u64,
}

/// A phase's samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PhaseSamples {
    /// The phase's name (`sphere test`) or the user's name.
    pub name: String,
    /// Samples with this phase innermost.
    pub self_samples: u64,
    /// Samples with this phase anywhere on the stack.
    pub total_samples: u64,
}

/// A probe file, read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProbeFile {
    /// `c` or `rust`.
    pub writer: String,
    /// The process that wrote it.
    pub pid: u32,
    /// Why it was written.
    pub reason: Reason,
    /// Threads that used the probe.
    pub threads: u64,
    /// Phase sampling period in nanoseconds of a thread's CPU time (0: not sampled).
    pub period_ns: u64,
    /// Phase samples, all threads.
    pub samples: u64,
    /// CPU time of the sampled threads between their registration and last sample.
    pub cpu_ns: u64,
    /// Phase ends that did not match the innermost phase.
    pub unbalanced: u64,
    /// Samples outside any phase.
    pub outside: u64,
    /// The standard counters, in file order.
    pub counters: Vec<CounterTotal>,
    /// The user's counters.
    pub user_counters: Vec<CounterTotal>,
    /// The standard phases, in file order.
    pub phases: Vec<PhaseSamples>,
    /// The user's phases.
    pub user_phases: Vec<PhaseSamples>,
}

impl ProbeFile {
    /// A standard counter's total by its key.
    pub fn counter(&self, key: &str) -> Option<u64> {
        self.counters
            .iter()
            .find(|c| c.name == key)
            .map(|c| c.value)
    }

    /// A user counter's total by its name.
    pub fn user_counter(&self, name: &str) -> Option<u64> {
        self.user_counters
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.value)
    }

    /// A standard or user phase by name (standard first).
    pub fn phase(&self, name: &str) -> Option<&PhaseSamples> {
        self.phases
            .iter()
            .chain(&self.user_phases)
            .find(|p| p.name == name)
    }

    /// CPU seconds a sample stands for (measured CPU time over samples), if sampled.
    pub fn seconds_per_sample(&self) -> Option<f64> {
        (self.samples > 0).then(|| self.cpu_ns as f64 * 1e-9 / self.samples as f64)
    }

    /// The file's text (what the writers write for the same values).
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let header = Header {
            writer: &self.writer,
            pid: u64::from(self.pid),
            reason: self.reason,
            threads: self.threads,
            period_ns: self.period_ns,
            samples: self.samples,
            cpu_ns: self.cpu_ns,
            unbalanced: self.unbalanced,
        };
        header.write(&mut out);
        for c in &self.counters {
            line(&mut out, "counter", &[c.value], &c.name);
        }
        for c in &self.user_counters {
            line(&mut out, "user_counter", &[c.value], &c.name);
        }
        line(&mut out, "outside", &[self.outside], "");
        for p in &self.phases {
            line(
                &mut out,
                "phase",
                &[p.self_samples, p.total_samples],
                &p.name,
            );
        }
        for p in &self.user_phases {
            line(
                &mut out,
                "user_phase",
                &[p.self_samples, p.total_samples],
                &p.name,
            );
        }
        out.push_str("end\n");
        out
    }
}

/// Where the writer's text goes: a `String`, or the runtime's fixed buffer (no
/// allocation in a signal handler).
pub(crate) trait Sink {
    fn text(&mut self, text: &str);

    fn number(&mut self, mut value: u64) {
        let mut digits = [0u8; 20];
        let mut n = digits.len();
        loop {
            n -= 1;
            digits[n] = b'0' + (value % 10) as u8;
            value /= 10;
            if value == 0 {
                break;
            }
        }
        // Only ASCII digits were written.
        self.text(std::str::from_utf8(&digits[n..]).unwrap_or("0"));
    }
}

impl Sink for String {
    fn text(&mut self, text: &str) {
        self.push_str(text);
    }
}

/// `KIND N... NAME\n` (no name: the numbers end the line).
pub(crate) fn line(out: &mut impl Sink, kind: &str, numbers: &[u64], name: &str) {
    out.text(kind);
    for &n in numbers {
        out.text(" ");
        out.number(n);
    }
    if !name.is_empty() {
        out.text(" ");
        out.text(name);
    }
    out.text("\n");
}

/// The lines before the counters.
pub(crate) struct Header<'a> {
    pub writer: &'a str,
    pub pid: u64,
    pub reason: Reason,
    pub threads: u64,
    pub period_ns: u64,
    pub samples: u64,
    pub cpu_ns: u64,
    pub unbalanced: u64,
}

impl Header<'_> {
    pub(crate) fn write(&self, out: &mut impl Sink) {
        out.text(FORMAT_LINE);
        out.text("\nwriter ");
        out.text(self.writer);
        out.text("\n");
        line(out, "pid", &[self.pid], "");
        match self.reason {
            Reason::Exit => out.text("reason exit\n"),
            Reason::Signal(s) => line(out, "reason signal", &[u64::from(s)], ""),
        }
        line(out, "threads", &[self.threads], "");
        line(out, "period_ns", &[self.period_ns], "");
        line(out, "samples", &[self.samples], "");
        line(out, "cpu_ns", &[self.cpu_ns], "");
        line(out, "unbalanced", &[self.unbalanced], "");
    }
}

/// A fault in a probe file: where, and what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FormatError {
    /// 1-based line.
    pub line: usize,
    /// Byte offset of the fault from the start of the file.
    pub offset: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "line {} (byte {}): {}",
            self.line, self.offset, self.message
        )
    }
}

impl std::error::Error for FormatError {}

/// Reading a probe file from disk failed.
#[derive(Debug)]
pub enum ReadError {
    /// The file could not be read.
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// The file is not a valid probe file.
    Format {
        /// The file.
        path: std::path::PathBuf,
        /// Where and why.
        error: FormatError,
    },
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Io { path, error } => {
                write!(f, "cannot read probe file {}: {error}", path.display())
            }
            ReadError::Format { path, error } => {
                write!(f, "{}: not a valid probe file: {error}", path.display())
            }
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReadError::Io { error, .. } => Some(error),
            ReadError::Format { error, .. } => Some(error),
        }
    }
}

/// Reads and parses the probe file at `path` (at most [`MAX_FILE_BYTES`] are read).
pub fn read_file(path: &std::path::Path) -> Result<ProbeFile, ReadError> {
    use std::io::Read;
    let io = |error| ReadError::Io {
        path: path.to_path_buf(),
        error,
    };
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(io)?
        .take(MAX_FILE_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    parse(&bytes).map_err(|error| ReadError::Format {
        path: path.to_path_buf(),
        error,
    })
}

/// Which header line a key is, and whether it was seen.
const SINGLES: [&str; 9] = [
    "writer",
    "pid",
    "reason",
    "threads",
    "period_ns",
    "samples",
    "cpu_ns",
    "unbalanced",
    "outside",
];

/// Parses a probe file's bytes; never panics, whatever the bytes.
pub fn parse(bytes: &[u8]) -> Result<ProbeFile, FormatError> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(FormatError {
            line: 1,
            offset: MAX_FILE_BYTES,
            message: format!("larger than {MAX_FILE_BYTES} bytes"),
        });
    }
    let mut file = ProbeFile {
        writer: String::new(),
        pid: 0,
        reason: Reason::Exit,
        threads: 0,
        period_ns: 0,
        samples: 0,
        cpu_ns: 0,
        unbalanced: 0,
        outside: 0,
        counters: Vec::new(),
        user_counters: Vec::new(),
        phases: Vec::new(),
        user_phases: Vec::new(),
    };
    let mut seen = [false; SINGLES.len()];
    let mut offset = 0;
    let mut number = 0;
    let mut ended = None;
    while offset < bytes.len() {
        number += 1;
        let rest = &bytes[offset..];
        let Some(length) = rest.iter().position(|&b| b == b'\n') else {
            return Err(FormatError {
                line: number,
                offset: bytes.len(),
                message: "truncated: the last line has no end (the writer was cut short)".into(),
            });
        };
        let at = Line {
            number,
            offset,
            bytes: &rest[..length],
        };
        if let Some(end_line) = ended {
            return at.fail(0, format!("text after the `end` line (line {end_line})"));
        }
        let text = at.text()?;
        if number == 1 {
            if text != FORMAT_LINE {
                let message = match text.strip_prefix("rtprof.probe ") {
                    Some(version) => format!(
                        "probe format version {version:?}; this rtprof reads `{FORMAT_LINE}`"
                    ),
                    None => format!("not a probe file: the first line is not `{FORMAT_LINE}`"),
                };
                return at.fail(0, message);
            }
        } else if text == "end" {
            ended = Some(number);
        } else {
            record(&at, text, &mut file, &mut seen)?;
        }
        offset += length + 1;
    }
    let end = FormatError {
        line: number.max(1),
        offset: bytes.len(),
        message: String::new(),
    };
    if number == 0 {
        return Err(FormatError {
            message: "empty: not a probe file".into(),
            ..end
        });
    }
    if ended.is_none() {
        return Err(FormatError {
            message: "truncated: no `end` line (the writer was cut short)".into(),
            ..end
        });
    }
    if let Some(missing) = SINGLES.iter().zip(seen).find(|(_, s)| !s) {
        return Err(FormatError {
            message: format!("no `{}` line", missing.0),
            ..end
        });
    }
    check_samples(&file).map_err(|message| FormatError { message, ..end })?;
    Ok(file)
}

/// The sample counts add up: each phase's self within its total within all samples,
/// and outside plus the self samples are all samples.
fn check_samples(file: &ProbeFile) -> Result<(), String> {
    if file.period_ns == 0 && file.samples != 0 {
        return Err(format!(
            "{} samples but period_ns 0 (phases not sampled)",
            file.samples
        ));
    }
    let mut sum = file.outside;
    for p in file.phases.iter().chain(&file.user_phases) {
        if p.self_samples > p.total_samples || p.total_samples > file.samples {
            return Err(format!(
                "phase {:?}: self samples {} and total {} must not exceed each other's and samples {}",
                p.name, p.self_samples, p.total_samples, file.samples
            ));
        }
        sum = sum.saturating_add(p.self_samples);
    }
    if sum != file.samples {
        return Err(format!(
            "outside and the phases' self samples add up to {sum}, not samples {}",
            file.samples
        ));
    }
    Ok(())
}

/// One line of the file, for its errors.
struct Line<'a> {
    number: usize,
    offset: usize,
    bytes: &'a [u8],
}

impl<'a> Line<'a> {
    fn fail<T>(&self, column: usize, message: String) -> Result<T, FormatError> {
        Err(FormatError {
            line: self.number,
            offset: self.offset + column,
            message,
        })
    }

    fn text(&self) -> Result<&'a str, FormatError> {
        let text = match std::str::from_utf8(self.bytes) {
            Ok(text) => text,
            Err(e) => return self.fail(e.valid_up_to(), "not UTF-8 text".into()),
        };
        // The character itself, not its first byte: C1 controls (U+0080-U+009F) take
        // two bytes in UTF-8 (the fuzz campaign found a slice inside one).
        if let Some((i, c)) = text.char_indices().find(|(_, c)| c.is_control()) {
            return self.fail(i, format!("control character {c:?}"));
        }
        Ok(text)
    }
}

/// Splits `n` numbers off the front of `rest` (after the kind), then the name.
fn fields<'a>(
    at: &Line<'_>,
    start: usize,
    rest: &'a str,
    n: usize,
    named: bool,
) -> Result<(Vec<u64>, &'a str), FormatError> {
    let mut numbers = Vec::with_capacity(n);
    let mut rest = rest;
    let mut column = start;
    for _ in 0..n {
        let Some(after) = rest.strip_prefix(' ') else {
            return at.fail(column, "a number is missing".into());
        };
        column += 1;
        let token = after.split(' ').next().unwrap_or_default();
        numbers.push(parse_number(at, column, token)?);
        column += token.len();
        rest = &after[token.len()..];
    }
    if !named {
        if !rest.is_empty() {
            return at.fail(column, format!("unexpected text {rest:?}"));
        }
        return Ok((numbers, ""));
    }
    let Some(name) = rest.strip_prefix(' ') else {
        return at.fail(column, "the name is missing".into());
    };
    if name.is_empty() || name.len() > MAX_NAME_BYTES || name.trim() != name {
        return at.fail(
            column + 1,
            format!(
                "a name must be 1 to {MAX_NAME_BYTES} bytes without spaces at its ends: {name:?}"
            ),
        );
    }
    Ok((numbers, name))
}

fn parse_number(at: &Line<'_>, column: usize, token: &str) -> Result<u64, FormatError> {
    if token.is_empty() || !token.bytes().all(|b| b.is_ascii_digit()) {
        return at.fail(column, format!("not a number: {token:?}"));
    }
    token
        .parse()
        .or_else(|_| at.fail(column, format!("number out of range: {token}")))
}

/// Reads one record (a line other than the first and `end`) into `file`.
fn record(
    at: &Line<'_>,
    text: &str,
    file: &mut ProbeFile,
    seen: &mut [bool; SINGLES.len()],
) -> Result<(), FormatError> {
    let kind = text.split(' ').next().unwrap_or_default();
    let rest = &text[kind.len()..];
    let start = kind.len();
    if let Some(index) = SINGLES.iter().position(|s| *s == kind) {
        if seen[index] {
            return at.fail(0, format!("a second `{kind}` line"));
        }
        seen[index] = true;
    }
    match kind {
        "writer" => {
            let (_, name) = fields(at, start, rest, 0, true)?;
            if name.contains(' ') {
                return at.fail(start + 1, format!("writer {name:?} is not one word"));
            }
            file.writer = name.to_string();
        }
        "pid" => {
            let (n, _) = fields(at, start, rest, 1, false)?;
            file.pid = u32::try_from(n[0])
                .or_else(|_| at.fail(start + 1, format!("pid {} out of range", n[0])))?;
        }
        "reason" => {
            file.reason = match rest {
                " exit" => Reason::Exit,
                _ => match rest.strip_prefix(" signal") {
                    Some(signal) => {
                        let (n, _) = fields(at, start + 7, signal, 1, false)?;
                        match u32::try_from(n[0]) {
                            Ok(s) if (1..=64).contains(&s) => Reason::Signal(s),
                            _ => return at.fail(start + 8, format!("no signal {}", n[0])),
                        }
                    }
                    None => {
                        return at.fail(
                            start,
                            format!("reason must be `exit` or `signal N`, not {rest:?}"),
                        );
                    }
                },
            };
        }
        "threads" | "period_ns" | "samples" | "cpu_ns" | "unbalanced" | "outside" => {
            let (n, _) = fields(at, start, rest, 1, false)?;
            let slot = match kind {
                "threads" => &mut file.threads,
                "period_ns" => &mut file.period_ns,
                "samples" => &mut file.samples,
                "cpu_ns" => &mut file.cpu_ns,
                "unbalanced" => &mut file.unbalanced,
                _ => &mut file.outside,
            };
            *slot = n[0];
        }
        "counter" | "user_counter" => {
            let (n, name) = fields(at, start, rest, 1, true)?;
            let list = if kind == "counter" {
                &mut file.counters
            } else {
                &mut file.user_counters
            };
            if list.iter().any(|c| c.name == name) {
                return at.fail(0, format!("{kind} {name:?} a second time"));
            }
            list.push(CounterTotal {
                name: name.to_string(),
                value: n[0],
            });
        }
        "phase" | "user_phase" => {
            let (n, name) = fields(at, start, rest, 2, true)?;
            let list = if kind == "phase" {
                &mut file.phases
            } else {
                &mut file.user_phases
            };
            if list.iter().any(|p| p.name == name) {
                return at.fail(0, format!("{kind} {name:?} a second time"));
            }
            list.push(PhaseSamples {
                name: name.to_string(),
                self_samples: n[0],
                total_samples: n[1],
            });
        }
        _ => return at.fail(0, format!("unknown record {kind:?}")),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> ProbeFile {
        ProbeFile {
            writer: "c".into(),
            pid: 4242,
            reason: Reason::Signal(15),
            threads: 8,
            period_ns: 1_000_000,
            samples: 10,
            cpu_ns: 10_200_000,
            unbalanced: 0,
            outside: 3,
            counters: vec![
                CounterTotal {
                    name: "rays.primary".into(),
                    value: 307_200,
                },
                CounterTotal {
                    name: "tests.sphere.tests".into(),
                    value: u64::MAX,
                },
            ],
            user_counters: vec![CounterTotal {
                name: "bvh refits".into(),
                value: 12,
            }],
            phases: vec![PhaseSamples {
                name: "sphere test".into(),
                self_samples: 5,
                total_samples: 7,
            }],
            user_phases: vec![PhaseSamples {
                name: "setup".into(),
                self_samples: 2,
                total_samples: 2,
            }],
        }
    }

    #[test]
    fn a_file_reads_back_as_written() {
        let file = example();
        let text = file.to_text();
        assert!(text.starts_with("rtprof.probe 1\nwriter c\npid 4242\nreason signal 15\n"));
        assert!(text.contains("\ncounter 18446744073709551615 tests.sphere.tests\n"));
        assert!(text.contains("\nphase 5 7 sphere test\n"));
        assert!(text.ends_with("\nend\n"));
        assert_eq!(parse(text.as_bytes()), Ok(file.clone()));
        assert_eq!(file.counter("rays.primary"), Some(307_200));
        assert_eq!(file.user_counter("bvh refits"), Some(12));
        assert_eq!(file.phase("setup").map(|p| p.total_samples), Some(2));
        assert_eq!(file.seconds_per_sample(), Some(0.00102));
    }

    /// The error for `text`, as displayed.
    fn refusal(text: &str) -> String {
        match parse(text.as_bytes()) {
            Ok(file) => panic!("accepted: {file:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn faults_are_named_with_their_line_and_byte() {
        let good = example().to_text();
        // Hand-located: line 2 starts at byte 15 ("rtprof.probe 1\n" is 15 bytes).
        assert_eq!(
            refusal(&good.replace("writer c", "writer c d")),
            "line 2 (byte 22): writer \"c d\" is not one word"
        );
        assert_eq!(
            refusal(&good.replace("pid 4242", "pid 42x")),
            "line 3 (byte 28): not a number: \"42x\""
        );
        assert_eq!(
            refusal(&good.replace("rtprof.probe 1", "rtprof.probe 2")),
            "line 1 (byte 0): probe format version \"2\"; this rtprof reads `rtprof.probe 1`"
        );
        assert!(
            refusal(&good.replace("pid 4242", "pid 99999999999999999999"))
                .ends_with("number out of range: 99999999999999999999")
        );
        assert!(refusal(&good.replace("\nend\n", "\n")).contains("truncated: no `end` line"));
        assert!(refusal(&good[..good.len() - 1]).contains("the last line has no end"));
        assert!(refusal(&format!("{good}counter 1 x\n")).contains("text after the `end` line"));
        assert!(refusal(&good.replace("threads 8\n", "")).contains("no `threads` line"));
        assert!(
            refusal(&good.replace("threads 8\n", "threads 8\nthreads 9\n"))
                .contains("a second `threads` line")
        );
        assert!(
            refusal(&good.replace("outside 3", "outside 4"))
                .contains("add up to 11, not samples 10")
        );
        assert!(refusal(&good.replace("phase 5 7", "phase 8 7")).contains("must not exceed"));
        assert!(refusal(&good.replace("counter 307200 ", "counter 307200  ")).contains("a name"));
        assert!(refusal(&good.replace("writer c", "writer\tc")).contains("control character"));
        // A two-byte control character (U+008B), as the fuzz campaign's finding had it:
        // named whole, at its first byte.
        let c1 = good.replace("writer c", "writer \u{8b}c");
        let error = parse(c1.as_bytes())
            .err()
            .map(|e| (e.offset, e.to_string()));
        let at = c1.find('\u{8b}');
        assert!(
            error
                .as_ref()
                .is_some_and(|(offset, text)| Some(*offset) == at
                    && text.contains("control character '\\u{8b}'")),
            "{error:?}"
        );
        assert!(
            refusal(&good.replace("reason signal 15", "reason signal 99")).contains("no signal")
        );
        assert!(refusal(&good.replace("unbalanced", "imbalance")).contains("unknown record"));
        assert!(refusal("").contains("empty"));
        let mut bytes = good.clone().into_bytes();
        bytes[16] = 0xff; // inside "writer"
        let error = parse(&bytes).err().map(|e| (e.line, e.offset));
        assert_eq!(error, Some((2, 16)));
    }

    /// A xorshift64 generator: reproducible hostile inputs without a dependency.
    struct XorShift(u64);

    impl XorShift {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
    }

    #[test]
    fn truncations_and_random_bytes_are_refused_without_a_panic() {
        let good = example().to_text().into_bytes();
        // Every cut short of the whole file is refused, and says where.
        for cut in 0..good.len() {
            let error = parse(&good[..cut]).err();
            assert!(error.is_some(), "a file cut at {cut} bytes was accepted");
            assert!(error.is_some_and(|e| e.offset <= cut && e.line >= 1));
        }
        let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
        for round in 0..20_000 {
            let mut bytes = good.clone();
            // Flip, insert or delete a few bytes, or replace the whole with noise.
            match round % 4 {
                0 => {
                    for _ in 0..=rng.next() % 4 {
                        let i = (rng.next() % bytes.len() as u64) as usize;
                        bytes[i] = rng.next() as u8;
                    }
                }
                1 => {
                    let i = (rng.next() % bytes.len() as u64) as usize;
                    let b = b" 0123456789\nabcdeprt_"[(rng.next() % 21) as usize];
                    bytes.insert(i, b);
                }
                2 => {
                    let i = (rng.next() % bytes.len() as u64) as usize;
                    bytes.remove(i);
                }
                _ => {
                    let n = (rng.next() % 300) as usize;
                    bytes = (0..n).map(|_| rng.next() as u8).collect();
                }
            }
            // What fuzz/fuzz_targets/probe_file.rs checks: a refusal names a byte of the
            // input, an accepted file reads back from its text.
            match parse(&bytes) {
                Err(e) => {
                    assert!(e.offset <= bytes.len(), "{e} beyond {} bytes", bytes.len());
                    assert!(!e.message.is_empty() && e.line >= 1);
                }
                Ok(file) => assert_eq!(parse(file.to_text().as_bytes()), Ok(file)),
            }
        }
        let huge = vec![b'a'; MAX_FILE_BYTES + 1];
        assert!(parse(&huge).is_err_and(|e| e.message.contains("larger than")));
    }
}
