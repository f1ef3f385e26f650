//! gprof2dot (`-f prof`, PyPI), the usual reader of gprof's text, reads rtprof's call
//! graphs as it reads real gprof's: `rtprof profile`'s two views, and as the control
//! gprof's own output of a `-pg` build (analysis/tests/data/gprof/loops.c) with
//! rtprof's reprint of it. Each run must exit 0 with nothing on stderr (gprof2dot
//! warns there about lines it cannot read and about times that do not add up), and
//! the dot graph must have a node for every function and an edge for every call the
//! text lists. Ignored without gprof2dot (and gcc and gprof for the control):
//! `scripts/install-gprof2dot.sh` installs them, `.ci/run` runs these.

use analysis::profile::gprof_text::{ParsedEntry, parse_call_graph_text};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A scratch directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rtprof-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// gprof2dot's graph: node names with their total share, and edges by name with
/// their labels.
#[derive(Debug, PartialEq)]
struct Dot {
    /// Name -> total percent (the first figure of the node's label).
    nodes: BTreeMap<String, f64>,
    /// (caller, callee) -> the edge's label (`share%\ncount×`).
    edges: BTreeMap<(String, String), String>,
}

/// The quoted `label="…"` value of a dot line, unescaped.
fn label_of(line: &str) -> Option<String> {
    let start = line.find("label=\"")? + "label=\"".len();
    let mut label = String::new();
    let mut chars = line[start..].chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return Some(label),
            '\\' => match chars.next()? {
                'n' => label.push('\n'),
                other => label.push(other),
            },
            c => label.push(c),
        }
    }
    None
}

fn read_dot(dot: &str) -> Dot {
    let mut names = BTreeMap::new();
    let mut shares = BTreeMap::new();
    let mut edge_lines = Vec::new();
    for line in dot.lines().map(str::trim) {
        let Some(id) = line.split_whitespace().next() else {
            continue;
        };
        if !id.bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        let label = label_of(line).unwrap_or_else(|| panic!("no label in {line:?}"));
        if let Some((_, rest)) = line.split_once(" -> ") {
            let callee = rest.split_whitespace().next().unwrap().to_owned();
            edge_lines.push((id.to_owned(), callee, label));
        } else {
            let mut parts = label.split('\n');
            let name = parts.next().unwrap().to_owned();
            let share: f64 = parts
                .next()
                .and_then(|p| p.strip_suffix('%'))
                .and_then(|p| p.parse().ok())
                .unwrap_or_else(|| panic!("no share in {label:?}"));
            shares.insert(name.clone(), share);
            names.insert(id.to_owned(), name);
        }
    }
    let edges = edge_lines
        .into_iter()
        .map(|(from, to, label)| ((names[&from].clone(), names[&to].clone()), label))
        .collect();
    Dot {
        nodes: shares,
        edges,
    }
}

/// Runs `python3 -m gprof2dot -f prof` on `text` (all nodes and edges kept) and
/// returns its graph; fails unless it exits 0 with an empty stderr.
fn gprof2dot(text: &str, dir: &Path, name: &str) -> Dot {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let out = Command::new("python3")
        .args([
            "-m",
            "gprof2dot",
            "-f",
            "prof",
            "--node-thres=0",
            "--edge-thres=0",
        ])
        .arg(&path)
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 -m gprof2dot: {e}"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && stderr.is_empty(),
        "gprof2dot on {name}: {}\nstderr:\n{stderr}\ntext:\n{text}",
        out.status
    );
    read_dot(&String::from_utf8(out.stdout).unwrap())
}

/// The functions and calls a call graph text lists (cycles as a whole left out).
fn listed(entries: &[ParsedEntry]) -> (BTreeSet<String>, BTreeSet<(String, String)>) {
    let functions = entries
        .iter()
        .filter(|e| !e.name.starts_with("<cycle "))
        .map(|e| e.name.clone())
        .collect();
    let calls = entries
        .iter()
        .filter(|e| !e.name.starts_with("<cycle "))
        .flat_map(|e| e.children.iter().map(|c| (e.name.clone(), c.name.clone())))
        .collect();
    (functions, calls)
}

#[test]
#[ignore = "needs gprof2dot (scripts/install-gprof2dot.sh)"]
fn gprof2dot_reads_rtprofs_call_graphs() {
    let dir = Scratch::new("gprof2dot-rtprof");
    let out_dir = dir.0.join("prof");
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args([
            "profile",
            "spd:balls:1",
            "--size",
            "32x24",
            "--threads",
            "1",
        ])
        // 2,000 samples: the texts' seconds have two decimals, so a small total makes
        // coarse shares.
        .args(["--min-samples", "2000", "-o"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for (file, expected_functions, expected_calls) in [
        (
            "callgraph-baseline.txt",
            &[
                "sample row",
                "shading",
                "shadow query",
                "sphere test",
                "polygon test",
            ][..],
            &[("shadow query", "sphere test"), ("sample row", "shading")][..],
        ),
        (
            "callgraph-baseline-native.txt",
            &["render::render_into"][..],
            &[][..],
        ),
    ] {
        let text = std::fs::read_to_string(out_dir.join(file)).unwrap();
        let entries = parse_call_graph_text(&text).unwrap_or_else(|e| panic!("{file}: {e}"));
        let dot = gprof2dot(&text, &dir.0, file);
        // The flat profile in front, as gprof prints both: the same graph.
        let flat =
            std::fs::read_to_string(out_dir.join(file.replace("callgraph", "flat"))).unwrap();
        let both = format!("{flat}\x0c\n{text}");
        assert_eq!(gprof2dot(&both, &dir.0, "both.txt"), dot, "{file}");
        // A node for every function, an edge for every call the text lists.
        let (functions, calls) = listed(&entries);
        let nodes: BTreeSet<String> = dot.nodes.keys().cloned().collect();
        assert_eq!(nodes, functions, "{file}");
        let edges: BTreeSet<(String, String)> = dot.edges.keys().cloned().collect();
        assert_eq!(edges, calls, "{file}");
        for name in expected_functions {
            assert!(dot.nodes.contains_key(*name), "{file}: no node {name}");
        }
        for (caller, callee) in expected_calls {
            let key = (caller.to_string(), callee.to_string());
            assert!(dot.edges.contains_key(&key), "{file}: no edge {key:?}");
        }
        // gprof2dot splits a callee's time among its callers by the counts of their
        // lines: with samples there, no function holds more than the whole run, and a
        // root holds what rtprof says (up to the texts' rounding to 0.01 s). With
        // "no count" (0/0) every caller would get each callee's whole time.
        for (name, share) in &dot.nodes {
            assert!(*share <= 100.5, "{file}: {name} at {share} %");
        }
        let root = entries
            .iter()
            .filter(|e| e.parents.iter().any(|p| p.name == "<spontaneous>"))
            .filter(|e| !e.children.is_empty())
            .max_by(|a, b| a.percent.total_cmp(&b.percent))
            .unwrap();
        let drawn = dot.nodes[&root.name];
        assert!(
            (drawn - root.percent).abs() < 10.0,
            "{file}: {} drawn at {drawn} %, {} % in the text",
            root.name,
            root.percent
        );
    }
}

#[test]
#[ignore = "needs gcc, gprof and gprof2dot (scripts/install-gprof2dot.sh)"]
fn gprof2dot_reads_real_gprof_and_rtprofs_reprint_alike() {
    let dir = Scratch::new("gprof2dot-gprof");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("analysis/tests/data/gprof/loops.c");
    let binary = dir.0.join("loops");
    let run = |command: &mut Command| {
        let out = command.output().unwrap();
        assert!(
            out.status.success(),
            "{command:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    run(Command::new("gcc")
        .args(["-pg", "-O1", "-o"])
        .arg(&binary)
        .arg(&source));
    run(Command::new(&binary).current_dir(&dir.0));
    let gprof = run(Command::new("gprof")
        .arg("-b")
        .arg(&binary)
        .arg(dir.0.join("gmon.out")));

    let dot = gprof2dot(&gprof, &dir.0, "gprof.txt");
    let names: BTreeSet<&str> = dot.nodes.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        BTreeSet::from(["main", "f", "g", "even", "odd", "fact"])
    );
    // loops.c's calls, on the edges as gprof counted them.
    let label = |caller: &str, callee: &str| {
        dot.edges
            .get(&(caller.to_owned(), callee.to_owned()))
            .unwrap_or_else(|| panic!("no edge {caller} -> {callee}: {dot:?}"))
            .clone()
    };
    assert!(label("main", "f").ends_with("\n1000×"));
    assert!(label("f", "g").ends_with("\n3000×"));
    assert!(label("main", "even").ends_with("\n100×"));
    assert!(label("even", "odd").ends_with("500×"));
    assert!(label("main", "fact").ends_with("100×"));
    assert_eq!(dot.edges.len(), 7, "{dot:?}"); // and odd -> even, fact -> fact

    // rtprof's text of the imported graph draws the same graph.
    let imported = analysis::profile::gprof_import::parse(&gprof).unwrap();
    let reprint = imported.call_graph.unwrap().to_text();
    assert_eq!(gprof2dot(&reprint, &dir.0, "reprint.txt"), dot);
}
