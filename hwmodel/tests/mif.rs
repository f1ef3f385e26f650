//! The scene memory's MIF: round trip bit for bit, layout, hand-written files, errors.

use hwmodel::hw_scene::{HwKind, HwPrimitive, HwScene};
use hwmodel::mif::{MifError, decode_primitives, parse_mif, to_mif};

/// A sphere at (0.1, -2.7, 3) of radius 1.3 and a cylinder from (0, 0, 0) to
/// (1, 2, 2) (length 3, axis (1, 2, 2)/3) of radius 0.25.
const SCENE: &str = "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.01\n\
                     resolution 64 48\nl 5 5 -5\nf 1 1 1 1 0 1 0 1\n\
                     s 0.1 -2.7 3 1.3\nc\n0 0 0 0.25\n1 2 2 0.25\n";

fn scene() -> HwScene {
    let parsed = tracer::parse_nff(SCENE, "mif.nff").unwrap_or_else(|e| panic!("{e}"));
    HwScene::from_scene(&parsed).unwrap_or_else(|e| panic!("{e}"))
}

fn bits(p: &HwPrimitive) -> Vec<u32> {
    p.floats().iter().map(|f| f.to_bits()).collect()
}

#[test]
fn sphere_and_cylinder_round_trip_bit_for_bit() {
    let scene = scene();
    let text = to_mif(&scene);
    let words = parse_mif(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let decoded = decode_primitives(&words).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(decoded.len(), 2);
    for (got, want) in decoded.iter().zip(&scene.primitives) {
        assert_eq!(got.kind, want.kind);
        assert_eq!(bits(got), bits(want));
    }

    // Independent expectations: the values written in the scene and the hand geometry.
    let sphere = &decoded[0];
    assert_eq!(sphere.kind, HwKind::Sphere);
    assert_eq!(
        bits(sphere),
        [0.1f32, -2.7, 3.0, 1.3, 0.0, 0.0, 0.0, 0.0].map(f32::to_bits)
    );
    let cylinder = &decoded[1];
    assert_eq!(cylinder.kind, HwKind::Cylinder);
    assert_eq!(cylinder.center, [0.0, 0.0, 0.0]);
    assert_eq!(cylinder.radius, 0.25);
    let expected_axis = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    for (got, want) in cylinder.axis.iter().zip(expected_axis) {
        assert!((got - want).abs() < 1e-6, "axis {:?}", cylinder.axis);
    }
    assert!(
        (cylinder.m_max - 3.0).abs() < 1e-6,
        "m max {}",
        cylinder.m_max
    );

    // The type words sit at the ninth word of each primitive.
    assert_eq!((words[8], words[17]), (0, 1));
    // 0.1f32 is 0x3DCCCCCD: the first data line says so, with its comment.
    assert!(
        text.lines()
            .any(|l| l.contains(": 3DCCCCCD;") && l.contains("-- ") && l.contains("centre.x")),
        "{text}"
    );
}

#[test]
fn header_declares_nine_words_per_primitive() {
    let scene = scene();
    let text = to_mif(&scene);
    let n = scene.primitive_count();
    let declared = |key: &str| {
        text.lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .map(|v| v.trim_end_matches(';').to_string())
    };
    assert_eq!(declared("WIDTH="), Some("32".to_string()));
    assert_eq!(declared("DEPTH="), Some((9 * n).to_string()));
    assert_eq!(declared("ADDRESS_RADIX="), Some("HEX".to_string()));
    assert_eq!(declared("DATA_RADIX="), Some("HEX".to_string()));
    assert!(text.contains("CONTENT BEGIN") && text.trim_end().ends_with("END;"));
    // One data line per word, each with a trailing comment.
    let data: Vec<&str> = text
        .lines()
        .filter(|l| l.contains(" : ") && !l.trim_start().starts_with("--"))
        .collect();
    assert_eq!(data.len(), 9 * n);
    assert!(data.iter().all(|l| l.contains(";") && l.contains("--")));
    assert_eq!(parse_mif(&text).map(|w| w.len()), Ok(9 * n));
}

#[test]
fn hand_written_mif_with_ranges_and_comments_parses() {
    let text = "% a block comment\n  over two lines %\n\
                -- a line comment\n\
                WIDTH = 32;\n\
                DEPTH = 13;   -- words\n\
                ADDRESS_RADIX = HEX;\n\
                data_radix = hex;\n\
                CONTENT BEGIN\n\
                \t[0..8] : 3F800000;  -- nine ones\n\
                \t9 : 1;\n\
                \tA : DEADBEEF 12; % two consecutive words %\n\
                END;\n";
    let mut expected = vec![0x3F80_0000u32; 9];
    expected.extend([1, 0xDEAD_BEEF, 0x12, 0]);
    assert_eq!(parse_mif(text), Ok(expected));

    // Decimal data, binary addresses, narrow words.
    let text = "WIDTH=8; DEPTH=4; ADDRESS_RADIX=BIN; DATA_RADIX=UNS;\n\
                CONTENT BEGIN 0 : 255; [10..11] : 7; END;";
    assert_eq!(parse_mif(text), Ok(vec![255, 0, 7, 7]));
}

#[test]
fn malformed_mif_is_an_error_not_a_panic() {
    let header = "WIDTH=32;\nDEPTH=4;\nADDRESS_RADIX=HEX;\nDATA_RADIX=HEX;\n";
    let bad = [
        String::new(),
        format!("{header}CONTENT BEGIN\n0 : 1;\n"), // no END
        format!("{header}0 : 1;\nEND;\n"),          // no CONTENT BEGIN
        format!("{header}CONTENT BEGIN\n4 : 1;\nEND;\n"), // address past DEPTH
        format!("{header}CONTENT BEGIN\n0 : 1FFFFFFFF;\nEND;"), // wider than 32 bits
        format!("{header}CONTENT BEGIN\n0 : 12G4;\nEND;\n"), // not hex
        format!("{header}CONTENT BEGIN\n0 : -1;\nEND;\n"), // signed
        format!("{header}CONTENT BEGIN\n0 : ;\nEND;\n"), // no value
        format!("{header}CONTENT BEGIN\n0 1;\nEND;\n"), // no ':'
        format!("{header}CONTENT BEGIN\n[3..1] : 0;\nEND;\n"), // reversed range
        format!("{header}CONTENT BEGIN\n[0..1] : 1 2;\nEND;\n"), // range, two values
        format!("{header}CONTENT BEGIN\n3 : 1 2;\nEND;\n"), // runs past the end
        format!("{header}CONTENT BEGIN\n0 : 1\nEND;\n"), // missing ';'
        format!("{header}CONTENT BEGIN\n0 : 1;\nEND;\n1 : 2;"), // after END
        format!("{header}CONTENT BEGIN\n0 : 1; % open\nEND;\n"), // unterminated %
        "DEPTH=4;\nCONTENT BEGIN\n0 : 1;\nEND;\n".to_string(), // no WIDTH
        "WIDTH=33;\nDEPTH=4;\nCONTENT BEGIN\nEND;\n".to_string(),
        "WIDTH=32;\nDEPTH=99999999999;\nCONTENT BEGIN\nEND;\n".to_string(),
        "WIDTH=32;\nDEPTH=4;\nDATA_RADIX=FLOAT;\nCONTENT BEGIN\nEND;\n".to_string(),
        "WIDTH=32;\nDEPTH=4;\nSPEED=3;\nCONTENT BEGIN\nEND;\n".to_string(),
        "WIDTH=32;\nDEPTH=4;\nCONTENT BEGIN\n0 : 1;\nEND\n".to_string(),
    ];
    for text in &bad {
        assert!(
            matches!(parse_mif(text), Err(MifError::Syntax { .. })),
            "accepted:\n{text}"
        );
    }

    // Errors point at the offending line.
    let message = parse_mif(&format!("{header}CONTENT BEGIN\n0 : 1;\n7 : 2;\nEND;\n"))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(message.starts_with("line 7:"), "{message}");

    // Every truncation of a valid file is refused (none panics), short of its END;.
    let full = to_mif(&scene());
    let end = full.rfind("END;").unwrap_or(full.len()) + "END;".len();
    for (cut, _) in full.char_indices().filter(|&(i, _)| i < end) {
        assert!(parse_mif(&full[..cut]).is_err(), "accepted a cut at {cut}");
    }
}

#[test]
fn decoding_checks_whole_primitives_and_type_words() {
    assert_eq!(decode_primitives(&[]), Ok(vec![]));
    assert!(matches!(
        decode_primitives(&[0; 10]),
        Err(MifError::PartialPrimitive { words: 10, .. })
    ));
    let mut words = vec![0u32; 18];
    words[17] = 2;
    assert!(matches!(
        decode_primitives(&words),
        Err(MifError::BadType {
            index: 1,
            address: 17,
            value: 2
        })
    ));
}
