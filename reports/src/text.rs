//! Plain text for a terminal: a document [`Table`] in aligned columns (`rtprof hw
//! table` prints the report's hardware table with it).

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
}
