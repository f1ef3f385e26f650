//! `--call-graph dwarf`: perf copied each sample's user registers and the top of its
//! stack; the callers are found here with framehop from the `.eh_frame` unwind tables
//! of the files mapped in that process (what `perf script` does with libdw, without
//! the subprocess), for code built without frame pointers.

use std::collections::HashMap;
use std::ops::Range;
use std::sync::Arc;

use framehop::x86_64::{CacheX86_64, UnwindRegsX86_64, UnwinderX86_64};
use framehop::{ExplicitModuleSectionInfo, FrameAddress, Module, Unwinder};
use object::{Object, ObjectSection, ObjectSegment};

use super::maps::Maps;

/// perf's x86-64 user register numbers (`arch/x86/include/uapi/asm/perf_regs.h`).
pub use linux_perf_data::linux_perf_event_reader::constants::{
    PERF_REG_X86_BP as REG_BP, PERF_REG_X86_IP as REG_IP, PERF_REG_X86_SP as REG_SP,
};

/// A file's unwind tables and its segments (to place it in a process).
struct FileTables {
    text: Option<(Range<u64>, Arc<[u8]>)>,
    eh_frame: Option<(Range<u64>, Arc<[u8]>)>,
    eh_frame_hdr: Option<(Range<u64>, Arc<[u8]>)>,
    got: Option<Range<u64>>,
    /// `(file offset, size in the file, address)` of each segment.
    segments: Vec<(u64, u64, u64)>,
}

impl FileTables {
    fn open(path: &str) -> Option<FileTables> {
        let data = std::fs::read(path).ok()?;
        let file = object::File::parse(&*data).ok()?;
        let section = |name: &str| {
            let s = file.section_by_name(name)?;
            let bytes: Arc<[u8]> = Arc::from(s.uncompressed_data().ok()?.as_ref());
            Some((s.address()..s.address().saturating_add(s.size()), bytes))
        };
        Some(FileTables {
            text: section(".text"),
            eh_frame: section(".eh_frame"),
            eh_frame_hdr: section(".eh_frame_hdr"),
            got: file
                .section_by_name(".got")
                .map(|s| s.address()..s.address().saturating_add(s.size())),
            segments: file
                .segments()
                .map(|s| {
                    let (offset, size) = s.file_range();
                    (offset, size, s.address())
                })
                .collect(),
        })
    }

    /// Load bias: the process address of the file's address 0, from one mapping. A
    /// mapping starts at its segment's page: a segment at file offset 0x1ee5010 and
    /// address 0x20e6010 is mapped from offset 0x1ee5000 at 0x20e6000.
    fn bias(&self, start: u64, file_offset: u64) -> Option<u64> {
        const PAGE: u64 = 0x1000;
        let &(seg_offset, _, address) = self
            .segments
            .iter()
            .find(|&&(o, _, _)| o & !(PAGE - 1) == file_offset)
            .or_else(|| {
                self.segments
                    .iter()
                    .rfind(|&&(o, size, _)| file_offset >= o && file_offset - o < size.max(1))
            })?;
        let page_address = address.wrapping_sub(seg_offset - (seg_offset & !(PAGE - 1)));
        let mapped_offset = seg_offset & !(PAGE - 1);
        Some(start.wrapping_sub((file_offset - mapped_offset).wrapping_add(page_address)))
    }

    fn section_info(&self) -> ExplicitModuleSectionInfo<Arc<[u8]>> {
        let range = |s: &Option<(Range<u64>, Arc<[u8]>)>| s.as_ref().map(|(r, _)| r.clone());
        let data = |s: &Option<(Range<u64>, Arc<[u8]>)>| s.as_ref().map(|(_, d)| d.clone());
        ExplicitModuleSectionInfo {
            base_svma: 0,
            text_svma: range(&self.text),
            text: data(&self.text),
            got_svma: self.got.clone(),
            eh_frame_svma: range(&self.eh_frame),
            eh_frame: data(&self.eh_frame),
            eh_frame_hdr_svma: range(&self.eh_frame_hdr),
            eh_frame_hdr: data(&self.eh_frame_hdr),
            ..ExplicitModuleSectionInfo::default()
        }
    }
}

/// One process's unwinder, built for a version of its mappings.
struct ProcessUnwinder {
    version: u64,
    unwinder: UnwinderX86_64<Arc<[u8]>>,
    cache: CacheX86_64,
}

/// Unwinders of every process, their files read once.
#[derive(Default)]
pub struct Unwinders {
    files: HashMap<String, Option<FileTables>>,
    processes: HashMap<i32, ProcessUnwinder>,
}

/// The user-space addresses of one sample, innermost first, and whether the unwinder
/// stopped on an error (a truncated stack) rather than at the stack's end.
pub struct Unwound {
    pub addresses: Vec<u64>,
    pub truncated: bool,
}

impl Unwinders {
    /// Unwinds from `ip`, `sp`, `bp` over `stack` (the bytes perf copied from `sp`
    /// up). Return addresses come back as they are (the caller looks up `address - 1`).
    pub fn unwind(&mut self, maps: &Maps, pid: i32, regs: [u64; 3], stack: &[u8]) -> Unwound {
        let [ip, sp, bp] = regs;
        let version = maps.version(pid);
        let stale = self
            .processes
            .get(&pid)
            .is_none_or(|p| p.version != version);
        if stale {
            let unwinder = self.build(maps, pid);
            self.processes.insert(
                pid,
                ProcessUnwinder {
                    version,
                    unwinder,
                    cache: CacheX86_64::new(),
                },
            );
        }
        let mut out = Unwound {
            addresses: Vec::new(),
            truncated: false,
        };
        let Some(process) = self.processes.get_mut(&pid) else {
            return out;
        };
        let mut read_stack = |address: u64| {
            let at = usize::try_from(address.checked_sub(sp).ok_or(())?).map_err(|_| ())?;
            let bytes = stack.get(at..at.checked_add(8).ok_or(())?).ok_or(())?;
            Ok(u64::from_le_bytes(bytes.try_into().map_err(|_| ())?))
        };
        let mut frames = process.unwinder.iter_frames(
            ip,
            UnwindRegsX86_64::new(ip, sp, bp),
            &mut process.cache,
            &mut read_stack,
        );
        loop {
            match frames.next() {
                Ok(Some(FrameAddress::InstructionPointer(a))) => out.addresses.push(a),
                Ok(Some(FrameAddress::ReturnAddress(a))) => out.addresses.push(a.get()),
                Ok(None) => break,
                Err(_) => {
                    out.truncated = true;
                    break;
                }
            }
        }
        out
    }

    fn build(&mut self, maps: &Maps, pid: i32) -> UnwinderX86_64<Arc<[u8]>> {
        let mut unwinder = UnwinderX86_64::new();
        // Each module once, over the span of its mappings.
        let mut spans: Vec<(usize, u64, u64, u64, u64)> = Vec::new();
        for m in maps.of(pid) {
            match spans.iter_mut().find(|s| s.0 == m.module) {
                Some(s) => {
                    s.1 = s.1.min(m.start);
                    s.2 = s.2.max(m.end);
                }
                None => spans.push((m.module, m.start, m.end, m.start, m.file_offset)),
            }
        }
        for (module, start, end, first_start, first_offset) in spans {
            let path = &maps.modules[module];
            let tables = self
                .files
                .entry(path.clone())
                .or_insert_with(|| FileTables::open(path));
            let Some(tables) = tables else { continue };
            let Some(bias) = tables.bias(first_start, first_offset) else {
                continue;
            };
            unwinder.add_module(Module::new(
                path.clone(),
                start..end,
                bias,
                tables.section_info(),
            ));
        }
        unwinder
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tables(segments: Vec<(u64, u64, u64)>) -> FileTables {
        FileTables {
            text: None,
            eh_frame: None,
            eh_frame_hdr: None,
            got: None,
            segments,
        }
    }

    #[test]
    fn the_bias_of_a_segment_that_does_not_start_on_a_page() {
        // rtprof's own release binary (non-PIE, lld): R at 0, R E at offset 0x1ee5010,
        // address 0x20e6010, mapped from 0x1ee5000 at 0x20e6000: no relocation.
        let t = tables(vec![
            (0, 0x1ee500c, 0x200000),
            (0x1ee5010, 0x3c51300, 0x20e6010),
        ]);
        assert_eq!(t.bias(0x20e6000, 0x1ee5000), Some(0));
        // A PIE library loaded at 0x7f00_0000_0000: its text segment at offset and
        // address 0x26000.
        let lib = tables(vec![(0, 0x26000, 0), (0x26000, 0x156000, 0x26000)]);
        assert_eq!(lib.bias(0x7f00_0002_6000, 0x26000), Some(0x7f00_0000_0000));
    }
}
