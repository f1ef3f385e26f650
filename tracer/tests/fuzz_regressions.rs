//! Every input in `tests/fuzz-regressions/` (crashes and NaN images the fuzz campaign
//! found, minimized, plus hand-written hostile inputs; docs/fuzzing.md) runs through
//! the fuzz target's own path, `tracer::fuzz_check::parse_and_render_tiny`: parse, build
//! brute force, SIMD and BVH, render a tiny image with each. No input may panic, and
//! each must end as its first line says:
//!
//! - `# expect: rendered` — the scene renders with finite pixels only;
//! - `# expect: rejected at line N: TEXT` — a parse error naming line N whose message
//!   contains TEXT (and whose display starts with `file:N: `).

use std::path::{Path, PathBuf};
use tracer::fuzz_check::{Outcome, parse_and_render_tiny};

#[derive(Debug, PartialEq)]
enum Expected {
    Rendered,
    Rejected { line: usize, text: String },
}

fn expectation(path: &Path, text: &str) -> Expected {
    let first = text.lines().next().unwrap_or("");
    let Some(spec) = first.strip_prefix("# expect: ") else {
        panic!(
            "{}: the first line must be '# expect: rendered' or '# expect: rejected at line N: TEXT'",
            path.display()
        );
    };
    if spec.trim() == "rendered" {
        return Expected::Rendered;
    }
    let parsed = spec.strip_prefix("rejected at line ").and_then(|rest| {
        let (line, text) = rest.split_once(": ")?;
        Some(Expected::Rejected {
            line: line.parse().ok()?,
            text: text.trim().to_string(),
        })
    });
    parsed.unwrap_or_else(|| panic!("{}: cannot read the expectation '{spec}'", path.display()))
}

fn regression_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap_or_else(|e| panic!("{e}")).path())
        .filter(|path| path.extension().is_some_and(|x| x == "nff"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_fuzz_regression_ends_as_its_first_line_says() {
    let files = regression_files();
    assert!(files.len() >= 10, "only {} regression inputs", files.len());
    for path in &files {
        // Read as bytes and decoded as the fuzz target decodes them.
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let text = String::from_utf8_lossy(&bytes);
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let expected = expectation(path, &text);
        let outcome =
            parse_and_render_tiny(&text, &name).unwrap_or_else(|defect| panic!("{name}: {defect}"));
        match (&expected, &outcome) {
            (Expected::Rendered, Outcome::Rendered) => {}
            (Expected::Rejected { line, text }, Outcome::Rejected(error)) => {
                assert_eq!(error.line, *line, "{name}: {error}");
                assert!(
                    error.message.contains(text.as_str()),
                    "{name}: '{error}' lacks '{text}'"
                );
                assert!(
                    error.to_string().starts_with(&format!("{name}:{line}: ")),
                    "{error}"
                );
            }
            _ => panic!("{name}: expected {expected:?}, got {outcome:?}"),
        }
    }
}

/// `count` vertex lines in the plane z = 0, facing the eye at z = -5. `Star`: around
/// the view axis, alternating between radius 2 and 1 (concave at every other vertex).
/// `Fan`: the centre, then an arc of radius 2 over 350°, so that the first three vertices
/// span a plane even when the arc's neighbours are collinear in f32 (a regular
/// 65536-gon's are: its sagitta is below f32 precision).
fn outline(count: usize, shape: Shape, with_normals: bool) -> String {
    let mut out = String::new();
    for i in 0..count {
        let (x, y) = match shape {
            Shape::Star => {
                let angle = std::f64::consts::TAU * i as f64 / count as f64;
                let radius = if i % 2 == 1 { 1.0 } else { 2.0 };
                (radius * angle.cos(), radius * angle.sin())
            }
            Shape::Fan if i == 0 => (0.0, 0.0),
            Shape::Fan => {
                let angle = 350f64.to_radians() * (i - 1) as f64 / (count - 2) as f64;
                (2.0 * angle.cos(), 2.0 * angle.sin())
            }
        };
        out.push_str(&format!("{x:.6} {y:.6} 0"));
        out.push_str(if with_normals { " 0 0 -1\n" } else { "\n" });
    }
    out
}

#[derive(Clone, Copy)]
enum Shape {
    Star,
    Fan,
}

#[test]
fn generated_inputs_at_the_size_limits_render() {
    let view =
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 32 24\nl 0 0 -9\n";
    // Too large to keep as files: a 10 000-vertex star polygon, a patch with exactly
    // Limits::max_polygon_vertices (65536) vertices, which the limit admits, and 70 000
    // coincident spheres (more equal centroids than a BVH leaf holds: split by count).
    let cases = [
        (
            "coincident-spheres-70000.nff",
            format!("{view}{}", "s 0 0 0 1\n".repeat(70_000)),
        ),
        (
            "star-10000.nff",
            format!("{view}p 10000\n{}", outline(10_000, Shape::Star, false)),
        ),
        (
            "patch-65536.nff",
            format!("{view}pp 65536\n{}", outline(65_536, Shape::Fan, true)),
        ),
    ];
    for (name, text) in &cases {
        match parse_and_render_tiny(text, name) {
            Ok(Outcome::Rendered) => {}
            other => panic!("{name}: expected a finite render, got {other:?}"),
        }
    }
    // One vertex more than the limit is refused on the `pp` line (line 9).
    let over = format!("{view}pp 65537\n{}", outline(65_537, Shape::Fan, true));
    match parse_and_render_tiny(&over, "over.nff") {
        Ok(Outcome::Rejected(e)) => {
            assert_eq!(e.line, 9, "{e}");
            assert!(e.message.contains("exceeds the limit of 65536"), "{e}");
        }
        other => panic!("expected the vertex limit to refuse 65537 vertices, got {other:?}"),
    }
}

#[test]
fn expectation_lines_are_read_strictly() {
    let p = Path::new("x.nff");
    assert_eq!(
        expectation(p, "# expect: rendered\nv\n"),
        Expected::Rendered
    );
    assert_eq!(
        expectation(p, "# expect: rejected at line 12: must lie between\n"),
        Expected::Rejected {
            line: 12,
            text: "must lie between".into()
        }
    );
    let bad = std::panic::catch_unwind(|| expectation(p, "# expect: rejected at line x: y\n"));
    assert!(bad.is_err());
    let missing = std::panic::catch_unwind(|| expectation(p, "v\n"));
    assert!(missing.is_err());
}

// The check itself on two hand-written texts (here rather than as unit tests of
// fuzz_check: a unit test that renders compiles the whole renderer into the tracer's
// test binary again, about half of that binary's build time).
const VIEW: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 640 480\n";

#[test]
fn a_plain_scene_renders_with_every_entry() {
    let text = format!("{VIEW}l 1 1 -5\nf 1 0 0 1 0.5 10 0.5 1.5\ns 0 0 0 1\n");
    assert!(matches!(
        parse_and_render_tiny(&text, "ok.nff"),
        Ok(Outcome::Rendered)
    ));
}

#[test]
fn a_bad_line_is_a_rejection_naming_it() {
    let text = format!("{VIEW}s 0 0 0\n");
    match parse_and_render_tiny(&text, "bad.nff") {
        Ok(Outcome::Rejected(e)) => assert_eq!(e.line, 8, "{e}"),
        other => panic!("expected a rejection, got {other:?}"),
    }
}
