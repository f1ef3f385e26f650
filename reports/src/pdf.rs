//! The PDF report: the [`Document`] typeset by typst with the template
//! `reports/templates/report.typ`.
//!
//! The document goes to typst as data: serialized to JSON and handed over as the input
//! `document` (`sys.inputs.document` in the template), the assets (pictures, chart and
//! flamegraph SVGs) as files at their virtual paths. Text from the results is never
//! markup, so no character in a scene name or message can change the layout. The
//! fonts are the ones `typst-assets` embeds (Libertinus Serif, New Computer Modern,
//! DejaVu Sans Mono): typesetting reads no system font and no network.
//!
//! A file typst cannot read (a damaged PNG, an SVG it rejects) costs only that
//! picture: when the whole document does not compile, every asset is tried on its own
//! and the ones that fail are replaced by a note.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::sync::LazyLock;

use typst::foundations::{Bytes, Dict, Element, IntoValue, Selector};
use typst::introspection::Introspector as _;
use typst::model::HeadingElem;
use typst::text::Font;
use typst_as_lib::TypstEngine;
use typst_layout::PagedDocument;

use crate::Run;
use crate::document::{self, Asset, Block, Document, Figure, Image, Section, Visual};

/// Why no PDF could be made.
#[derive(Debug, thiserror::Error)]
pub enum PdfError {
    #[error("nothing to report: no runs given")]
    NoRuns,
    #[error("the report document cannot be serialized: {0}")]
    Data(#[from] serde_json::Error),
    #[error("typst could not typeset the report: {0}")]
    Typeset(String),
    #[error("typst could not write the PDF: {0}")]
    Export(String),
}

/// The template that lays the document out.
pub const TEMPLATE: &str = include_str!("../templates/report.typ");

/// Renders the report of `runs` (one run, or several side by side) to PDF bytes.
pub fn render_pdf(runs: &[Run]) -> Result<Vec<u8>, PdfError> {
    render_pdf_counted(runs).map(|(pdf, _)| pdf)
}

/// [`render_pdf`], with how many pages the PDF has and how many of them are the main
/// body.
pub fn render_pdf_counted(runs: &[Run]) -> Result<(Vec<u8>, PageCount), PdfError> {
    let doc = document::build(runs).ok_or(PdfError::NoRuns)?;
    render_counted(&doc.for_print())
}

/// Typesets a document to PDF bytes, leaving out the assets typst rejects.
pub fn render(doc: &Document) -> Result<Vec<u8>, PdfError> {
    render_counted(doc).map(|(pdf, _)| pdf)
}

/// [`render`], with the page count.
fn render_counted(doc: &Document) -> Result<(Vec<u8>, PageCount), PdfError> {
    let counted = |d: PagedDocument| export(&d).map(|pdf| (pdf, page_count(&d)));
    let first_error = match typeset(doc).and_then(counted) {
        Ok(pdf) => return Ok(pdf),
        Err(err) => err,
    };
    let rejected: BTreeSet<String> = doc
        .assets
        .iter()
        .filter(|a| !asset_typesets(a))
        .map(|a| a.path.clone())
        .collect();
    if !rejected.is_empty() {
        let pruned = doc.without_assets(
            &rejected,
            "could not be typeset here; it is in the HTML report",
        );
        if let Ok(pdf) = typeset(&pruned).and_then(counted) {
            return Ok(pdf);
        }
    }
    // Last resort: the text and tables alone, with the reason on the title page.
    let every: BTreeSet<String> = doc.assets.iter().map(|a| a.path.clone()).collect();
    let mut bare = doc.without_assets(&every, "left out");
    bare.notices.push(format!(
        "Figures and images are left out of this PDF because typst could not typeset them ({first_error}). The HTML report has them."
    ));
    typeset(&bare).and_then(counted).map_err(|_| first_error)
}

/// The data typst gets: the document as JSON (without the assets' bytes).
pub fn input_data(doc: &Document) -> Result<Vec<u8>, PdfError> {
    Ok(serde_json::to_vec(doc)?)
}

/// The embedded fonts, parsed once per process. Parsing them is most of the cost of a
/// small document, and a report with a damaged file typesets once per asset.
static FONTS: LazyLock<Vec<Font>> = LazyLock::new(|| {
    typst_assets::fonts()
        .flat_map(|data| Font::iter(typst::foundations::Bytes::new(data)))
        .collect()
});

/// Lays a document out with the template.
pub fn typeset(doc: &Document) -> Result<PagedDocument, PdfError> {
    let mut inputs = Dict::new();
    inputs.insert("document".into(), Bytes::new(input_data(doc)?).into_value());
    let engine = TypstEngine::builder()
        .main_file(TEMPLATE)
        .fonts(FONTS.iter().cloned())
        .with_static_file_resolver(
            doc.assets
                .iter()
                .map(|a| (a.path.as_str(), a.bytes.as_slice())),
        )
        .build();
    engine
        .compile_with_input(inputs)
        .output
        .map_err(|err| PdfError::Typeset(describe(&err)))
}

/// How long a typeset report is: all its pages, and those before the appendix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PageCount {
    pub total: usize,
    /// Pages of the answers and the chapters (all of them without an appendix).
    pub main_body: usize,
}

/// The page count of a typeset document (the template labels the appendix's heading
/// `appendix`; the main body ends on the page before it).
pub fn page_count(typeset: &PagedDocument) -> PageCount {
    let total = typeset.pages().len();
    let introspector = typeset.introspector();
    let appendix_page = typst::foundations::Label::new(typst::utils::PicoStr::intern("appendix"))
        .and_then(|label| introspector.query_label(label).ok())
        .and_then(|heading| heading.location())
        .and_then(|location| introspector.page(location));
    PageCount {
        total,
        main_body: appendix_page.map_or(total, |page| page.get() - 1),
    }
}

/// The level-1 headings of a typeset document: the label the template gave each (the
/// section's id) and its text, in order.
pub fn section_headings(typeset: &PagedDocument) -> Vec<(String, String)> {
    typeset
        .introspector()
        .query(&Selector::Elem(Element::of::<HeadingElem>(), None))
        .iter()
        .filter_map(|heading| {
            let label = heading.label()?;
            let body = &heading.to_packed::<HeadingElem>()?.body;
            Some((label.resolve().to_string(), body.plain_text().to_string()))
        })
        .collect()
}

fn export(document: &PagedDocument) -> Result<Vec<u8>, PdfError> {
    typst_pdf::pdf(document, &typst_pdf::PdfOptions::default()).map_err(|diags| {
        PdfError::Export(
            diags
                .iter()
                .map(|d| d.message.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        )
    })
}

/// Whether typst can place one asset as a picture (through the same template).
fn asset_typesets(asset: &Asset) -> bool {
    let mut doc = Document::default();
    let mut assets = document::Assets::default();
    let path = assets.add(asset.kind, asset.bytes.clone());
    doc.assets = assets;
    doc.sections.push(Section {
        id: "probe".to_string(),
        heading: "probe".to_string(),
        blocks: vec![Block::Figure(Figure {
            id: "probe".to_string(),
            title: "probe".to_string(),
            caption: String::new(),
            visual: Visual::Image(Image {
                asset: path,
                width: 1.0,
                height: 1.0,
                alt: String::new(),
                file: None,
            }),
            max_height_cm: 2.0,
        })],
        ..Section::default()
    });
    typeset(&doc).is_ok()
}

/// A typst error, readably.
fn describe(err: &typst_as_lib::TypstAsLibError) -> String {
    match err {
        typst_as_lib::TypstAsLibError::TypstSource(diags) => diags
            .iter()
            .map(|d| {
                let mut text = d.message.to_string();
                for hint in &d.hints {
                    let _ = write!(text, " (hint: {})", hint.v);
                }
                text
            })
            .collect::<Vec<_>>()
            .join("; "),
        other => other.to_string(),
    }
}
