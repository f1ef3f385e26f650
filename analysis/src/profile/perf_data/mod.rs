//! A `perf.data` file (Linux perf's recording: samples with call chains or copied user
//! stacks, and the mappings of every process) read into [`StackSamples`], the model
//! every profile output reads: each sample's addresses placed in their files
//! ([`maps`]), unwound from the copied stack under `--call-graph dwarf` ([`unwind`]),
//! named with inlined functions as themselves ([`symbols`]), folded into distinct
//! stacks, and what could not be named or placed counted per module ([`coverage`]).
//! The file is parsed with `linux-perf-data` (samply's reader), its header checked
//! first ([`header`]); no `perf script`. How it was recorded and the CPU time its
//! samples stand for are read from it too ([`info`]), for a recording made elsewhere.

pub mod coverage;
pub mod header;
pub mod info;
pub mod maps;
pub mod symbols;
pub mod unwind;

use std::collections::{BTreeMap, HashMap};
use std::io::{Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::rc::Rc;

use linux_perf_data::linux_perf_event_reader::{EventRecord, SampleRecord, constants};
use linux_perf_data::{Feature, PerfFileReader, PerfFileRecord};

use super::{Stack, StackSamples};
use coverage::{KERNEL, ModuleCoverage, module_name};
pub use info::{CpuTimeSource, RecordingInfo};
use maps::Maps;
pub use symbols::MissingFile;
use symbols::{Resolved, Symbolizer, unknown_in};
use unwind::{REG_BP, REG_IP, REG_SP, Unwinders};

/// The module of addresses in no mapped file.
pub const UNMAPPED: &str = "[unmapped]";

/// A perf recording as samples and how well they were named.
#[derive(Clone, Debug, PartialEq)]
pub struct PerfProfile {
    /// Frames outermost first; `seconds_per_sample` from the samples' periods (the
    /// caller puts its own measured CPU time over the samples when it has one).
    pub samples: StackSamples,
    /// Per module of the innermost frame, most samples first.
    pub modules: Vec<ModuleCoverage>,
    /// Samples the kernel dropped (perf's buffers full).
    pub lost: u64,
    /// CPU seconds the samples stand for, from [`PerfProfile::cpu_seconds_from`].
    pub sampled_seconds: f64,
    pub cpu_seconds_from: CpuTimeSource,
    /// Processes that were sampled.
    pub processes: usize,
    /// The user stacks were copied for unwinding here (`--call-graph dwarf`).
    pub dwarf: bool,
    /// Each function's source file, where the debug info names one (the first seen).
    pub sources: BTreeMap<String, String>,
    /// The event, rate, perf's command line and program of the recording.
    pub recording: RecordingInfo,
    /// Files with samples whose names could not be read: not at their recorded path
    /// nor in perf's cache, or another build than the one recorded.
    pub missing_files: Vec<MissingFile>,
}

/// A `perf.data` that could not be read.
#[derive(Debug, thiserror::Error)]
pub enum PerfDataError {
    #[error("cannot open {path}: {message}")]
    Open { path: String, message: String },
    #[error("{path} is not a perf.data file rtprof can read: {message}")]
    Parse { path: String, message: String },
    /// The header, checked before reading: truncated, damaged, or a kind not read.
    #[error("{path}: {problem}")]
    Header { path: String, problem: String },
}

/// perf's build-id cache: `$PERF_BUILDID_DIR`, else `~/.debug` (perf's default).
fn perf_cache_dir() -> Option<PathBuf> {
    std::env::var_os("PERF_BUILDID_DIR")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| Path::new(&home).join(".debug")))
}

/// One sample's addresses before they are named.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RawStack {
    pub pid: i32,
    /// The sample was taken in the kernel (its kernel frames show as one `[kernel]`).
    pub kernel: bool,
    /// User-space addresses, innermost first: the interrupted instruction, then return
    /// addresses.
    pub user: Vec<u64>,
    /// The unwinder stopped on an error, not at the stack's end.
    pub truncated: bool,
}

/// Names addresses: the symbolizer, or a stand-in in tests.
pub trait Names {
    /// The functions at `file_offset` in the file at `path` (short name `module`).
    fn names(&mut self, path: &str, module: &str, file_offset: u64) -> Rc<Resolved>;
}

impl Names for Symbolizer {
    fn names(&mut self, path: &str, module: &str, file_offset: u64) -> Rc<Resolved> {
        self.resolve(path, module, file_offset)
    }
}

/// Samples folded into distinct stacks, with the per-module tallies.
#[derive(Default)]
pub struct Folding {
    stacks: HashMap<Vec<String>, u64>,
    modules: BTreeMap<String, ModuleCoverage>,
    sources: BTreeMap<String, String>,
}

impl Folding {
    /// Adds one sample.
    pub fn add(&mut self, maps: &Maps, names: &mut impl Names, raw: &RawStack) {
        let mut frames: Vec<String> = Vec::new();
        let mut leaf: Option<(String, bool)> = None;
        let mut placed = 0usize;
        let mut truncated = raw.truncated;
        for (i, &address) in raw.user.iter().enumerate() {
            // A return address points after its call: look up the call itself.
            let probe = if i == 0 {
                address
            } else {
                address.saturating_sub(1)
            };
            let Some(mapping) = maps.find(raw.pid, probe) else {
                if i == 0 {
                    frames.push(unknown_in(UNMAPPED));
                    leaf = Some((UNMAPPED.to_string(), false));
                } else {
                    // A frame pointer that was not one: the rest is garbage.
                    truncated = true;
                }
                break;
            };
            let path = &maps.modules[mapping.module];
            let resolved = names.names(path, module_name(path), mapping.file_offset_of(probe));
            if i == 0 {
                leaf = Some((path.clone(), resolved.symbol));
            }
            // Innermost first here; each address's own frames are outer first.
            frames.extend(resolved.frames.iter().rev().cloned());
            for (name, file) in resolved.frames.iter().zip(&resolved.files) {
                if let Some(file) = file
                    && !self.sources.contains_key(name)
                {
                    self.sources.insert(name.clone(), file.clone());
                }
            }
            placed += 1;
        }
        frames.reverse();
        if raw.kernel {
            frames.push(KERNEL.to_string());
        }
        if frames.is_empty() {
            return;
        }
        let (path, symbol) = match (&leaf, raw.kernel) {
            (_, true) => (KERNEL.to_string(), true),
            (Some(l), false) => l.clone(),
            (None, false) => (UNMAPPED.to_string(), false),
        };
        let m = self
            .modules
            .entry(path.clone())
            .or_insert_with(|| ModuleCoverage::new(module_name(&path), &path));
        m.samples += 1;
        if !symbol {
            m.no_symbol += 1;
        }
        if !raw.kernel && !raw.user.is_empty() {
            if placed <= 1 {
                m.no_stack += 1;
            } else if truncated {
                m.cut_short += 1;
            }
        }
        *self.stacks.entry(frames).or_default() += 1;
    }

    /// Each function's source file so far (the first seen), taken out.
    pub fn take_sources(&mut self) -> BTreeMap<String, String> {
        std::mem::take(&mut self.sources)
    }

    /// The stacks (sorted, for stable outputs) and the modules, most samples first.
    pub fn finish(
        self,
        dwarf: bool,
        seconds_per_sample: f64,
    ) -> (StackSamples, Vec<ModuleCoverage>) {
        let mut stacks: Vec<Stack> = self
            .stacks
            .into_iter()
            .map(|(frames, count)| Stack { frames, count })
            .collect();
        stacks.sort_by(|a, b| a.frames.cmp(&b.frames));
        let mut modules: Vec<ModuleCoverage> = self.modules.into_values().collect();
        let total = modules.iter().map(|m| m.samples).sum();
        for m in &mut modules {
            m.advise(dwarf, total);
        }
        modules.sort_by(|a, b| {
            b.samples
                .cmp(&a.samples)
                .then_with(|| a.module.cmp(&b.module))
        });
        (
            StackSamples {
                stacks,
                seconds_per_sample,
            },
            modules,
        )
    }
}

/// Reads `path` (recorded by `perf record` with `-g` or `--call-graph dwarf`).
pub fn read_perf_data(path: &Path) -> Result<PerfProfile, PerfDataError> {
    let name = path.display().to_string();
    let parse_error = |e: &dyn std::fmt::Display| PerfDataError::Parse {
        path: name.clone(),
        message: e.to_string(),
    };
    let open_error = |e: std::io::Error| PerfDataError::Open {
        path: name.clone(),
        message: e.to_string(),
    };
    let mut file = std::fs::File::open(path).map_err(open_error)?;
    let length = file.metadata().map_err(open_error)?.len();
    header::check(&mut file, length).map_err(|problem| PerfDataError::Header {
        path: name.clone(),
        problem,
    })?;
    file.seek(SeekFrom::Start(0)).map_err(open_error)?;
    let PerfFileReader {
        mut perf_file,
        mut record_iter,
    } = PerfFileReader::parse_file(std::io::BufReader::new(file)).map_err(|e| parse_error(&e))?;
    // One sampling event is read: the first that samples (perf adds a `dummy` one for
    // side-band records); samples of others would mix units.
    let attributes = perf_file.event_attributes();
    let sampled = attributes
        .iter()
        .position(info::samples_anything)
        .unwrap_or(0);
    let mut recording = attributes
        .get(sampled)
        .map(RecordingInfo::of_event)
        .unwrap_or_default();
    recording.perf_command = perf_file
        .feature_section_data(Feature::CMDLINE)
        .map(|section| info::command_line(section, perf_file.endian()))
        .unwrap_or_default();
    let build_ids = perf_file
        .build_ids()
        .unwrap_or_default()
        .into_values()
        .map(|d| (String::from_utf8_lossy(&d.path).into_owned(), d.build_id))
        .collect();
    let mut maps = Maps::default();
    let mut symbols = Symbolizer::new(build_ids, perf_cache_dir());
    let mut unwinders = Unwinders::default();
    let mut folding = Folding::default();
    let (mut lost, mut periods, mut samples, mut dwarf) = (0u64, 0u64, 0u64, false);
    let mut per_pid: HashMap<i32, u64> = HashMap::new();
    let mut names: HashMap<i32, String> = HashMap::new();
    let mut times: Option<(u64, u64)> = None;
    while let Some(record) = record_iter
        .next_record(&mut perf_file)
        .map_err(|e| parse_error(&e))?
    {
        let PerfFileRecord::EventRecord { attr_index, record } = record else {
            continue;
        };
        // A record this reader does not know is skipped, not fatal.
        let Ok(parsed) = record.parse() else {
            continue;
        };
        match parsed {
            EventRecord::Sample(_) if attr_index != sampled => {
                recording.other_event_samples += 1;
            }
            EventRecord::Sample(s) => {
                let raw = raw_stack(&s, &maps, &mut unwinders);
                dwarf |= s.user_stack.is_some();
                periods += s.period.unwrap_or(0);
                samples += 1;
                *per_pid.entry(raw.pid).or_default() += 1;
                if let Some(t) = s.timestamp {
                    times = Some(times.map_or((t, t), |(a, b)| (a.min(t), b.max(t))));
                }
                folding.add(&maps, &mut symbols, &raw);
            }
            EventRecord::Mmap(m) if m.is_executable => {
                let path = String::from_utf8_lossy(&m.path.as_slice()).into_owned();
                maps.map(m.pid, m.address, m.length, m.page_offset, &path);
            }
            EventRecord::Mmap2(m) if m.protection & libc::PROT_EXEC as u32 != 0 => {
                let path = String::from_utf8_lossy(&m.path.as_slice()).into_owned();
                maps.map(m.pid, m.address, m.length, m.page_offset, &path);
            }
            EventRecord::Comm(c) => {
                names.insert(
                    c.pid,
                    String::from_utf8_lossy(&c.name.as_slice()).into_owned(),
                );
                if c.is_execve {
                    maps.exec(c.pid);
                }
            }
            EventRecord::Fork(f) => maps.fork(f.ppid, f.pid),
            EventRecord::Lost(l) => lost += l.count,
            _ => {}
        }
    }
    recording.span_seconds = times.map_or(0.0, |(a, b)| (b - a) as f64 * 1e-9);
    recording.program = per_pid
        .iter()
        .max_by_key(|&(pid, n)| (n, std::cmp::Reverse(pid)))
        .and_then(|(pid, _)| names.get(pid).cloned());
    let (sampled_seconds, cpu_seconds_from) = recording.cpu_seconds(samples, periods);
    let sources = folding.take_sources();
    let (stacks, modules) = folding.finish(dwarf, sampled_seconds / samples.max(1) as f64);
    Ok(PerfProfile {
        samples: stacks,
        modules,
        lost,
        sampled_seconds,
        cpu_seconds_from,
        processes: per_pid.len(),
        dwarf,
        sources,
        recording,
        missing_files: symbols.missing().to_vec(),
    })
}

/// A sample's addresses: the call chain the kernel walked (frame pointers), or the
/// copied stack unwound here (`--call-graph dwarf`).
fn raw_stack(s: &SampleRecord, maps: &Maps, unwinders: &mut Unwinders) -> RawStack {
    let pid = s.pid.unwrap_or(-1);
    let mut raw = RawStack {
        pid,
        ..RawStack::default()
    };
    let mut in_kernel = matches!(
        s.cpu_mode,
        linux_perf_data::linux_perf_event_reader::CpuMode::Kernel
    );
    raw.kernel = in_kernel;
    if let Some(chain) = &s.callchain {
        for i in 0..chain.len() {
            let Some(address) = chain.get(i) else { break };
            if address >= constants::PERF_CONTEXT_MAX {
                in_kernel = address == constants::PERF_CONTEXT_KERNEL;
                continue;
            }
            if in_kernel {
                raw.kernel = true;
            } else {
                raw.user.push(address);
            }
        }
    }
    let regs = s
        .user_regs
        .as_ref()
        .and_then(|r| Some([r.get(REG_IP)?, r.get(REG_SP)?, r.get(REG_BP)?]));
    if let (Some(regs), Some((stack, size))) = (regs, &s.user_stack) {
        let bytes = stack.as_slice();
        let valid = usize::try_from(*size).unwrap_or(0).min(bytes.len());
        let unwound = unwinders.unwind(maps, pid, regs, &bytes[..valid]);
        raw.user = unwound.addresses;
        raw.truncated = unwound.truncated;
    }
    if raw.user.is_empty() && !raw.kernel {
        raw.user.extend(s.ip);
    }
    raw
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names from a table: (path, file offset) → frames, outer first.
    struct Table(Vec<(&'static str, u64, Vec<&'static str>)>);

    impl Names for Table {
        fn names(&mut self, path: &str, module: &str, offset: u64) -> Rc<Resolved> {
            let hit = self.0.iter().find(|(p, o, _)| *p == path && *o == offset);
            Rc::new(match hit {
                Some((_, _, frames)) => Resolved {
                    frames: frames.iter().map(|s| s.to_string()).collect(),
                    files: frames.iter().map(|f| Some(format!("{f}.cc"))).collect(),
                    symbol: true,
                },
                None => Resolved {
                    frames: vec![unknown_in(module)],
                    files: vec![None],
                    symbol: false,
                },
            })
        }
    }

    fn setup() -> (Maps, Table) {
        let mut maps = Maps::default();
        maps.map(10, 0x1000, 0x1000, 0, "/bin/rt");
        maps.map(10, 0x8000, 0x1000, 0x2000, "/lib/libt.so");
        let names = Table(vec![
            ("/bin/rt", 0x100, vec!["main"]),
            // a return address 0x201 looks up 0x200: `render` with `shade` inlined
            ("/bin/rt", 0x200, vec!["render", "shade"]),
            ("/bin/rt", 0x300, vec!["Sphere::hit"]),
        ]);
        (maps, names)
    }

    #[test]
    fn frames_come_outermost_first_with_inlined_calls_in_place() {
        let (maps, mut names) = setup();
        let mut f = Folding::default();
        let raw = RawStack {
            pid: 10,
            kernel: false,
            user: vec![0x1300, 0x1201, 0x1101],
            truncated: false,
        };
        f.add(&maps, &mut names, &raw);
        f.add(&maps, &mut names, &raw);
        let (s, modules) = f.finish(false, 0.001);
        assert_eq!(s.stacks.len(), 1);
        assert_eq!(
            s.stacks[0].frames,
            ["main", "render", "shade", "Sphere::hit"]
        );
        assert_eq!(s.stacks[0].count, 2);
        assert_eq!(modules[0].module, "rt");
        assert_eq!(
            (
                modules[0].samples,
                modules[0].no_symbol,
                modules[0].no_stack
            ),
            (2, 0, 0)
        );
    }

    #[test]
    fn code_without_symbols_and_stacks_is_counted_per_module() {
        let (maps, mut names) = setup();
        let mut f = Folding::default();
        // in libt.so at file offset 0x2000 + 0x10, no symbol; no caller found
        f.add(
            &maps,
            &mut names,
            &RawStack {
                pid: 10,
                user: vec![0x8010],
                ..RawStack::default()
            },
        );
        // in libt.so, caller in rt, then a garbage frame pointer (unmapped)
        f.add(
            &maps,
            &mut names,
            &RawStack {
                pid: 10,
                user: vec![0x8020, 0x1101, 0xdead_0000],
                ..RawStack::default()
            },
        );
        // in the kernel, called from main
        f.add(
            &maps,
            &mut names,
            &RawStack {
                pid: 10,
                kernel: true,
                user: vec![0x1100],
                truncated: false,
            },
        );
        let (s, modules) = f.finish(false, 0.001);
        let lib = modules.iter().find(|m| m.module == "libt.so").unwrap();
        assert_eq!(
            (lib.samples, lib.no_symbol, lib.no_stack, lib.cut_short),
            (2, 2, 1, 1)
        );
        assert_eq!(lib.advice.len(), 2);
        let kernel = modules.iter().find(|m| m.module == KERNEL).unwrap();
        assert_eq!(
            (kernel.samples, kernel.no_symbol, kernel.no_stack),
            (1, 0, 0)
        );
        let frames: Vec<_> = s.stacks.iter().map(|s| s.frames.join(";")).collect();
        assert!(
            frames.contains(&"[unknown in libt.so]".to_string()),
            "{frames:?}"
        );
        assert!(
            frames.contains(&"main;[unknown in libt.so]".to_string()),
            "{frames:?}"
        );
        assert!(frames.contains(&"main;[kernel]".to_string()), "{frames:?}");
        assert_eq!(s.total(), 3);
    }

    #[test]
    fn an_unmapped_leaf_is_its_own_module() {
        let (maps, mut names) = setup();
        let mut f = Folding::default();
        f.add(
            &maps,
            &mut names,
            &RawStack {
                pid: 10,
                user: vec![0x50_0000, 0x1101],
                ..RawStack::default()
            },
        );
        let (s, modules) = f.finish(false, 0.001);
        assert_eq!(s.stacks[0].frames, ["[unknown in [unmapped]]"]);
        assert_eq!(modules[0].module, UNMAPPED);
        assert_eq!(modules[0].no_symbol, 1);
    }

    #[test]
    fn a_file_that_is_not_perf_data_is_an_error_not_a_panic() {
        let dir = std::env::temp_dir().join(format!("perf-data-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("perf.data");
        std::fs::write(&bad, b"not a perf file at all, just text").unwrap();
        let err = read_perf_data(&bad).unwrap_err();
        assert!(matches!(err, PerfDataError::Header { .. }), "{err}");
        assert!(err.to_string().contains("PERFILE2"), "{err}");
        assert!(matches!(
            read_perf_data(&dir.join("missing")),
            Err(PerfDataError::Open { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
