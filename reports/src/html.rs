//! The HTML report: the [`Document`] written as one self-contained HTML5 file.
//!
//! Everything is inline: the style sheet and script of `reports/templates/`, the
//! charts as SVG, pictures as `data:image/png;base64,…` URIs, flamegraph SVGs in
//! `<iframe srcdoc="…">`, and a few lines of JavaScript that sort tables of class
//! `sortable` when a header is clicked (by each cell's sort key, kept in `data-v`). The
//! file makes no network reference: no `src` or `href` points outside the document.
//! A [`Tone`] becomes the CSS class `tone-<name>` ([`tone_class`]), which the style
//! sheet colours.

use std::fmt::Write as _;

use crate::Run;
use crate::document::{
    self, Align, Block, Cell, Column, Document, Figure, Flamegraph, ImageGrid, Inline,
    Preformatted, Section, Table, Tone, Visual,
};
use crate::markup::{base64, escape};

/// A report that cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum HtmlError {
    #[error("no runs to report: give at least one results file")]
    NoRuns,
}

const STYLE: &str = include_str!("../templates/report.css");
/// Sorts `table.sortable` by the clicked header: numbers (from `data-v` when present)
/// numerically, text alphabetically; a second click reverses.
const SCRIPT: &str = include_str!("../templates/report.js");

/// Renders the report of `runs` (the first is shown in detail).
pub fn render_html(runs: &[Run]) -> Result<String, HtmlError> {
    let doc = document::build(runs).ok_or(HtmlError::NoRuns)?;
    Ok(render(&doc))
}

/// Writes a document as HTML.
pub fn render(doc: &Document) -> String {
    let mut page = Page {
        doc,
        out: String::with_capacity(1 << 20),
    };
    page.head();
    let mut in_appendix = false;
    for section in &doc.sections {
        if section.appendix && !in_appendix {
            in_appendix = true;
            page.push("<h1 id=\"appendix\" class=\"part\">Appendix</h1>\n");
        }
        page.section(section);
    }
    page.foot();
    page.out
}

/// The CSS class of a tone (`None` for neutral): the one place a tone meets HTML.
pub fn tone_class(tone: Tone) -> Option<String> {
    (tone != Tone::Neutral).then(|| format!("tone-{}", tone.name()))
}

/// The SVG without its XML prologue, doctype and the comments before its first script
/// (they name web addresses and mean nothing inside an HTML document).
fn strip_svg_prologue(svg: &str) -> String {
    let body = svg.find("<svg").map_or(svg, |i| &svg[i..]);
    let script = body.find("<script").unwrap_or(body.len());
    let (head, tail) = body.split_at(script);
    let mut out = String::with_capacity(body.len());
    let mut rest = head;
    while let Some(open) = rest.find("<!--") {
        out.push_str(&rest[..open]);
        match rest[open..].find("-->") {
            Some(close) => rest = &rest[open + close + 3..],
            None => rest = "",
        }
    }
    out.push_str(rest);
    out.push_str(tail);
    without_xmlns(&out)
}

/// The SVG with the namespace declarations of its root tag removed: an HTML parser
/// places inline `<svg>` in the SVG namespace by itself, and the declarations are web
/// addresses a reader of the report should never see as references.
fn without_xmlns(svg: &str) -> String {
    let Some(start) = svg.find("<svg") else {
        return svg.to_string();
    };
    let Some(len) = svg[start..].find('>') else {
        return svg.to_string();
    };
    let tag = &svg[start..start + len];
    let mut cleaned = String::with_capacity(tag.len());
    let mut rest = tag;
    while let Some(at) = rest.find(" xmlns") {
        cleaned.push_str(&rest[..at]);
        let attribute = &rest[at + 1..];
        // Skip `xmlns[:prefix]="value"` (or single quotes).
        let end = attribute
            .find('=')
            .and_then(|eq| {
                let quote = attribute[eq + 1..].chars().next()?;
                if quote != '"' && quote != '\'' {
                    return None;
                }
                let close = attribute[eq + 2..].find(quote)?;
                Some(eq + 2 + close + 1)
            })
            .unwrap_or(attribute.len());
        rest = &attribute[end..];
    }
    cleaned.push_str(rest);
    format!("{}{cleaned}{}", &svg[..start], &svg[start + len..])
}

/// ` class="a b"` from the non-empty class names, or nothing.
fn classes(names: &[Option<String>]) -> String {
    let names: Vec<&str> = names.iter().flatten().map(String::as_str).collect();
    if names.is_empty() {
        String::new()
    } else {
        format!(" class=\"{}\"", names.join(" "))
    }
}

struct Page<'d> {
    doc: &'d Document,
    out: String,
}

impl Page<'_> {
    fn push(&mut self, s: &str) {
        self.out.push_str(s);
    }

    fn head(&mut self) {
        let doc = self.doc;
        let _ = write!(
            self.out,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<meta name=\"generator\" content=\"{}\">\n<title>{}: {}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header><h1>{}</h1><p class=\"sub\">{}</p><p class=\"sub\">{}</p>{}</header>\n",
            escape(&doc.metadata.generator),
            escape(&doc.title),
            escape(&doc.metadata.subject),
            escape(&doc.title),
            escape(&doc.metadata.subtitle),
            escape(&doc.metadata.byline),
            // A recorded program's report reproduces no publication: no line.
            if doc.metadata.reference.is_empty() {
                String::new()
            } else {
                format!(
                    "<p class=\"reference\">Reproduces {}.</p>",
                    escape(&doc.metadata.reference)
                )
            },
        );
        for notice in &doc.notices {
            let _ = writeln!(
                self.out,
                "<p class=\"note tone-bad\">{}</p>",
                escape(notice)
            );
        }
        // The main body's chapters, then the appendix's sections.
        self.push("<nav><ol>");
        for s in doc.sections.iter().filter(|s| !s.appendix) {
            self.nav_item(s);
        }
        self.push("</ol>");
        if doc.sections.iter().any(|s| s.appendix) {
            self.push("<details><summary>Appendix</summary><ol type=\"A\">");
            for s in doc.sections.iter().filter(|s| s.appendix) {
                self.nav_item(s);
            }
            self.push("</ol></details>");
        }
        self.push("</nav>\n<main>\n");
    }

    fn nav_item(&mut self, s: &Section) {
        let _ = write!(
            self.out,
            "<li><a href=\"#{}\">{}</a></li>",
            escape(&s.id),
            escape(&s.heading)
        );
    }

    fn foot(&mut self) {
        let _ = write!(
            self.out,
            "</main>\n<footer>Made by {} from results.json; self-contained, no network access.</footer>\n<script>{SCRIPT}</script>\n</body>\n</html>\n",
            escape(&self.doc.metadata.generator)
        );
    }

    fn section(&mut self, s: &Section) {
        let _ = writeln!(
            self.out,
            "<section id=\"{}\">\n<h2>{}</h2>",
            escape(&s.id),
            escape(&s.heading)
        );
        if let Some(t) = &s.thesis {
            let _ = writeln!(self.out, "<p class=\"thesis\">Thesis: {}</p>", escape(t));
        }
        for block in &s.blocks {
            self.block(block);
        }
        self.push("</section>\n");
    }

    fn block(&mut self, block: &Block) {
        match block {
            Block::Heading {
                level,
                text,
                detail,
                anchor,
            } => {
                let tag = match level {
                    0..=2 => "h3",
                    3 => "h4",
                    _ => "h5",
                };
                let id = anchor
                    .as_ref()
                    .map_or_else(String::new, |a| format!(" id=\"{}\"", escape(a)));
                let detail = detail.as_ref().map_or_else(String::new, |d| {
                    format!(" <span class=\"detail\">({})</span>", escape(d))
                });
                let _ = writeln!(self.out, "<{tag}{id}>{}{detail}</{tag}>", escape(text));
            }
            Block::Paragraph { content } => {
                let _ = writeln!(self.out, "<p>{}</p>", inlines(content));
            }
            Block::List { items } => {
                self.push("<ul class=\"findings\">");
                for item in items {
                    let _ = write!(self.out, "<li>{}</li>", escape(item));
                }
                self.push("</ul>\n");
            }
            Block::Pairs { pairs } => {
                self.push("<table class=\"kv\">");
                for p in pairs {
                    let _ = write!(
                        self.out,
                        "<tr><th>{}</th><td>{}</td></tr>",
                        escape(&p.key),
                        escape(&p.value)
                    );
                }
                self.push("</table>\n");
            }
            Block::Table(t) => self.table(t),
            Block::Figure(f) => self.figure(f),
            Block::ImageGrid(g) => self.grid(g),
            Block::Flamegraph(f) => self.flamegraph(f),
            Block::Preformatted(p) => self.preformatted(p),
            Block::Note(n) => {
                let _ = writeln!(
                    self.out,
                    "<p{}>{}</p>",
                    classes(&[Some("note".to_string()), tone_class(n.tone)]),
                    escape(&n.text)
                );
            }
        }
    }

    fn table(&mut self, t: &Table) {
        if let Some(c) = &t.caption {
            let _ = writeln!(self.out, "<p class=\"caption\">{}</p>", escape(c));
        }
        let _ = write!(
            self.out,
            "<table{}><thead><tr>",
            classes(&[
                t.sortable.then(|| "sortable".to_string()),
                t.dense.then(|| "dense".to_string()),
            ])
        );
        for c in &t.columns {
            self.header_cell(c);
        }
        self.push("</tr></thead><tbody>");
        for row in &t.rows {
            self.push("<tr>");
            let mut column = 0usize;
            for cell in row {
                let align = t.columns.get(column).map_or(Align::Left, |c| c.align);
                self.cell(cell, align);
                column += cell.span.max(1) as usize;
            }
            self.push("</tr>");
        }
        self.push("</tbody></table>\n");
    }

    fn header_cell(&mut self, c: &Column) {
        let detail = c.detail.as_ref().map_or_else(String::new, |d| {
            format!("<br><span class=\"detail\">{}</span>", escape(d))
        });
        let _ = write!(self.out, "<th>{}{detail}</th>", escape(&c.title));
    }

    fn cell(&mut self, cell: &Cell, align: Align) {
        let mut attributes = classes(&[
            (align == Align::Right).then(|| "num".to_string()),
            tone_class(cell.tone),
        ]);
        if cell.span > 1 {
            let _ = write!(attributes, " colspan=\"{}\"", cell.span);
        }
        if let Some(v) = cell.sort.filter(|v| !v.is_nan()) {
            // Exponent form: exact, short, and what parseFloat reads.
            let _ = write!(attributes, " data-v=\"{v:e}\"");
        }
        if let Some(h) = &cell.hover {
            let _ = write!(attributes, " title=\"{}\"", escape(h));
        }
        let text = if cell.code {
            format!("<code>{}</code>", escape(&cell.text))
        } else {
            escape(&cell.text)
        };
        let detail = cell.detail.as_ref().map_or_else(String::new, |d| {
            format!(" <span class=\"detail\">{}</span>", escape(d))
        });
        let _ = write!(self.out, "<td{attributes}>{text}{detail}</td>");
    }

    /// A picture as an element: an inline SVG, a PNG data URI, or a note.
    fn visual(&self, v: &Visual) -> String {
        match v {
            Visual::Image(image) => match self.doc.assets.get(&image.asset) {
                Some(asset) if asset.kind == document::AssetKind::Svg => {
                    without_xmlns(&String::from_utf8_lossy(&asset.bytes))
                }
                Some(asset) => format!(
                    "<img src=\"data:image/png;base64,{}\" alt=\"{}\"{} style=\"aspect-ratio: {} / {}\">",
                    base64(&asset.bytes),
                    escape(&image.alt),
                    image.file.as_ref().map_or_else(String::new, |f| format!(
                        " title=\"{} (full size next to this report)\"",
                        escape(f)
                    )),
                    image.width,
                    image.height
                ),
                None => format!(
                    "<div class=\"missing\">{}: not embedded</div>",
                    escape(&image.alt)
                ),
            },
            Visual::Missing { text } => {
                format!("<div class=\"missing\">{}</div>", escape(text))
            }
            Visual::Placeholder { text } => {
                format!("<div class=\"tile reference\">{}</div>", escape(text))
            }
            Visual::Empty => "<div></div>".to_string(),
        }
    }

    fn figure(&mut self, f: &Figure) {
        let body = self.visual(&f.visual);
        let _ = writeln!(
            self.out,
            "<figure class=\"chart\" id=\"chart-{}\">{body}<figcaption><b>{}.</b> {}</figcaption></figure>",
            escape(&f.id),
            escape(&f.title),
            escape(&f.caption)
        );
    }

    fn grid(&mut self, g: &ImageGrid) {
        let columns = g.columns.max(1) as usize;
        let labels = !g.row_labels.is_empty();
        let _ = write!(
            self.out,
            "<div class=\"scene-images\" style=\"grid-template-columns: {}repeat({columns}, minmax(0, 1fr))\">",
            if labels { "auto " } else { "" }
        );
        for (i, tile) in g.tiles.iter().enumerate() {
            if labels && i % columns == 0 {
                let label = g.row_labels.get(i / columns).map_or("", String::as_str);
                let _ = write!(self.out, "<div class=\"row-label\">{}</div>", escape(label));
            }
            match &tile.visual {
                Visual::Empty => self.push("<div></div>"),
                Visual::Placeholder { .. } => {
                    let body = self.visual(&tile.visual);
                    self.push(&body);
                }
                v => {
                    let body = self.visual(v);
                    let _ = write!(
                        self.out,
                        "<figure class=\"tile\">{body}<figcaption{}>{}</figcaption></figure>",
                        classes(&[tone_class(tile.tone)]),
                        escape(&tile.caption)
                    );
                }
            }
        }
        self.push("</div>\n");
    }

    fn flamegraph(&mut self, f: &Flamegraph) {
        let body = match &f.visual {
            Visual::Image(image) => match self.doc.assets.get(&image.asset) {
                Some(asset) => {
                    let document = format!(
                        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><style>html,body{{margin:0;overflow:hidden}}svg{{display:block;width:100%;height:auto}}</style></head><body>{}</body></html>",
                        strip_svg_prologue(&String::from_utf8_lossy(&asset.bytes))
                    );
                    format!(
                        "<iframe class=\"flame\" sandbox=\"allow-scripts\" title=\"{}\" style=\"aspect-ratio: {} / {}\" srcdoc=\"{}\"></iframe>",
                        escape(&f.title),
                        image.width,
                        image.height,
                        escape(&document)
                    )
                }
                None => self.visual(&f.visual),
            },
            other => self.visual(other),
        };
        let caption = f
            .caption
            .as_ref()
            .map_or_else(String::new, |c| format!(" {}", escape(c)));
        let _ = writeln!(
            self.out,
            "<figure class=\"flame\">{body}<figcaption><b>{}.</b>{caption}</figcaption></figure>",
            escape(&f.title)
        );
    }

    fn preformatted(&mut self, p: &Preformatted) {
        let pre = format!("<pre class=\"text\">{}</pre>", escape(&p.text));
        match &p.folded {
            Some(summary) => {
                let _ = writeln!(
                    self.out,
                    "<details><summary>{}</summary>{pre}</details>",
                    escape(summary)
                );
            }
            None => {
                let _ = writeln!(self.out, "{pre}");
            }
        }
    }
}

/// A paragraph's runs of text as HTML.
fn inlines(content: &[Inline]) -> String {
    let mut out = String::new();
    for inline in content {
        match inline {
            Inline::Text { text } => out.push_str(&escape(text)),
            Inline::Strong { text } => {
                let _ = write!(out, "<b>{}</b>", escape(text));
            }
            Inline::Code { text } => {
                let _ = write!(out, "<code>{}</code>", escape(text));
            }
            Inline::Link { text, target } => {
                let _ = write!(out, "<a href=\"#{}\">{}</a>", escape(target), escape(text));
            }
            Inline::Chip { text, tone } => {
                let _ = write!(
                    out,
                    "<span{}>{}</span>",
                    classes(&[Some("chip".to_string()), tone_class(*tone)]),
                    escape(text)
                );
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn namespace_declarations_leave_the_root_tag_only() {
        let svg = "<?xml version=\"1.0\"?><!-- see http://example.org --><svg width=\"10\" xmlns=\"http://www.w3.org/2000/svg\" xmlns:fg='http://x' height=\"5\"><text>xmlns</text></svg>";
        let cleaned = strip_svg_prologue(svg);
        assert_eq!(
            cleaned,
            "<svg width=\"10\" height=\"5\"><text>xmlns</text></svg>"
        );
        assert_eq!(without_xmlns("no svg here"), "no svg here");
    }

    #[test]
    fn every_tone_but_neutral_has_its_own_class() {
        let names: Vec<Option<String>> = Tone::ALL.iter().map(|t| tone_class(*t)).collect();
        assert_eq!(names[0], None);
        let distinct: std::collections::BTreeSet<&String> = names.iter().flatten().collect();
        assert_eq!(distinct.len(), Tone::ALL.len() - 1);
        // The style sheet colours each of them.
        for class in distinct {
            assert!(STYLE.contains(&format!(".{class} {{")), "{class}");
        }
    }

    #[test]
    fn no_runs_is_an_error() {
        assert!(matches!(render_html(&[]), Err(HtmlError::NoRuns)));
    }
}
