//! The report as plain data: a [`Document`] of [`Section`]s made of [`Block`]s
//! (paragraphs, lists, tables of typed [`Cell`]s, chart figures, image grids,
//! flamegraphs, preformatted texts, notes).
//!
//! [`build`] makes it once from the runs; [`crate::html`] and [`crate::pdf`] only lay it
//! out, and [`crate::text`] prints its tables on a terminal. Every judgement that
//! colours a cell is a [`Tone`] decided here (see [`tone`]), never by a renderer. Files
//! the report embeds (pictures, chart and flamegraph SVGs) are [`Asset`]s the blocks
//! name by a virtual path; the PDF gets the document as JSON and the assets as files.

mod assets;
mod build;
mod builder;
mod outline;
mod prune;
pub mod tone;

pub use assets::{Asset, AssetKind, Assets, svg_size};
pub use build::build;
pub(crate) use builder::Builder;
pub use outline::{Part, SECTIONS, heading_of, part_of};
pub use tone::Tone;

use serde::Serialize;

/// A whole report.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Document {
    pub title: String,
    pub metadata: Metadata,
    /// Things a reader must know before anything else (figures left out, …).
    pub notices: Vec<String>,
    pub sections: Vec<Section>,
    /// The files the blocks name; not part of the JSON.
    #[serde(skip)]
    pub assets: Assets,
}

/// What the report is about.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Metadata {
    /// One line under the title.
    pub subtitle: String,
    /// Run, machine, date and how many runs: "bench-1 · Intel … · 2026-11-21 · one run".
    pub byline: String,
    /// The runs' labels, for page headers: "bench-1 vs bench-2".
    pub subject: String,
    /// The work the report reproduces, cited in full.
    pub reference: String,
    pub generator: String,
}

/// One numbered section.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Section {
    /// Stable anchor (`summary`, `variants`, …; see [`SECTIONS`]).
    pub id: String,
    pub heading: String,
    /// Where the thesis has the same thing, if it does.
    pub thesis: Option<String>,
    /// Short sections may share a printed page with the one before.
    pub short: bool,
    /// In the appendix (see [`Part`]): after the main body, lettered.
    pub appendix: bool,
    /// Too long for paper (tables of every scene): the PDF shows only its opening
    /// paragraph and a pointer to the HTML report.
    pub html_only: bool,
    pub blocks: Vec<Block>,
}

/// One piece of a section.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Block {
    /// A sub-heading (`level` 2 under the section's 1; 3 below that); `anchor` is an
    /// id other blocks can link to.
    Heading {
        level: u8,
        text: String,
        detail: Option<String>,
        anchor: Option<String>,
    },
    Paragraph {
        content: Vec<Inline>,
    },
    List {
        items: Vec<String>,
    },
    /// Key-value lines (machine, build, …).
    Pairs {
        pairs: Vec<Pair>,
    },
    Table(Table),
    /// A chart.
    Figure(Figure),
    ImageGrid(ImageGrid),
    Flamegraph(Flamegraph),
    Preformatted(Preformatted),
    Note(Note),
}

/// A run of text inside a paragraph.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Inline {
    Text {
        text: String,
    },
    Strong {
        text: String,
    },
    Code {
        text: String,
    },
    /// A reference to a section or heading anchor of this document.
    Link {
        text: String,
        target: String,
    },
    /// A small sample of a tone (a legend).
    Chip {
        text: String,
        tone: Tone,
    },
}

#[derive(Clone, Debug, Serialize)]
pub struct Pair {
    pub key: String,
    pub value: String,
}

/// A table of typed cells.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Table {
    pub caption: Option<String>,
    pub columns: Vec<Column>,
    /// Each row has as many cells as there are columns, counting spans.
    pub rows: Vec<Vec<Cell>>,
    /// Readers may sort it by a column (HTML).
    pub sortable: bool,
    /// Many columns: a smaller type.
    pub dense: bool,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct Column {
    pub title: String,
    /// A second header line ("model / thesis (error)").
    pub detail: Option<String>,
    pub align: Align,
    /// Takes the width left over (long text).
    pub grow: bool,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Align {
    #[default]
    Left,
    Right,
}

/// One table cell.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Cell {
    pub text: String,
    /// Secondary text (an interval, the thesis's figure), smaller.
    pub detail: Option<String>,
    /// The value a sort by this column uses (text sorts alphabetically without it).
    pub sort: Option<f64>,
    pub tone: Tone,
    /// Code (function names, commits).
    pub code: bool,
    /// The whole story behind a short cell (the HTML shows it on hover).
    pub hover: Option<String>,
    /// Columns this cell covers (1 for most).
    pub span: u32,
}

/// A chart.
#[derive(Clone, Debug, Serialize)]
pub struct Figure {
    /// The chart's id (`calls`, `quality-speed`, …): an anchor.
    pub id: String,
    pub title: String,
    pub caption: String,
    pub visual: Visual,
    /// At most this high on a printed page, cm.
    pub max_height_cm: f64,
}

/// A picture, or why there is none.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Visual {
    Image(Image),
    /// A file that could not be shown, and why.
    Missing {
        text: String,
    },
    /// Nothing to show on purpose ("reference image: no heat map").
    Placeholder {
        text: String,
    },
    /// An empty grid cell.
    Empty,
}

/// An embedded picture: an [`Asset`] path and its natural size.
#[derive(Clone, Debug, Serialize)]
pub struct Image {
    pub asset: String,
    pub width: f64,
    pub height: f64,
    pub alt: String,
    /// The full-size file next to the report, if the picture is a thumbnail of one.
    pub file: Option<String>,
}

/// Pictures in `columns` columns, row by row; an optional label starts each row.
#[derive(Clone, Debug, Serialize)]
pub struct ImageGrid {
    pub columns: u32,
    pub row_labels: Vec<String>,
    pub tiles: Vec<Tile>,
    /// The columns share the whole text width (pictures with a legend to read), where
    /// a grid otherwise gives each column a sixth of it.
    pub wide: bool,
}

#[derive(Clone, Debug, Serialize)]
pub struct Tile {
    pub visual: Visual,
    pub caption: String,
    pub tone: Tone,
}

/// A flamegraph SVG (interactive in the HTML, a vector image in the PDF).
#[derive(Clone, Debug, Serialize)]
pub struct Flamegraph {
    pub title: String,
    pub caption: Option<String>,
    pub visual: Visual,
}

/// A text file shown as is (gprof layouts, commands).
#[derive(Clone, Debug, Serialize)]
pub struct Preformatted {
    pub text: String,
    /// The file it comes from, relative to the results.
    pub file: Option<String>,
    /// Folded away under this summary (HTML); printed only as a pointer to the file.
    pub folded: Option<String>,
    /// A printed page shows at most this many lines.
    pub print_lines: Option<u32>,
}

/// A remark set apart: why a section is empty, a warning, a missing file.
#[derive(Clone, Debug, Serialize)]
pub struct Note {
    pub tone: Tone,
    pub text: String,
}

impl Cell {
    /// A text cell.
    pub fn text(text: impl Into<String>) -> Cell {
        Cell {
            text: text.into(),
            span: 1,
            ..Cell::default()
        }
    }

    /// A number shown as `text` that sorts by `value`.
    pub fn number(text: impl Into<String>, value: f64) -> Cell {
        Cell {
            sort: Some(value),
            ..Cell::text(text)
        }
    }

    /// An exact count.
    pub fn count(n: u64) -> Cell {
        Cell::number(crate::format::count(n), n as f64)
    }

    /// A time estimate in seconds: the median, the interval as detail.
    pub fn estimate(median: f64, low: f64, high: f64) -> Cell {
        let text = crate::format::estimate(median, low, high);
        Cell {
            detail: (!text.interval.is_empty()).then_some(text.interval),
            ..Cell::number(text.median, median)
        }
    }

    /// A speed-up with its interval (detail), digits following the interval.
    pub fn ratio(median: f64, interval: Option<[f64; 2]>) -> Cell {
        let [low, high] = interval.unwrap_or([f64::NAN, f64::NAN]);
        let text = crate::format::ratio_estimate(median, low, high);
        Cell {
            detail: (!text.interval.is_empty()).then_some(text.interval),
            ..Cell::number(text.median, median)
        }
    }

    /// A verdict's label in its tone.
    pub fn verdict(verdict: crate::results::Verdict) -> Cell {
        Cell::text(verdict.label()).tone(Tone::of_verdict(verdict))
    }

    /// A dash for a value that is not there.
    pub fn dash() -> Cell {
        Cell::text(crate::format::DASH).tone(Tone::Muted)
    }

    pub fn tone(mut self, tone: Tone) -> Cell {
        self.tone = tone;
        self
    }

    pub fn detail(mut self, detail: impl Into<String>) -> Cell {
        self.detail = Some(detail.into());
        self
    }

    pub fn code(mut self) -> Cell {
        self.code = true;
        self
    }

    pub fn hover(mut self, hover: impl Into<String>) -> Cell {
        self.hover = Some(hover.into());
        self
    }

    pub fn span(mut self, columns: u32) -> Cell {
        self.span = columns.max(1);
        self
    }
}

impl Column {
    /// A left-aligned text column.
    pub fn text(title: impl Into<String>) -> Column {
        Column {
            title: title.into(),
            ..Column::default()
        }
    }

    /// A right-aligned number column.
    pub fn number(title: impl Into<String>) -> Column {
        Column {
            align: Align::Right,
            ..Column::text(title)
        }
    }

    pub fn grow(mut self) -> Column {
        self.grow = true;
        self
    }

    pub fn detail(mut self, detail: impl Into<String>) -> Column {
        self.detail = Some(detail.into());
        self
    }
}

impl Table {
    pub fn new(columns: Vec<Column>) -> Table {
        Table {
            columns,
            ..Table::default()
        }
    }

    pub fn sortable(mut self) -> Table {
        self.sortable = true;
        self
    }

    pub fn dense(mut self) -> Table {
        self.dense = true;
        self
    }

    pub fn caption(mut self, caption: impl Into<String>) -> Table {
        self.caption = Some(caption.into());
        self
    }
}

impl Block {
    /// A paragraph of plain text.
    pub fn text(text: impl Into<String>) -> Block {
        Block::Paragraph {
            content: vec![Inline::text(text)],
        }
    }

    /// A note with a tone.
    pub fn note(tone: Tone, text: impl Into<String>) -> Block {
        Block::Note(Note {
            tone,
            text: text.into(),
        })
    }

    /// Why a section or part of it is empty.
    pub fn empty(text: impl Into<String>) -> Block {
        Block::note(Tone::Fair, text)
    }

    /// A sub-heading of the section.
    pub fn heading(text: impl Into<String>) -> Block {
        Block::Heading {
            level: 2,
            text: text.into(),
            detail: None,
            anchor: None,
        }
    }

    /// A heading one level further down.
    pub fn subheading(text: impl Into<String>) -> Block {
        Block::Heading {
            level: 3,
            text: text.into(),
            detail: None,
            anchor: None,
        }
    }
}

impl Inline {
    pub fn text(text: impl Into<String>) -> Inline {
        Inline::Text { text: text.into() }
    }

    pub fn strong(text: impl Into<String>) -> Inline {
        Inline::Strong { text: text.into() }
    }

    pub fn code(text: impl Into<String>) -> Inline {
        Inline::Code { text: text.into() }
    }
}

impl ImageGrid {
    /// A grid of at least `columns` from rows of tiles; short rows are filled with empty
    /// tiles.
    pub fn from_rows(columns: usize, row_labels: Vec<String>, rows: Vec<Vec<Tile>>) -> ImageGrid {
        let longest = rows.iter().map(Vec::len).max().unwrap_or(0);
        let columns = columns.max(longest).max(1);
        let mut tiles = Vec::with_capacity(rows.len() * columns);
        for row in rows {
            let missing = columns - row.len();
            tiles.extend(row);
            tiles.extend((0..missing).map(|_| Tile {
                visual: Visual::Empty,
                caption: String::new(),
                tone: Tone::Neutral,
            }));
        }
        ImageGrid {
            columns: columns as u32,
            row_labels,
            tiles,
            wide: false,
        }
    }

    /// The grid across the whole text width.
    pub fn wide(mut self) -> ImageGrid {
        self.wide = true;
        self
    }
}

impl Pair {
    pub fn new(key: impl Into<String>, value: impl Into<String>) -> Pair {
        Pair {
            key: key.into(),
            value: value.into(),
        }
    }
}

impl Section {
    /// Adds a paragraph of plain text.
    pub fn text(&mut self, text: impl Into<String>) {
        self.blocks.push(Block::text(text));
    }

    /// Takes in `part` as one part of this chapter: its heading becomes a sub-heading
    /// anchored at its id (links to it still land), its thesis line a note, and its
    /// own headings move one level down.
    pub fn absorb(&mut self, part: Section) {
        self.blocks.push(Block::Heading {
            level: 2,
            text: part.heading,
            detail: None,
            anchor: Some(part.id),
        });
        if let Some(thesis) = part.thesis {
            self.blocks
                .push(Block::note(Tone::Muted, format!("Thesis: {thesis}")));
        }
        for mut block in part.blocks {
            if let Block::Heading { level, .. } = &mut block {
                *level = (*level + 1).min(4);
            }
            self.blocks.push(block);
        }
    }

    /// The section with only a note saying why it is empty.
    pub fn empty(mut self, why: impl Into<String>) -> Section {
        self.blocks.push(Block::empty(why));
        self
    }
}

impl Document {
    /// The section with this id.
    pub fn section(&self, id: &str) -> Option<&Section> {
        self.sections.iter().find(|s| s.id == id)
    }

    /// Every table of the document, in order.
    pub fn tables(&self) -> impl Iterator<Item = &Table> {
        self.sections
            .iter()
            .flat_map(|s| s.blocks.iter())
            .filter_map(|b| match b {
                Block::Table(t) => Some(t),
                _ => None,
            })
    }
}
