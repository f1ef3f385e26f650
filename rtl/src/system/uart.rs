//! The serial scene upload: the byte stream the host sends and the loader
//! (`rtl/verilog/uart_scene_loader.v`) receives, as the thesis's GUI sent a scene to
//! the FPGA "via serial" (thesis 4, 5.4, 6.1.1). The thesis does not publish its
//! framing; this is rtprof's, and this module is its one home.
//!
//! On the line: 8N1 (a start bit, 8 data bits least significant first, no parity, a
//! stop bit), [`clocks_per_bit`] of the design's clock per bit. The stream, every word
//! little-endian (least significant byte first):
//!
//! | bytes | what |
//! |---|---|
//! | 4 | [`MAGIC`], `RTSC`: the loader hunts for it, so a stream can follow noise |
//! | 4 | H0: width \| height << 16 (must equal the frame memory's) |
//! | 4 | H1: primitives per unit c = ⌈n/K⌉ \| n << 16 (1 ≤ n ≤ the scene memory) |
//! | 4 | H2: background gray \| words per primitive << 8 (9, or 14 with rsqrt-free shading); bits 16–31 zero |
//! | 84 | H3 … H23: the frame vectors, x y z each, IEEE-754 bits ([`crate::sim::FRAME_VECTORS`] order) |
//! | 4·n·w | the scene memory's words, primitive by primitive, word by word (the MIF's order) |
//! | 4 | CRC-32 of every byte from H0 to the last memory word |
//!
//! The CRC is zlib's, PNG's and Ethernet's (reflected polynomial 0xEDB88320, initial
//! value and final XOR 0xFFFFFFFF; check value 0xCBF43926 for `123456789`): cheap in
//! hardware (an XOR network per byte, no carry chain) and computed here by
//! `crc32fast`, an implementation independent of the Verilog's.

use crate::RtlError;
use crate::generate::FIELDS;
use crate::sim::FrameSetup;

/// The stream's first four bytes.
pub const MAGIC: [u8; 4] = *b"RTSC";

/// Header words after the magic: H0, H1, H2 and the 21 vector words.
pub const HEADER_WORDS: usize = 24;

/// The thesis's clock (the DE2-115's 50 MHz oscillator).
pub const SYSTEM_CLOCK_HZ: u32 = 50_000_000;

/// The default line rate: 115,200 baud, the fastest standard rate common USB-serial
/// bridges and PC serial ports share (the thesis does not state its own).
pub const DEFAULT_BAUD: u32 = 115_200;

/// Clock cycles per bit for `baud` at `clock_hz`, rounded to the nearest (434 for
/// 115,200 baud at 50 MHz: 0.01 % fast). Errors when the rate is not within 2 % of
/// what the divider gives, or below the receiver's minimum of 4 cycles per bit.
pub fn clocks_per_bit(clock_hz: u32, baud: u32) -> Result<u32, RtlError> {
    if baud == 0 {
        return Err(RtlError::Generate("a UART rate of 0 baud".into()));
    }
    let cycles = (u64::from(clock_hz) + u64::from(baud) / 2) / u64::from(baud);
    let actual = f64::from(clock_hz) / cycles.max(1) as f64;
    let error = (actual - f64::from(baud)).abs() / f64::from(baud);
    if cycles < 4 || error > 0.02 {
        return Err(RtlError::Generate(format!(
            "{baud} baud at {clock_hz} Hz: {cycles} cycles per bit is {:.1} % off (at least 4 cycles, within 2 %)",
            error * 100.0
        )));
    }
    u32::try_from(cycles).map_err(|_| RtlError::Generate(format!("{cycles} cycles per bit")))
}

fn too_big(what: &str, value: u32, limit: u32) -> RtlError {
    RtlError::Generate(format!(
        "scene upload: {what} {value} does not fit (at most {limit})"
    ))
}

/// The header words H0 … H23 of `setup`.
pub fn header_words(setup: &FrameSetup) -> Result<[u32; HEADER_WORDS], RtlError> {
    let sixteen = |what: &str, v: u32| {
        if v > 0xFFFF {
            Err(too_big(what, v, 0xFFFF))
        } else {
            Ok(v)
        }
    };
    let fields = words_per_primitive(setup)?;
    let mut words = [0u32; HEADER_WORDS];
    words[0] = sixteen("width", setup.width)? | sixteen("height", setup.height)? << 16;
    words[1] =
        sixteen("per_unit", setup.per_unit)? | sixteen("prim_count", setup.prim_count)? << 16;
    words[2] = u32::from(setup.background) | fields << 8;
    for (slot, value) in words[3..].iter_mut().zip(setup.vectors.iter().flatten()) {
        *slot = value.to_bits();
    }
    Ok(words)
}

/// Words per primitive in `setup` (the same for every primitive, at most the RTL's
/// [`FIELDS`]).
pub fn words_per_primitive(setup: &FrameSetup) -> Result<u32, RtlError> {
    let first = setup.words.first().map_or(0, Vec::len);
    if setup.words.iter().any(|w| w.len() != first) {
        return Err(RtlError::Generate(
            "scene upload: primitives with different numbers of words".into(),
        ));
    }
    let first = u32::try_from(first).unwrap_or(u32::MAX);
    if first == 0 || first > FIELDS {
        return Err(too_big("words per primitive", first, FIELDS));
    }
    Ok(first)
}

/// The stream that uploads `setup` (see the module doc).
pub fn scene_stream(setup: &FrameSetup) -> Result<Vec<u8>, RtlError> {
    if setup.words.len() != setup.prim_count as usize {
        return Err(RtlError::Generate(format!(
            "scene upload: {} primitives' words for prim_count {}",
            setup.words.len(),
            setup.prim_count
        )));
    }
    let header = header_words(setup)?;
    let mut body = Vec::with_capacity(4 * (HEADER_WORDS + setup.words.len() * 14));
    for word in header.iter().chain(setup.words.iter().flatten()) {
        body.extend_from_slice(&word.to_le_bytes());
    }
    let crc = crc32fast::hash(&body);
    let mut stream = Vec::with_capacity(body.len() + 8);
    stream.extend_from_slice(&MAGIC);
    stream.extend_from_slice(&body);
    stream.extend_from_slice(&crc.to_le_bytes());
    Ok(stream)
}

/// Bytes of the stream that uploads `primitives` of `words_per_primitive` words: the
/// magic, the header, the words and the CRC, four bytes each ([`scene_stream`]).
pub fn stream_bytes(primitives: u64, words_per_primitive: u32) -> u64 {
    4 + 4 * (HEADER_WORDS as u64 + u64::from(words_per_primitive) * primitives + 1)
}

/// Seconds the stream takes on the line at `baud` (10 bits a byte, back to back).
pub fn upload_seconds(bytes: usize, baud: u32) -> f64 {
    bytes as f64 * 10.0 / f64::from(baud)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> FrameSetup {
        FrameSetup {
            width: 0x0280,
            height: 0x01E0,
            per_unit: 3,
            prim_count: 1,
            background: 0x33,
            vectors: [[1.0, -2.0, 0.5]; 7],
            words: vec![(0..9).map(|i| 0x1122_3300 + i).collect()],
        }
    }

    #[test]
    fn the_stream_is_the_documented_bytes() {
        let s = scene_stream(&setup()).unwrap();
        // Magic, header, 9 memory words, CRC.
        assert_eq!(s.len(), 4 + 4 * 24 + 4 * 9 + 4);
        assert_eq!(&s[0..4], b"RTSC");
        // H0: 640 | 480 << 16 = 0x01E0_0280, least significant byte first.
        assert_eq!(&s[4..8], &[0x80, 0x02, 0xE0, 0x01]);
        // H1: c = 3, n = 1.
        assert_eq!(&s[8..12], &[3, 0, 1, 0]);
        // H2: background 0x33, 9 words per primitive.
        assert_eq!(&s[12..16], &[0x33, 9, 0, 0]);
        // H3 … H5: 1.0 = 0x3F800000, -2.0 = 0xC0000000, 0.5 = 0x3F000000.
        assert_eq!(&s[16..20], &[0x00, 0x00, 0x80, 0x3F]);
        assert_eq!(&s[20..24], &[0x00, 0x00, 0x00, 0xC0]);
        assert_eq!(&s[24..28], &[0x00, 0x00, 0x00, 0x3F]);
        // The last vector word (light_dir z = 0.5) ends the header at byte 100.
        assert_eq!(&s[96..100], &[0x00, 0x00, 0x00, 0x3F]);
        // Memory word 0 = 0x11223300, word 8 = 0x11223308.
        assert_eq!(&s[100..104], &[0x00, 0x33, 0x22, 0x11]);
        assert_eq!(&s[132..136], &[0x08, 0x33, 0x22, 0x11]);
    }

    #[test]
    fn the_crc_is_zlibs_over_header_and_memory() {
        // The standard check value of CRC-32/ISO-HDLC.
        assert_eq!(crc32fast::hash(b"123456789"), 0xCBF4_3926);
        let s = scene_stream(&setup()).unwrap();
        let n = s.len();
        let crc = u32::from_le_bytes([s[n - 4], s[n - 3], s[n - 2], s[n - 1]]);
        assert_eq!(crc, crc32fast::hash(&s[4..n - 4]));
        // One bit changed anywhere in the body changes it.
        let mut t = s.clone();
        t[57] ^= 0x10;
        assert_ne!(crc, crc32fast::hash(&t[4..n - 4]));
    }

    #[test]
    fn what_the_registers_cannot_hold_is_refused() {
        let mut s = setup();
        s.width = 70_000;
        assert!(scene_stream(&s).is_err());
        let mut s = setup();
        s.words[0].push(0);
        s.words.push(vec![0; 9]);
        s.prim_count = 2;
        assert!(scene_stream(&s).is_err(), "uneven words per primitive");
        let mut s = setup();
        s.prim_count = 2;
        assert!(scene_stream(&s).is_err(), "prim_count without its words");
    }

    #[test]
    fn the_bit_rate_divider_rounds_and_refuses_what_it_cannot_reach() {
        assert_eq!(clocks_per_bit(SYSTEM_CLOCK_HZ, DEFAULT_BAUD).unwrap(), 434);
        assert_eq!(clocks_per_bit(50_000_000, 9_600).unwrap(), 5_208);
        assert!(clocks_per_bit(50_000_000, 0).is_err());
        assert!(clocks_per_bit(100, 40).is_err(), "2.5 cycles per bit");
        // 14.7456 MHz / 4,000,000 baud = 3.69: 4 cycles is 7.8 % slow.
        assert!(clocks_per_bit(14_745_600, 4_000_000).is_err());
    }

    #[test]
    fn the_stream_size_is_the_framing_s_formula() {
        // both7's upload (docs/rtl-system.md): 4 + 4 · (24 + 9 · 7 + 1) = 356 bytes,
        // 356 · 10 / 115,200 = 30.9 ms.
        assert_eq!(stream_bytes(7, 9), 356);
        assert!((upload_seconds(356, DEFAULT_BAUD) - 0.030903).abs() < 1e-6);
        let s = setup();
        let words = words_per_primitive(&s).unwrap();
        assert_eq!(
            scene_stream(&s).unwrap().len() as u64,
            stream_bytes(u64::from(s.prim_count), words)
        );
    }
}
