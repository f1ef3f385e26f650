//! Reading a results file: what the JSON is (an rtprof results file, or what else),
//! the schema dispatch (`/3`, `/2`, or `/1` upgraded) and the errors that say where a
//! file is wrong (line, column and JSON path).

use std::io::Read;
use std::path::{Path, PathBuf};

pub use crate::error::ResultsError;
use crate::limits::MAX_FILE_BYTES;
use crate::schema::{Results, SCHEMA, SCHEMA_V1, SCHEMA_V2};
use crate::v1;

/// At most 64 characters of a name from the file (an unknown schema, a field), on one
/// line (escaped), for a message.
fn truncated(text: &str) -> String {
    clipped(&text.escape_debug().collect::<String>())
}

/// At most 64 characters of `text`.
fn clipped(text: &str) -> String {
    let mut out: String = text.chars().take(64).collect();
    if out.len() < text.len() {
        out.push('…');
    }
    out
}

/// A JSON path as the validation's messages spell it: `scenes[0].variants[1].time`,
/// keys that are not plain names quoted (`counts."rays.primary"`).
fn path_text(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut text = String::new();
    for segment in path {
        let name = match segment {
            Segment::Seq { index } => {
                text += &format!("[{index}]");
                continue;
            }
            Segment::Map { key } => key.as_str(),
            Segment::Enum { variant } => variant.as_str(),
            Segment::Unknown => "?",
        };
        if !text.is_empty() {
            text.push('.');
        }
        let plain = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '?');
        if plain {
            text += name;
        } else {
            text += &format!("\"{}\"", name.escape_debug());
        }
    }
    text
}

/// Deserializes the whole of `text` as a `T`; an error names the JSON path where it
/// happened.
fn parse<T: serde::de::DeserializeOwned>(text: &str) -> Result<T, ResultsError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value = serde_path_to_error::deserialize(&mut de)
        .map_err(|e| ResultsError::json_at(e.inner(), path_text(e.path())))?;
    de.end()?;
    Ok(value)
}

/// A results file that cannot be read, with its name. The cause is part of the message
/// (and not a `source`), so that an error chain prints it once.
#[derive(Debug, thiserror::Error)]
#[error("{}: {error}", path.display())]
pub struct FileError {
    pub path: PathBuf,
    pub error: ResultsError,
}

/// What the top level of a JSON text is, read first so that a file of another version
/// or another tool is named as such instead of failing on its first different field.
enum Head {
    /// An object: its `schema` field (any JSON), the names of its first fields.
    Object {
        schema: Option<serde_json::Value>,
        fields: Vec<String>,
        more_fields: bool,
    },
    /// Anything else: "a JSON array", "a JSON string", …
    Other(&'static str),
}

/// Field names a [`Head`] keeps for the message.
const HEAD_FIELDS: usize = 6;

impl<'de> serde::Deserialize<'de> for Head {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(HeadVisitor)
    }
}

struct HeadVisitor;

impl<'de> serde::de::Visitor<'de> for HeadVisitor {
    type Value = Head;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Head, A::Error> {
        let mut schema = None;
        let mut fields = Vec::new();
        let mut more_fields = false;
        while let Some(key) = map.next_key::<String>()? {
            if key == "schema" {
                schema = Some(map.next_value::<serde_json::Value>()?);
            } else {
                map.next_value::<serde::de::IgnoredAny>()?;
            }
            if fields.len() < HEAD_FIELDS {
                fields.push(truncated(&key));
            } else {
                more_fields = true;
            }
        }
        Ok(Head::Object {
            schema,
            fields,
            more_fields,
        })
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Head, A::Error> {
        while seq.next_element::<serde::de::IgnoredAny>()?.is_some() {}
        Ok(Head::Other("a JSON array"))
    }

    fn visit_str<E>(self, _: &str) -> Result<Head, E> {
        Ok(Head::Other("a JSON string"))
    }

    fn visit_bool<E>(self, _: bool) -> Result<Head, E> {
        Ok(Head::Other("a JSON boolean"))
    }

    fn visit_i64<E>(self, _: i64) -> Result<Head, E> {
        Ok(Head::Other("a JSON number"))
    }

    fn visit_u64<E>(self, _: u64) -> Result<Head, E> {
        Ok(Head::Other("a JSON number"))
    }

    fn visit_f64<E>(self, _: f64) -> Result<Head, E> {
        Ok(Head::Other("a JSON number"))
    }

    fn visit_unit<E>(self) -> Result<Head, E> {
        Ok(Head::Other("JSON null"))
    }
}

/// What a JSON object without a `schema` field is, for the message.
fn describe_object(fields: &[String], more_fields: bool) -> String {
    if fields.is_empty() {
        return "an empty JSON object".to_string();
    }
    let mut text = format!(
        "a JSON object with the fields {}{}",
        fields.join(", "),
        if more_fields { ", …" } else { "" }
    );
    // criterion's estimates.json is the JSON file most often given by mistake.
    if ["mean", "median", "std_dev"]
        .iter()
        .all(|f| fields.iter().any(|g| g == f))
    {
        text += " (criterion's estimates.json?)";
    }
    text
}

/// Which schema a JSON text claims, or why it is no rtprof results file.
fn schema_of(text: &str) -> Result<String, ResultsError> {
    match serde_json::from_str::<Head>(text)? {
        Head::Other(what) => Err(ResultsError::NotResults(what.to_string())),
        Head::Object {
            schema: None,
            fields,
            more_fields,
        } => Err(ResultsError::NotResults(describe_object(
            &fields,
            more_fields,
        ))),
        Head::Object {
            schema: Some(serde_json::Value::String(schema)),
            ..
        } => {
            if schema.starts_with("rtprof.results/") {
                Ok(schema)
            } else {
                Err(ResultsError::ForeignSchema(format!(
                    "'{}'",
                    truncated(&schema)
                )))
            }
        }
        Head::Object {
            schema: Some(other),
            ..
        } => Err(ResultsError::ForeignSchema(clipped(&other.to_string()))),
    }
}

impl Results {
    /// Reads a results file of schema `/3` or `/2`, or `/1` upgraded, and validates it
    /// ([`Results::validate`]): the file is untrusted input.
    pub fn from_json(text: &str) -> Result<Self, ResultsError> {
        if text.len() > MAX_FILE_BYTES {
            return Err(ResultsError::TooLarge(text.len()));
        }
        let schema = schema_of(text)?;
        let results = match schema.as_str() {
            SCHEMA => parse(text)?,
            SCHEMA_V2 => {
                let mut results: Results = parse(text)?;
                results.schema = SCHEMA.to_string();
                results
            }
            SCHEMA_V1 => parse::<v1::Results>(text)?.upgrade()?,
            other => return Err(ResultsError::Schema(truncated(other))),
        };
        results.validate()?;
        Ok(results)
    }
}

impl Results {
    /// Reads and validates the results file at `path` ([`Results::from_json`]); at
    /// most [`MAX_FILE_BYTES`] are read, whatever the file's size.
    pub fn read_file(path: &Path) -> Result<Self, FileError> {
        let read = || -> Result<Self, ResultsError> {
            let mut text = String::new();
            std::fs::File::open(path)?
                .take(MAX_FILE_BYTES as u64 + 1)
                .read_to_string(&mut text)?;
            Self::from_json(&text)
        };
        read().map_err(|error| FileError {
            path: path.to_path_buf(),
            error,
        })
    }
}
