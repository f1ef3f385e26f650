//! Inferno's flamegraph SVGs for a page that runs no script (the PDF): the interactive
//! parts taken out, what a reader can see kept and finished.
//!
//! An inferno flamegraph is an interactive document: a script zooms, searches and
//! re-fits the frames' labels to the window, and writes the hovered frame's name into
//! a details line. On a printed page the script never runs, so its controls are dead
//! ("Search", "Reset Zoom"), its details line and search-match count are empty and
//! the labels stay as inferno first cut them (the root frame's without its name).
//! [`static_flamegraph`] removes the script and the script's elements (`#search`,
//! `#unzoom`, `#matched`, `#details`, the root's `onload`), keeps every frame, its
//! title (the full name and share) and its colour, and writes each frame's label as
//! the script would at the SVG's own width: the name from the frame's title, cut with
//! ".." where the frame is too narrow, nothing where not even one character fits. The
//! labels' generic `monospace` font is named (DejaVu Sans Mono, which the PDF's typst
//! embeds and which has the advance inferno fits labels to), since typst does not
//! resolve generic families in SVGs.
//!
//! The work is done on the source text: the XML is parsed (roxmltree) only to find the
//! byte ranges of what to remove or rewrite, so everything else stays byte for byte.
//! [`for_print`] applies it to every flamegraph of a document, for the PDF; the HTML
//! keeps the interactive originals.

use std::collections::BTreeSet;
use std::ops::Range;

use crate::document::{AssetKind, Block, Document, Visual};
use crate::markup::escape;

/// The elements of inferno's interface, by id: what the script drives.
const INTERFACE_IDS: [&str; 4] = ["search", "unzoom", "matched", "details"];

/// The font the labels are named in for print (typst embeds it).
const PRINT_MONOSPACE: &str = "'DejaVu Sans Mono', monospace";

/// The advance of one DejaVu Sans Mono character, in ems (1233 / 2048): labels are
/// fitted with at least this, so that they stay inside their frames in print.
const PRINT_CHAR_EM: f64 = 0.602;

/// Why an SVG was not made static.
#[derive(Debug, thiserror::Error)]
pub enum FlameStaticError {
    #[error("not well-formed XML: {0}")]
    Xml(#[from] roxmltree::Error),
    #[error("not an inferno flamegraph (no frames container)")]
    NotInferno,
}

/// The static form of inferno flamegraph `svg` (see the module documentation).
pub fn static_flamegraph(svg: &str) -> Result<String, FlameStaticError> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(svg, options)?;
    let root = doc.root_element();
    let frames = root
        .descendants()
        .find(|n| n.has_tag_name("svg") && n.attribute("id") == Some("frames"))
        .ok_or(FlameStaticError::NotInferno)?;
    let mut edits: Vec<(Range<usize>, String)> = Vec::new();

    // The script's settings, read before it goes: the labels' size and advance.
    let script: String = root
        .descendants()
        .filter(|n| n.has_tag_name("script"))
        .flat_map(|n| n.descendants())
        .filter_map(|n| n.text())
        .collect();
    let font_size = script_number(&script, "fontsize").unwrap_or(12.0);
    let font_width = script_number(&script, "fontwidth")
        .unwrap_or(0.59)
        .max(PRINT_CHAR_EM);

    // The script, its controls and read-outs, and the root's handlers.
    for node in root.descendants().filter(|n| n.is_element()) {
        let interface = node
            .attribute("id")
            .is_some_and(|id| INTERFACE_IDS.contains(&id));
        if node.has_tag_name("script") || interface {
            edits.push((node.range(), String::new()));
        }
    }
    for attribute in root.attributes() {
        if attribute.name().starts_with("on") {
            edits.push((attribute.range(), String::new()));
        }
    }

    // The labels' font, named.
    for style in root.descendants().filter(|n| n.has_tag_name("style")) {
        for text in style.children().filter(|n| n.is_text()) {
            let range = text.range();
            let css = &svg[range.clone()];
            let named = name_monospace(css);
            if named != css {
                edits.push((range, named));
            }
        }
    }

    // Each frame's label, from its title, at the frames' own width.
    let frames_width = frames
        .attribute("width")
        .and_then(|w| w.parse::<f64>().ok())
        .unwrap_or(1180.0);
    let char_px = font_size * font_width;
    for label in frames.descendants().filter(|n| n.has_tag_name("text")) {
        let Some(frame) = label.parent_element() else {
            continue;
        };
        let title = frame
            .children()
            .find(|n| n.has_tag_name("title"))
            .and_then(|t| t.text());
        let width = frame
            .children()
            .find(|n| n.has_tag_name("rect"))
            .and_then(|r| r.attribute("width"))
            .and_then(percent);
        let (Some(title), Some(width)) = (title, width) else {
            continue;
        };
        let fitted = fit_label(name_of(title), width / 100.0 * frames_width, char_px);
        if let Some(range) = content_range(svg, label.range()) {
            edits.push((range, escape(&fitted)));
        }
    }
    Ok(apply(svg, edits))
}

/// The static form of `svg` when it is an inferno flamegraph; otherwise `None`.
fn static_bytes(svg: &[u8]) -> Option<Vec<u8>> {
    let text = std::str::from_utf8(svg).ok()?;
    static_flamegraph(text).ok().map(String::into_bytes)
}

/// `doc` for print: each flamegraph's SVG replaced by its static form (a flamegraph
/// that is not inferno's, or not well-formed, stays as it is). The document the HTML
/// is rendered from keeps the interactive originals.
pub fn for_print(doc: &Document) -> Document {
    let mut out = doc.clone();
    let mut replaced = BTreeSet::new();
    for section in &mut out.sections {
        for block in &mut section.blocks {
            let Block::Flamegraph(flame) = block else {
                continue;
            };
            let Visual::Image(image) = &mut flame.visual else {
                continue;
            };
            let Some(asset) = doc.assets.get(&image.asset) else {
                continue;
            };
            if asset.kind != AssetKind::Svg {
                continue;
            }
            if let Some(bytes) = static_bytes(&asset.bytes) {
                replaced.insert(image.asset.clone());
                image.asset = out.assets.add(AssetKind::Svg, bytes);
            }
        }
    }
    // The originals, unless another block still shows one.
    let still_used: BTreeSet<&str> = out
        .sections
        .iter()
        .flat_map(|s| &s.blocks)
        .flat_map(images)
        .collect();
    let gone: BTreeSet<String> = replaced
        .iter()
        .filter(|path| !still_used.contains(path.as_str()))
        .cloned()
        .collect();
    out.assets.remove_all(&gone);
    out
}

/// The assets a block shows.
fn images(block: &Block) -> Vec<&str> {
    let visuals: Vec<&Visual> = match block {
        Block::Figure(f) => vec![&f.visual],
        Block::Flamegraph(f) => vec![&f.visual],
        Block::ImageGrid(g) => g.tiles.iter().map(|t| &t.visual).collect(),
        _ => Vec::new(),
    };
    visuals
        .into_iter()
        .filter_map(|v| match v {
            Visual::Image(image) => Some(image.asset.as_str()),
            _ => None,
        })
        .collect()
}

/// The number a script sets `name` to (`var fontsize = 12;`).
fn script_number(script: &str, name: &str) -> Option<f64> {
    let at = script.find(&format!("var {name} = "))? + name.len() + 7;
    script[at..].split(';').next()?.trim().parse().ok()
}

/// `css` with the generic `monospace` family named for print.
fn name_monospace(css: &str) -> String {
    css.replace(
        "font-family:monospace",
        &format!("font-family:{PRINT_MONOSPACE}"),
    )
    .replace(
        "font-family: monospace",
        &format!("font-family: {PRINT_MONOSPACE}"),
    )
}

/// `38.7775%` as 38.7775.
fn percent(value: &str) -> Option<f64> {
    value.trim().strip_suffix('%')?.trim().parse().ok()
}

/// The frame's name from its title: `name (N samples, P%)` (and, in a differential
/// flamegraph, `; +D%` inside the parentheses) without the parenthesised counts, as
/// inferno's script takes it.
fn name_of(title: &str) -> &str {
    let title = title.trim_end();
    match (title.ends_with(')'), title.rfind('(')) {
        (true, Some(open)) => title[..open].trim_end(),
        _ => title,
    }
}

/// The label of a frame `width` pixels wide with characters `char_px` wide: the whole
/// name when it fits, else its start and "..", else nothing (fewer than three
/// characters' room), as inferno cuts labels.
fn fit_label(name: &str, width: f64, char_px: f64) -> String {
    let fits = if char_px > 0.0 && width.is_finite() {
        (width / char_px).max(0.0).trunc() as usize
    } else {
        0
    };
    let length = name.chars().count();
    if fits < 3 {
        String::new()
    } else if length < fits {
        name.to_string()
    } else {
        name.chars().take(fits - 2).chain("..".chars()).collect()
    }
}

/// The bytes between an element's start tag and its end tag, from the element's
/// range; for an empty element written `<text .../>`, `None`.
fn content_range(svg: &str, element: Range<usize>) -> Option<Range<usize>> {
    let text = svg.get(element.clone())?;
    let mut quote = None;
    let mut open_end = None;
    for (i, c) in text.char_indices() {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '>') => {
                open_end = Some(i + 1);
                break;
            }
            _ => {}
        }
    }
    let open_end = open_end?;
    if text[..open_end].ends_with("/>") {
        return None;
    }
    let close_start = text.rfind("</")?;
    (open_end <= close_start).then(|| element.start + open_end..element.start + close_start)
}

/// `svg` with each range replaced by its text. Ranges inside a range already taken
/// out (an element's label inside a removed element) are dropped.
fn apply(svg: &str, mut edits: Vec<(Range<usize>, String)>) -> String {
    edits.sort_by_key(|(range, _)| (range.start, std::cmp::Reverse(range.end)));
    let mut out = String::with_capacity(svg.len());
    let mut at = 0;
    for (range, text) in edits {
        if range.start < at {
            continue;
        }
        out.push_str(&svg[at..range.start]);
        out.push_str(&text);
        at = range.end;
    }
    out.push_str(&svg[at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A real inferno flamegraph, drawn with the options rtprof's profiles use
    /// (analysis::profile::folded): a root with a wide and a narrow callee, a name too
    /// long for its frame, and one with XML's special characters.
    fn inferno_svg() -> String {
        let folded = [
            "scene;closest hit;cylinder test 400",
            "scene;closest hit;sphere test 80",
            "scene;shading;shadow query;sphere test 300",
            "scene;shading;reflection/refraction set-up with a very long name 30",
            "scene;camera ray 5",
            "scene;<&T as Sum>::sum 100",
        ]
        .join("\n");
        let mut options = inferno::flamegraph::Options::default();
        options.title = "rings (baseline), phases".to_string();
        options.count_name = "samples".to_string();
        options.hash = true;
        options.deterministic = true;
        let mut svg = Vec::new();
        inferno::flamegraph::from_lines(&mut options, folded.lines(), &mut svg)
            .expect("inferno draws");
        String::from_utf8(svg).expect("UTF-8")
    }

    /// Every frame of an SVG: its title and its label.
    fn frames(svg: &str) -> Vec<(String, String)> {
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            ..Default::default()
        };
        let doc = roxmltree::Document::parse_with_options(svg, options).expect("XML");
        doc.descendants()
            .filter(|n| n.has_tag_name("g"))
            .filter_map(|g| {
                let title = g.children().find(|n| n.has_tag_name("title"))?.text()?;
                let label = g
                    .children()
                    .find(|n| n.has_tag_name("text"))
                    .map_or("", |t| t.text().unwrap_or(""));
                Some((title.to_string(), label.to_string()))
            })
            .collect()
    }

    #[test]
    fn a_real_inferno_svg_loses_its_interface_and_keeps_its_frames() {
        let interactive = inferno_svg();
        // What the interactive one has that a printed page cannot use.
        for part in [
            "<script",
            "onload=\"init(evt)\"",
            "id=\"search\"",
            ">Search</text>",
            ">Reset Zoom</text>",
            "id=\"matched\"",
            "id=\"details\"",
        ] {
            assert!(
                interactive.contains(part),
                "inferno no longer writes {part}"
            );
        }
        let printed = static_flamegraph(&interactive).expect("static");
        for part in [
            "<script",
            "init(evt)",
            "Search",
            "Reset Zoom",
            "id=\"matched\"",
            "id=\"details\"",
            "id=\"unzoom\"",
        ] {
            assert!(!printed.contains(part), "{part} is still there");
        }
        // Still an SVG that parses, with its title, the frames' container and every
        // frame: same titles, same rectangles, same colours.
        assert!(printed.contains("rings (baseline), phases"));
        let before = frames(&interactive);
        let after = frames(&printed);
        assert_eq!(before.len(), after.len());
        assert!(before.len() >= 9, "{before:?}");
        for ((t0, _), (t1, _)) in before.iter().zip(&after) {
            assert_eq!(t0, t1);
        }
        let rects = |svg: &str| svg.matches("<rect ").count();
        assert_eq!(rects(&interactive), rects(&printed));
        assert!(printed.contains("font-family:'DejaVu Sans Mono', monospace"));
    }

    #[test]
    fn labels_are_the_titles_names_fitted_to_their_frames() {
        let printed = static_flamegraph(&inferno_svg()).expect("static");
        let labels: Vec<(String, String)> = frames(&printed);
        let label = |name: &str| {
            labels
                .iter()
                .find(|(title, _)| title.starts_with(&format!("{name} (")))
                .map(|(_, label)| label.clone())
                .unwrap_or_else(|| panic!("no frame {name}"))
        };
        // 915 samples in all: the frames' container is 1,180 pixels wide and a
        // character 12 × 0.602 = 7.224 pixels.
        let px = |samples: f64| samples / 915.0 * 1180.0;
        let fits = |samples: f64| (px(samples) / 7.224).trunc() as usize;
        // The root frame: the script names it "all"; inferno's own label is empty.
        assert_eq!(label("all"), "all");
        // 400 samples: 388 pixels, 53 characters; the name fits whole.
        assert!(fits(400.0) > "cylinder test".len());
        assert_eq!(label("cylinder test"), "cylinder test");
        // 30 samples: 38.7 pixels, 5 characters: 3 of the name and "..".
        assert_eq!(fits(30.0), 5);
        assert_eq!(
            label("reflection/refraction set-up with a very long name"),
            "ref.."
        );
        // 5 samples: 6.4 pixels, not one character: no label.
        assert_eq!(label("camera ray"), "");
        // Special characters are written back escaped and read back as themselves.
        assert!(fits(100.0) > "<&T as Sum>::sum".len());
        assert_eq!(label("<&T as Sum>::sum"), "<&T as Sum>::sum");
        assert!(printed.contains(">&lt;&amp;T as Sum&gt;::sum</text>"));
    }

    #[test]
    fn what_is_not_an_inferno_flamegraph_is_refused() {
        assert!(matches!(
            static_flamegraph("<svg xmlns=\"http://www.w3.org/2000/svg\"><rect/></svg>"),
            Err(FlameStaticError::NotInferno)
        ));
        assert!(matches!(
            static_flamegraph("<svg><g></svg>"),
            Err(FlameStaticError::Xml(_))
        ));
    }

    #[test]
    fn names_lose_their_counts_and_labels_their_tails() {
        assert_eq!(name_of("all (1,047 samples, 100%)"), "all");
        assert_eq!(name_of("shading (553 samples, 52.82%; +3.10%)"), "shading");
        assert_eq!(name_of("f(x) (2 samples, 0.19%)"), "f(x)");
        assert_eq!(name_of("plain"), "plain");
        assert_eq!(fit_label("cylinder test", 100.0, 7.0), "cylinder test");
        // Room for 10 characters: 8 of the name and "..".
        assert_eq!(fit_label("cylinder test", 70.0, 7.0), "cylinder..");
        assert_eq!(fit_label("abc", 21.0, 7.0), "a..");
        assert_eq!(fit_label("abc", 20.9, 7.0), "");
        assert_eq!(fit_label("abc", f64::NAN, 7.0), "");
    }

    #[test]
    fn the_pdf_gets_the_static_flamegraph_and_the_html_the_interactive_one() {
        use crate::document::{Assets, Flamegraph, Image, Section};
        let interactive = inferno_svg();
        let mut assets = Assets::default();
        let path = assets.add(AssetKind::Svg, interactive.clone().into_bytes());
        let doc = Document {
            sections: vec![Section {
                id: "flamegraphs".to_string(),
                blocks: vec![Block::Flamegraph(Flamegraph {
                    title: "rings".to_string(),
                    caption: None,
                    visual: Visual::Image(Image {
                        asset: path.clone(),
                        width: 1200.0,
                        height: 300.0,
                        alt: "rings".to_string(),
                        file: None,
                    }),
                })],
                ..Section::default()
            }],
            assets,
            ..Document::default()
        };
        let printed = for_print(&doc);
        let Block::Flamegraph(flame) = &printed.sections[0].blocks[0] else {
            panic!("a flamegraph");
        };
        let Visual::Image(image) = &flame.visual else {
            panic!("an image");
        };
        let bytes = &printed
            .assets
            .get(&image.asset)
            .expect("the static asset")
            .bytes;
        let text = String::from_utf8_lossy(bytes);
        assert!(!text.contains("<script") && text.contains("id=\"frames\""));
        assert!(
            printed.assets.get(&path).is_none(),
            "the original is dropped"
        );
        assert_eq!(printed.assets.len(), 1);
        // typst places it.
        assert!(crate::pdf::typeset(&printed).is_ok());
        // The document the HTML is made from still has the interactive one.
        assert_eq!(
            doc.assets.get(&path).expect("original").bytes,
            interactive.into_bytes()
        );
        let html = crate::html::render(&doc);
        assert!(html.contains("Reset Zoom"));
    }
}
