//! The architecture's invariants (docs/architecture.md), checked against the
//! workspace's Cargo.toml files: which crate may depend on which, every dependency
//! declared once in the root's `[workspace.dependencies]`, and the counters declared
//! only in the counter table. A crate edge that breaks a rule fails here, naming the
//! rule.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One workspace crate's dependencies on other workspace crates.
#[derive(Default, Debug)]
struct Crate {
    /// `[dependencies]`, `[build-dependencies]` and their `[target.*]` forms.
    normal: BTreeSet<String>,
    /// `[dev-dependencies]` (and `[target.*.dev-dependencies]`).
    dev: BTreeSet<String>,
}

type Graph = BTreeMap<String, Crate>;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read_toml(path: &Path) -> toml::Table {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The manifests of the workspace: the root package's and every member's, by package
/// name.
fn manifests() -> BTreeMap<String, toml::Table> {
    let root_manifest = read_toml(&root().join("Cargo.toml"));
    let members = root_manifest["workspace"]["members"]
        .as_array()
        .expect("[workspace] members")
        .iter()
        .map(|m| m.as_str().expect("a member path").to_string());
    let mut all = BTreeMap::new();
    for dir in members {
        let manifest = read_toml(&root().join(&dir).join("Cargo.toml"));
        let name = manifest["package"]["name"]
            .as_str()
            .expect("[package] name");
        all.insert(name.to_string(), manifest);
    }
    let name = root_manifest["package"]["name"]
        .as_str()
        .expect("[package] name");
    all.insert(name.to_string(), root_manifest);
    all
}

/// The dependency tables of a manifest: `(is dev, name, declaration)`.
fn dependency_entries(manifest: &toml::Table) -> Vec<(bool, String, toml::Value)> {
    let mut scopes = vec![manifest];
    if let Some(targets) = manifest.get("target").and_then(toml::Value::as_table) {
        scopes.extend(targets.values().filter_map(toml::Value::as_table));
    }
    let mut tables: Vec<(bool, &toml::Table)> = Vec::new();
    for scope in scopes {
        for (key, dev) in [
            ("dependencies", false),
            ("build-dependencies", false),
            ("dev-dependencies", true),
        ] {
            if let Some(table) = scope.get(key).and_then(toml::Value::as_table) {
                tables.push((dev, table));
            }
        }
    }
    let mut entries = Vec::new();
    for (dev, table) in tables {
        for (name, value) in table {
            // `package = "..."` renames: the crate is the package named.
            let package = value
                .get("package")
                .and_then(toml::Value::as_str)
                .unwrap_or(name);
            entries.push((dev, package.to_string(), value.clone()));
        }
    }
    entries
}

/// The workspace's crate graph (edges between workspace crates only).
fn workspace_graph(manifests: &BTreeMap<String, toml::Table>) -> Graph {
    let names: BTreeSet<&String> = manifests.keys().collect();
    manifests
        .iter()
        .map(|(name, manifest)| {
            let mut c = Crate::default();
            for (dev, dep, _) in dependency_entries(manifest) {
                if names.contains(&dep) {
                    if dev { &mut c.dev } else { &mut c.normal }.insert(dep);
                }
            }
            (name.clone(), c)
        })
        .collect()
}

/// Every crate `name` reaches through normal dependencies.
fn reaches(graph: &Graph, name: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut pending = vec![name.to_string()];
    while let Some(next) = pending.pop() {
        for dep in graph.get(&next).map(|c| &c.normal).into_iter().flatten() {
            if seen.insert(dep.clone()) {
                pending.push(dep.clone());
            }
        }
    }
    seen
}

/// The rules of docs/architecture.md a crate graph breaks, one line each.
fn violations(graph: &Graph) -> Vec<String> {
    let mut out = Vec::new();
    let mut forbid = |from: &str, to: &str, rule: &str| {
        if graph.get(from).is_some_and(|c| c.normal.contains(to)) {
            out.push(format!("{from} depends on {to}: {rule}"));
        }
    };
    // The base crate stands alone: everything else builds on it.
    for other in graph.keys() {
        forbid("tracer", other, "tracer depends on no workspace crate");
    }
    // Reports read results: they never render a scene nor run the suite.
    for renderer in ["tracer", "spd", "reference", "rtl", "runner", "serve"] {
        forbid(
            "reports",
            renderer,
            "reports read results and never render (nor run the suite)",
        );
    }
    // The callers sit on top: the binary and serve call runner and reports.
    for library in graph.keys().filter(|n| *n != "rtprof") {
        forbid(
            library,
            "rtprof",
            "nothing depends on the binary: it calls the libraries",
        );
    }
    for library in graph
        .keys()
        .filter(|n| !["rtprof", "serve"].contains(&n.as_str()))
    {
        forbid(
            library,
            "serve",
            "only the binary calls serve; runner and reports never call their callers",
        );
    }
    // analysis measures plain data: not even through another crate does it reach the tracer.
    if reaches(graph, "analysis").contains("tracer") {
        out.push(
            "analysis reaches tracer: analysis depends on no renderer, directly or not".into(),
        );
    }
    // Running other programs is launch's job; the renderer and the measurements stay free
    // of processes, not even through another crate.
    for pure in ["tracer", "analysis"] {
        if reaches(graph, pure).contains("launch") {
            out.push(format!(
                "{pure} reaches launch: running other programs is launch's job, {pure} stays free of it"
            ));
        }
    }
    if graph.get("tracer").is_some_and(|c| !c.dev.is_empty()) {
        out.push(
            "tracer has workspace dev-dependencies: tracer depends on no workspace crate".into(),
        );
    }
    // Test fixtures stay out of library code.
    for (name, c) in graph {
        if c.normal.contains("testkit") {
            out.push(format!(
                "{name} depends on testkit: test fixtures are dev-dependencies only"
            ));
        }
    }
    out
}

/// A graph from `(crate, normal dependencies)` pairs, for the rules' own tests.
fn graph_of(edges: &[(&str, &[&str])]) -> Graph {
    edges
        .iter()
        .map(|(name, deps)| {
            let c = Crate {
                normal: deps.iter().map(|d| d.to_string()).collect(),
                dev: BTreeSet::new(),
            };
            (name.to_string(), c)
        })
        .collect()
}

/// The layering as docs/architecture.md draws it.
const LAYERS: &[(&str, &[&str])] = &[
    ("tracer", &[]),
    ("launch", &[]),
    ("analysis", &[]),
    ("spd", &["tracer"]),
    ("reference", &["tracer"]),
    ("hwmodel", &["tracer"]),
    ("results", &["tracer", "analysis", "hwmodel"]),
    ("rtl", &["hwmodel", "tracer", "results"]),
    ("reports", &["results", "hwmodel", "analysis"]),
    (
        "runner",
        &[
            "spd",
            "tracer",
            "reference",
            "analysis",
            "hwmodel",
            "rtl",
            "results",
            "reports",
            "launch",
        ],
    ),
    (
        "serve",
        &["runner", "reports", "results", "tracer", "spd", "analysis"],
    ),
    ("terminal", &["runner", "reports", "tracer"]),
    (
        "rtprof",
        &[
            "runner", "reports", "serve", "terminal", "hwmodel", "results", "analysis", "tracer",
        ],
    ),
];

#[test]
fn the_workspace_keeps_the_architecture_invariants() {
    let graph = workspace_graph(&manifests());
    // The test reads what it means to: every member, with the edges it knows exist.
    for name in [
        "tracer", "analysis", "results", "runner", "reports", "serve", "rtprof", "launch",
    ] {
        assert!(
            graph.contains_key(name),
            "{name} is not a workspace crate: {graph:?}"
        );
    }
    assert!(graph["runner"].normal.contains("reports"), "{graph:?}");
    assert!(graph["runner"].normal.contains("launch"), "{graph:?}");
    let broken = violations(&graph);
    assert!(
        broken.is_empty(),
        "the crate graph breaks docs/architecture.md:\n  {}",
        broken.join("\n  ")
    );
}

#[test]
fn the_drawn_layering_keeps_the_invariants() {
    assert_eq!(violations(&graph_of(LAYERS)), Vec::<String>::new());
}

#[test]
fn each_forbidden_edge_is_named_with_its_rule() {
    let with = |from: &str, to: &'static str| {
        let mut edges: Vec<(&str, Vec<&str>)> =
            LAYERS.iter().map(|(n, d)| (*n, d.to_vec())).collect();
        if let Some((_, deps)) = edges.iter_mut().find(|(n, _)| *n == from) {
            deps.push(to);
        }
        let edges: Vec<(&str, &[&str])> = edges.iter().map(|(n, d)| (*n, d.as_slice())).collect();
        violations(&graph_of(&edges))
    };
    assert_eq!(
        with("tracer", "analysis"),
        ["tracer depends on analysis: tracer depends on no workspace crate"]
    );
    assert_eq!(
        with("analysis", "tracer"),
        ["analysis reaches tracer: analysis depends on no renderer, directly or not"]
    );
    // Through another crate: analysis -> hwmodel -> tracer.
    assert_eq!(
        with("analysis", "hwmodel"),
        ["analysis reaches tracer: analysis depends on no renderer, directly or not"]
    );
    assert_eq!(
        with("reports", "runner"),
        ["reports depends on runner: reports read results and never render (nor run the suite)"]
    );
    assert_eq!(
        with("runner", "serve"),
        [
            "runner depends on serve: only the binary calls serve; runner and reports never call their callers"
        ]
    );
    assert_eq!(
        with("serve", "rtprof"),
        ["serve depends on rtprof: nothing depends on the binary: it calls the libraries"]
    );
    assert_eq!(
        with("analysis", "launch"),
        [
            "analysis reaches launch: running other programs is launch's job, analysis stays free of it"
        ]
    );
    assert_eq!(
        with("results", "testkit"),
        ["results depends on testkit: test fixtures are dev-dependencies only"]
    );
}

#[test]
fn every_dependency_is_declared_in_the_workspace() {
    let root_manifest = read_toml(&root().join("Cargo.toml"));
    let declared = root_manifest["workspace"]["dependencies"]
        .as_table()
        .expect("[workspace.dependencies]");
    let mut loose = Vec::new();
    for (name, manifest) in manifests() {
        for (_, dep, value) in dependency_entries(&manifest) {
            let inherited = value
                .get("workspace")
                .and_then(toml::Value::as_bool)
                .unwrap_or(false);
            if !inherited || !declared.contains_key(&dep) {
                loose.push(format!("{name}: {dep} = {value}"));
            }
        }
    }
    assert!(
        loose.is_empty(),
        "dependencies are declared once, in the root's [workspace.dependencies], and \
         inherited with `workspace = true`:\n  {}",
        loose.join("\n  ")
    );
}

/// The Rust sources of the workspace's crates (not `target/`, not the fuzz workspace).
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if !["target", "fuzz", ".git", "node_modules"].contains(&name.as_ref())
                && !name.starts_with('.')
            {
                sources(&path, out);
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}

#[test]
fn counters_are_declared_only_in_the_counter_table() {
    let table = root().join("tracer/src/counter/table.rs");
    let mut files = Vec::new();
    sources(&root(), &mut files);
    assert!(files.contains(&table), "no {}", table.display());
    let invocation = concat!("counter_table", "! {");
    let declaring: Vec<String> = files
        .iter()
        .filter(|f| std::fs::read_to_string(f).is_ok_and(|text| text.contains(invocation)))
        .map(|f| f.strip_prefix(root()).unwrap_or(f).display().to_string())
        .collect();
    assert_eq!(declaring, ["tracer/src/counter/table.rs"]);
}

/// The binary's share of the code (docs/architecture.md): it only parses and prints.
const BINARY_LINES: usize = 1_200;

#[test]
fn the_binary_stays_thin() {
    let mut files = Vec::new();
    sources(&root().join("src"), &mut files);
    let lines: usize = files
        .iter()
        .map(|f| {
            std::fs::read_to_string(f)
                .unwrap_or_else(|e| panic!("{}: {e}", f.display()))
                .lines()
                .count()
        })
        .sum();
    assert!(
        files.len() > 3 && lines <= BINARY_LINES,
        "src/ has {lines} lines in {} files (at most {BINARY_LINES}): move logic into a library crate",
        files.len()
    );
}
