//! Two-dimensional arrays as NumPy `.npy` files (format version 1.0), so that the
//! per-pixel counter maps open with `numpy.load` for analysis outside rtprof, and read
//! back ([`read_npy`]), so that the report draws the maps from their raw values.
//!
//! Written by hand rather than with a crate: the format is a short, fixed
//! specification (numpy.lib.format: a magic string, a version, a Python dict literal
//! naming the element type and shape, then the raw data), while the NPY crates pull in
//! `ndarray` for what is a page of code here. The data is written row-major (C order)
//! and little-endian whatever the machine, and the header says so.

/// The first bytes of every NPY file.
const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Magic, the two version bytes and the header length field: the header's text starts
/// after this many bytes.
const PREAMBLE_LEN: usize = MAGIC.len() + 2 + 2;

/// The specification pads the header so that the data starts at a multiple of this
/// (aligned for memory-mapping the data as an array).
const DATA_ALIGNMENT: usize = 64;

/// An element type that NumPy reads: its type string and its little-endian bytes.
pub trait NpyElement: Copy {
    /// NumPy's type string: byte order (`<` little-endian, `|` not applicable), kind
    /// and size in bytes (`<u8` is a 64-bit unsigned integer).
    const DESCR: &'static str;
    /// Bytes per element.
    const SIZE: usize;
    /// Appends the element's little-endian bytes to `out`.
    fn append_le_bytes(self, out: &mut Vec<u8>);
}

macro_rules! npy_element {
    ($type:ty, $descr:literal) => {
        impl NpyElement for $type {
            const DESCR: &'static str = $descr;
            const SIZE: usize = std::mem::size_of::<$type>();
            fn append_le_bytes(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}

npy_element!(u8, "|u1");
npy_element!(u32, "<u4");
npy_element!(u64, "<u8");
npy_element!(f32, "<f4");
npy_element!(f64, "<f8");

/// Why an array cannot be written as NPY.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NpyError {
    /// The data does not hold `rows * columns` elements.
    #[error("an array of {rows} x {columns} cannot be made of {len} elements")]
    Shape {
        rows: usize,
        columns: usize,
        len: usize,
    },
    /// A header longer than version 1.0's 16-bit length field allows (not possible
    /// for two dimensions; kept as an error rather than a panic).
    #[error("an NPY header of {0} bytes does not fit version 1.0")]
    HeaderTooLong(usize),
    /// Bytes that are not an NPY file of a two-dimensional array this reader knows.
    #[error("not a readable NPY array: {0}")]
    Format(String),
}

/// The NPY header of a `rows` x `columns` C-order array of `descr`: magic, version
/// 1.0, header length and the dict literal, padded with spaces and ended by a newline
/// so that the data starts at a multiple of [`DATA_ALIGNMENT`].
fn header(descr: &str, rows: usize, columns: usize) -> Result<Vec<u8>, NpyError> {
    // The trailing ", " inside the braces is how NumPy itself writes the dict.
    let dict =
        format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': ({rows}, {columns}), }}");
    let data_offset = (PREAMBLE_LEN + dict.len() + 1).next_multiple_of(DATA_ALIGNMENT);
    let header_len = data_offset - PREAMBLE_LEN;
    // The dict is at most about 100 characters (two usize numbers), so the padded
    // header is at most 128 bytes, far below the u16 limit of version 1.0.
    let header_len_field =
        u16::try_from(header_len).map_err(|_| NpyError::HeaderTooLong(header_len))?;
    let mut out = Vec::with_capacity(data_offset);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(&header_len_field.to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.resize(data_offset - 1, b' ');
    out.push(b'\n');
    Ok(out)
}

/// The bytes of an NPY file (version 1.0) of the `rows` x `columns` array `data`,
/// given row by row (C order). Fails when `data` does not hold `rows * columns`
/// elements.
pub fn npy_bytes<T: NpyElement>(
    rows: usize,
    columns: usize,
    data: &[T],
) -> Result<Vec<u8>, NpyError> {
    if rows.checked_mul(columns) != Some(data.len()) {
        return Err(NpyError::Shape {
            rows,
            columns,
            len: data.len(),
        });
    }
    let mut out = header(T::DESCR, rows, columns)?;
    out.reserve_exact(data.len() * T::SIZE);
    for &element in data {
        element.append_le_bytes(&mut out);
    }
    Ok(out)
}

/// A two-dimensional array read from an NPY file, its values widened to f64.
#[derive(Clone, Debug, PartialEq)]
pub struct NpyArray {
    pub rows: usize,
    pub columns: usize,
    /// Row by row (C order).
    pub values: Vec<f64>,
}

/// Reads an NPY file (versions 1.0 to 3.0) of a two-dimensional C-order array of
/// unsigned or signed integers (1 to 8 bytes) or floats (4 or 8 bytes), little-endian
/// or single-byte; its values as f64 (exact for integers below 2^53).
pub fn read_npy(bytes: &[u8]) -> Result<NpyArray, NpyError> {
    let bad = |why: &str| NpyError::Format(why.to_string());
    if bytes.len() < PREAMBLE_LEN || &bytes[..MAGIC.len()] != MAGIC {
        return Err(bad("no NPY magic"));
    }
    let (header_len, text_start) = match bytes[MAGIC.len()] {
        1 => (
            usize::from(u16::from_le_bytes([bytes[8], bytes[9]])),
            PREAMBLE_LEN,
        ),
        2 | 3 => {
            let field = bytes.get(8..12).ok_or_else(|| bad("a short preamble"))?;
            let len = u32::from_le_bytes([field[0], field[1], field[2], field[3]]);
            (
                usize::try_from(len).map_err(|_| bad("a header too long"))?,
                PREAMBLE_LEN + 2,
            )
        }
        v => return Err(NpyError::Format(format!("version {v}"))),
    };
    let data_start = text_start
        .checked_add(header_len)
        .filter(|end| *end <= bytes.len())
        .ok_or_else(|| bad("a header past the end"))?;
    let header = std::str::from_utf8(&bytes[text_start..data_start])
        .map_err(|_| bad("a header that is not text"))?;
    let descr = dict_value(header, "descr").ok_or_else(|| bad("no descr"))?;
    let descr = descr.trim_matches(|c| c == '\'' || c == '"');
    if dict_value(header, "fortran_order").map(str::trim) != Some("False") {
        return Err(bad("not in C order"));
    }
    let shape = dict_value(header, "shape").ok_or_else(|| bad("no shape"))?;
    let dims: Vec<usize> = shape
        .trim_matches(|c| c == '(' || c == ')')
        .split(',')
        .map(str::trim)
        .filter(|d| !d.is_empty())
        .map(|d| {
            d.parse::<usize>()
                .map_err(|_| bad("a shape that is not numbers"))
        })
        .collect::<Result<_, _>>()?;
    let [rows, columns] = dims[..] else {
        return Err(NpyError::Format(format!("{} dimensions", dims.len())));
    };
    let (kind, size) =
        element_type(descr).ok_or_else(|| NpyError::Format(format!("element type {descr}")))?;
    let count = rows
        .checked_mul(columns)
        .ok_or_else(|| bad("a shape too large"))?;
    let data = &bytes[data_start..];
    if count.checked_mul(size) != Some(data.len()) {
        return Err(NpyError::Shape {
            rows,
            columns,
            len: data.len() / size,
        });
    }
    let values = data.chunks_exact(size).map(|e| kind.value(e)).collect();
    Ok(NpyArray {
        rows,
        columns,
        values,
    })
}

/// The text of `key`'s value in an NPY header's dict literal: up to the next top-level
/// comma (a tuple's commas are inside its parentheses).
fn dict_value<'h>(header: &'h str, key: &str) -> Option<&'h str> {
    let quoted = [format!("'{key}'"), format!("\"{key}\"")];
    let at = quoted
        .iter()
        .find_map(|q| header.find(q.as_str()).map(|i| i + q.len()))?;
    let rest = header[at..].trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0i32;
    for (i, c) in rest.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

/// How one element's bytes give its value.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Unsigned,
    Signed,
    Float,
}

impl Kind {
    /// The value of one little-endian element of 1, 2, 4 or 8 bytes.
    fn value(self, e: &[u8]) -> f64 {
        let mut wide = [0u8; 8];
        wide[..e.len()].copy_from_slice(e);
        let bits = u64::from_le_bytes(wide);
        match (self, e.len()) {
            (Kind::Float, 4) => f64::from(f32::from_bits(bits as u32)),
            (Kind::Float, _) => f64::from_bits(bits),
            (Kind::Unsigned, _) => bits as f64,
            (Kind::Signed, n) => {
                // Sign-extend from n bytes.
                let shift = 64 - 8 * n as u32;
                ((bits << shift) as i64 >> shift) as f64
            }
        }
    }
}

/// The kind and size of NumPy type string `descr` (`<u8`, `|u1`, `<f4`), if this
/// reader knows it: little-endian or single-byte only.
fn element_type(descr: &str) -> Option<(Kind, usize)> {
    let mut chars = descr.chars();
    let order = chars.next()?;
    let kind = match chars.next()? {
        'u' => Kind::Unsigned,
        'i' => Kind::Signed,
        'f' => Kind::Float,
        _ => return None,
    };
    let size: usize = chars.as_str().parse().ok()?;
    let fits = match kind {
        Kind::Float => matches!(size, 4 | 8),
        _ => matches!(size, 1 | 2 | 4 | 8),
    };
    let order_ok = order == '<'
        || (order == '|' && size == 1)
        || (order == '=' && cfg!(target_endian = "little"));
    (fits && order_ok).then_some((kind, size))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The header's dict text: what follows the 10-byte preamble, up to the padding.
    const DICT_2X3_U8: &str = "{'descr': '<u8', 'fortran_order': False, 'shape': (2, 3), }";

    #[test]
    fn a_2x3_u64_array_has_the_spec_layout() {
        let data: [u64; 6] = [0, 1, 255, 256, 0x0102_0304_0506_0708, u64::MAX];
        let bytes = npy_bytes(2, 3, &data).unwrap();

        assert_eq!(&bytes[..6], b"\x93NUMPY");
        assert_eq!(&bytes[6..8], &[1, 0], "version 1.0");
        // 10 bytes of preamble + 59 of dict + padding + '\n' is 70 rounded up to the
        // next multiple of 64: 128, so the header (after the preamble) is 118 bytes.
        assert_eq!(DICT_2X3_U8.len(), 59);
        assert_eq!(&bytes[8..10], &118u16.to_le_bytes());
        let header = std::str::from_utf8(&bytes[10..128]).unwrap();
        let expected = format!("{DICT_2X3_U8}{}\n", " ".repeat(118 - 59 - 1));
        assert_eq!(header, expected);
        assert!(header.ends_with('\n'));

        let payload = &bytes[128..];
        assert_eq!(payload.len(), 6 * 8);
        assert_eq!(&payload[..8], &[0; 8]);
        assert_eq!(&payload[8..16], &[1, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(&payload[16..24], &[255, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(&payload[24..32], &[0, 1, 0, 0, 0, 0, 0, 0]);
        assert_eq!(&payload[32..40], &[8, 7, 6, 5, 4, 3, 2, 1], "little-endian");
        assert_eq!(&payload[40..48], &[0xff; 8]);
    }

    #[test]
    fn element_types_name_their_numpy_descr() {
        let f32_file = npy_bytes(1, 2, &[1.5f32, -2.0]).unwrap();
        let text = String::from_utf8_lossy(&f32_file[10..128]);
        assert!(text.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (1, 2), }"));
        assert_eq!(&f32_file[128..132], &[0x00, 0x00, 0xc0, 0x3f], "1.5f32");
        assert_eq!(&f32_file[132..136], &[0x00, 0x00, 0x00, 0xc0], "-2.0f32");

        let u8_file = npy_bytes(2, 2, &[1u8, 2, 3, 4]).unwrap();
        assert!(u8_file[10..].starts_with(b"{'descr': '|u1', "));
        assert_eq!(&u8_file[128..], &[1, 2, 3, 4]);

        assert_eq!(u32::DESCR, "<u4");
        assert_eq!(f64::DESCR, "<f8");
    }

    #[test]
    fn every_header_keeps_the_data_aligned() {
        for (rows, columns) in [(0, 0), (1, 1), (480, 640), (usize::MAX, 0)] {
            let len = rows * columns;
            let bytes = npy_bytes(rows, columns, &vec![0u32; len]).unwrap();
            let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
            let data_offset = PREAMBLE_LEN + header_len;
            assert_eq!(data_offset % 64, 0, "{rows} x {columns}");
            assert_eq!(bytes[data_offset - 1], b'\n');
            assert_eq!(bytes.len(), data_offset + len * 4);
        }
    }

    #[test]
    fn data_of_the_wrong_length_is_an_error() {
        assert_eq!(
            npy_bytes(2, 3, &[0u64; 5]),
            Err(NpyError::Shape {
                rows: 2,
                columns: 3,
                len: 5
            })
        );
        // rows * columns overflows: no length matches.
        assert!(npy_bytes(usize::MAX, 2, &[0u8; 2]).is_err());
    }

    #[test]
    fn what_is_written_reads_back() {
        let counts: [u64; 6] = [0, 1, 255, 256, 70_000, 1 << 40];
        let array = read_npy(&npy_bytes(2, 3, &counts).unwrap()).unwrap();
        assert_eq!((array.rows, array.columns), (2, 3));
        assert_eq!(
            array.values,
            [0.0, 1.0, 255.0, 256.0, 70_000.0, 1_099_511_627_776.0]
        );
        let depth = read_npy(&npy_bytes(1, 3, &[1u8, 5, 0]).unwrap()).unwrap();
        assert_eq!(depth.values, [1.0, 5.0, 0.0]);
        let nanos = read_npy(&npy_bytes(3, 1, &[7u32, 701, u32::MAX]).unwrap()).unwrap();
        assert_eq!(nanos.values, [7.0, 701.0, 4_294_967_295.0]);
        let floats = read_npy(&npy_bytes(1, 2, &[1.5f32, -2.0]).unwrap()).unwrap();
        assert_eq!(floats.values, [1.5, -2.0]);
        let empty = read_npy(&npy_bytes(0, 4, &[0f64; 0]).unwrap()).unwrap();
        assert_eq!((empty.rows, empty.columns, empty.values.len()), (0, 4, 0));
    }

    #[test]
    fn numpy_s_own_spelling_reads() {
        // As numpy 1.x writes np.array([[-1, 2]], dtype='<i2'): version 1.0, the
        // 10-byte preamble and the 59-byte dict padded to 128 bytes in all, ending in
        // a newline.
        let dict = "{'descr': '<i2', 'fortran_order': False, 'shape': (1, 2), }";
        let mut file = b"\x93NUMPY\x01\x00".to_vec();
        file.extend_from_slice(&118u16.to_le_bytes());
        file.extend_from_slice(dict.as_bytes());
        file.resize(127, b' ');
        file.push(b'\n');
        file.extend_from_slice(&(-1i16).to_le_bytes());
        file.extend_from_slice(&2i16.to_le_bytes());
        assert_eq!(read_npy(&file).unwrap().values, [-1.0, 2.0]);
    }

    #[test]
    fn files_this_reader_cannot_use_are_errors() {
        let good = npy_bytes(2, 2, &[1u32, 2, 3, 4]).unwrap();
        // Truncated data: the shape says four elements.
        assert!(matches!(
            read_npy(&good[..good.len() - 4]),
            Err(NpyError::Shape {
                rows: 2,
                columns: 2,
                len: 3
            })
        ));
        assert!(read_npy(b"not numpy at all").is_err());
        assert!(read_npy(&good[..20]).is_err());
        let swap = |from: &str, to: &str| {
            let text = String::from_utf8_lossy(&good).replacen(from, to, 1);
            read_npy(text.as_bytes())
        };
        assert!(swap("<u4", ">u4").is_err(), "big-endian");
        assert!(swap("<u4", "<c8").is_err(), "complex");
        assert!(swap("False", "True ").is_err(), "Fortran order");
        assert!(swap("(2, 2)", "(4,  )").is_err(), "one dimension");
    }
}
