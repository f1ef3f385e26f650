//! Which file each address of each process came from: the mappings perf recorded
//! (`MMAP`/`MMAP2`), copied to a forked process, cleared by an `exec`.

use std::collections::HashMap;

/// A module (executable or shared library) by its index in [`Maps::modules`].
pub type ModuleId = usize;

/// One mapped range of a file in a process.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mapping {
    pub start: u64,
    pub end: u64,
    /// Offset in the file of `start`.
    pub file_offset: u64,
    pub module: ModuleId,
}

impl Mapping {
    /// The file offset of `address` (inside this mapping).
    pub fn file_offset_of(&self, address: u64) -> u64 {
        (address - self.start).wrapping_add(self.file_offset)
    }
}

/// Mappings of every process seen, and the modules they map.
#[derive(Debug, Default)]
pub struct Maps {
    /// Module paths as perf recorded them (`[vdso]` and the like included).
    pub modules: Vec<String>,
    by_path: HashMap<String, ModuleId>,
    /// Per process: mappings sorted by start, not overlapping.
    processes: HashMap<i32, Vec<Mapping>>,
    /// Per process: bumped at each change, so that what is built from its mappings
    /// (the unwinder's modules) is rebuilt only when they changed.
    versions: HashMap<i32, u64>,
    changes: u64,
}

impl Maps {
    /// The id of the module at `path`, added if new.
    pub fn module(&mut self, path: &str) -> ModuleId {
        if let Some(&id) = self.by_path.get(path) {
            return id;
        }
        let id = self.modules.len();
        self.modules.push(path.to_string());
        self.by_path.insert(path.to_string(), id);
        id
    }

    /// `pid` mapped `len` bytes of `path` at `start`, from `file_offset`. A new mapping
    /// replaces what it overlaps, as mmap does.
    pub fn map(&mut self, pid: i32, start: u64, len: u64, file_offset: u64, path: &str) {
        let Some(end) = start.checked_add(len).filter(|_| len > 0) else {
            return;
        };
        let module = self.module(path);
        let list = self.processes.entry(pid).or_default();
        let mut kept = Vec::with_capacity(list.len() + 2);
        for m in list.drain(..) {
            if m.end <= start || m.start >= end {
                kept.push(m);
                continue;
            }
            // Keep the parts of the old mapping outside the new one.
            if m.start < start {
                kept.push(Mapping { end: start, ..m });
            }
            if m.end > end {
                kept.push(Mapping {
                    start: end,
                    file_offset: m.file_offset + (end - m.start),
                    ..m
                });
            }
        }
        kept.push(Mapping {
            start,
            end,
            file_offset,
            module,
        });
        kept.sort_by_key(|m| m.start);
        *list = kept;
        self.changed(pid);
    }

    fn changed(&mut self, pid: i32) {
        self.changes += 1;
        self.versions.insert(pid, self.changes);
    }

    /// Changes when `pid`'s mappings change.
    pub fn version(&self, pid: i32) -> u64 {
        self.versions.get(&pid).copied().unwrap_or(0)
    }

    /// A new process `child` forked from `parent`: it starts with the parent's mappings.
    pub fn fork(&mut self, parent: i32, child: i32) {
        if parent == child {
            return;
        }
        let copied = self.processes.get(&parent).cloned().unwrap_or_default();
        self.processes.insert(child, copied);
        self.changed(child);
    }

    /// `pid` called exec: its old mappings are gone.
    pub fn exec(&mut self, pid: i32) {
        self.processes.remove(&pid);
        self.changed(pid);
    }

    /// The mapping holding `address` in `pid`.
    pub fn find(&self, pid: i32, address: u64) -> Option<&Mapping> {
        let list = self.processes.get(&pid)?;
        let at = list.partition_point(|m| m.start <= address);
        list[..at].last().filter(|m| address < m.end)
    }

    /// The mappings of `pid` (for the unwinder's modules).
    pub fn of(&self, pid: i32) -> &[Mapping] {
        self.processes.get(&pid).map_or(&[], Vec::as_slice)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_find_their_mapping_and_file_offset() {
        let mut maps = Maps::default();
        maps.map(7, 0x1000, 0x2000, 0x400, "/bin/a");
        maps.map(7, 0x8000, 0x1000, 0, "/lib/b.so");
        let m = maps.find(7, 0x1800).unwrap();
        assert_eq!(maps.modules[m.module], "/bin/a");
        assert_eq!(m.file_offset_of(0x1800), 0xc00);
        assert!(maps.find(7, 0x3000).is_none());
        assert!(maps.find(7, 0xfff).is_none());
        assert_eq!(
            maps.modules[maps.find(7, 0x8fff).unwrap().module],
            "/lib/b.so"
        );
        assert!(maps.find(8, 0x1800).is_none());
    }

    #[test]
    fn a_new_mapping_splits_what_it_covers() {
        let mut maps = Maps::default();
        maps.map(1, 0x1000, 0x3000, 0, "/old");
        maps.map(1, 0x2000, 0x1000, 0, "/new");
        assert_eq!(maps.modules[maps.find(1, 0x1800).unwrap().module], "/old");
        assert_eq!(maps.modules[maps.find(1, 0x2800).unwrap().module], "/new");
        let tail = maps.find(1, 0x3800).unwrap();
        assert_eq!(maps.modules[tail.module], "/old");
        assert_eq!(tail.file_offset_of(0x3800), 0x2800);
        assert_eq!(maps.of(1).len(), 3);
    }

    #[test]
    fn fork_copies_and_exec_clears() {
        let mut maps = Maps::default();
        maps.map(1, 0x1000, 0x1000, 0, "/bin/sh");
        maps.fork(1, 2);
        assert!(maps.find(2, 0x1000).is_some());
        maps.exec(2);
        assert!(maps.find(2, 0x1000).is_none());
        assert!(maps.find(1, 0x1000).is_some());
        assert_eq!(maps.module("/bin/sh"), 0, "paths are not duplicated");
    }
}
