//! The HTML report of the synthetic sample: sections, self-containment, embedded
//! images, missing files, the comparison of two runs and escaping.

use std::path::Path;

use reports::Run;
use reports::document::{Part, SECTIONS};
use reports::html::render_html;
use testkit::{TempDir, sample_results, write_sample_files};

fn sample_run(label: &str, dir: &Path) -> Run {
    write_sample_files(dir).expect("write sample files");
    Run {
        label: label.to_string(),
        results: sample_results(),
        base_dir: dir.to_path_buf(),
    }
}

#[test]
fn every_section_is_present_and_nothing_reaches_the_network() {
    let dir = TempDir::new("html-test-sections").expect("temp dir");
    let html = render_html(&[sample_run("bench-1", dir.path())]).expect("render");
    assert!(html.starts_with("<!DOCTYPE html>"));
    for (id, _, part) in SECTIONS {
        let present = match part {
            // A chapter's parts are anchored headings inside it.
            Part::Within(_) => html.contains(&format!(" id=\"{id}\">")),
            _ => html.contains(&format!("<section id=\"{id}\">")),
        };
        assert_eq!(present, id != "comparison", "section {id}");
    }
    for bad in [
        "src=\"http",
        "href=\"http",
        "src=\"//",
        "href=\"//",
        "src='http",
        "href='http",
        "url(http",
        "url(//",
    ] {
        assert!(!html.contains(bad), "found {bad}");
    }
    // The sample's per-pixel maps are named but not written (their section shows
    // that); every image it writes is embedded.
    assert!(
        !html.contains("image missing: images/"),
        "every sample image was written"
    );
    assert!(html.contains("<table class=\"sortable\""));
    assert!(html.contains("<script>"));
    assert!(html.contains("<iframe class=\"flame\""));
    assert!(html.contains("srcdoc=\"&lt;!DOCTYPE html&gt;"));
}

#[test]
fn images_are_embedded_as_data_uris() {
    let dir = TempDir::new("html-test-images").expect("temp dir");
    let html = render_html(&[sample_run("bench-1", dir.path())]).expect("render");
    let tiny_png = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAAAAAA6fptVAAAACklEQVR4nGNoAAAAggCBd81ytgAAAABJRU5ErkJggg==";
    assert!(html.contains(&format!("src=\"data:image/png;base64,{tiny_png}\"")));
    let images = html.matches("<img ").count();
    let data_images = html.matches("<img src=\"data:image/png;base64,").count();
    assert!(
        images > 20 && images == data_images,
        "{images} images, {data_images} data URIs"
    );
    // The charts are inline SVG.
    assert!(html.contains("<figure class=\"chart\" id=\"chart-calls\"><svg"));
}

#[test]
fn a_missing_image_gives_a_visible_note() {
    let dir = TempDir::new("html-test-missing").expect("temp dir");
    let run = sample_run("bench-1", dir.path());
    let gone = "images/balls4-ortho.png";
    std::fs::remove_file(dir.path().join(gone)).expect("remove");
    let html = render_html(&[run]).expect("render");
    assert!(
        html.contains(&format!("image missing: {gone}")),
        "no note for {gone}"
    );

    // A whole missing directory (texts, flamegraphs) still renders, with notes.
    let empty = TempDir::new("html-test-empty").expect("temp dir");
    let run = Run {
        label: "bare".into(),
        results: sample_results(),
        base_dir: empty.path().to_path_buf(),
    };
    let html = render_html(&[run]).expect("render");
    assert!(html.contains("flamegraph missing: profile/rings-baseline-flame.svg"));
    assert!(html.contains("call graph text missing: profile/rings-baseline-callgraph.txt"));
}

#[test]
fn two_runs_give_the_comparison_section() {
    let dir = TempDir::new("html-test-two").expect("temp dir");
    let first = sample_run("bench-1", dir.path());
    let mut second = sample_run("bench-2", dir.path());
    second.results.machine.hostname = "bench-2".into();
    // Every render 20 % slower, the yardsticks unchanged: baseline ÷ yardstick
    // grows 20 %, the variants ÷ baseline do not.
    for scene in &mut second.results.scenes {
        for v in &mut scene.variants {
            v.time = v.time.scaled(1.2);
            for x in v.samples.iter_mut().chain(v.cpu_samples.iter_mut()) {
                *x *= 1.2;
            }
        }
    }
    if let Some(v) = second.results.scenes[0].variants.get_mut(0) {
        *v.counts.entry("ops.dot".into()).or_insert(0) += 1;
    }
    let html = render_html(&[first, second]).expect("render");
    assert!(html.contains("<section id=\"comparison\">"));
    assert!(html.contains("<a href=\"#comparison\">"));
    assert!(html.contains("bench-2 vs bench-1"));
    assert!(
        html.contains(">+20"),
        "baseline's change against the yardstick"
    );
    assert!(html.contains(">slower<"), "its verdict");
    assert!(
        html.contains("changed: ops.dot: "),
        "a flagged count difference"
    );
}

#[test]
fn scene_names_are_escaped() {
    let dir = TempDir::new("html-test-escape").expect("temp dir");
    let mut run = sample_run("bench-1", dir.path());
    run.results.scenes[0].name = "<script>alert(1)</script>".into();
    run.results.failures[0].message = "bad \"quote\" & <b>tag</b>".into();
    let html = render_html(&[run]).expect("render");
    assert!(
        !html.contains("<script>alert(1)"),
        "raw scene name in the HTML"
    );
    assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert!(!html.contains("<b>tag</b>"));
    // Only the report's own script element.
    assert_eq!(html.matches("<script>").count(), 1);
}

#[test]
fn an_empty_run_explains_its_empty_sections() {
    let dir = TempDir::new("html-test-bare").expect("temp dir");
    let mut results = sample_results();
    results.scenes.clear();
    results.profile = None;
    results.hardware = None;
    results.failures.clear();
    results.criterion.clear();
    results.instructions.clear();
    let run = Run {
        label: "empty".into(),
        results,
        base_dir: dir.path().to_path_buf(),
    };
    let html = render_html(&[run]).expect("render");
    for note in [
        "No profile in this run",
        "No hardware model in this run",
        "No SPD scene ran",
        "No benchmark estimates",
        "No failures",
        "No test-bench scene",
    ] {
        assert!(html.contains(note), "missing note: {note}");
    }
}

#[test]
fn no_development_issue_number_reaches_a_reader() {
    // The report's text (HTML and the summary.md of the same document model; CI checks
    // report.pdf's text too) speaks of the thesis and the program, never of the issues
    // the program was built in.
    let dir = TempDir::new("html-test-issues").expect("temp dir");
    let runs = [sample_run("bench-1", dir.path())];
    let html = render_html(&runs).expect("render");
    let summary = reports::exports::summary_markdown(&runs);
    // The words around the first "issue <digit>", if any.
    let issue = |text: &str| -> Option<String> {
        let lower = text.to_lowercase();
        let words: Vec<&str> = lower.split_whitespace().collect();
        words
            .windows(2)
            .position(|w| w[0].ends_with("issue") && w[1].starts_with(|c: char| c.is_ascii_digit()))
            .map(|i| words[i.saturating_sub(8)..(i + 4).min(words.len())].join(" "))
    };
    assert_eq!(issue(&html), None, "report.html names an issue");
    assert_eq!(issue(&summary), None, "summary.md names an issue");
    // The check itself finds one.
    assert!(issue("as in Issue 38 before").is_some());
}
