//! The forms a command prints its table in (hyperfine's exports): aligned text for a
//! terminal, GitHub-flavoured Markdown (a pull-request comment, a CI job summary), CSV
//! or JSON, chosen by one [`Format`] and written by each table's [`Exports`]. With the
//! `clap` feature [`Format`] is also the `--format` flag's values.

use serde::Serialize;

/// How a table is printed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Format {
    #[default]
    Text,
    Markdown,
    Csv,
    Json,
}

/// A table a command prints: its three text forms; JSON is its serde form.
pub trait Exports: Serialize {
    fn to_text(&self) -> String;
    fn to_markdown(&self) -> String;
    fn to_csv(&self) -> String;

    /// The table in `format` (JSON pretty-printed, with a final newline).
    fn render(&self, format: Format) -> Result<String, serde_json::Error> {
        Ok(match format {
            Format::Text => self.to_text(),
            Format::Markdown => self.to_markdown(),
            Format::Csv => self.to_csv(),
            Format::Json => serde_json::to_string_pretty(self)? + "\n",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Two {
        a: u32,
    }

    impl Exports for Two {
        fn to_text(&self) -> String {
            "text".into()
        }
        fn to_markdown(&self) -> String {
            "md".into()
        }
        fn to_csv(&self) -> String {
            "csv".into()
        }
    }

    #[test]
    fn each_format_is_its_own_form() {
        let t = Two { a: 2 };
        let forms: Vec<String> = [Format::Text, Format::Markdown, Format::Csv, Format::Json]
            .into_iter()
            .map(|f| t.render(f).unwrap_or_default())
            .collect();
        assert_eq!(forms, ["text", "md", "csv", "{\n  \"a\": 2\n}\n"]);
    }
}
