//! The NFF parser's tests: every entity, every malformed input named by file and line, the limits.

use super::*;

const VIEW: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 64 48\n";

fn parse(body: &str) -> Result<Scene, NffError> {
    parse_nff(&format!("{VIEW}{body}"), "t.nff")
}

fn err_line(body: &str) -> (usize, String) {
    match parse(body) {
        Ok(_) => panic!("expected an error for {body:?}"),
        Err(e) => (e.line, e.message),
    }
}

#[test]
fn parses_every_entity_with_comments_tabs_and_crlf() {
    let text = "# header comment\r\nb 0.1 0.2 0.3\r\nv\r\nfrom\t0 0 -5\r\nat 0 0 0\r\nup 0 1 0\r\nangle 45\r\nhither 1\r\nresolution 32 16\r\n\r\n\
                    l 1 2 3\r\nl 4 5 6 0.5 0.5 0.5 # coloured\r\nf 1 0 0 0.8 0.2 10 0 1\r\ns 0 0 0 1\r\nc\r\n0 0 0 1\r\n0 1 0 1\r\nc 0 0 0 1 0 1 0 0.5\r\n\
                    f 0 1 0 0.5 0.5 3 0.5 1.5\r\np 3\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\npp 3\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n\r\n0 1 0 0 0 1\r\n";
    let scene = parse_nff(text, "crlf.nff").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((scene.view.width, scene.view.height), (32, 16));
    assert_eq!(scene.view.hither, 1.0);
    assert_eq!(scene.background, Rgb::new(0.1, 0.2, 0.3));
    assert_eq!(scene.lights.len(), 2);
    // One light without colour out of two: sqrt(2)/4 each.
    assert!((scene.lights[0].color.r - 2f32.sqrt() / 4.0).abs() < 1e-6);
    assert_eq!(scene.lights[1].color, Rgb::gray(0.5));
    assert_eq!(
        (
            scene.spheres.len(),
            scene.cylinders.len(),
            scene.cones.len()
        ),
        (1, 1, 1)
    );
    assert_eq!((scene.polygons.len(), scene.patches.len()), (1, 1));
    assert_eq!(scene.materials.len(), 2);
    assert_eq!(scene.polygons[0].material, 1);
    assert_eq!(scene.spheres[0].material, 0);
    assert_eq!(scene.materials[1].ior, 1.5);
}

#[test]
fn malformed_inputs_name_the_line_and_the_expectation() {
    let cases: &[(&str, usize, &str)] = &[
        ("s 0 0 0\n", 8, "expected 4 numbers"),
        ("s 0 0 zero 1\n", 8, "'zero' is not a number"),
        ("s 0 0 nan 1\n", 8, "not a finite number"),
        ("s 0 0 inf 1\n", 8, "not a finite number"),
        ("s 0 0 1e40 1\n", 8, "not a finite number"),
        ("sphere 0 0 0 1\n", 8, "unknown keyword 'sphere'"),
        ("p 2\n0 0 0\n1 0 0\n", 8, "at least 3 vertices"),
        ("p 3\n0 0 0\n1 1 1\n2 2 2\n", 8, "collinear"),
        ("p 3\n0 0 0\n1 0 0\n", 10, "unexpected end of file"),
        ("p 4000000000\n", 8, "exceeds the limit"),
        ("p three\n", 8, "not a whole number"),
        ("c\n1 1 1 0.5\n1 1 1 0.5\n", 8, "zero-length axis"),
        ("c\n1 1 1 0.5\n", 9, "cone apex"),
        ("c 1 1 1 0.5 2 2 2\n", 8, "expected 8 numbers"),
        (
            "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n",
            8,
            "zero length",
        ),
        ("l 1 2\n", 8, "expected 3 numbers"),
        ("f 1 1 1 1 0 0 0\n", 8, "expected 8 numbers"),
        (
            "f 1 1 1 1 0 0 0.5 0\n",
            8,
            "index of refraction 0 of a transmitting material (T = 0.5) must lie between 0.01 and 100",
        ),
        ("f 1 1 1 1 0 0 0.5 5e18\n", 8, "index of refraction 5e18"),
        (
            "f 1 1 1 1 0 0 0.5 0.001\n",
            8,
            "must lie between 0.01 and 100",
        ),
        ("f 1 1 1 1 0 0 0 0\nq\n", 9, "unknown keyword 'q'"),
        ("b 1 1\n", 8, "background"),
        (
            "b 0 -0.5 0\n",
            8,
            "background colour channel -0.5 must lie between 0 and 1000",
        ),
        ("l 0 0 0 1 1 2000\n", 8, "light colour channel 2000"),
        ("f 1 1 1 1 1e19 20 0 1\n", 8, "specular coefficient Ks 1e19"),
        ("f 1 1 1 -1 0 20 0 1\n", 8, "diffuse coefficient Kd -1"),
        ("f 1 1 1 1 0 20 1001 1\n", 8, "transmittance T 1001"),
        ("f 1 1e30 1 1 0 20 0 1\n", 8, "material colour channel"),
        ("f 1 1 1 1 0.5 -2 0 1\n", 8, "Shine -2 must not be negative"),
        (
            "s 0 0 1e10 1\n",
            8,
            "1e10 is beyond the supported coordinate range ±1e9",
        ),
        (
            "s 0 0 0 -2e9\n",
            8,
            "-2e9 is beyond the supported coordinate range",
        ),
        ("l 3e38 0 0\n", 8, "3e38 is beyond"),
        (
            "l 0 0 0 1 x 1\n",
            8,
            "'x' is not a number (expected light colour r g b)",
        ),
        ("l 0 -1e20 0 1 1 1\n", 8, "-1e20 is beyond"),
        ("c\n0 0 0 1\n0 0 1e12 1\n", 10, "1e12 is beyond"),
        ("p 3\n0 0 0\n1 0 0\n0 1.1e9 0\n", 11, "1.1e9 is beyond"),
        ("pp 3\n0 0 0 0 0 1e30\n", 9, "1e30 is beyond"),
    ];
    for (body, line, needle) in cases {
        let (got_line, message) = err_line(body);
        assert_eq!(got_line, *line, "{body:?}: {message}");
        assert!(
            message.contains(needle),
            "{body:?}: '{message}' lacks '{needle}'"
        );
    }
}

#[test]
fn geometry_spanning_the_coordinate_range_keeps_finite_normals() {
    // The largest edges the range admits: their cross product's squared length
    // (the degeneracy test) must not overflow to infinity and reject the polygon.
    let scene = parse("p 3\n-1e9 -1e9 -1e9\n1e9 -1e9 1e9\n-1e9 1e9 1e9\nl 1e9 1e9 -1e9\n")
        .unwrap_or_else(|e| panic!("{e}"));
    let n = scene.polygons[0].normal().to_array();
    let length: f32 = n.iter().map(|v| v * v).sum();
    assert!((length - 1.0).abs() < 1e-6, "{n:?}");
    // (2,0,2) × (0,2,2) = (-4,-4,4): the unit normal is (-1,-1,1)/√3.
    let s = 1.0 / 3f32.sqrt();
    assert!(
        n.iter().zip([-s, -s, s]).all(|(a, b)| (a - b).abs() < 1e-6),
        "{n:?}"
    );
}

#[test]
fn view_block_errors() {
    let cases: &[(&str, usize, &str)] = &[
        ("s 0 0 0 1\n", 1, "no view block"),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution 0 10\n",
            6,
            "must be positive",
        ),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution 100000000 100000000\n",
            6,
            "exceeds the limit",
        ),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution -5 10\n",
            6,
            "must be positive",
        ),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution 1.5 10\n",
            6,
            "not a whole number",
        ),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 0\nresolution 8 8\n",
            5,
            "between 0 and 180",
        ),
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 0 2\nangle 45\nresolution 8 8\n",
            1,
            "parallel",
        ),
        (
            "v\nfrom 1 1 1\nat 1 1 1\nup 0 0 1\nangle 45\nresolution 8 8\n",
            1,
            "same point",
        ),
        (
            "v\nfrom 0 0 0\nup 0 1 0\nangle 45\nresolution 8 8\n",
            1,
            "no 'at' line",
        ),
        ("v\nfrom 0 0 0\nfrom 0 0 0\n", 3, "given twice"),
        (
            "v\nfrom 1e30 0 -10\nat -1e30 0 0\nup 0 1 0\nangle 40\nresolution 8 8\n",
            2,
            "1e30 is beyond the supported coordinate range",
        ),
        ("v\nfrom 0 0 0\nat 0 0 1\nup 0 2e9 0\n", 4, "2e9 is beyond"),
    ];
    for (text, line, needle) in cases {
        match parse_nff(text, "v.nff") {
            Ok(_) => panic!("expected an error for {text:?}"),
            Err(e) => {
                assert_eq!(e.line, *line, "{text:?}: {e}");
                assert!(
                    e.message.contains(needle),
                    "{text:?}: '{}' lacks '{needle}'",
                    e.message
                );
                assert!(e.to_string().starts_with(&format!("v.nff:{line}: ")));
            }
        }
    }
}

#[test]
fn second_view_block_is_an_error() {
    let (line, message) = err_line(VIEW);
    assert_eq!(line, 8);
    assert!(message.contains("second view block"), "{message}");
}

#[test]
fn utf8_errors_report_their_line() {
    let dir = std::env::temp_dir().join(format!("rtprof-nff-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("bin.nff");
    std::fs::write(&path, b"v\nfrom 0 0 0\n\xff\xfe\n").unwrap_or_else(|e| panic!("{e}"));
    match load_nff(&path) {
        Err(LoadError::Parse(e)) => assert_eq!(e.line, 3, "{e}"),
        other => panic!("unexpected {other:?}"),
    }
    assert!(matches!(
        load_nff(&dir.join("missing.nff")),
        Err(LoadError::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}
