//! The scene memory as an Altera/Intel Memory Initialization File (MIF), the format
//! Quartus reads to preload an on-chip RAM or ROM.
//!
//! Layout: 32-bit words, nine per primitive, primitive `k` at addresses `9k … 9k+8`:
//! centre x, y, z, radius, axis V x, y, z, m max as IEEE-754 single-precision bit
//! patterns, then the type word (0 sphere, 1 cylinder). The thesis describes a
//! primitive as eight floats plus a type bit (257 bits); here the bit gets a word of
//! its own (288 bits) because a MIF describes a memory of one fixed word width: packing
//! the bit would mean 33-bit words (every float misaligned, the block RAM 33 bits
//! wide) or a second one-bit memory with its own file. A whole word keeps one 32-bit
//! memory, one file and plain addressing (`9·index + field`) for 31 bits per primitive.
//! The observer, light and screen set-up live in the scene block's registers, not here.
//!
//! [`parse_mif`] reads the subset of MIF syntax Quartus documents for such files:
//! `WIDTH`, `DEPTH`, `ADDRESS_RADIX`, `DATA_RADIX` (HEX, DEC, UNS, OCT, BIN; HEX when
//! absent), `CONTENT BEGIN … END;`, entries `addr : value;`, `addr : v0 v1 …;`
//! (consecutive addresses) and `[a..b] : value;` (a range), comments `-- …` to the end
//! of the line and `% … %` (possibly over several lines). Addresses no entry sets read
//! as 0.

use crate::hw_scene::{HwPrimitive, HwScene};
use std::fmt::Write as _;

/// Largest DEPTH [`parse_mif`] accepts (4 Mi words, 128 Mbit: far beyond any on-chip
/// memory), so a bad header cannot make it allocate without bound.
pub const MAX_DEPTH: u64 = 1 << 22;

/// Why a MIF could not be read or decoded.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MifError {
    #[error("line {line}: {message}")]
    Syntax { line: usize, message: String },
    #[error(
        "the memory holds {words} words, not a whole number of {per_primitive}-word primitives"
    )]
    PartialPrimitive { words: usize, per_primitive: usize },
    #[error(
        "primitive {index} (address {address:#x}): type word {value:#x} is neither 0 (sphere) nor 1 (cylinder)"
    )]
    BadType {
        index: usize,
        address: usize,
        value: u32,
    },
}

fn syntax(line: usize, message: impl Into<String>) -> MifError {
    MifError::Syntax {
        line,
        message: message.into(),
    }
}

/// The scene memory's words in address order.
pub fn scene_words(scene: &HwScene) -> Vec<u32> {
    scene
        .primitives
        .iter()
        .flat_map(HwPrimitive::to_words)
        .collect()
}

/// The scene memory of `scene` as a MIF (see the module doc for the layout). An empty
/// scene gives `DEPTH=0`, which Quartus refuses; [`HwScene::from_scene`] never makes one.
pub fn to_mif(scene: &HwScene) -> String {
    let depth = scene.primitives.len() * HwPrimitive::WORDS;
    // Enough hex digits for the last address, at least one.
    let address_digits = format!("{:X}", depth.saturating_sub(1)).len();
    let mut out = String::new();
    // `write!` to a String cannot fail; the results are ignored on purpose.
    let _ = writeln!(
        out,
        "-- Scene memory of the thesis's FPGA ray caster (rtprof hwmodel::mif)."
    );
    let _ = writeln!(
        out,
        "-- {} primitives x {} words: centre x y z (a cylinder's base), radius, axis V x y z, m max",
        scene.primitives.len(),
        HwPrimitive::WORDS
    );
    let _ = writeln!(
        out,
        "-- (IEEE-754 single precision), then the type word (0 sphere, 1 cylinder)."
    );
    let _ = writeln!(out);
    let _ = writeln!(out, "WIDTH=32;");
    let _ = writeln!(out, "DEPTH={depth};");
    let _ = writeln!(out);
    let _ = writeln!(out, "ADDRESS_RADIX=HEX;");
    let _ = writeln!(out, "DATA_RADIX=HEX;");
    let _ = writeln!(out);
    let _ = writeln!(out, "CONTENT BEGIN");
    for (index, primitive) in scene.primitives.iter().enumerate() {
        let floats = primitive.floats();
        for (field, word) in primitive.to_words().into_iter().enumerate() {
            let address = index * HwPrimitive::WORDS + field;
            let name = HwPrimitive::WORD_NAMES[field];
            let value = match floats.get(field) {
                Some(f) => f.to_string(),
                None => primitive.kind.name().to_string(),
            };
            let _ = writeln!(
                out,
                "\t{address:0address_digits$X} : {word:08X}; -- [{index}] {name} = {value}"
            );
        }
    }
    let _ = writeln!(out, "END;");
    out
}

/// The radices MIF allows for addresses and data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Radix {
    Hex,
    Dec,
    Oct,
    Bin,
}

impl Radix {
    fn parse(name: &str) -> Option<Self> {
        match name.to_ascii_uppercase().as_str() {
            "HEX" => Some(Self::Hex),
            "DEC" | "UNS" => Some(Self::Dec),
            "OCT" => Some(Self::Oct),
            "BIN" => Some(Self::Bin),
            _ => None,
        }
    }

    fn base(self) -> u32 {
        match self {
            Self::Hex => 16,
            Self::Dec => 10,
            Self::Oct => 8,
            Self::Bin => 2,
        }
    }

    fn number(self, token: &str, what: &str, line: usize) -> Result<u64, MifError> {
        // from_str_radix would take a leading '+'; MIF numbers are bare digits.
        let digits_ok = !token.is_empty() && token.chars().all(|c| c.is_digit(self.base()));
        digits_ok
            .then(|| u64::from_str_radix(token, self.base()).ok())
            .flatten()
            .ok_or_else(|| syntax(line, format!("'{token}' is not a valid {what} in {self:?}")))
    }
}

/// The text with every comment replaced by spaces (line breaks kept, so positions
/// still give line numbers).
fn strip_comments(text: &str) -> Result<String, MifError> {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut line = 1;
    while let Some(c) = chars.next() {
        match c {
            '-' if chars.peek() == Some(&'-') => {
                // A line comment: drop up to (not including) the line break.
                while let Some(&next) = chars.peek() {
                    if next == '\n' {
                        break;
                    }
                    chars.next();
                }
                out.push(' ');
            }
            '%' => {
                let start = line;
                let mut closed = false;
                for next in chars.by_ref() {
                    if next == '%' {
                        closed = true;
                        break;
                    }
                    if next == '\n' {
                        line += 1;
                        out.push('\n');
                    }
                }
                if !closed {
                    return Err(syntax(start, "unterminated '%' comment"));
                }
                out.push(' ');
            }
            '\n' => {
                line += 1;
                out.push('\n');
            }
            other => out.push(other),
        }
    }
    Ok(out)
}

/// Where the parser is in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Section {
    Header,
    Content,
    Done,
}

/// The header's settings and, once `CONTENT BEGIN` is read, the memory.
struct MifReader {
    width: Option<u32>,
    depth: Option<u64>,
    address_radix: Radix,
    data_radix: Radix,
    words: Vec<u32>,
}

impl MifReader {
    fn header(&mut self, statement: &str, line: usize) -> Result<(), MifError> {
        let Some((key, value)) = statement.split_once('=') else {
            return Err(syntax(
                line,
                format!("expected 'KEY = VALUE;' or 'CONTENT BEGIN', found '{statement}'"),
            ));
        };
        let (key, value) = (key.trim(), value.trim());
        let radix = || {
            Radix::parse(value).ok_or_else(|| {
                syntax(
                    line,
                    format!("unknown radix '{value}' (HEX, DEC, UNS, OCT or BIN)"),
                )
            })
        };
        match key.to_ascii_uppercase().as_str() {
            "WIDTH" => {
                let width = Radix::Dec.number(value, "WIDTH", line)?;
                if !(1..=32).contains(&width) {
                    return Err(syntax(line, format!("WIDTH={width}: must be 1 to 32 bits")));
                }
                self.width = Some(width as u32);
            }
            "DEPTH" => {
                let depth = Radix::Dec.number(value, "DEPTH", line)?;
                if depth > MAX_DEPTH {
                    return Err(syntax(
                        line,
                        format!("DEPTH={depth} is larger than {MAX_DEPTH} words"),
                    ));
                }
                self.depth = Some(depth);
            }
            "ADDRESS_RADIX" => self.address_radix = radix()?,
            "DATA_RADIX" => self.data_radix = radix()?,
            _ => return Err(syntax(line, format!("unknown header setting '{key}'"))),
        }
        Ok(())
    }

    /// Reads `CONTENT BEGIN`: the header must be complete.
    fn begin(&mut self, line: usize) -> Result<(), MifError> {
        let (Some(_), Some(depth)) = (self.width, self.depth) else {
            return Err(syntax(
                line,
                "CONTENT BEGIN before both WIDTH and DEPTH are set",
            ));
        };
        self.words = vec![0; depth as usize];
        Ok(())
    }

    fn address(&self, token: &str, line: usize) -> Result<usize, MifError> {
        let address = self.address_radix.number(token, "address", line)?;
        if address >= self.words.len() as u64 {
            return Err(syntax(
                line,
                format!(
                    "address {token} is outside the memory (DEPTH={})",
                    self.words.len()
                ),
            ));
        }
        Ok(address as usize)
    }

    fn value(&self, token: &str, line: usize) -> Result<u32, MifError> {
        let width = self.width.unwrap_or(32);
        let value = self.data_radix.number(token, "value", line)?;
        if value >> width != 0 {
            return Err(syntax(
                line,
                format!("value {token} does not fit in WIDTH={width} bits"),
            ));
        }
        Ok(value as u32)
    }

    /// One `addr : values` or `[a..b] : value` entry.
    fn entry(&mut self, statement: &str, line: usize) -> Result<(), MifError> {
        let Some((target, values)) = statement.split_once(':') else {
            return Err(syntax(
                line,
                format!("expected 'address : value;', found '{statement}'"),
            ));
        };
        let values: Vec<u32> = values
            .split_whitespace()
            .map(|token| self.value(token, line))
            .collect::<Result<_, _>>()?;
        if values.is_empty() {
            return Err(syntax(line, "an entry needs a value after ':'"));
        }
        let target = target.trim();
        if let Some(range) = target.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
            let Some((first, last)) = range.split_once("..") else {
                return Err(syntax(
                    line,
                    format!("expected a range '[a..b]', found '{target}'"),
                ));
            };
            let first = self.address(first.trim(), line)?;
            let last = self.address(last.trim(), line)?;
            if first > last {
                return Err(syntax(line, format!("empty range '{target}'")));
            }
            let [value] = values[..] else {
                return Err(syntax(line, "a range takes exactly one value"));
            };
            self.words[first..=last].fill(value);
        } else {
            let first = self.address(target, line)?;
            let Some(slots) = self.words.get_mut(first..first + values.len()) else {
                return Err(syntax(
                    line,
                    format!(
                        "{} values from address {target} run past the end of the memory",
                        values.len()
                    ),
                ));
            };
            slots.copy_from_slice(&values);
        }
        Ok(())
    }
}

/// The memory words a MIF describes (DEPTH of them, in address order).
pub fn parse_mif(text: &str) -> Result<Vec<u32>, MifError> {
    let clean = strip_comments(text)?;
    let mut reader = MifReader {
        width: None,
        depth: None,
        address_radix: Radix::Hex,
        data_radix: Radix::Hex,
        words: Vec::new(),
    };
    let mut section = Section::Header;
    let mut line = 1;
    let pieces: Vec<&str> = clean.split(';').collect();
    let last_piece = pieces.len() - 1;
    for (piece_index, piece) in pieces.into_iter().enumerate() {
        let leading = &piece[..piece.len() - piece.trim_start().len()];
        let statement_line = line + leading.matches('\n').count();
        line += piece.matches('\n').count();
        let statement = piece.trim();
        if statement.is_empty() {
            continue;
        }
        // The text after the last ';' is not a statement: it lacks its terminator.
        if piece_index == last_piece {
            let message = if section == Section::Done {
                format!("text after END;: '{statement}'")
            } else {
                format!("'{statement}' is not terminated by ';'")
            };
            return Err(syntax(statement_line, message));
        }
        match section {
            Section::Header => {
                let mut words = statement.split_whitespace();
                let is_begin = words
                    .next()
                    .is_some_and(|w| w.eq_ignore_ascii_case("CONTENT"))
                    && words
                        .next()
                        .is_some_and(|w| w.eq_ignore_ascii_case("BEGIN"));
                if is_begin {
                    reader.begin(statement_line)?;
                    section = Section::Content;
                    // `CONTENT BEGIN` has no ';': the first entry shares its statement.
                    let begin_at = statement
                        .to_ascii_uppercase()
                        .find("BEGIN")
                        .map_or(statement.len(), |at| at + "BEGIN".len());
                    let rest = &statement[begin_at..];
                    if !rest.trim().is_empty() {
                        let rest_line =
                            statement_line + statement[..begin_at].matches('\n').count();
                        if rest.trim().eq_ignore_ascii_case("END") {
                            section = Section::Done;
                        } else {
                            reader.entry(rest, rest_line)?;
                        }
                    }
                } else {
                    reader.header(statement, statement_line)?;
                }
            }
            Section::Content => {
                if statement.eq_ignore_ascii_case("END") {
                    section = Section::Done;
                } else {
                    reader.entry(statement, statement_line)?;
                }
            }
            Section::Done => {
                return Err(syntax(
                    statement_line,
                    format!("text after END;: '{statement}'"),
                ));
            }
        }
    }
    match section {
        Section::Done => Ok(reader.words),
        Section::Header => Err(syntax(line, "no 'CONTENT BEGIN'")),
        Section::Content => Err(syntax(line, "no 'END;' after the content")),
    }
}

/// The primitives stored in scene-memory words (nine per primitive, see the module doc).
pub fn decode_primitives(words: &[u32]) -> Result<Vec<HwPrimitive>, MifError> {
    let per_primitive = HwPrimitive::WORDS;
    let (chunks, rest) = words.as_chunks::<{ HwPrimitive::WORDS }>();
    if !rest.is_empty() {
        return Err(MifError::PartialPrimitive {
            words: words.len(),
            per_primitive,
        });
    }
    chunks
        .iter()
        .enumerate()
        .map(|(index, chunk)| {
            HwPrimitive::from_words(chunk).ok_or(MifError::BadType {
                index,
                address: index * per_primitive + per_primitive - 1,
                value: chunk[per_primitive - 1],
            })
        })
        .collect()
}
