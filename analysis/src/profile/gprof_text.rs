//! Readers of the gprof-format texts [`super::gprof`] writes: the flat profile and the
//! call graph parsed back into rows. Only tests use them (to check that the texts say
//! what the tables hold, and that `rtprof profile`'s files are well-formed), so they
//! are compiled for tests and, through the `gprof-text` feature, for the workspace's
//! test targets; the binary never carries them. Besides gprof's two tables, the flat
//! profile's noise list and shares table ([`super::flat`]) are read back too.

use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Why a gprof text could not be read back.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum GprofParseError {
    #[error("no {0} header line found")]
    MissingHeader(&'static str),
    #[error("line {line}: {problem}")]
    Line { line: usize, problem: String },
}

/// A flat-profile row as read back from text (per-call values in the text's unit).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedFlatRow {
    pub name: String,
    pub percent: f64,
    pub cumulative_seconds: f64,
    pub self_seconds: f64,
    pub calls: Option<u64>,
    pub self_per_call: Option<f64>,
    pub total_per_call: Option<f64>,
}

/// A call-graph entry as read back from text.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedEntry {
    pub index: usize,
    pub percent: f64,
    pub self_seconds: f64,
    pub children_seconds: f64,
    /// Calls from the `called` column (the part before a `+`).
    pub called: Option<u64>,
    /// Name without the ` <cycle N>` suffix.
    pub name: String,
    /// Cycle from ` <cycle N>` or `<cycle N as a whole>`.
    pub cycle: Option<u32>,
    pub parents: Vec<ParsedArc>,
    pub children: Vec<ParsedArc>,
}

/// A parent or child line as read back from text.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedArc {
    /// Name without ` <cycle N>`; `<spontaneous>` for gprof's no-caller line.
    pub name: String,
    pub index: Option<usize>,
    pub cycle: Option<u32>,
    /// Blank for calls among siblings of a cycle and for `<spontaneous>`.
    pub self_seconds: Option<f64>,
    pub children_seconds: Option<f64>,
    /// The raw `called` columns (e.g. `5/10`), when not blank.
    pub called: Option<String>,
}

/// Reads printf-style fields off one line. Widths are minimums, as in printf: a value
/// wider than its field runs on and pushes the rest of the line to the right.
struct Columns<'a> {
    line: &'a str,
    position: usize,
    number: usize,
}

impl<'a> Columns<'a> {
    fn new(line: &'a str, number: usize) -> Self {
        Columns {
            line,
            position: 0,
            number,
        }
    }

    fn error(&self, problem: impl Into<String>) -> GprofParseError {
        line_error(self.number, problem)
    }

    /// The rest of the line, which must hold a name.
    fn label(&self) -> Result<&'a str, GprofParseError> {
        let label = self.line.get(self.position..).unwrap_or("").trim_start();
        if label.is_empty() {
            Err(self.error("name is missing"))
        } else {
            Ok(label)
        }
    }

    /// The next field of `width` bytes, trimmed; `None` when blank.
    fn field(&mut self, width: usize) -> Result<Option<&'a str>, GprofParseError> {
        let rest = self.line.get(self.position..).unwrap_or("");
        let bytes = rest.as_bytes();
        let mut end = width.min(bytes.len());
        while end > 0 && end < bytes.len() && bytes[end] != b' ' && bytes[end - 1] != b' ' {
            end += 1;
        }
        let text = rest
            .get(..end)
            .ok_or_else(|| self.error("a column boundary cuts a character"))?;
        self.position += end;
        let text = text.trim();
        Ok((!text.is_empty()).then_some(text))
    }

    fn number<T: FromStr>(
        &mut self,
        width: usize,
        what: &str,
    ) -> Result<Option<T>, GprofParseError> {
        match self.field(width)? {
            None => Ok(None),
            Some(text) => text
                .parse()
                .map(Some)
                .map_err(|_| self.error(format!("{what} is not a number: {text:?}"))),
        }
    }

    fn required<T: FromStr>(&mut self, width: usize, what: &str) -> Result<T, GprofParseError> {
        self.number(width, what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }
}

fn line_error(line: usize, problem: impl Into<String>) -> GprofParseError {
    GprofParseError::Line {
        line,
        problem: problem.into(),
    }
}

/// Lines (numbered from 1) after the first line accepted by `is_header`.
fn lines_after<'a>(
    text: &'a str,
    is_header: impl Fn(&str) -> bool,
    what: &'static str,
) -> Result<impl Iterator<Item = (usize, &'a str)>, GprofParseError> {
    let mut lines = text.lines().enumerate().map(|(i, line)| (i + 1, line));
    if lines.by_ref().any(|(_, line)| is_header(line)) {
        Ok(lines)
    } else {
        Err(GprofParseError::MissingHeader(what))
    }
}

/// Reads the rows of a gprof flat profile (ours or GNU gprof's) by its column layout
/// `%6.2f %9.2f %8.2f %8lu %8.2f %8.2f  name`, with blank call columns read as `None`.
/// Rows run from the ` time   seconds` header line to the first blank line.
pub fn parse_flat_text(text: &str) -> Result<Vec<ParsedFlatRow>, GprofParseError> {
    let mut rows = Vec::new();
    for (number, line) in lines_after(text, |line| line.starts_with(" time "), "flat profile")? {
        if line.trim().is_empty() {
            break;
        }
        let mut columns = Columns::new(line, number);
        let percent = columns.required(6, "% time")?;
        let cumulative_seconds = columns.required(10, "cumulative seconds")?;
        let self_seconds = columns.required(9, "self seconds")?;
        let calls = columns.number(9, "calls")?;
        let self_per_call = columns.number(9, "self per call")?;
        let total_per_call = columns.number(9, "total per call")?;
        if columns.field(2)?.is_some() {
            return Err(columns.error("expected two spaces before the name"));
        }
        let name = columns.label()?;
        rows.push(ParsedFlatRow {
            name: name.to_owned(),
            percent,
            cumulative_seconds,
            self_seconds,
            calls,
            self_per_call,
            total_per_call,
        });
    }
    Ok(rows)
}

/// Reads the entries of a gprof call graph (ours or GNU gprof's): primary lines start
/// with `[`, the lines above one are its parents, those below its children, and the
/// dash line ends an entry. The table runs from the `index % time` header line to the
/// first blank line.
pub fn parse_call_graph_text(text: &str) -> Result<Vec<ParsedEntry>, GprofParseError> {
    let mut entries = Vec::new();
    let mut parents = Vec::new();
    let mut current: Option<ParsedEntry> = None;
    let mut last_line = 0;
    for (number, line) in lines_after(text, |line| line.starts_with("index % time"), "call graph")?
    {
        if line.trim().is_empty() {
            break;
        }
        last_line = number;
        if line.bytes().all(|b| b == b'-') {
            match current.take() {
                Some(entry) => entries.push(entry),
                None if parents.is_empty() => {}
                None => return Err(line_error(number, "entry has no primary line")),
            }
        } else if line.starts_with('[') {
            if current.is_some() {
                return Err(line_error(number, "second primary line in one entry"));
            }
            let mut entry = parse_primary_line(line, number)?;
            entry.parents = std::mem::take(&mut parents);
            current = Some(entry);
        } else {
            let arc = parse_arc_line(line, number)?;
            match current.as_mut() {
                Some(entry) => entry.children.push(arc),
                None => parents.push(arc),
            }
        }
    }
    match current {
        Some(entry) => {
            entries.push(entry);
            Ok(entries)
        }
        None if !parents.is_empty() => Err(line_error(last_line, "entry has no primary line")),
        None => Ok(entries),
    }
}

/// `%-6.6s %5.1f %7.2f %7.2f`, the 17-column `called` part, then `name [index]`.
fn parse_primary_line(line: &str, number: usize) -> Result<ParsedEntry, GprofParseError> {
    let mut columns = Columns::new(line, number);
    let tag = columns.field(6)?.unwrap_or("");
    let index = tag
        .strip_prefix('[')
        .and_then(|t| t.strip_suffix(']'))
        .and_then(|t| t.parse().ok())
        .ok_or_else(|| columns.error(format!("bad index {tag:?}")))?;
    let percent = columns.required(6, "% time")?;
    let self_seconds = columns.required(8, "self")?;
    let children_seconds = columns.required(8, "children")?;
    let called = match columns.field(17)? {
        None => None,
        Some(text) => {
            let calls = text.split('+').next().unwrap_or(text);
            Some(
                calls
                    .parse()
                    .map_err(|_| columns.error(format!("called is not a count: {text:?}")))?,
            )
        }
    };
    let (name, _, cycle) = split_label(columns.label()?);
    Ok(ParsedEntry {
        index,
        percent,
        self_seconds,
        children_seconds,
        called,
        name,
        cycle,
        parents: Vec::new(),
        children: Vec::new(),
    })
}

/// `%6.6s %5.5s %7.2f %7.2f` (times may be blank), the 21-column `called` part, name.
fn parse_arc_line(line: &str, number: usize) -> Result<ParsedArc, GprofParseError> {
    let mut columns = Columns::new(line, number);
    if columns.field(13)?.is_some() {
        return Err(columns.error("a parent or child line must start with 13 blanks"));
    }
    let self_seconds = columns.number(7, "self")?;
    let children_seconds = columns.number(8, "children")?;
    let called = columns.field(21)?.map(str::to_owned);
    let (name, index, cycle) = split_label(columns.label()?);
    Ok(ParsedArc {
        name,
        index,
        cycle,
        self_seconds,
        children_seconds,
        called,
    })
}

/// Splits `name <cycle N> [index]` into its parts.
fn split_label(label: &str) -> (String, Option<usize>, Option<u32>) {
    let (mut name, index) = match label.rsplit_once(" [") {
        Some((name, tail)) => match tail.strip_suffix(']').and_then(|t| t.parse().ok()) {
            Some(index) => (name, Some(index)),
            None => (label, None),
        },
        None => (label, None),
    };
    let mut cycle = None;
    if let Some((base, tail)) = name.rsplit_once(" <cycle ")
        && let Some(number) = tail.strip_suffix('>').and_then(|t| t.parse().ok())
    {
        name = base;
        cycle = Some(number);
    } else if let Some(number) = name
        .strip_prefix("<cycle ")
        .and_then(|t| t.strip_suffix(" as a whole>"))
        .and_then(|t| t.parse().ok())
    {
        cycle = Some(number);
    }
    (name.to_owned(), index, cycle)
}

/// A row of the flat profile's list of rows below the noise floor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedNoiseRow {
    pub name: String,
    /// Calls per render; `None` when blank.
    pub calls: Option<u64>,
}

/// A row of the flat profile's shares table (percent).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedShareRow {
    pub name: String,
    pub inclusive_percent: f64,
    pub inclusive_interval: (f64, f64),
    /// `None` where the text says `noise`.
    pub self_percent: Option<f64>,
    pub self_interval: (f64, f64),
}

/// Width of the shares table's columns before the name:
/// `%11.2f  (%6.2f, %6.2f)  %8s  (%6.2f, %6.2f)  `.
const SHARE_COLUMNS: usize = 11 + 2 + 16 + 2 + 8 + 2 + 16 + 2;

/// Reads the flat profile's rows below the noise floor: `%10s  name` lines after the
/// `calls  name` heading that follows the `Below the noise floor` paragraph, up to the
/// next blank line. No such paragraph: no rows.
pub fn parse_flat_noise(text: &str) -> Result<Vec<ParsedNoiseRow>, GprofParseError> {
    let Ok(mut lines) = lines_after(
        text,
        |line| line.starts_with("Below the noise floor"),
        "noise floor",
    ) else {
        return Ok(Vec::new());
    };
    if !lines
        .by_ref()
        .any(|(_, line)| line.trim_start().starts_with("calls  name"))
    {
        return Err(GprofParseError::MissingHeader("noise floor table"));
    }
    let mut rows = Vec::new();
    for (number, line) in lines {
        if line.trim().is_empty() {
            break;
        }
        let mut columns = Columns::new(line, number);
        let calls = columns.number(10, "calls")?;
        let name = columns.label()?;
        rows.push(ParsedNoiseRow {
            name: name.to_owned(),
            calls,
        });
    }
    Ok(rows)
}

/// Reads the flat profile's shares table: the lines after the `inclusive %` heading up
/// to the next blank line.
pub fn parse_flat_shares(text: &str) -> Result<Vec<ParsedShareRow>, GprofParseError> {
    let mut rows = Vec::new();
    for (number, line) in lines_after(text, |line| line.starts_with("inclusive %"), "shares")? {
        if line.trim().is_empty() {
            break;
        }
        let (figures, name) = match (line.get(..SHARE_COLUMNS), line.get(SHARE_COLUMNS..)) {
            (Some(figures), Some(name)) if !name.trim().is_empty() => (figures, name),
            _ => return Err(line_error(number, "line too short for the shares columns")),
        };
        let cleaned: String = figures
            .chars()
            .map(|c| if matches!(c, '(' | ',' | ')') { ' ' } else { c })
            .collect();
        let tokens: Vec<&str> = cleaned.split_whitespace().collect();
        let [inclusive, i_low, i_high, own, s_low, s_high] = tokens.as_slice() else {
            return Err(line_error(number, "expected six share columns"));
        };
        let number_at = |text: &str| {
            text.parse::<f64>()
                .map_err(|_| line_error(number, format!("not a number: {text:?}")))
        };
        rows.push(ParsedShareRow {
            name: name.to_owned(),
            inclusive_percent: number_at(inclusive)?,
            inclusive_interval: (number_at(i_low)?, number_at(i_high)?),
            self_percent: if *own == "noise" {
                None
            } else {
                Some(number_at(own)?)
            },
            self_interval: (number_at(s_low)?, number_at(s_high)?),
        });
    }
    Ok(rows)
}
