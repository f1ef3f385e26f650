//! Addresses to function names, inlined functions as themselves: the DWARF of the file
//! that was mapped (addr2line: each inlined call is a frame of its own), else its
//! symbol table (`.symtab`, or `.dynsym` when stripped), else no symbol. C++ names are
//! demangled without their parameter lists, Rust names cleaned into plain paths
//! ([`clean_symbol`]), as the reports print them.
//!
//! The file is the one at the path perf recorded, when it is the build that was
//! recorded (its build id is the one the recording lists, or either has none); else
//! perf's copy by build id in its cache (`~/.debug/.build-id/`, which `perf record`
//! fills and `perf archive` packs for another machine). A file found in neither, or
//! only as another build, names nothing ([`MissingFile`]): its samples count as
//! without a symbol.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use addr2line::gimli;
use object::{Object, ObjectSegment};

use crate::profile::names::clean_symbol;

/// What one address resolved to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Resolved {
    /// Function names, the outer function first and the innermost inlined call last;
    /// one name when nothing was inlined there, or `[unknown in MODULE]`.
    pub frames: Vec<String>,
    /// The source file of each frame's code, where the debug info says (the phase
    /// rules' `file` patterns read it), in the order of `frames`.
    pub files: Vec<Option<String>>,
    /// A symbol (debug info or symbol table) named it.
    pub symbol: bool,
}

/// One file's symbols and the segments that place file offsets at its addresses.
struct FileSymbols {
    loader: Option<addr2line::Loader>,
    /// `(file offset, size in the file, address)` of each loaded segment.
    segments: Vec<(u64, u64, u64)>,
}

impl FileSymbols {
    /// The symbols of the file at `path` (the recorded build when `expected` names
    /// it), or why there are none.
    fn open(path: &str, expected: Option<&[u8]>, cache: Option<&Path>) -> Result<Self, String> {
        let cached = || {
            let id = expected?;
            let copy = cache?.join(build_id_path(id)?).join("elf");
            copy.is_file().then_some(copy)
        };
        let (file_path, data) = match std::fs::read(path) {
            Ok(data) => {
                let id = object::File::parse(&*data)
                    .ok()
                    .and_then(|f| f.build_id().ok().flatten().map(<[u8]>::to_vec));
                match (expected, id) {
                    (Some(want), Some(have)) if want != have.as_slice() => match cached() {
                        Some(copy) => read_copy(copy)?,
                        None => {
                            return Err(format!(
                                "another build: its build id {} is not the recording's {}, and perf's cache has no copy",
                                hex(&have),
                                hex(want)
                            ));
                        }
                    },
                    _ => (PathBuf::from(path), data),
                }
            }
            Err(e) => match cached() {
                Some(copy) => read_copy(copy)?,
                None => {
                    return Err(match (expected, cache) {
                        (Some(id), Some(cache)) => format!(
                            "cannot read it ({e}), and perf's cache {} has no copy of its build id {}",
                            cache.display(),
                            hex(id)
                        ),
                        _ => format!("cannot read it ({e})"),
                    });
                }
            },
        };
        let file = object::File::parse(&*data).map_err(|e| format!("not readable: {e}"))?;
        let segments = file
            .segments()
            .map(|s| {
                let (offset, size) = s.file_range();
                (offset, size, s.address())
            })
            .collect();
        // A debug package's file (`-dbgsym`, `libc6-dbg`) found by build id has the
        // symbols a stripped library lacks; the addresses are the same.
        let loader = debug_file(&file, cache)
            .and_then(|debug| addr2line::Loader::new(debug).ok())
            .or_else(|| addr2line::Loader::new(&file_path).ok());
        Ok(FileSymbols { loader, segments })
    }

    /// The address in the file (its own, before relocation) of a file offset.
    fn file_address(&self, offset: u64) -> Option<u64> {
        self.segments
            .iter()
            .find(|&&(start, size, _)| offset >= start && offset - start < size.max(1))
            .map(|&(start, _, address)| (offset - start).wrapping_add(address))
    }
}

fn read_copy(copy: PathBuf) -> Result<(PathBuf, Vec<u8>), String> {
    let data = std::fs::read(&copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    Ok((copy, data))
}

/// Where Debian's debug packages put a file's symbols: by its GNU build id.
const DEBUG_DIR: &str = "/usr/lib/debug/.build-id";

/// A build id in lower-case hex.
fn hex(id: &[u8]) -> String {
    id.iter().map(|b| format!("{b:02x}")).collect()
}

/// `.build-id/ab/cdef…`: where perf's cache and debug packages file a build id.
fn build_id_path(id: &[u8]) -> Option<PathBuf> {
    let (first, rest) = id.split_first()?;
    Some(
        Path::new(".build-id")
            .join(format!("{first:02x}"))
            .join(hex(rest)),
    )
}

/// The separate debug file of `file`, when one is installed (a debug package), or
/// perf's cache holds one (`perf buildid-cache` keeps it beside the copy).
fn debug_file(file: &object::File, cache: Option<&Path>) -> Option<PathBuf> {
    let id = file.build_id().ok()??;
    let (first, rest) = id.split_first()?;
    let package = Path::new(DEBUG_DIR)
        .join(format!("{first:02x}"))
        .join(format!("{}.debug", hex(rest)));
    let cached = cache.and_then(|c| Some(c.join(build_id_path(id)?).join("debug")));
    std::iter::once(package)
        .chain(cached)
        .find(|path| path.is_file())
}

/// A file of the recording that names nothing: not on this machine, or another build.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct MissingFile {
    /// The path perf recorded.
    pub path: String,
    /// What is wrong, as a sentence.
    pub problem: String,
}

/// Whether perf's `path` names a file (not `[vdso]`, `//anon`, `/memfd:…`).
fn is_file_path(path: &str) -> bool {
    path.starts_with('/') && !path.starts_with("//") && !path.starts_with("/memfd:")
}

/// Resolves addresses of many files, each file opened once and each address once.
#[derive(Default)]
pub struct Symbolizer {
    files: HashMap<String, Option<FileSymbols>>,
    cache: HashMap<(String, u64), Rc<Resolved>>,
    /// The build id of each file the recording lists, by path.
    build_ids: HashMap<String, Vec<u8>>,
    /// perf's build-id cache (`~/.debug`).
    cache_dir: Option<PathBuf>,
    missing: Vec<MissingFile>,
}

impl Symbolizer {
    /// A symbolizer that checks each file against the build id the recording lists
    /// for its path and falls back to perf's copies under `cache_dir`.
    pub fn new(build_ids: HashMap<String, Vec<u8>>, cache_dir: Option<PathBuf>) -> Self {
        Symbolizer {
            build_ids,
            cache_dir,
            ..Symbolizer::default()
        }
    }

    /// The files (with samples) that could not be read or were another build, in the
    /// order they were met.
    pub fn missing(&self) -> &[MissingFile] {
        &self.missing
    }

    /// The functions at `file_offset` of the file at `path` (`module` is its short
    /// name for the unknown frame).
    pub fn resolve(&mut self, path: &str, module: &str, file_offset: u64) -> Rc<Resolved> {
        let key = (path.to_string(), file_offset);
        if let Some(hit) = self.cache.get(&key) {
            return hit.clone();
        }
        if !self.files.contains_key(path) {
            let expected = self.build_ids.get(path).map(Vec::as_slice);
            let opened = FileSymbols::open(path, expected, self.cache_dir.as_deref());
            let opened = opened
                .map_err(|problem| {
                    if is_file_path(path) {
                        self.missing.push(MissingFile {
                            path: path.to_string(),
                            problem,
                        });
                    }
                })
                .ok();
            self.files.insert(path.to_string(), opened);
        }
        let file = self.files.get(path).and_then(Option::as_ref);
        let named = file.and_then(|f| {
            let address = f.file_address(file_offset)?;
            names_at(f.loader.as_ref()?, address)
        });
        let resolved = Rc::new(match named {
            Some((frames, files)) => Resolved {
                frames,
                files,
                symbol: true,
            },
            None => Resolved {
                frames: vec![unknown_in(module)],
                files: vec![None],
                symbol: false,
            },
        });
        self.cache.insert(key, resolved.clone());
        resolved
    }
}

/// The frame of code without a symbol, one per module.
pub fn unknown_in(module: &str) -> String {
    format!("[unknown in {module}]")
}

/// Names and source files at an address: outer function first, innermost inlined call
/// last; `None` without a symbol. A frame's file is that of its location (for the
/// innermost, the address's own line; for an outer one, the line of the inlined call:
/// both in that frame's function).
fn names_at(
    loader: &addr2line::Loader,
    address: u64,
) -> Option<(Vec<String>, Vec<Option<String>>)> {
    let mut names = Vec::new();
    let mut files = Vec::new();
    if let Ok(mut frames) = loader.find_frames(address) {
        while let Ok(Some(frame)) = frames.next() {
            let Some(function) = frame.function else {
                continue;
            };
            if let Ok(raw) = function.raw_name() {
                names.push(demangle(&raw, function.language));
                files.push(frame.location.and_then(|l| l.file).map(str::to_string));
            }
        }
    }
    if names.is_empty() {
        names.push(demangle(loader.find_symbol(address)?, None));
        files.push(None);
    }
    // addr2line lists the innermost inlined call first.
    names.reverse();
    files.reverse();
    Some((names, files))
}

/// A symbol as the reports print it: Rust paths cleaned, C++ names without their
/// parameters and return types, C names as they are.
pub fn demangle(raw: &str, language: Option<gimli::DwLang>) -> String {
    let rust = match language {
        Some(gimli::DW_LANG_Rust) => true,
        Some(_) => false,
        // A symbol table does not say: v0 names start with `_R`; legacy ones are
        // C++-like but end in a `h` + 16 hex digits hash.
        None => raw.starts_with("_R") || (raw.starts_with("_ZN") && has_rust_hash(raw)),
    };
    if rust {
        if let Ok(d) = rustc_demangle::try_demangle(raw) {
            return clean_symbol(&format!("{d:#}"));
        }
        return clean_symbol(raw);
    }
    if raw.starts_with("_Z") {
        let options = cpp_demangle::DemangleOptions::new()
            .no_params()
            .no_return_type();
        // Without parameters where the demangler manages; with them where only its
        // default form works (some template return types); else the mangled name.
        if let Ok(symbol) = cpp_demangle::Symbol::new(raw) {
            if let Ok(name) = symbol.demangle_with_options(&options) {
                return name;
            }
            if let Ok(name) = symbol.demangle() {
                return name;
            }
        }
    }
    raw.to_string()
}

/// Legacy Rust mangling: the last path component is `17h` and 16 hex digits.
fn has_rust_hash(raw: &str) -> bool {
    raw.strip_suffix('E')
        .and_then(|body| body.get(body.len().checked_sub(19)?..))
        .is_some_and(|t| t.starts_with("17h") && t[3..].bytes().all(|c| c.is_ascii_hexdigit()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpp_names_lose_their_parameters() {
        assert_eq!(
            demangle("_ZNK6sphere3hitERK3ray8intervalR10hit_record", None),
            "sphere::hit"
        );
        assert_eq!(
            demangle(
                "_ZNK8bvh_node3hitERK3ray8intervalR10hit_record",
                Some(gimli::DW_LANG_C_plus_plus)
            ),
            "bvh_node::hit"
        );
    }

    #[test]
    fn a_name_the_demangler_cannot_parse_stays_as_it_is() {
        // std::make_shared<bvh_node, hittable_list&> with an enable_if return type
        // (RTIOW): c++filt reads it, cpp_demangle 0.5 does not (docs/record.md, limits).
        let raw = "_ZSt11make_sharedI8bvh_nodeJR13hittable_listEESt10shared_ptrINSt9enable_ifIXntsrSt8is_arrayIT_E5valueES6_E4typeEEDpOT0_";
        assert_eq!(demangle(raw, None), raw);
        assert_eq!(demangle("_Z", None), "_Z");
    }

    #[test]
    fn rust_names_are_cleaned_paths() {
        // legacy mangling, with its hash
        assert_eq!(
            demangle("_ZN6tracer6sphere9intersect17h0123456789abcdefE", None),
            "tracer::sphere::intersect"
        );
        assert_eq!(
            demangle("_RNvCs1234_7mycrate3foo", Some(gimli::DW_LANG_Rust)),
            "mycrate::foo"
        );
    }

    #[test]
    fn c_names_stay_as_they_are() {
        assert_eq!(demangle("hot", None), "hot");
        assert_eq!(
            demangle("rt_renderscene", Some(gimli::DW_LANG_C99)),
            "rt_renderscene"
        );
    }

    #[test]
    fn an_unreadable_file_gives_one_unknown_frame_per_module() {
        let mut s = Symbolizer::default();
        let r = s.resolve("/nonexistent/libx.so", "libx.so", 0x1234);
        assert_eq!(r.frames, vec!["[unknown in libx.so]".to_string()]);
        assert!(!r.symbol);
    }

    /// This test binary's path and the file offset of one of its functions.
    fn own_function() -> (String, u64) {
        let exe = std::env::current_exe().unwrap();
        let path = exe.to_str().unwrap().to_string();
        let maps = std::fs::read_to_string("/proc/self/maps").unwrap();
        let here = this_test_binary_names_its_own_functions as *const () as u64;
        let line = maps
            .lines()
            .find(|l| {
                let range = l.split_whitespace().next().unwrap();
                let (a, b) = range.split_once('-').unwrap();
                let (a, b) = (
                    u64::from_str_radix(a, 16).unwrap(),
                    u64::from_str_radix(b, 16).unwrap(),
                );
                (a..b).contains(&here)
            })
            .unwrap();
        let mut fields = line.split_whitespace();
        let start =
            u64::from_str_radix(fields.next().unwrap().split('-').next().unwrap(), 16).unwrap();
        let offset = u64::from_str_radix(fields.nth(1).unwrap(), 16).unwrap();
        (path, here - start + offset)
    }

    fn names_this_function(r: &Resolved) -> bool {
        r.symbol
            && r.frames
                .last()
                .unwrap()
                .ends_with("this_test_binary_names_its_own_functions")
    }

    #[test]
    fn this_test_binary_names_its_own_functions() {
        // The test binary has debug info: a function of it, by the file offset of its
        // address, resolves to its own name.
        let (path, offset) = own_function();
        let mut s = Symbolizer::default();
        let r = s.resolve(&path, "test", offset);
        assert!(names_this_function(&r), "{r:?}");
    }

    #[test]
    fn a_file_gone_from_its_path_is_read_from_perfs_cache_by_build_id() {
        let (path, offset) = own_function();
        let data = std::fs::read(&path).unwrap();
        let Some(id) = object::File::parse(&*data)
            .unwrap()
            .build_id()
            .unwrap()
            .map(<[u8]>::to_vec)
        else {
            return; // linked without a build id: nothing to look up
        };
        let cache = std::env::temp_dir().join(format!("symbols-cache-{}", std::process::id()));
        let copy_dir = cache.join(build_id_path(&id).unwrap());
        std::fs::create_dir_all(&copy_dir).unwrap();
        let copy = copy_dir.join("elf");
        if std::fs::hard_link(&path, &copy).is_err() {
            std::fs::copy(&path, &copy).unwrap();
        }
        let gone = "/nonexistent/the-test-binary";
        let ids = HashMap::from([(gone.to_string(), id.clone())]);
        let mut s = Symbolizer::new(ids.clone(), Some(cache.clone()));
        let r = s.resolve(gone, "the-test-binary", offset);
        assert!(names_this_function(&r), "{r:?}");
        assert!(s.missing().is_empty());
        // Without the cache: nothing named, and the file is listed with the cache's
        // absence said.
        let mut s = Symbolizer::new(ids, Some(cache.join("empty")));
        assert!(!s.resolve(gone, "the-test-binary", offset).symbol);
        assert_eq!(s.missing().len(), 1);
        assert_eq!(s.missing()[0].path, gone);
        assert!(
            s.missing()[0].problem.contains(&hex(&id)),
            "{:?}",
            s.missing()
        );
        std::fs::remove_dir_all(&cache).unwrap();
    }

    #[test]
    fn another_build_at_the_recorded_path_names_nothing() {
        let (path, offset) = own_function();
        let data = std::fs::read(&path).unwrap();
        if object::File::parse(&*data)
            .unwrap()
            .build_id()
            .unwrap()
            .is_none()
        {
            return; // linked without a build id: no build to tell apart
        }
        let mut s = Symbolizer::new(HashMap::from([(path.clone(), vec![1, 2, 3, 4])]), None);
        let r = s.resolve(&path, "test", offset);
        assert!(!r.symbol, "{r:?}");
        assert!(
            s.missing()[0].problem.starts_with("another build"),
            "{:?}",
            s.missing()
        );
        // Pseudo-files perf records are not listed as missing.
        s.resolve("[vdso]", "[vdso]", 0x10);
        s.resolve("//anon", "//anon", 0x10);
        assert_eq!(s.missing().len(), 1);
    }
}
