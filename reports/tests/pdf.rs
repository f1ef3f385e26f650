//! The PDF report: it typesets the sample, has the pages it should, survives hostile
//! text and missing files.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

use reports::Run;
use reports::pdf::PdfError;
use testkit::{sample_results, write_sample_files};

/// typst lays a document out on every core, so two typesets at once only contend: this
/// file's tests took 42 s on two cores side by side and 34 s one after another.
static TYPESETTING: Mutex<()> = Mutex::new(());

/// [`reports::pdf::render_pdf`], one typeset at a time.
fn render_pdf(runs: &[Run]) -> Result<Vec<u8>, PdfError> {
    let _alone = TYPESETTING.lock().unwrap_or_else(|e| e.into_inner());
    reports::pdf::render_pdf(runs)
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-pdf-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn sample_run(dir: &Path, label: &str) -> Run {
    write_sample_files(dir).expect("sample files");
    Run {
        label: label.to_string(),
        results: sample_results(),
        base_dir: dir.to_path_buf(),
    }
}

/// Page objects: `/Type /Page` (or `/Type/Page`) not followed by `s`, counted in the
/// uncompressed object headers typst writes; falls back to `pdfinfo` when it sees none.
fn page_count(pdf: &[u8], path: &Path) -> usize {
    let mut count = 0;
    for pattern in [&b"/Type /Page"[..], &b"/Type/Page"[..]] {
        count += pdf
            .windows(pattern.len() + 1)
            .filter(|w| w.starts_with(pattern) && w[pattern.len()] != b's')
            .count();
    }
    if count > 0 {
        return count;
    }
    pdfinfo_pages(path).unwrap_or(0)
}

fn pdfinfo_pages(path: &Path) -> Option<usize> {
    let out = Command::new("pdfinfo").arg(path).output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout);
    text.lines()
        .find_map(|l| l.strip_prefix("Pages:"))
        .and_then(|n| n.trim().parse().ok())
}

/// The text of a PDF through `pdftotext`, when poppler is installed.
fn pdf_text(path: &Path) -> Option<String> {
    let out = Command::new("pdftotext")
        .args([path.as_os_str(), "-".as_ref()])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

#[test]
fn sample_renders_to_a_pdf_of_at_least_eight_pages() {
    let dir = temp_dir("sample");
    let run = sample_run(&dir, "bench-1");
    let pdf = render_pdf(&[run]).expect("render");
    assert!(pdf.starts_with(b"%PDF"), "not a PDF");
    let path = dir.join("report.pdf");
    std::fs::write(&path, &pdf).expect("write");
    if let Ok(out) = std::env::var("RTPROF_PDF_OUT") {
        std::fs::write(out, &pdf).expect("write RTPROF_PDF_OUT");
    }
    let pages = page_count(&pdf, &path);
    assert!(pages >= 8, "{pages} pages");
    if let Some(n) = pdfinfo_pages(&path) {
        assert_eq!(n, pages, "pdfinfo disagrees with the page objects");
    }
    if let Some(text) = pdf_text(&path) {
        for expected in [
            "rtprof report",
            "Findings beside the answers",
            "Flat profile",
            "Amdahl",
            "Table 7",
            "Table 8",
            "Device utilization",
            "How to reproduce",
            "rtprof suite --scenes ../shared/spd -o out/suite",
            "EP4CE115",
            "render exceeded the 60 s budget",
        ] {
            assert!(
                text.contains(expected),
                "missing from the PDF text: {expected}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn typst_syntax_in_user_text_is_only_text() {
    let dir = temp_dir("hostile");
    let mut run = sample_run(&dir, "host #1 *x*");
    let name = r#"#set text(red) *bold* $x$ "quote" back\slash _u_ @ref <lbl> [b] `t` // c /* d"#;
    run.results.scenes[0].name = name.to_string();
    // Variant names are checked names now; a failure's scene is still free text.
    run.results.failures[0].scene = Some("]#panic(\"no\")[".to_string());
    run.results.command = "rtprof suite --scenes \"dir with \\\"quotes\\\"\" #{1/0}".to_string();
    run.results.failures[0].message = "line one\nline two\t$$ #}".to_string();
    run.results.machine.cpu_model = "\u{0}\u{7}ctrl".to_string();
    if let Some(p) = &mut run.results.profile {
        p.baseline.flat[0].name = "<T as core::ops::Fn>::call#{}".to_string();
    }
    let pdf = render_pdf(&[run]).expect("render");
    assert!(pdf.starts_with(b"%PDF"));
    let path = dir.join("hostile.pdf");
    std::fs::write(&path, &pdf).expect("write");
    if let Some(text) = pdf_text(&path) {
        for piece in [
            "#set text(red) *bold* $x$",
            "\"quote\" back\\slash _u_ @ref <lbl> [b] `t` // c /* d",
            "]#panic(\"no\")[",
            "#{1/0}",
            "line two",
        ] {
            assert!(text.contains(piece), "missing from the PDF text: {piece}");
        }
        assert!(
            !text.contains("left out of this PDF"),
            "figures were dropped"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn missing_and_damaged_files_do_not_fail() {
    let dir = temp_dir("missing");
    let run = sample_run(&dir, "bench-1");
    // No images at all, one damaged PNG, one SVG typst cannot read, no texts.
    std::fs::remove_dir_all(dir.join("images")).expect("remove images");
    let first = run.results.scenes[0].variants[0]
        .image
        .clone()
        .expect("sample has an image");
    std::fs::create_dir_all(dir.join("images")).expect("mkdir");
    let mut damaged = b"\x89PNG\r\n\x1a\n".to_vec();
    damaged.extend_from_slice(b"not really a png");
    std::fs::write(dir.join(&first), damaged).expect("write");
    let p = run.results.profile.as_ref().expect("sample has a profile");
    std::fs::write(dir.join(&p.baseline.flame_svg), "<svg this is not xml").expect("write");
    std::fs::remove_file(dir.join(&p.baseline.callgraph_text)).expect("remove");
    let pdf = render_pdf(std::slice::from_ref(&run)).expect("render");
    assert!(pdf.starts_with(b"%PDF"));
    let path = dir.join("missing.pdf");
    std::fs::write(&path, &pdf).expect("write");
    assert!(page_count(&pdf, &path) >= 8);
    if let Some(text) = pdf_text(&path) {
        // Only the damaged files are left out, with a note; the charts stay.
        assert!(
            !text.contains("left out of this PDF"),
            "everything was left out"
        );
        assert!(
            text.contains("could not be typeset here"),
            "no note for the bad SVG"
        );
        assert!(text.contains("missing"), "no note for the missing images");
        assert!(
            text.contains("Calls per function"),
            "the charts went missing"
        );
    }

    // A base directory that does not exist at all.
    let nowhere = Run {
        base_dir: dir.join("does-not-exist"),
        ..run
    };
    let pdf = render_pdf(&[nowhere]).expect("render");
    assert!(pdf.starts_with(b"%PDF"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn several_runs_get_a_comparison() {
    let dir = temp_dir("compare");
    let a = sample_run(&dir, "bench-1");
    let mut b = sample_run(&dir, "bench-2");
    b.results.machine.hostname = "bench-2".to_string();
    // Every render 20 % slower, the yardsticks unchanged: baseline ÷ yardstick
    // grows 20 %.
    for scene in &mut b.results.scenes {
        for v in &mut scene.variants {
            v.time = v.time.scaled(1.2);
            for x in v.samples.iter_mut().chain(v.cpu_samples.iter_mut()) {
                *x *= 1.2;
            }
        }
    }
    let pdf = render_pdf(&[a, b]).expect("render");
    assert!(pdf.starts_with(b"%PDF"));
    let path = dir.join("compare.pdf");
    std::fs::write(&path, &pdf).expect("write");
    if let Ok(out) = std::env::var("RTPROF_PDF_COMPARE_OUT") {
        std::fs::write(out, &pdf).expect("write RTPROF_PDF_COMPARE_OUT");
    }
    if let Some(text) = pdf_text(&path) {
        assert!(text.contains("What changed between the runs"));
        assert!(text.contains("bench-2 vs bench-1"));
        assert!(text.contains("+20"), "baseline's change against the kernel");
        assert!(text.contains("slower"));
    }
    assert!(render_pdf(&[]).is_err());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Renders a real results file when asked to, for looking at the result:
/// `RTPROF_PDF_RESULTS=out/results.json RTPROF_PDF_OUT=/tmp/report.pdf cargo test -p reports --test pdf real_results -- --ignored`.
#[test]
#[ignore = "renders the results file RTPROF_PDF_RESULTS names, for looking at"]
fn real_results_when_given() {
    let path = std::env::var("RTPROF_PDF_RESULTS")
        .expect("set RTPROF_PDF_RESULTS to the results.json to render");
    let path = PathBuf::from(path);
    let text = std::fs::read_to_string(&path).expect("read results");
    let results = reports::results::Results::from_json(&text).expect("parse results");
    let run = Run {
        label: results.machine.hostname.clone(),
        results,
        base_dir: path.parent().expect("parent").to_path_buf(),
    };
    let pdf = render_pdf(&[run]).expect("render");
    assert!(pdf.starts_with(b"%PDF"));
    let out = std::env::var("RTPROF_PDF_OUT").unwrap_or_else(|_| "/tmp/rtprof-real.pdf".into());
    std::fs::write(out, &pdf).expect("write");
}

#[test]
fn an_empty_run_still_has_every_section() {
    let dir = temp_dir("empty");
    let mut results = sample_results();
    results.scenes.clear();
    results.profile = None;
    results.hardware = None;
    results.failures.clear();
    results.criterion.clear();
    results.instructions.clear();
    let run = Run {
        label: "empty".to_string(),
        results,
        base_dir: dir.clone(),
    };
    let pdf = render_pdf(&[run]).expect("render");
    let path = dir.join("empty.pdf");
    std::fs::write(&path, &pdf).expect("write");
    assert!(page_count(&pdf, &path) >= 8);
    if let Some(text) = pdf_text(&path) {
        assert!(text.contains("No profile in this run"));
        assert!(text.contains("No SPD scene ran"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
