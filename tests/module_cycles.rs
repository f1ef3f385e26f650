//! No circle of imports between the files of one crate (docs/architecture.md). Each
//! `.rs` file of every workspace crate is parsed (syn), and each path it names inside
//! its crate — `use` trees and paths in code, through `crate::`, `super::`, `self::`
//! or a child module — becomes an edge to the file that defines the item's module.
//! A path through a re-export (`pub use child::Item` in a `lib.rs` or `mod.rs`) is
//! followed to the file that defines the item, so a facade does not hide a circle, and
//! re-exports themselves are plumbing, not imports. A file naming an item of its parent
//! module (or an ancestor) is not an edge: in Rust a module's own items are its
//! children's namespace (`super::Port`), the owner of what they share; circles between
//! siblings, or between unrelated files, are what this catches. Test code
//! (`#[cfg(test)]`) is left out. A circle means an item sits in the wrong file: the test names the files and the
//! edges that close it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use syn::visit::Visit;

/// A module path inside a crate: `[]` is the crate root, `["accel", "bvh"]` is
/// `accel/bvh.rs` (or `accel/bvh/mod.rs`).
type ModulePath = Vec<String>;

/// One crate's files: module path → (file, parsed items without test code).
struct CrateFiles {
    files: BTreeMap<ModulePath, (PathBuf, syn::File)>,
}

/// The module a file defines, from its path under `src/`.
fn module_of(relative: &Path) -> ModulePath {
    let mut parts: Vec<String> = relative
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("lib" | "main" | "mod")
    ) {
        parts.pop();
    }
    parts
}

fn is_cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.parse_args::<syn::Meta>()
                .is_ok_and(|m| m.path().is_ident("test"))
    })
}

/// Strips test code from `file`, returning the names of the test-only child modules it
/// declares (`#[cfg(test)] mod tests;`), whose files are test code too.
fn strip_tests(file: &mut syn::File) -> Vec<String> {
    let test_children = file
        .items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Mod(m) if is_cfg_test(&m.attrs) && m.content.is_none() => {
                Some(m.ident.to_string())
            }
            _ => None,
        })
        .collect();
    file.items.retain(|item| match item {
        syn::Item::Mod(m) => !is_cfg_test(&m.attrs),
        syn::Item::Fn(f) => !is_cfg_test(&f.attrs),
        syn::Item::Use(u) => !is_cfg_test(&u.attrs),
        _ => true,
    });
    test_children
}

impl CrateFiles {
    fn read(src: &Path) -> CrateFiles {
        let mut files = BTreeMap::new();
        let mut test_modules = BTreeSet::new();
        let mut stack = vec![src.to_path_buf()];
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).expect("read a source directory") {
                let path = entry.expect("a directory entry").path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    let text = std::fs::read_to_string(&path).expect("read a source file");
                    let mut parsed = syn::parse_file(&text)
                        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                    let relative = path.strip_prefix(src).expect("under src").to_path_buf();
                    let module = module_of(&relative);
                    for child in strip_tests(&mut parsed) {
                        let mut child_module = module.clone();
                        child_module.push(child);
                        test_modules.insert(child_module);
                    }
                    files.insert(module, (relative, parsed));
                }
            }
        }
        files.retain(|module, _| !test_modules.contains(module));
        CrateFiles { files }
    }

    /// The file module that holds `path` (the longest module prefix that is a file).
    fn file_module(&self, path: &[String]) -> ModulePath {
        (0..=path.len())
            .rev()
            .map(|n| path[..n].to_vec())
            .find(|prefix| self.files.contains_key(prefix))
            .unwrap_or_default()
    }
}

/// Every path a `use` tree names, with its prefix, as segments, and the name it
/// binds in the file (`None` for a glob).
fn use_paths(
    tree: &syn::UseTree,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Option<String>, Vec<String>)>,
) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            use_paths(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let mut path = prefix.clone();
            if n.ident != "self" {
                path.push(n.ident.to_string());
            }
            out.push((path.last().cloned(), path));
        }
        syn::UseTree::Rename(r) => {
            let mut path = prefix.clone();
            if r.ident != "self" {
                path.push(r.ident.to_string());
            }
            out.push((Some(r.rename.to_string()), path));
        }
        syn::UseTree::Glob(_) => out.push((None, prefix.clone())),
        syn::UseTree::Group(g) => g.items.iter().for_each(|t| use_paths(t, prefix, out)),
    }
}

/// The paths a file names: in `use` items (public ones are re-exports, kept apart)
/// and in code.
#[derive(Default)]
struct Names {
    imports: Vec<Vec<String>>,
    reexports: Vec<(String, Vec<String>)>,
    /// Names the file's private `use` items bind, and the paths they stand for: code
    /// that writes `document::build(…)` after `use crate::document::{self, …}` names
    /// `crate::document::build`.
    aliases: BTreeMap<String, Vec<String>>,
    /// Paths in code, resolved through `aliases` once the file is read.
    code: Vec<Vec<String>>,
}

impl Names {
    /// The paths the file names: its imports, and its code's paths with a first
    /// segment that a `use` bound replaced by what it stands for.
    fn all_imports(&self) -> Vec<Vec<String>> {
        let mut out = self.imports.clone();
        for path in &self.code {
            match path.first().and_then(|first| self.aliases.get(first)) {
                Some(target) if path.len() > 1 => {
                    out.push(target.iter().chain(&path[1..]).cloned().collect());
                }
                _ => out.push(path.clone()),
            }
        }
        out
    }
}

impl<'a> Visit<'a> for Names {
    fn visit_item_use(&mut self, item: &'a syn::ItemUse) {
        let mut paths = Vec::new();
        use_paths(&item.tree, &mut Vec::new(), &mut paths);
        if matches!(item.vis, syn::Visibility::Inherited) {
            for (name, path) in paths {
                if let Some(name) = name {
                    self.aliases.insert(name, path.clone());
                }
                self.imports.push(path);
            }
        } else {
            for (_, path) in paths {
                if let Some(name) = path.last() {
                    self.reexports.push((name.clone(), path.clone()));
                }
            }
        }
    }

    fn visit_path(&mut self, path: &'a syn::Path) {
        self.code
            .push(path.segments.iter().map(|s| s.ident.to_string()).collect());
        syn::visit::visit_path(self, path);
    }

    // `pub(super)` and `pub(in crate::x)` name who may see an item, not what it uses.
    fn visit_visibility(&mut self, _: &'a syn::Visibility) {}

    fn visit_item_mod(&mut self, item: &'a syn::ItemMod) {
        if !is_cfg_test(&item.attrs) {
            syn::visit::visit_item_mod(self, item);
        }
    }
}

/// `path` as written in module `at`, made absolute in the crate; `None` when it
/// leaves the crate (another crate, std, a local name).
fn absolute(at: &ModulePath, path: &[String], crate_files: &CrateFiles) -> Option<Vec<String>> {
    let first = path.first()?;
    match first.as_str() {
        "crate" => Some(path[1..].to_vec()),
        "self" => Some(at.iter().chain(&path[1..]).cloned().collect()),
        "super" => {
            let mut base = at.clone();
            let mut rest = path;
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
            Some(base.into_iter().chain(rest.iter().cloned()).collect())
        }
        // A child module named directly (`mod child; use child::Item;`).
        name => {
            let mut child = at.clone();
            child.push(name.to_string());
            crate_files
                .files
                .contains_key(&child)
                .then(|| at.iter().chain(path).cloned().collect())
        }
    }
}

/// The file-level import graph of one crate.
fn graph(crate_files: &CrateFiles) -> BTreeMap<ModulePath, BTreeSet<ModulePath>> {
    let names: BTreeMap<&ModulePath, Names> = crate_files
        .files
        .iter()
        .map(|(module, (_, file))| {
            let mut names = Names::default();
            names.visit_file(file);
            (module, names)
        })
        .collect();
    // (file module, item name) → the absolute path it re-exports.
    let mut reexports: BTreeMap<(ModulePath, String), Vec<String>> = BTreeMap::new();
    for (module, n) in &names {
        for (name, path) in &n.reexports {
            if let Some(target) = absolute(module, path, crate_files) {
                reexports.insert(((*module).clone(), name.clone()), target);
            }
        }
    }
    // The file that defines what `path` names, through re-exports.
    let resolve = |mut path: Vec<String>| -> ModulePath {
        for _ in 0..8 {
            let file = crate_files.file_module(&path);
            let Some(next) = path.get(file.len()) else {
                return file;
            };
            match reexports.get(&(file.clone(), next.clone())) {
                Some(target) if *target != path[..=file.len()] => {
                    let mut followed = target.clone();
                    followed.extend_from_slice(&path[file.len() + 1..]);
                    path = followed;
                }
                _ => return file,
            }
        }
        crate_files.file_module(&path)
    };
    let mut edges = BTreeMap::new();
    for (module, n) in &names {
        // A module's own items are its children's namespace: a child naming its parent's
        // (or an ancestor's) item is not an import that can close a circle.
        let targets: BTreeSet<ModulePath> = n
            .all_imports()
            .iter()
            .filter_map(|p| absolute(module, p, crate_files))
            .map(&resolve)
            .filter(|t| t != *module && !module.starts_with(t))
            .collect();
        edges.insert((*module).clone(), targets);
    }
    edges
}

/// The strongly connected components of more than one file (Tarjan's algorithm).
fn circles(edges: &BTreeMap<ModulePath, BTreeSet<ModulePath>>) -> Vec<Vec<ModulePath>> {
    struct State<'a> {
        edges: &'a BTreeMap<ModulePath, BTreeSet<ModulePath>>,
        index: BTreeMap<&'a ModulePath, usize>,
        low: BTreeMap<&'a ModulePath, usize>,
        stack: Vec<&'a ModulePath>,
        found: Vec<Vec<ModulePath>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a ModulePath) {
        let i = s.index.len();
        s.index.insert(v, i);
        s.low.insert(v, i);
        s.stack.push(v);
        for w in s.edges.get(v).into_iter().flatten() {
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[w].min(s.low[v]);
                s.low.insert(v, low);
            } else if s.stack.contains(&w) {
                let low = s.index[w].min(s.low[v]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.found.push(component);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.found
}

/// Each circle of a crate, one line per file and the edges inside the circle.
fn describe(crate_files: &CrateFiles) -> Vec<String> {
    let edges = graph(crate_files);
    let name = |m: &ModulePath| crate_files.files[m].0.display().to_string();
    circles(&edges)
        .iter()
        .map(|component| {
            let inside: Vec<String> = component
                .iter()
                .flat_map(|a| {
                    edges[a]
                        .iter()
                        .filter(|b| component.contains(b))
                        .map(move |b| format!("{} -> {}", name(a), name(b)))
                })
                .collect();
            inside.join(", ")
        })
        .collect()
}

fn workspace_crates() -> Vec<(String, PathBuf)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let manifest: toml::Table = std::fs::read_to_string(root.join("Cargo.toml"))
        .expect("root Cargo.toml")
        .parse()
        .expect("root Cargo.toml parses");
    let mut crates = vec![("rtprof".to_string(), root.join("src"))];
    for member in manifest["workspace"]["members"]
        .as_array()
        .expect("members")
    {
        let dir = member.as_str().expect("a member path");
        crates.push((dir.to_string(), root.join(dir).join("src")));
    }
    crates
}

#[test]
fn no_crate_has_a_circle_of_imports_between_its_files() {
    let mut broken = Vec::new();
    let mut files = 0;
    for (name, src) in workspace_crates() {
        let crate_files = CrateFiles::read(&src);
        files += crate_files.files.len();
        broken.extend(
            describe(&crate_files)
                .into_iter()
                .map(|c| format!("{name}: {c}")),
        );
    }
    assert!(files > 300, "only {files} files read");
    assert!(
        broken.is_empty(),
        "circles of imports (move the item that closes each into the file that owns it):\n  {}",
        broken.join("\n  ")
    );
}

/// A crate written in a temporary directory, for the checker's own tests.
fn temp_crate(files: &[(&str, &str)]) -> CrateFiles {
    let dir = std::env::temp_dir().join(format!(
        "rtprof-cycles-{}-{}",
        std::process::id(),
        files.len()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("mkdir");
        std::fs::write(&path, text).expect("write");
    }
    let read = CrateFiles::read(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    read
}

#[test]
fn the_checker_finds_a_circle_through_a_re_export_and_ignores_test_code() {
    // b uses a's item through the crate root's re-export; a uses b's directly.
    let circle = temp_crate(&[
        ("lib.rs", "mod a; mod b; pub use a::Alpha;"),
        (
            "a.rs",
            "pub struct Alpha; fn f() -> crate::b::Beta { crate::b::Beta }",
        ),
        ("b.rs", "pub struct Beta; fn g(_: crate::Alpha) {}"),
    ]);
    assert_eq!(describe(&circle), vec!["a.rs -> b.rs, b.rs -> a.rs"]);
    // The same edge back, but only in a test module: no circle.
    let tested = temp_crate(&[
        ("lib.rs", "mod a; mod b; pub use a::Alpha;"),
        (
            "a.rs",
            "pub struct Alpha; use super::b::Beta; fn f(_: Beta) {}",
        ),
        (
            "b.rs",
            "pub struct Beta;\n#[cfg(test)]\nmod tests { use crate::Alpha; }",
        ),
    ]);
    assert_eq!(describe(&tested), Vec::<String>::new());
    // A parent and the child it declares, each using the other's item: the parent's
    // items are the child's namespace, no circle. Two siblings that do: a circle, even
    // when one reaches the other through the parent's re-export.
    let family = temp_crate(&[
        ("lib.rs", "mod m;"),
        ("m/mod.rs", "mod child; pub struct P; fn f(_: child::C) {}"),
        ("m/child.rs", "pub struct C; fn g(_: super::P) {}"),
    ]);
    assert_eq!(describe(&family), Vec::<String>::new());
    let siblings = temp_crate(&[
        ("lib.rs", "mod m;"),
        ("m/mod.rs", "mod a; mod b; pub use b::B;"),
        ("m/a.rs", "pub struct A; fn f(_: super::B) {}"),
        ("m/b.rs", "pub struct B; fn g(_: super::a::A) {}"),
    ]);
    assert_eq!(
        describe(&siblings),
        vec!["m/a.rs -> m/b.rs, m/b.rs -> m/a.rs"]
    );
    // A module imported by name and called through it (`use crate::b::{self};
    // b::g()`, `use crate::b as other; other::g()`): the call is the edge.
    for a in [
        "use crate::b::{self}; pub fn f() { b::g() }",
        "use crate::b as other; pub fn f() { other::g() }",
        "use crate::b::{self as other}; pub fn f() { other::g() }",
    ] {
        let called = temp_crate(&[
            ("lib.rs", "mod a; mod b;"),
            ("a.rs", a),
            ("b.rs", "pub fn g() { crate::a::f(); }"),
        ]);
        assert_eq!(describe(&called), vec!["a.rs -> b.rs, b.rs -> a.rs"], "{a}");
    }
    // The call alone, with no edge back: no circle.
    let one_way = temp_crate(&[
        ("lib.rs", "mod a; mod b;"),
        ("a.rs", "use crate::b::{self}; pub fn f() { b::g() }"),
        ("b.rs", "pub fn g() {}"),
    ]);
    assert_eq!(describe(&one_way), Vec::<String>::new());
}
