//! GNU gprof's text output read into rtprof's flat profile and call graph, with
//! gprof's own exact call counts: what `gprof a.out gmon.out` (with or without `-b`)
//! prints for a `-pg` build, the thesis's way of profiling.
//!
//! # What is read
//! - The flat profile (binutils `gprof/hist.c`): the `Each sample counts as X
//!   seconds.` line, the per-call unit from the column headings (`us/call`,
//!   ` s/call`, gprof's SI prefixes from `T` to `y`), and each row
//!   `%6.2f %9.2f %8.2f` then `%8lu %8.2f %8.2f` or 28 blanks, two spaces and the
//!   name. The rows end at a blank or form feed line.
//! - The call graph (`gprof/cg_print.c`, GNU layout, the `index % time    self
//!   children    called     name` heading): entries between dash lines, each with its
//!   parents, its `[index]` line and its children; `<spontaneous>`; cycle members
//!   (`name <cycle N> [index]`) and `<cycle N as a whole>` entries with their member
//!   lines; counts `calls/total`, calls among siblings and to itself (one count), and
//!   `calls+self` on `[index]` and member lines. Names are whatever gprof printed:
//!   demangled C++ with spaces, parentheses and templates, read as the rest of the
//!   line up to ` [index]` (or ` (index)`, gprof's mark of a function it does not
//!   list). The table ends at a blank or form feed line.
//! - Not read: the explanations, the index by function name (the entries carry the
//!   same names and indexes), the BSD layout of `gprof -T` (an error says so), and
//!   rtprof's own sampled call graph, whose arc counts are samples (an error says so;
//!   its flat profile reads, calls per render and all).
//!
//! Widths are printf minimums, so a wide value pushes the rest of its line right:
//! columns are found as whitespace-separated tokens, and a blank `calls` column is
//! told from a filled one by where the next token starts (a count starts in the
//! columns of `called`, a name only after them), so names that start with a digit
//! still read as names.
//!
//! # The model
//! [`ImportedGprof`] holds a [`FlatProfile`] and a [`CallGraph`] of
//! [`Origin::Gprof`], the types rtprof's sampled profile fills:
//! - samples = seconds / the seconds per sample (gprof's histogram ticks), so the
//!   shares, their Wilson intervals and the noise rows mean what they mean for a
//!   sampled profile; percents are gprof's as printed;
//! - a flat row's children seconds are its call graph entry's (gprof's propagated
//!   time); without a call graph, total per call × calls − self;
//! - calls are gprof's counts ([`FlatRow::calls`], [`CallGraphEntry::calls`] and
//!   `self_calls`, and each arc's [`CallArc::calls`]), `renders` is 1;
//! - a row is a root when its entry has no callers (`<spontaneous>`) and calls
//!   others.
//!
//! Bad input gives a [`GprofImportError`] with the line number, never a panic.

use super::flat::{FlatProfile, FlatRow};
use super::gprof::{CallArc, CallGraph, CallGraphEntry, SAMPLED_COUNTS_LINE};
use super::share_interval::{Z_95, below_noise_floor, wilson_interval};
use super::{CallCounts, Origin};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::{Path, PathBuf};

/// gprof's flat profile and call graph as rtprof's types (either may be absent:
/// `gprof -p` prints only the first, `gprof -q` only the second).
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedGprof {
    pub flat: Option<FlatProfile>,
    pub call_graph: Option<CallGraph>,
}

impl ImportedGprof {
    /// Exact calls by function name: the flat profile's counts, or the call graph's
    /// where there is no flat profile (calls from itself not included, as in gprof's
    /// `calls` column).
    pub fn calls(&self) -> CallCounts {
        match (&self.flat, &self.call_graph) {
            (Some(flat), _) => flat
                .rows
                .iter()
                .filter_map(|r| r.calls.map(|c| (r.name.clone(), c)))
                .collect(),
            (None, Some(graph)) => graph
                .entries
                .iter()
                .filter(|e| !e.whole_cycle)
                .filter_map(|e| e.calls.map(|c| (e.name.clone(), c)))
                .collect(),
            (None, None) => CallCounts::new(),
        }
    }

    /// Exact calls along each arc, `(caller, callee)`, from the call graph's child
    /// lines (a function calling itself included).
    pub fn arc_calls(&self) -> BTreeMap<(String, String), u64> {
        let mut arcs = BTreeMap::new();
        for entry in self.call_graph.iter().flat_map(|g| &g.entries) {
            if entry.whole_cycle {
                continue;
            }
            for child in &entry.children {
                if let Some(calls) = child.calls {
                    arcs.insert((entry.name.clone(), child.name.clone()), calls);
                }
            }
        }
        arcs
    }
}

/// Why gprof's output could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GprofImportError {
    #[error("line {line}: {problem}")]
    Line { line: usize, problem: String },
    #[error(
        "no gprof output found: neither a flat profile (\"Flat profile:\") nor a call graph (\"index % time    self  children    called     name\")"
    )]
    NothingFound,
}

/// Why a file of gprof's output could not be read: `path:line: problem`.
#[derive(Debug, thiserror::Error)]
pub enum GprofFileError {
    #[error("cannot read {}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}:{line}: {problem}", path.display())]
    Line {
        path: PathBuf,
        line: usize,
        problem: String,
    },
    #[error("{}: {error}", path.display())]
    Whole {
        path: PathBuf,
        error: GprofImportError,
    },
}

/// Reads a file of gprof's output (bytes that are not UTF-8 are replaced).
pub fn read(path: &Path) -> Result<ImportedGprof, GprofFileError> {
    let bytes = std::fs::read(path).map_err(|source| GprofFileError::Io {
        path: path.to_owned(),
        source,
    })?;
    parse(&String::from_utf8_lossy(&bytes)).map_err(|error| match error {
        GprofImportError::Line { line, problem } => GprofFileError::Line {
            path: path.to_owned(),
            line,
            problem,
        },
        error => GprofFileError::Whole {
            path: path.to_owned(),
            error,
        },
    })
}

/// Reads gprof's text output (flat profile, call graph, or both).
pub fn parse(text: &str) -> Result<ImportedGprof, GprofImportError> {
    let lines: Vec<&str> = text.lines().collect();
    let flat = parse_flat(&lines)?;
    let graph = parse_graph(&lines)?;
    if flat.is_none() && graph.is_none() {
        return Err(GprofImportError::NothingFound);
    }
    // Seconds per sample: the flat profile's, else the granularity line's one sample
    // (a share of the total), else gprof's usual 100 Hz.
    let from_granularity = |(percent, total): (f64, f64)| {
        let one = percent / 100.0 * total;
        (one.is_finite() && one > 0.0).then_some(one)
    };
    let seconds_per_sample = match (&flat, &graph) {
        (Some(flat), _) => flat.seconds_per_sample,
        (None, Some(graph)) => graph.granularity.and_then(from_granularity).unwrap_or(0.01),
        (None, None) => 0.01,
    };
    let call_graph = graph.map(|g| g.into_model(seconds_per_sample));
    let flat = flat.map(|f| f.into_model(call_graph.as_ref()));
    Ok(ImportedGprof { flat, call_graph })
}

fn line_error(line: usize, problem: impl Into<String>) -> GprofImportError {
    GprofImportError::Line {
        line,
        problem: problem.into(),
    }
}

/// Whether a line ends a table: blank, or gprof's form feed (whitespace to `trim`).
fn ends_table(line: &str) -> bool {
    line.trim().is_empty()
}

/// Whitespace-separated tokens of one line, with their byte positions.
struct Cursor<'a> {
    line: &'a str,
    position: usize,
    number: usize,
}

impl<'a> Cursor<'a> {
    fn new(line: &'a str, number: usize) -> Self {
        Cursor {
            line,
            position: 0,
            number,
        }
    }

    fn error(&self, problem: impl Into<String>) -> GprofImportError {
        line_error(self.number, problem)
    }

    /// Where the next token starts (the line's length when none is left).
    fn next_start(&self) -> usize {
        let rest = self.line.get(self.position..).unwrap_or("");
        self.position + (rest.len() - rest.trim_start().len())
    }

    /// The next token; `None` at the end of the line.
    fn token(&mut self) -> Option<&'a str> {
        let start = self.next_start();
        let rest = self.line.get(start..).unwrap_or("");
        let length = rest.find(char::is_whitespace).unwrap_or(rest.len());
        self.position = start + length;
        (length > 0).then(|| &rest[..length])
    }

    fn float(&mut self, what: &str) -> Result<f64, GprofImportError> {
        let token = self
            .token()
            .ok_or_else(|| self.error(format!("{what} is missing")))?;
        parse_float(token).ok_or_else(|| self.error(format!("{what} is not a number: {token:?}")))
    }

    /// The rest of the line from the next token on.
    fn rest(&self) -> &'a str {
        self.line.get(self.next_start()..).unwrap_or("").trim_end()
    }
}

/// A time or percent as gprof prints it (`%f`): digits with a decimal point.
fn parse_float(token: &str) -> Option<f64> {
    let plain = token.bytes().all(|b| b.is_ascii_digit() || b == b'.') && token.contains('.');
    plain.then(|| token.parse().ok()).flatten()
}

/// A `called` token: `N`, `N/M` or `N+M`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Count {
    calls: u64,
    /// The number after `/` (the callee's calls) or `+` (calls from itself).
    second: Option<u64>,
    plus: bool,
}

fn parse_count(token: &str) -> Option<Count> {
    let digits = |t: &str| -> Option<u64> {
        (!t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()))
            .then(|| t.parse().ok())
            .flatten()
    };
    if let Some((calls, total)) = token.split_once('/') {
        return Some(Count {
            calls: digits(calls)?,
            second: Some(digits(total)?),
            plus: false,
        });
    }
    if let Some((calls, own)) = token.split_once('+') {
        return Some(Count {
            calls: digits(calls)?,
            second: Some(digits(own)?),
            plus: true,
        });
    }
    Some(Count {
        calls: digits(token)?,
        second: None,
        plus: false,
    })
}

// ---------------------------------------------------------------- flat profile

struct ParsedFlat {
    seconds_per_sample: f64,
    /// The per-call unit as rtprof writes it (`us/call`, ` s/call`).
    unit: String,
    rows: Vec<ParsedFlatRow>,
}

struct ParsedFlatRow {
    name: String,
    percent: f64,
    cumulative_seconds: f64,
    self_seconds: f64,
    calls: Option<u64>,
    self_per_call: Option<f64>,
    total_per_call: Option<f64>,
}

/// Columns from the end of `self seconds` to the name when the call columns are
/// blank: ` %8.8s %8.8s %8.8s  ` (hist.c).
const FLAT_BLANK_CALLS: usize = 3 * 9 + 2;

fn parse_flat(lines: &[&str]) -> Result<Option<ParsedFlat>, GprofImportError> {
    let Some(title) = lines.iter().position(|l| l.trim() == "Flat profile:") else {
        return Ok(None);
    };
    let mut seconds_per_sample = None;
    let mut unit = None;
    let mut first_row = None;
    for (i, line) in lines.iter().enumerate().skip(title + 1) {
        let number = i + 1;
        if let Some(rest) = line.trim_start().strip_prefix("Each sample counts as ") {
            let value = rest.split_whitespace().next().unwrap_or("");
            let value: f64 = value.parse().map_err(|_| {
                line_error(
                    number,
                    format!("seconds per sample is not a number: {value:?}"),
                )
            })?;
            if !(value.is_finite() && value > 0.0) {
                return Err(line_error(
                    number,
                    format!("seconds per sample must be positive, not {value}"),
                ));
            }
            seconds_per_sample = Some(value);
        } else if line.trim_start().starts_with("time ") && line.contains("seconds") {
            // " time   seconds   seconds    calls  us/call  us/call  name"
            let tokens: Vec<&str> = line.split_whitespace().collect();
            let per_call = tokens.get(4).copied().unwrap_or("");
            if !per_call.ends_with("s/call") {
                return Err(line_error(
                    number,
                    format!(
                        "expected the per-call unit (like us/call) in the headings, found {per_call:?}"
                    ),
                ));
            }
            unit = Some(if per_call == "s/call" {
                " s/call".to_owned()
            } else {
                per_call.to_owned()
            });
            first_row = Some(i + 1);
            break;
        } else if line.trim_start().starts_with("Call graph") || line.starts_with("index % time") {
            break;
        }
    }
    let (Some(first_row), Some(unit)) = (first_row, unit) else {
        return Err(line_error(
            title + 1,
            "flat profile without its column headings (\" time   seconds   seconds    calls ...\")",
        ));
    };
    let seconds_per_sample = seconds_per_sample.ok_or_else(|| {
        line_error(
            title + 1,
            "flat profile without \"Each sample counts as ... seconds.\"",
        )
    })?;
    let mut rows = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(first_row) {
        if ends_table(line) {
            break;
        }
        rows.push(parse_flat_row(line, i + 1)?);
    }
    Ok(Some(ParsedFlat {
        seconds_per_sample,
        unit,
        rows,
    }))
}

fn parse_flat_row(line: &str, number: usize) -> Result<ParsedFlatRow, GprofImportError> {
    let mut cursor = Cursor::new(line, number);
    let percent = cursor.float("% time")?;
    let cumulative_seconds = cursor.float("cumulative seconds")?;
    let self_seconds = cursor.float("self seconds")?;
    let self_end = cursor.position;
    let (mut calls, mut self_per_call, mut total_per_call) = (None, None, None);
    if cursor.next_start() < self_end + FLAT_BLANK_CALLS {
        let token = cursor.token().unwrap_or("");
        let count = parse_count(token)
            .filter(|c| c.second.is_none())
            .ok_or_else(|| cursor.error(format!("calls is not a count: {token:?}")))?;
        calls = Some(count.calls);
        self_per_call = Some(cursor.float("self per call")?);
        total_per_call = Some(cursor.float("total per call")?);
    }
    let name = cursor.rest();
    if name.is_empty() {
        return Err(cursor.error("the function's name is missing"));
    }
    Ok(ParsedFlatRow {
        name: name.to_owned(),
        percent,
        cumulative_seconds,
        self_seconds,
        calls,
        self_per_call,
        total_per_call,
    })
}

/// The factor from seconds to the unit `Xs/call` (gprof's SItab).
fn per_call_scale(unit: &str) -> Option<f64> {
    let prefix = unit.strip_suffix("s/call")?;
    Some(match prefix.trim() {
        "" => 1.0,
        "T" => 1e-12,
        "G" => 1e-9,
        "M" => 1e-6,
        "K" => 1e-3,
        "m" => 1e3,
        "u" => 1e6,
        "n" => 1e9,
        "p" => 1e12,
        "f" => 1e15,
        "a" => 1e18,
        "z" => 1e21,
        "y" => 1e24,
        _ => return None,
    })
}

impl ParsedFlat {
    fn into_model(self, graph: Option<&CallGraph>) -> FlatProfile {
        let spp = self.seconds_per_sample;
        let samples_of = |seconds: f64| (seconds / spp).round().max(0.0) as u64;
        let total_seconds = self
            .rows
            .last()
            .map_or(0.0, |r| r.cumulative_seconds)
            .max(self.rows.iter().map(|r| r.self_seconds).sum::<f64>());
        let total = samples_of(total_seconds);
        let entries: HashMap<&str, &CallGraphEntry> = graph
            .iter()
            .flat_map(|g| &g.entries)
            .filter(|e| !e.whole_cycle)
            .map(|e| (e.name.as_str(), e))
            .collect();
        let scale = per_call_scale(&self.unit);
        let rows = self
            .rows
            .into_iter()
            .map(|row| {
                let entry = entries.get(row.name.as_str());
                let children_seconds = match (entry, row.calls, row.total_per_call, scale) {
                    (Some(e), ..) => e.children_seconds,
                    (None, Some(calls), Some(total), Some(scale)) => {
                        (total / scale * calls as f64 - row.self_seconds).max(0.0)
                    }
                    _ => 0.0,
                };
                let inclusive_seconds = row.self_seconds + children_seconds;
                let (own, inclusive) =
                    (samples_of(row.self_seconds), samples_of(inclusive_seconds));
                let interval = |count: u64| wilson_interval(count, total, Z_95).scaled(100.0);
                FlatRow {
                    percent: row.percent,
                    cumulative_seconds: row.cumulative_seconds,
                    self_seconds: row.self_seconds,
                    calls: row.calls,
                    self_per_call: row.self_per_call,
                    total_per_call: row.total_per_call,
                    children_seconds,
                    self_samples: own,
                    inclusive_samples: inclusive,
                    inclusive_seconds,
                    inclusive_percent: entry.map_or_else(
                        || 100.0 * inclusive as f64 / total.max(1) as f64,
                        |e| e.percent,
                    ),
                    self_interval: interval(own),
                    inclusive_interval: interval(inclusive),
                    noise: below_noise_floor(own, total),
                    root: entry.is_some_and(|e| e.parents.is_empty() && !e.children.is_empty()),
                    name: row.name,
                }
            })
            .collect();
        FlatProfile {
            origin: Origin::Gprof,
            seconds_per_sample: spp,
            total_seconds,
            samples: total,
            renders: 1,
            unit: self.unit,
            rows,
        }
    }
}

// ----------------------------------------------------------------- call graph

struct ParsedGraph {
    /// `for X% of Y seconds` of the granularity line.
    granularity: Option<(f64, f64)>,
    entries: Vec<ParsedEntry>,
}

struct ParsedEntry {
    index: usize,
    name: String,
    cycle: Option<u32>,
    whole_cycle: bool,
    percent: f64,
    self_seconds: f64,
    children_seconds: f64,
    count: Option<Count>,
    parents: Vec<ParsedArc>,
    children: Vec<ParsedArc>,
}

struct ParsedArc {
    name: String,
    index: usize,
    times: Option<(f64, f64)>,
    count: Count,
}

/// A parent, child or member line.
enum ArcLine {
    Spontaneous,
    Arc(ParsedArc),
}

/// Columns from the end of `children` to the name when `called` is blank:
/// ` %7.7s %7.7s ` (cg_print.c).
const PRIMARY_BLANK_CALLS: usize = 1 + 7 + 1 + 7 + 1;

fn is_separator(line: &str) -> bool {
    let line = line.trim_end();
    line.len() >= 10 && line.bytes().all(|b| b == b'-')
}

fn parse_graph(lines: &[&str]) -> Result<Option<ParsedGraph>, GprofImportError> {
    let is_header = |line: &str| {
        let words: Vec<&str> = line.split_whitespace().collect();
        words == ["index", "%", "time", "self", "children", "called", "name"]
    };
    let Some(header) = lines.iter().position(|l| is_header(l)) else {
        if let Some(bsd) = lines.iter().position(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            words.starts_with(&["index", "%time", "self", "descendents"])
        }) {
            return Err(line_error(
                bsd + 1,
                "the BSD layout of the call graph (gprof -T) is not read: run gprof without -T",
            ));
        }
        return Ok(None);
    };
    // rtprof's own sampled graph has samples where gprof has calls: not gprof's.
    if let Some(marker) = lines[..header]
        .iter()
        .position(|l| l.trim() == SAMPLED_COUNTS_LINE)
    {
        return Err(line_error(
            marker + 1,
            "this is rtprof's sampled call graph (its callers' and callees' counts are samples), not gprof's output",
        ));
    }
    let granularity = lines[..header]
        .iter()
        .rev()
        .find(|l| l.starts_with("granularity:"))
        .and_then(|l| {
            let (_, tail) = l.split_once(" for ")?;
            let (percent, tail) = tail.split_once("% of ")?;
            let seconds = tail.split_whitespace().next()?;
            Some((percent.trim().parse().ok()?, seconds.parse().ok()?))
        });

    let mut entries: Vec<ParsedEntry> = Vec::new();
    let mut group: Vec<(usize, &str)> = Vec::new();
    let mut last = header + 1;
    for (i, line) in lines.iter().enumerate().skip(header + 1) {
        let number = i + 1;
        last = number;
        if ends_table(line) {
            break;
        }
        if is_separator(line) {
            if !group.is_empty() {
                entries.push(parse_entry(&group, number)?);
                group.clear();
            }
        } else {
            group.push((number, line));
        }
    }
    if !group.is_empty() {
        entries.push(parse_entry(&group, last)?);
    }
    let mut seen = HashSet::new();
    for entry in &entries {
        if !seen.insert(entry.index) {
            return Err(GprofImportError::Line {
                line: header + 1,
                problem: format!("index [{}] has two entries", entry.index),
            });
        }
    }
    Ok(Some(ParsedGraph {
        granularity,
        entries,
    }))
}

/// One entry's lines (numbered); `end` is the line that closed it, for errors.
fn parse_entry(group: &[(usize, &str)], end: usize) -> Result<ParsedEntry, GprofImportError> {
    let primary_at = group
        .iter()
        .position(|(_, line)| line.starts_with('['))
        .ok_or_else(|| line_error(end, "call graph entry without its [index] line"))?;
    if let Some((number, _)) = group[primary_at + 1..]
        .iter()
        .find(|(_, line)| line.starts_with('['))
    {
        return Err(line_error(*number, "a second [index] line in one entry"));
    }
    let (number, line) = group[primary_at];
    let mut entry = parse_primary(line, number)?;
    for &(number, line) in &group[..primary_at] {
        match parse_arc(line, number)? {
            ArcLine::Spontaneous => {}
            ArcLine::Arc(arc) => entry.parents.push(arc),
        }
    }
    for &(number, line) in &group[primary_at + 1..] {
        // gprof prints <spontaneous> only above a function's line.
        if let ArcLine::Arc(arc) = parse_arc(line, number)? {
            entry.children.push(arc);
        }
    }
    Ok(entry)
}

/// `name <cycle N> [index]`, `<cycle N as a whole> [index]` or `name (index)`.
struct Label {
    name: String,
    index: usize,
    cycle: Option<u32>,
    whole_cycle: bool,
}

fn parse_label(text: &str, number: usize) -> Result<Label, GprofImportError> {
    let text = text.trim();
    let index_of = |open: char, close: char| -> Option<(usize, &str)> {
        let body = text.strip_suffix(close)?;
        let (name, index) = body.rsplit_once(&format!(" {open}"))?;
        let index = (!index.is_empty() && index.bytes().all(|b| b.is_ascii_digit()))
            .then(|| index.parse().ok())
            .flatten()?;
        Some((index, name))
    };
    let (index, name) = index_of('[', ']')
        .or_else(|| index_of('(', ')'))
        .ok_or_else(|| line_error(number, format!("no [index] after the name in {text:?}")))?;
    if let Some(cycle) = name
        .strip_prefix("<cycle ")
        .and_then(|t| t.strip_suffix(" as a whole>"))
    {
        let cycle = cycle
            .parse()
            .map_err(|_| line_error(number, format!("bad cycle number in {name:?}")))?;
        return Ok(Label {
            name: name.to_owned(),
            index,
            cycle: Some(cycle),
            whole_cycle: true,
        });
    }
    let (name, cycle) = match name.rsplit_once(" <cycle ") {
        Some((base, tail)) => match tail.strip_suffix('>').and_then(|t| t.parse().ok()) {
            Some(cycle) => (base, Some(cycle)),
            None => (name, None),
        },
        None => (name, None),
    };
    let name = name.trim();
    if name.is_empty() {
        return Err(line_error(number, "the function's name is missing"));
    }
    Ok(Label {
        name: name.to_owned(),
        index,
        cycle,
        whole_cycle: false,
    })
}

/// `[index] %time self children [called] name [index]`.
fn parse_primary(line: &str, number: usize) -> Result<ParsedEntry, GprofImportError> {
    let mut cursor = Cursor::new(line, number);
    let tag = cursor.token().unwrap_or("");
    // gprof cuts the tag to 6 characters (`%-6.6s`): the index after the name counts.
    let tag_digits = tag.trim_start_matches('[').trim_end_matches(']');
    if tag_digits.is_empty() || !tag_digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(cursor.error(format!("bad index {tag:?}")));
    }
    let percent = cursor.float("% time")?;
    let self_seconds = cursor.float("self")?;
    let children_seconds = cursor.float("children")?;
    let children_end = cursor.position;
    let mut count = None;
    if cursor.next_start() < children_end + PRIMARY_BLANK_CALLS {
        let token = cursor.token().unwrap_or("");
        count = Some(
            parse_count(token)
                .filter(|c| c.second.is_none() || c.plus)
                .ok_or_else(|| cursor.error(format!("called is not a count: {token:?}")))?,
        );
    }
    let label = parse_label(cursor.rest(), number)?;
    if tag.ends_with(']') && tag_digits.parse::<usize>().ok() != Some(label.index) {
        return Err(cursor.error(format!(
            "the line's index {tag} differs from the name's [{}]",
            label.index
        )));
    }
    Ok(ParsedEntry {
        index: label.index,
        name: label.name,
        cycle: label.cycle,
        whole_cycle: label.whole_cycle,
        percent,
        self_seconds,
        children_seconds,
        count,
        parents: Vec::new(),
        children: Vec::new(),
    })
}

/// `[self children] called name [index]` below or above an entry's own line.
fn parse_arc(line: &str, number: usize) -> Result<ArcLine, GprofImportError> {
    if line.trim() == "<spontaneous>" {
        return Ok(ArcLine::Spontaneous);
    }
    let mut cursor = Cursor::new(line, number);
    let first = cursor
        .token()
        .ok_or_else(|| cursor.error("empty call graph line"))?;
    let (times, count_token) = match parse_float(first) {
        Some(own) => {
            let children = cursor.float("children")?;
            let token = cursor
                .token()
                .ok_or_else(|| cursor.error("called is missing"))?;
            (Some((own, children)), token)
        }
        None => (None, first),
    };
    let count = parse_count(count_token)
        .ok_or_else(|| cursor.error(format!("called is not a count: {count_token:?}")))?;
    let label = parse_label(cursor.rest(), number)?;
    if label.whole_cycle {
        return Err(cursor.error("a cycle as a whole cannot be a caller or callee"));
    }
    Ok(ArcLine::Arc(ParsedArc {
        name: label.name,
        index: label.index,
        times,
        count,
    }))
}

impl ParsedGraph {
    fn into_model(self, seconds_per_sample: f64) -> CallGraph {
        let samples_of = |seconds: f64| (seconds / seconds_per_sample).round().max(0.0) as u64;
        let arc = |a: ParsedArc| {
            let (own, children) = a.times.unwrap_or((0.0, 0.0));
            CallArc {
                name: a.name,
                index: a.index,
                self_seconds: own,
                children_seconds: children,
                samples: samples_of(own + children),
                calls: Some(a.count.calls),
            }
        };
        // The granularity line's total; without it (`no time propagated`), the
        // entries' own time.
        let total_seconds = self.granularity.map_or_else(
            || {
                self.entries
                    .iter()
                    .filter(|e| !e.whole_cycle)
                    .map(|e| e.self_seconds)
                    .sum()
            },
            |(_, total)| total,
        );
        let entries = self
            .entries
            .into_iter()
            .map(|e| {
                let (calls, self_calls) = match e.count {
                    Some(Count {
                        calls,
                        second,
                        plus: true,
                    }) => (Some(calls), second),
                    Some(c) => (Some(c.calls), None),
                    None => (None, None),
                };
                CallGraphEntry {
                    index: e.index,
                    name: e.name,
                    percent: e.percent,
                    self_seconds: e.self_seconds,
                    children_seconds: e.children_seconds,
                    calls,
                    self_calls,
                    parents: e.parents.into_iter().map(arc).collect(),
                    children: e.children.into_iter().map(arc).collect(),
                    cycle: e.cycle,
                    whole_cycle: e.whole_cycle,
                }
            })
            .collect();
        CallGraph {
            origin: Origin::Gprof,
            total_seconds,
            total_samples: samples_of(total_seconds),
            renders: 1,
            entries,
        }
    }
}

#[cfg(test)]
mod tests;
