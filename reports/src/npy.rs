//! Two-dimensional arrays as NumPy `.npy` files (format version 1.0), so that the
//! per-pixel counter maps open with `numpy.load` for analysis outside rtprof.
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
}
