//! Folded stacks (Brendan Gregg's format: `root;caller;callee count` per line) and the
//! flamegraphs drawn from them with inferno, including differential flamegraphs of two
//! profiles both ways: what grew, drawn on the second profile, and what shrank or
//! vanished, drawn on the first (a frame that is gone from the second profile has no
//! width there, so only the first profile's shape can show it). In both, red = grew,
//! blue = shrank, and frame titles give the change as `+D%` / `-D%` of the samples.
//!
//! One root per flamegraph: the sampler keeps each thread's stack from its outermost
//! profiled frame, so the main thread's stacks and the workers' stacks of the same
//! render start at different frames and would be drawn as separate towers;
//! [`under_one_root`] puts them all under one frame.

use super::{Stack, StackSamples};
use std::io::BufReader;

/// Why a flamegraph could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the flamegraph: {0}")]
pub struct FlamegraphError(#[from] std::io::Error);

/// One line per stack, root first, frames joined by `;`, then a space and the count.
/// Semicolons inside names (none in Rust paths) would split frames, so they are
/// replaced by `,`.
pub fn folded(samples: &StackSamples) -> String {
    let mut lines: Vec<String> = samples
        .stacks
        .iter()
        .filter(|s| s.count > 0 && !s.frames.is_empty())
        .map(|s| {
            let frames: Vec<String> = s.frames.iter().map(|f| f.replace(';', ",")).collect();
            format!("{} {}", frames.join(";"), s.count)
        })
        .collect();
    lines.sort();
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

fn options(title: &str, count_name: &str) -> inferno::flamegraph::Options<'static> {
    let mut options = inferno::flamegraph::Options::default();
    options.title = title.to_string();
    options.count_name = count_name.to_string();
    // Same input, same SVG: colours from the names, not from a random generator.
    options.hash = true;
    options.deterministic = true;
    options
}

/// An interactive flamegraph (SVG) of folded stacks.
pub fn flamegraph_svg(folded_text: &str, title: &str) -> Result<String, FlamegraphError> {
    let mut svg = Vec::new();
    let mut opts = options(title, "samples");
    inferno::flamegraph::from_lines(&mut opts, folded_text.lines(), &mut svg)?;
    Ok(String::from_utf8_lossy(&svg).into_owned())
}

/// The same stacks with `root` as their one outermost frame, so that the stacks of
/// all threads (and of the phase view's several outermost phases) form one tree.
/// Stacks that already start at `root` are kept; stacks without frames stay empty.
/// Use the same root (e.g. the scene's name) for profiles that are diffed, so that
/// their frames line up.
pub fn under_one_root(samples: &StackSamples, root: &str) -> StackSamples {
    let stacks = samples
        .stacks
        .iter()
        .map(|stack| {
            let frames = match stack.frames.first() {
                None => Vec::new(),
                Some(first) if first == root => stack.frames.clone(),
                Some(_) => std::iter::once(root.to_owned())
                    .chain(stack.frames.iter().cloned())
                    .collect(),
            };
            Stack {
                frames,
                count: stack.count,
            }
        })
        .collect();
    StackSamples {
        stacks,
        seconds_per_sample: samples.seconds_per_sample,
    }
}

/// Folded stacks of two profiles merged into inferno's differential input (two counts
/// per line: `first`, then `second`), `first` normalized to `second`'s total so that
/// profiles of different lengths compare by share.
fn differential_lines(first: &str, second: &str) -> Result<String, FlamegraphError> {
    let mut diff = Vec::new();
    let diff_options = inferno::differential::Options {
        normalize: true,
        ..Default::default()
    };
    inferno::differential::from_readers(
        diff_options,
        BufReader::new(first.as_bytes()),
        BufReader::new(second.as_bytes()),
        &mut diff,
    )?;
    Ok(String::from_utf8_lossy(&diff).into_owned())
}

/// Draws inferno differential input; `negate` turns `second - first` into
/// `first - second` for the colours and the `+D%` of the titles.
fn differential_drawing(
    lines: &str,
    title: &str,
    subtitle: Option<String>,
    negate: bool,
) -> Result<String, FlamegraphError> {
    let mut svg = Vec::new();
    let mut opts = options(title, "samples");
    opts.subtitle = subtitle.clone();
    opts.negate_differentials = negate;
    inferno::flamegraph::from_lines(&mut opts, lines.lines(), &mut svg)?;
    let svg = String::from_utf8_lossy(&svg).into_owned();
    Ok(fit_headings(svg, title, subtitle.as_deref()))
}

/// The width of a monospace glyph in ems (inferno's `fontwidth` is 0.59), with a
/// little room: a heading of n characters fits in n × this ems.
const GLYPH_EMS: f64 = 0.62;

/// `svg` with its title and subtitle shrunk to fit the drawing's width where it is
/// narrower than they are long: inferno draws them at a fixed 17 and 12 px centred in
/// a drawing that stretches to its container, so a long heading was cut off at both
/// ends in the page's column (a 97-character title needs about 1,000 px). A second
/// style sheet sets each font size to the smaller of inferno's and the share of the
/// viewport width (`vw`, the drawing's own width when it is embedded) that its
/// characters fill.
fn fit_headings(svg: String, title: &str, subtitle: Option<&str>) -> String {
    let size = |text: &str, px: f64| {
        let chars = text.chars().count().max(1) as f64;
        format!("min({px}px, {:.2}vw)", 100.0 / (GLYPH_EMS * chars))
    };
    let mut style = format!("#title {{ font-size: {}; }}", size(title, 17.0));
    if let Some(subtitle) = subtitle {
        style += &format!(" #subtitle {{ font-size: {}; }}", size(subtitle, 12.0));
    }
    match svg.find("</style>") {
        Some(at) => {
            let end = at + "</style>".len();
            format!(
                "{}<style type=\"text/css\">{style}</style>{}",
                &svg[..end],
                &svg[end..]
            )
        }
        None => svg,
    }
}

/// A differential flamegraph: the shape of `after`, coloured by the change from
/// `before` (counts normalized so that different run lengths compare). It cannot show
/// what vanished; [`differential_svgs`] draws both ways.
pub fn differential_svg(before: &str, after: &str, title: &str) -> Result<String, FlamegraphError> {
    differential_drawing(&differential_lines(before, after)?, title, None, false)
}

/// One profile of a differential flamegraph.
#[derive(Clone, Copy, Debug)]
pub struct DiffSide<'a> {
    /// Folded stacks ([`folded`]), under the same root as the other side's.
    pub folded: &'a str,
    /// The profile's name in the titles (the variant).
    pub label: &'a str,
    /// CPU seconds of one render as sampled (`FlatProfile::seconds_per_render`): the
    /// titles state the whole render's absolute change from these.
    pub seconds_per_render: f64,
    /// What one of those is: "render" (rtprof's tracer), "run" (a recorded program).
    pub unit: &'a str,
}

/// The two differential flamegraphs of a change from `before` to `after`.
#[derive(Clone, Debug, PartialEq)]
pub struct DifferentialSvgs {
    /// Drawn on `after`: frames that grew are red (new frames included).
    pub grown: String,
    /// Drawn on `before` (inferno's negated diff with the profiles swapped): frames
    /// that shrank or vanished are blue.
    pub shrunk: String,
}

/// Both differential flamegraphs (see [`DifferentialSvgs`]). Colours and the `±D%` of
/// frame titles are changes in share of the samples (each profile normalized to the
/// other's total, so runs of different lengths compare); the subtitle states the
/// whole render's absolute change per render, e.g. `whole render: 12.0 ms → 4.00 ms
/// per render (-8.00 ms, speed-up 3.00×)`.
pub fn differential_svgs(
    before: &DiffSide<'_>,
    after: &DiffSide<'_>,
    title: &str,
) -> Result<DifferentialSvgs, FlamegraphError> {
    let change = render_change(
        before.seconds_per_render,
        after.seconds_per_render,
        after.unit,
    );
    let (from, to) = (before.label, after.label);
    // Short titles; how to read the colours goes in the subtitle, with the change.
    let grown = differential_drawing(
        &differential_lines(before.folded, after.folded)?,
        &format!("{title}: what grew, {from} \u{2192} {to}"),
        Some(format!(
            "drawn on {to}: red grew, blue shrank (share of samples); {change}"
        )),
        false,
    )?;
    // Swapped inputs draw `before`'s shape with delta = before - after; negated, the
    // sign again means after - before, so red still grew and blue shrank.
    let shrunk = differential_drawing(
        &differential_lines(after.folded, before.folded)?,
        &format!("{title}: what shrank or vanished, {from} \u{2192} {to}"),
        Some(format!(
            "drawn on {from}: blue shrank, red grew (share of samples); {change}"
        )),
        true,
    )?;
    Ok(DifferentialSvgs { grown, shrunk })
}

/// `whole render: 12.0 ms → 4.00 ms per render (-8.00 ms, speed-up 3.00×)`.
fn render_change(before: f64, after: f64, unit: &str) -> String {
    let delta = after - before;
    let sign = if delta < 0.0 { "-" } else { "+" };
    let ratio = if before > 0.0 {
        // A speed-up, as × means everywhere in rtprof: old time over new time.
        format!(", speed-up {:.2}\u{d7}", before / after)
    } else {
        String::new()
    };
    format!(
        "whole {unit}: {} \u{2192} {} per {unit} ({sign}{}{ratio})",
        duration_text(before),
        duration_text(after),
        duration_text(delta.abs())
    )
}

/// Seconds with three significant digits in s, ms, us or ns: `12.0 ms`, `4.00 ms`.
pub fn duration_text(seconds: f64) -> String {
    if !seconds.is_finite() {
        return format!("{seconds} s");
    }
    let (value, unit) = match seconds.abs() {
        s if s >= 1.0 || s == 0.0 => (seconds, "s"),
        s if s >= 1e-3 => (seconds * 1e3, "ms"),
        s if s >= 1e-6 => (seconds * 1e6, "us"),
        _ => (seconds * 1e9, "ns"),
    };
    let decimals = match value.abs() {
        v if v >= 100.0 => 0,
        v if v >= 10.0 => 1,
        _ => 2,
    };
    format!("{value:.decimals$} {unit}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Stack;

    fn samples() -> StackSamples {
        let stack = |frames: &[&str], count| Stack {
            frames: frames.iter().map(|f| f.to_string()).collect(),
            count,
        };
        StackSamples {
            stacks: vec![
                stack(&["render", "trace", "Sphere::intersect"], 30),
                stack(&["render", "trace"], 5),
                stack(&["render", "shade"], 10),
            ],
            seconds_per_sample: 0.001,
        }
    }

    #[test]
    fn folded_lines_are_root_first_with_counts() {
        let text = folded(&samples());
        assert_eq!(
            text,
            "render;shade 10\nrender;trace 5\nrender;trace;Sphere::intersect 30\n"
        );
    }

    #[test]
    fn flamegraphs_are_svg_with_the_function_names() {
        let text = folded(&samples());
        let svg = flamegraph_svg(&text, "rings").unwrap_or_else(|e| panic!("{e}"));
        assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("Sphere::intersect"));
        let after = "render;shade 40\nrender;trace 5\n";
        let diff = differential_svg(&text, after, "diff").unwrap_or_else(|e| panic!("{e}"));
        assert!(diff.contains("<svg") && diff.contains("shade"));
    }

    /// Each frame of an SVG: its `<title>` text and its rectangle's fill colour.
    fn frames(svg: &str) -> Vec<(String, String)> {
        svg.split("<title>")
            .skip(1)
            .map(|part| {
                let (title, rest) = part.split_once("</title>").unwrap();
                let fill = rest
                    .split_once("fill=\"")
                    .map(|(_, f)| f.split('"').next().unwrap().to_string())
                    .unwrap_or_default();
                (title.to_string(), fill)
            })
            .collect()
    }

    /// The frame whose title starts with `name (`.
    fn frame<'a>(frames: &'a [(String, String)], name: &str) -> Option<&'a (String, String)> {
        frames
            .iter()
            .find(|(t, _)| t.starts_with(&format!("{name} (")))
    }

    /// `rgb(r,g,b)` as numbers.
    fn rgb(fill: &str) -> (u32, u32, u32) {
        let inner = fill.trim_start_matches("rgb(").trim_end_matches(')');
        let v: Vec<u32> = inner
            .split(',')
            .map(|x| x.trim().parse().unwrap())
            .collect();
        (v[0], v[1], v[2])
    }

    #[test]
    fn differential_svgs_show_growth_and_shrinkage_both_ways() {
        // A shrinks 70 -> 20, B grows 20 -> 80, C (10) vanishes; 100 samples each.
        let before = "scene;A 70\nscene;B 20\nscene;C 10\n";
        let after = "scene;A 20\nscene;B 80\n";
        let svgs = differential_svgs(
            &DiffSide {
                folded: before,
                label: "baseline",
                seconds_per_render: 0.012,
                unit: "render",
            },
            &DiffSide {
                folded: after,
                label: "bvh",
                seconds_per_render: 0.004,
                unit: "render",
            },
            "rings",
        )
        .unwrap();
        // Drawn on after: B +60 % red, A -50 % blue, C absent.
        let grown = frames(&svgs.grown);
        let (b, b_fill) = frame(&grown, "B").unwrap();
        assert_eq!(b, "B (80 samples, 80.00%; +60.00%)");
        let (r, g, bl) = rgb(b_fill);
        assert!(r == 255 && g < 255 && bl < 255, "{b_fill}");
        let (a, a_fill) = frame(&grown, "A").unwrap();
        assert_eq!(a, "A (20 samples, 20.00%; -50.00%)");
        assert_eq!(rgb(a_fill).2, 255);
        assert!(frame(&grown, "C").is_none());
        // Drawn on before: A 70 samples, -50 % (after - before, negated back), blue;
        // C vanished: -10 %, blue; B +60 %, red.
        let shrunk = frames(&svgs.shrunk);
        let (a, a_fill) = frame(&shrunk, "A").unwrap();
        assert_eq!(a, "A (70 samples, 70.00%; -50.00%)");
        let (r, g, bl) = rgb(a_fill);
        assert!(bl == 255 && r < 255 && g < 255, "{a_fill}");
        let (c, c_fill) = frame(&shrunk, "C").unwrap();
        assert_eq!(c, "C (10 samples, 10.00%; -10.00%)");
        assert_eq!(rgb(c_fill).2, 255);
        let (b, b_fill) = frame(&shrunk, "B").unwrap();
        assert_eq!(b, "B (20 samples, 20.00%; +60.00%)");
        assert_eq!(rgb(b_fill).0, 255);
        // Both state the whole render's change: 12 ms -> 4 ms, -8 ms, 1/3.
        let change =
            "whole render: 12.0 ms \u{2192} 4.00 ms per render (-8.00 ms, speed-up 3.00\u{d7})";
        assert!(svgs.grown.contains(change) && svgs.shrunk.contains(change));
        assert!(
            svgs.grown.contains("what grew") && svgs.shrunk.contains("what shrank or vanished")
        );
        // The headings shrink to the drawing's width where it is narrower than they are
        // long: "rings: what shrank or vanished, baseline → bvh" is 46 characters of
        // 0.62 em, so 100 / 28.52 = 3.51 vw (17 px from a 485 px wide drawing up).
        let title = "rings: what shrank or vanished, baseline \u{2192} bvh";
        assert!(svgs.shrunk.contains(&format!(">{title}<")));
        assert!(
            svgs.shrunk
                .contains("#title { font-size: min(17px, 3.51vw); }")
        );
        assert!(svgs.shrunk.contains("#subtitle { font-size: min(12px, "));
        // After inferno's style sheet, so that it wins.
        let at = |text: &str| svgs.shrunk.find(text).unwrap();
        assert!(at("#title { text-anchor:middle") < at("#title { font-size: min("));
    }

    #[test]
    fn differential_normalizes_runs_of_different_lengths() {
        // The same split twice as long: no frame changed its share.
        let before = "scene;A 30\nscene;B 10\n";
        let after = "scene;A 60\nscene;B 20\n";
        let side = |folded| DiffSide {
            folded,
            label: "x",
            seconds_per_render: 1.0,
            unit: "render",
        };
        let svgs = differential_svgs(&side(before), &side(after), "same").unwrap();
        for svg in [&svgs.grown, &svgs.shrunk] {
            let all = frames(svg);
            let (a, _) = frame(&all, "A").unwrap();
            assert!(a.ends_with("; 0.00%)"), "{a}");
        }
    }

    #[test]
    fn durations_read_in_three_digits() {
        assert_eq!(duration_text(0.012), "12.0 ms");
        assert_eq!(duration_text(0.004), "4.00 ms");
        assert_eq!(duration_text(1.5), "1.50 s");
        assert_eq!(duration_text(4e-8), "40.0 ns");
        assert_eq!(duration_text(0.000_250), "250 us");
        assert_eq!(duration_text(0.0), "0.00 s");
    }

    #[test]
    fn threads_merge_under_one_root() {
        // The main thread's stacks start at render_variant, a worker's at the closure,
        // idle samples at the scheduler frame: three roots before.
        let threads = StackSamples {
            stacks: vec![
                Stack {
                    frames: vec![
                        "render_variant".into(),
                        "render::{{closure}}".into(),
                        "trace".into(),
                    ],
                    count: 10,
                },
                Stack {
                    frames: vec!["render::{{closure}}".into(), "trace".into()],
                    count: 30,
                },
                Stack {
                    frames: vec!["[scheduler and idle]".into()],
                    count: 5,
                },
                Stack {
                    frames: vec![],
                    count: 2,
                },
            ],
            seconds_per_sample: 0.001,
        };
        let rooted = under_one_root(&threads, "lattice5");
        let text = folded(&rooted);
        assert!(text.lines().all(|l| l.starts_with("lattice5;")), "{text}");
        assert_eq!(text.lines().count(), 3);
        // Idempotent: a second call adds nothing.
        assert_eq!(under_one_root(&rooted, "lattice5"), rooted);
        assert_eq!(rooted.stacks[3].frames, Vec::<String>::new());
        // One tower: the root frame holds all 45 drawn samples.
        let svg = flamegraph_svg(&text, "one root").unwrap();
        let all = frames(&svg);
        let (root, _) = frame(&all, "lattice5").unwrap();
        assert_eq!(root, "lattice5 (45 samples, 100.00%)");
        // The two threads' trace frames stay apart (different paths), both under it.
        assert_eq!(
            all.iter().filter(|(t, _)| t.starts_with("trace (")).count(),
            2
        );
    }
}
