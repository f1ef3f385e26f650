//! Plain-text forms of a document [`Table`], for the places results go besides the
//! reports: aligned columns for a terminal ([`table`]; `rtprof hw table`, `gate`,
//! `compare`), a GitHub-flavoured Markdown table for a pull-request comment or a CI job
//! summary ([`markdown`]), and CSV of plain values ([`csv`](fn@csv)).

use crate::document::{Align, Cell, Table};

/// Space between columns.
const GAP: &str = "  ";

/// The table as aligned lines: the column titles, their second lines when any column
/// has one, then one line per row. A cell prints its text and its detail; a cell that
/// spans columns takes the first of them.
pub fn table(t: &Table) -> String {
    let n = t.columns.len();
    let mut lines: Vec<Vec<String>> = Vec::new();
    lines.push(t.columns.iter().map(|c| c.title.clone()).collect());
    if t.columns.iter().any(|c| c.detail.is_some()) {
        lines.push(
            t.columns
                .iter()
                .map(|c| c.detail.clone().unwrap_or_default())
                .collect(),
        );
    }
    let header_lines = lines.len();
    for row in &t.rows {
        let mut line = Vec::with_capacity(n);
        for cell in row {
            line.push(cell_text(cell));
            line.extend((1..cell.span).map(|_| String::new()));
        }
        line.resize(n, String::new());
        lines.push(line);
    }
    let widths: Vec<usize> = (0..n)
        .map(|c| {
            lines
                .iter()
                .map(|l| l.get(c).map_or(0, |s| s.chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    for (i, line) in lines.iter().enumerate() {
        let mut text = String::new();
        for (c, cell) in line.iter().enumerate().take(n) {
            if c > 0 {
                text.push_str(GAP);
            }
            let pad = widths[c].saturating_sub(cell.chars().count());
            // Headers align as their column does, so titles sit over their numbers.
            let right = t.columns[c].align == Align::Right;
            if right {
                text.extend(std::iter::repeat_n(' ', pad));
                text.push_str(cell);
            } else {
                text.push_str(cell);
                text.extend(std::iter::repeat_n(' ', pad));
            }
        }
        out.push_str(text.trim_end());
        out.push('\n');
        if i + 1 == header_lines {
            let total = widths.iter().sum::<usize>() + GAP.len() * n.saturating_sub(1);
            out.push_str(&"-".repeat(total));
            out.push('\n');
        }
    }
    out
}

fn cell_text(cell: &Cell) -> String {
    match &cell.detail {
        Some(detail) if !detail.is_empty() => format!("{} {detail}", cell.text),
        _ => cell.text.clone(),
    }
}

/// The table in GitHub-flavoured Markdown: a header row (titles, with their second
/// line in parentheses), the alignment row, one row per table row. A cell prints its
/// text and detail; a cell with a bad tone is bold, so a failed row stands out in a
/// pull-request comment; `|` in text is escaped.
pub fn markdown(t: &Table) -> String {
    let escape = |s: &str| s.replace('|', "\\|").replace('\n', " ");
    let mut out = String::from("|");
    for c in &t.columns {
        let title = match &c.detail {
            Some(d) if !d.is_empty() => format!("{} ({d})", c.title),
            _ => c.title.clone(),
        };
        out += &format!(" {} |", escape(&title));
    }
    out += "\n|";
    for c in &t.columns {
        out += if c.align == Align::Right {
            "---:|"
        } else {
            "---|"
        };
    }
    out.push('\n');
    for row in &t.rows {
        out.push('|');
        let mut columns = 0;
        for cell in row {
            let text = escape(&cell_text(cell));
            let text = if cell.tone == crate::document::Tone::Bad && !text.is_empty() {
                format!("**{text}**")
            } else {
                text
            };
            out += &format!(" {text} |");
            // Markdown has no column spans: the other columns stay empty.
            out += &" |".repeat(cell.span.saturating_sub(1) as usize);
            columns += cell.span.max(1) as usize;
        }
        out += &" |".repeat(t.columns.len().saturating_sub(columns));
        out.push('\n');
    }
    out
}

/// Rows of plain values as CSV (RFC 4180 quoting by the `csv` crate): `header`, then
/// `rows`. Numbers should be written in full (seconds as seconds), not as the reports
/// print them, so that a spreadsheet can compute with them.
pub fn csv(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut writer = ::csv::Writer::from_writer(Vec::new());
    // Writing to memory cannot fail but for a row of the wrong length, which the
    // callers build from the same header.
    let mut write = || -> Result<Vec<u8>, ::csv::Error> {
        writer.write_record(header)?;
        for row in rows {
            writer.write_record(row)?;
        }
        writer.flush()?;
        Ok(writer.get_ref().clone())
    };
    match write() {
        Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
        Err(e) => format!("error: {e}\n"),
    }
}

/// A number for CSV: full precision, empty when missing or not finite.
pub fn csv_number(v: Option<f64>) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x}"),
        _ => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::Column;

    #[test]
    fn columns_line_up_with_numbers_to_the_right() {
        let mut t = Table::new(vec![
            Column::text("name"),
            Column::number("LEs").detail("model / thesis"),
        ]);
        t.rows.push(vec![
            Cell::text("dot_product"),
            Cell::count(3947).detail("/ 3,947"),
        ]);
        t.rows.push(vec![Cell::text("add"), Cell::count(12)]);
        t.rows.push(vec![Cell::text("spanning all").span(2)]);
        // Twelve characters for the names, fourteen for the widest figure line.
        let expected: String = [
            format!("{:<12}  {:>14}", "name", "LEs"),
            format!("{:<12}  {:>14}", "", "model / thesis"),
            "-".repeat(28),
            format!("{:<12}  {:>14}", "dot_product", "3,947 / 3,947"),
            format!("{:<12}  {:>14}", "add", "12"),
            "spanning all".to_string(),
        ]
        .iter()
        .map(|l| format!("{}\n", l.trim_end()))
        .collect();
        assert_eq!(table(&t), expected);
    }

    #[test]
    fn markdown_has_the_alignment_row_and_bold_bad_cells() {
        use crate::document::Tone;
        let mut t = Table::new(vec![Column::text("scene"), Column::number("change")]);
        t.rows.push(vec![
            Cell::text("a|b"),
            Cell::text("+25 %").tone(Tone::Bad).detail("slower"),
        ]);
        t.rows.push(vec![Cell::text("all").span(2)]);
        let expected = "| scene | change |\n|---|---:|\n| a\\|b | **+25 % slower** |\n| all | |\n";
        assert_eq!(markdown(&t), expected);
    }

    #[test]
    fn csv_quotes_what_needs_quoting() {
        let rows = vec![
            vec!["balls3".to_string(), "0.5".to_string()],
            vec!["a, b".to_string(), "say \"x\"".to_string()],
        ];
        assert_eq!(
            csv(&["scene", "seconds"], &rows),
            "scene,seconds\nballs3,0.5\n\"a, b\",\"say \"\"x\"\"\"\n"
        );
        assert_eq!(csv_number(Some(0.25)), "0.25");
        assert_eq!(csv_number(Some(f64::NAN)), "");
        assert_eq!(csv_number(None), "");
    }
}
