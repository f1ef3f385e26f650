//! A `perf.data` file's header checked against the file before `linux-perf-data` reads
//! it. That reader trusts the sizes and counts the file states: it allocates what a
//! section's size or an entry count says (a damaged count of 4 billion entries is an
//! allocation failure, which aborts the process: no error, no unwinding) and divides
//! by the attribute size. So every section the reader will load is checked to lie
//! inside the file, and every count to fit in its section, here; and the kinds of
//! recording it does not read (compressed, written to a pipe, simpleperf's) are named.
//!
//! The layout is perf's `struct perf_file_header` (tools/perf/util/header.h): the magic
//! `PERFILE2` (`2ELIFREP` when written big-endian), the header's size, the size of one
//! `perf_event_attr`, the attribute, data and event-type sections (offset, size), and
//! a 256-bit set of features; the features' sections are listed (offset, size each)
//! right after the data section.

use std::io::{Read, Seek, SeekFrom};

/// The magic of a perf.data file written little-endian (and big-endian, byte-swapped).
pub const MAGIC: &[u8; 8] = b"PERFILE2";
const MAGIC_SWAPPED: &[u8; 8] = b"2ELIFREP";
/// `sizeof(struct perf_file_header)`.
const HEADER_SIZE: u64 = 104;
/// The header of a recording written to a pipe (`perf record -o -`): magic and size.
const PIPE_HEADER_SIZE: u64 = 16;
/// `PERF_ATTR_SIZE_VER0`, the smallest `perf_event_attr`.
const MIN_ATTR_SIZE: u64 = 64;
/// Far above any `perf_event_attr` perf writes (136 bytes in Linux 6.x).
const MAX_ATTR_SIZE: u64 = 4096;
/// `struct perf_file_section`: offset and size.
const SECTION_SIZE: u64 = 16;

// Feature bits (tools/perf/util/header.h, `HEADER_*`).
const FEATURE_EVENT_DESC: u32 = 12;
const FEATURE_COMPRESSED: u32 = 27;
const FEATURE_SIMPLEPERF_META_INFO: u32 = 129;

/// Whether `bytes` start with perf.data's magic (either byte order).
pub fn has_magic(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC) || bytes.starts_with(MAGIC_SWAPPED)
}

/// One `(offset, size)` section, as the file states it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Section {
    offset: u64,
    size: u64,
}

impl Section {
    fn end(self) -> Option<u64> {
        self.offset.checked_add(self.size)
    }
}

/// Reads the file's integers in its byte order.
struct Bytes<'a> {
    data: &'a [u8],
    big_endian: bool,
}

impl Bytes<'_> {
    fn u64_at(&self, at: usize) -> Option<u64> {
        let raw: [u8; 8] = self.data.get(at..at.checked_add(8)?)?.try_into().ok()?;
        Some(if self.big_endian {
            u64::from_be_bytes(raw)
        } else {
            u64::from_le_bytes(raw)
        })
    }

    fn u32_at(&self, at: usize) -> Option<u32> {
        let raw: [u8; 4] = self.data.get(at..at.checked_add(4)?)?.try_into().ok()?;
        Some(if self.big_endian {
            u32::from_be_bytes(raw)
        } else {
            u32::from_le_bytes(raw)
        })
    }

    fn section_at(&self, at: usize) -> Option<Section> {
        Some(Section {
            offset: self.u64_at(at)?,
            size: self.u64_at(at + 8)?,
        })
    }
}

/// Checks the header of the perf.data open in `file` (`length` bytes long). The
/// error is a sentence saying what is wrong, for the caller to put after the path.
pub fn check<F: Read + Seek>(file: &mut F, length: u64) -> Result<(), String> {
    let mut head = vec![0u8; usize::try_from(HEADER_SIZE.min(length)).unwrap_or(0)];
    file.seek(SeekFrom::Start(0))
        .and_then(|_| file.read_exact(&mut head))
        .map_err(|e| format!("cannot read its header: {e}"))?;
    let big_endian = head.starts_with(MAGIC_SWAPPED);
    if !has_magic(&head) {
        return Err("no perf.data magic (PERFILE2) at its start".into());
    }
    let bytes = Bytes {
        data: &head,
        big_endian,
    };
    let header_size = bytes.u64_at(8);
    if header_size == Some(PIPE_HEADER_SIZE) {
        return Err(
            "recorded to a pipe (perf record -o -), which rtprof does not read: record to a file (perf record -o FILE)"
                .into(),
        );
    }
    if length < HEADER_SIZE {
        return Err(format!(
            "truncated: {length} bytes, shorter than perf's {HEADER_SIZE}-byte header"
        ));
    }
    let (Some(header_size), Some(attr_size)) = (header_size, bytes.u64_at(16)) else {
        return Err("truncated header".into());
    };
    if !(HEADER_SIZE..=MAX_ATTR_SIZE).contains(&header_size) {
        return Err(format!(
            "damaged header: it states a header size of {header_size} bytes"
        ));
    }
    if !(MIN_ATTR_SIZE..=MAX_ATTR_SIZE).contains(&attr_size) {
        return Err(format!(
            "damaged header: it states an event attribute size of {attr_size} bytes"
        ));
    }
    let sections = [("attribute", 24), ("data", 40), ("event type", 56)];
    let mut found = [Section { offset: 0, size: 0 }; 3];
    for (slot, (name, at)) in found.iter_mut().zip(sections) {
        let section = bytes
            .section_at(at)
            .ok_or_else(|| "truncated header".to_string())?;
        within(section, length, name)?;
        *slot = section;
    }
    let [attrs, data, event_types] = found;
    let features: Vec<u32> = (0..4)
        .filter_map(|word| bytes.u64_at(72 + 8 * word).map(|bits| (word, bits)))
        .flat_map(|(word, bits)| {
            (0..64u32)
                .filter(move |bit| bits & (1 << bit) != 0)
                .map(move |bit| 64 * word as u32 + bit)
        })
        .collect();
    if features.contains(&FEATURE_COMPRESSED) {
        return Err(
            "compressed (perf record -z), which rtprof does not read: record without -z".into(),
        );
    }
    // The table of feature sections follows the data section.
    let table = Section {
        offset: data.end().unwrap_or(u64::MAX),
        size: SECTION_SIZE * features.len() as u64,
    };
    within(table, length, "feature table")?;
    let mut event_desc = None;
    for (i, &feature) in features.iter().enumerate() {
        let at = table.offset + SECTION_SIZE * i as u64;
        let section = read_section(file, at, big_endian)?;
        within(section, length, "feature")?;
        if feature == FEATURE_EVENT_DESC {
            event_desc = Some(section);
        }
    }
    match event_desc {
        Some(section) => check_event_desc(file, section, big_endian),
        None if event_types.size != 0 => {
            check_id_sections(file, event_types, attr_size, big_endian, length)
        }
        None if features.contains(&FEATURE_SIMPLEPERF_META_INFO) => {
            Err("a simpleperf recording (Android), which rtprof does not read".into())
        }
        // The attributes alone: the reader divides their section by their size,
        // checked above, and allocates no more than the section holds.
        None => {
            if attrs.size < attr_size {
                Err("no event attributes in its header".into())
            } else {
                Ok(())
            }
        }
    }
}

/// That `section` lies inside a file of `length` bytes.
fn within(section: Section, length: u64, name: &str) -> Result<(), String> {
    match section.end() {
        Some(end) if end <= length => Ok(()),
        Some(end) => Err(format!(
            "truncated: its {name} section ends at byte {end}, but the file has {length} bytes (copied before perf finished writing it, or cut short)"
        )),
        None => Err(format!("damaged header: its {name} section overflows")),
    }
}

fn read_bytes<F: Read + Seek>(file: &mut F, at: u64, size: usize) -> Result<Vec<u8>, String> {
    let mut buffer = vec![0u8; size];
    file.seek(SeekFrom::Start(at))
        .and_then(|_| file.read_exact(&mut buffer))
        .map_err(|e| format!("cannot read it at byte {at}: {e}"))?;
    Ok(buffer)
}

fn read_section<F: Read + Seek>(
    file: &mut F,
    at: u64,
    big_endian: bool,
) -> Result<Section, String> {
    let raw = read_bytes(file, at, SECTION_SIZE as usize)?;
    Bytes {
        data: &raw,
        big_endian,
    }
    .section_at(0)
    .ok_or_else(|| "truncated feature table".to_string())
}

/// `HEADER_EVENT_DESC`: `nr`, `attr_size`, then per event the attribute, `nr_ids`,
/// a string (`len` and bytes) and `nr_ids` ids; all inside the section.
fn check_event_desc<F: Read + Seek>(
    file: &mut F,
    section: Section,
    big_endian: bool,
) -> Result<(), String> {
    let damaged = || "damaged event descriptions (HEADER_EVENT_DESC)".to_string();
    // Checked inside the file above, so its size is no more than the file's.
    let raw = read_bytes(
        file,
        section.offset,
        usize::try_from(section.size).map_err(|_| damaged())?,
    )?;
    let bytes = Bytes {
        data: &raw,
        big_endian,
    };
    let count = bytes.u32_at(0).ok_or_else(damaged)?;
    let attr_size = u64::from(bytes.u32_at(4).ok_or_else(damaged)?);
    if count == 0 || !(MIN_ATTR_SIZE..=MAX_ATTR_SIZE).contains(&attr_size) {
        return Err(damaged());
    }
    let mut at: u64 = 8;
    for _ in 0..count {
        at += attr_size;
        let position = usize::try_from(at).map_err(|_| damaged())?;
        let ids = u64::from(bytes.u32_at(position).ok_or_else(damaged)?);
        let name_length = u64::from(bytes.u32_at(position + 4).ok_or_else(damaged)?);
        at = at
            .checked_add(8 + name_length)
            .and_then(|a| a.checked_add(ids.checked_mul(8)?))
            .filter(|&end| end <= section.size)
            .ok_or_else(damaged)?;
    }
    Ok(())
}

/// The old event-type section: per event an attribute and the section of its ids,
/// each inside the file.
fn check_id_sections<F: Read + Seek>(
    file: &mut F,
    section: Section,
    attr_size: u64,
    big_endian: bool,
    length: u64,
) -> Result<(), String> {
    let entry = attr_size + SECTION_SIZE;
    for i in 0..section.size / entry {
        let at = section.offset + i * entry + attr_size;
        within(read_section(file, at, big_endian)?, length, "event id")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    /// A header with the given sections and features, padded to `length`.
    fn header(data: (u64, u64), features: u64, length: usize) -> Vec<u8> {
        let mut h = Vec::new();
        h.extend_from_slice(MAGIC);
        for v in [
            HEADER_SIZE,
            136,
            104,
            0,
            data.0,
            data.1,
            0,
            0,
            features,
            0,
            0,
            0,
        ] {
            h.extend_from_slice(&v.to_le_bytes());
        }
        h.resize(length, 0);
        h
    }

    fn check_bytes(bytes: &[u8]) -> Result<(), String> {
        check(&mut Cursor::new(bytes), bytes.len() as u64)
    }

    #[test]
    fn a_data_section_past_the_end_is_truncation() {
        let bytes = header((104, 5000), 0, 1000);
        let err = check_bytes(&bytes).unwrap_err();
        assert!(
            err.starts_with("truncated: its data section ends at byte 5104"),
            "{err}"
        );
        assert!(err.contains("1000 bytes"), "{err}");
    }

    #[test]
    fn the_kinds_it_does_not_read_are_named() {
        let mut pipe = MAGIC.to_vec();
        pipe.extend_from_slice(&16u64.to_le_bytes());
        assert!(check_bytes(&pipe).unwrap_err().contains("pipe"));
        let compressed = header((104, 0), 1 << FEATURE_COMPRESSED, 200);
        assert!(check_bytes(&compressed).unwrap_err().contains("-z"));
    }

    #[test]
    fn a_huge_event_count_is_refused_before_anything_is_allocated() {
        // One feature, EVENT_DESC, whose section says 2^32 - 1 events.
        let mut bytes = header((104, 0), 1 << FEATURE_EVENT_DESC, 104);
        for v in [120u64, 16] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes.extend_from_slice(&u32::MAX.to_le_bytes());
        bytes.extend_from_slice(&136u32.to_le_bytes());
        bytes.resize(136, 0);
        let err = check_bytes(&bytes).unwrap_err();
        assert!(err.contains("HEADER_EVENT_DESC"), "{err}");
    }

    #[test]
    fn garbage_after_the_magic_is_an_error() {
        // A fixed pseudo-random stream: whatever it states, no panic, an error.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for length in [8usize, 15, 16, 60, 104, 200, 4096] {
            let mut bytes = MAGIC.to_vec();
            while bytes.len() < length.max(8) {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                bytes.push(state as u8);
            }
            assert!(check_bytes(&bytes).is_err(), "{length} bytes");
        }
        assert!(check_bytes(b"").is_err());
        assert!(check_bytes(b"hello").is_err());
    }
}
