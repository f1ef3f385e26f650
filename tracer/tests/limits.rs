//! The size limits of [`tracer::Limits`]: each refuses input just over it with an error
//! that names the limit, and accepts input exactly at it. Numbers are worked out by hand.

use tracer::nff::{load_nff_with_limits, parse_nff_with_limits};
use tracer::{
    BruteForce, Count, Limits, LoadError, NffError, RenderError, RenderOptions, Sampling, Scene,
    ShadingMode, parse_nff,
};

/// A view block of `w` x `h` pixels: 7 lines.
fn view(w: u32, h: u32) -> String {
    format!("v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\nresolution {w} {h}\n")
}

fn parse_with(text: &str, limits: &Limits) -> Result<Scene, NffError> {
    parse_nff_with_limits(text, "limits.nff", limits)
}

fn expect_error(result: Result<Scene, NffError>, line: usize, needles: &[&str]) {
    match result {
        Ok(_) => panic!("expected an error at line {line}"),
        Err(e) => {
            assert_eq!(e.line, line, "{e}");
            for needle in needles {
                assert!(e.message.contains(needle), "'{e}' lacks '{needle}'");
            }
        }
    }
}

#[test]
fn defaults_are_the_documented_values() {
    let d = Limits::default();
    assert_eq!(d.max_side, 16_384);
    assert_eq!(d.max_pixels, 64 * 1024 * 1024);
    assert_eq!(d.max_framebuffer_bytes, 1 << 30);
    assert_eq!(d.max_polygon_vertices, 65_536);
    assert_eq!(d.max_primitives, 10_000_000);
    assert_eq!(d.max_ray_depth, 64);
    assert_eq!(d.max_file_bytes, 1 << 30);
    // The framebuffer holds one f32 RGB triple per pixel.
    assert_eq!(Limits::FRAMEBUFFER_BYTES_PER_PIXEL, 12);
}

#[test]
fn image_side_limit() {
    let limits = Limits {
        max_side: 8,
        ..Limits::default()
    };
    assert!(parse_with(&view(8, 8), &limits).is_ok());
    // The resolution is line 7 of the view block.
    expect_error(
        parse_with(&view(9, 1), &limits),
        7,
        &["9x1", "8 pixels per side", "max_side"],
    );
    expect_error(
        parse_with(&view(1, 9), &limits),
        7,
        &["8 pixels per side", "max_side"],
    );
}

#[test]
fn image_pixel_limit() {
    let limits = Limits {
        max_pixels: 20,
        ..Limits::default()
    };
    // 5 x 4 = 20 pixels: at the limit; 7 x 3 = 21: over.
    assert!(parse_with(&view(5, 4), &limits).is_ok());
    expect_error(
        parse_with(&view(7, 3), &limits),
        7,
        &["21 pixels", "limit of 20 pixels", "max_pixels"],
    );
}

#[test]
fn framebuffer_byte_limit() {
    let limits = Limits {
        max_framebuffer_bytes: 240,
        ..Limits::default()
    };
    // 5 x 4 pixels x 12 bytes = 240 bytes: at the limit; 7 x 3 x 12 = 252: over.
    assert!(limits.check_size(5, 4).is_ok());
    let error = limits.check_size(7, 3).err();
    assert_eq!(
        error.as_ref().and_then(|e| e.limit),
        Some(tracer::Limit::MaxFramebufferBytes)
    );
    let message = error.map(|e| e.to_string()).unwrap_or_default();
    assert!(
        message.contains("252 bytes") && message.contains("limit of 240 bytes"),
        "{message}"
    );
    assert!(message.contains("max_framebuffer_bytes"), "{message}");
    expect_error(parse_with(&view(7, 3), &limits), 7, &["252 bytes"]);
}

#[test]
fn render_checks_its_own_limits_before_allocating() {
    let scene =
        parse_nff(&format!("{}s 0 0 0 1\n", view(4, 3)), "r.nff").unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let mut options = RenderOptions::new(4, 3, Sampling::PixelCenters, ShadingMode::Color);
    // 4 x 3 = 12 pixels, 144 bytes.
    options.limits.max_pixels = 12;
    options.limits.max_framebuffer_bytes = 144;
    assert!(
        tracer::render::<Count, _>(
            &scene,
            &accel,
            &options,
            &tracer::RenderMethod::default(),
            &|_| {}
        )
        .is_ok()
    );
    options.width = 5;
    match tracer::render::<Count, _>(
        &scene,
        &accel,
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    ) {
        Err(RenderError::Size(e)) => assert_eq!(e.limit, Some(tracer::Limit::MaxPixels), "{e}"),
        other => panic!("expected a size error, got {:?}", other.map(|_| ())),
    }
    options.width = 4;
    options.limits.max_framebuffer_bytes = 143;
    match tracer::render::<Count, _>(
        &scene,
        &accel,
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    ) {
        Err(RenderError::Size(e)) => assert!(e.to_string().contains("144 bytes"), "{e}"),
        other => panic!("expected a size error, got {:?}", other.map(|_| ())),
    }
}

#[test]
fn polygon_vertex_limit() {
    let limits = Limits {
        max_polygon_vertices: 4,
        ..Limits::default()
    };
    let square = "p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    let pentagon = "p 5\n0 0 0\n1 0 0\n1 1 0\n0.5 1.5 0\n0 1 0\n";
    assert!(parse_with(&format!("{}{square}", view(4, 4)), &limits).is_ok());
    // The `p 5` line is line 8, right after the view block.
    expect_error(
        parse_with(&format!("{}{pentagon}", view(4, 4)), &limits),
        8,
        &["vertex count 5", "limit of 4", "max_polygon_vertices"],
    );
}

#[test]
fn primitive_limit() {
    let limits = Limits {
        max_primitives: 3,
        ..Limits::default()
    };
    let three = "s 0 0 0 1\nc 0 0 0 1 0 1 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n";
    let scene =
        parse_with(&format!("{}{three}", view(4, 4)), &limits).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.primitive_count(), 3);
    // A fourth primitive (a patch) on line 8 + 6 = 14 is refused on its own line,
    // before its vertex lines are read.
    let four = format!(
        "{}{three}pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n",
        view(4, 4)
    );
    expect_error(
        parse_with(&four, &limits),
        14,
        &["limit of 3 primitives", "max_primitives"],
    );
    // Every kind counts: four spheres, the fourth on line 11.
    let spheres = format!("{}{}", view(4, 4), "s 0 0 0 1\n".repeat(4));
    expect_error(parse_with(&spheres, &limits), 11, &["max_primitives"]);
}

#[test]
fn ray_depth_limit() {
    let scene =
        parse_nff(&format!("{}s 0 0 0 1\n", view(2, 2)), "d.nff").unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let mut options = RenderOptions::new(2, 2, Sampling::PixelCenters, ShadingMode::Color);
    assert_eq!(options.max_depth, tracer::MAX_DEPTH);
    options.limits.max_ray_depth = 8;
    options.max_depth = 8;
    assert!(
        tracer::render::<Count, _>(
            &scene,
            &accel,
            &options,
            &tracer::RenderMethod::default(),
            &|_| {}
        )
        .is_ok()
    );
    for (depth, needle) in [(9, "max_ray_depth"), (0, "at least 1")] {
        options.max_depth = depth;
        match tracer::render::<Count, _>(
            &scene,
            &accel,
            &options,
            &tracer::RenderMethod::default(),
            &|_| {},
        ) {
            Err(RenderError::Depth(e)) => assert!(e.to_string().contains(needle), "{e}"),
            other => panic!(
                "depth {depth}: expected an error, got {:?}",
                other.map(|_| ())
            ),
        }
    }
}

/// Reflection rays of one eye ray between two parallel mirrors: every reflection ray
/// hits the other mirror, so the tree is a chain of `max_depth - 1` reflection rays.
#[test]
fn max_depth_bounds_the_ray_tree_up_to_the_default_ceiling() {
    let mirrors = format!(
        "{}f 1 1 1 0.5 0.5 10 0 1\n\
         p 4\n-10 -10 5\n10 -10 5\n10 10 5\n-10 10 5\n\
         p 4\n-10 -10 -10\n10 -10 -10\n10 10 -10\n-10 10 -10\n",
        view(1, 1)
    );
    let scene = parse_nff(&mirrors, "mirrors.nff").unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(&scene);
    let mut options = RenderOptions::new(1, 1, Sampling::PixelCenters, ShadingMode::Color);
    let ceiling = Limits::default().max_ray_depth;
    for (depth, reflections) in [(1, 0), (2, 1), (5, 4), (ceiling, u64::from(ceiling) - 1)] {
        options.max_depth = depth;
        let out = tracer::render::<Count, _>(
            &scene,
            &accel,
            &options,
            &tracer::RenderMethod::default(),
            &|_| {},
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(out.rays.primary_hit, 1);
        assert_eq!(out.rays.reflection, reflections, "max depth {depth}");
        assert!(out.frame.is_finite());
    }
}

#[test]
fn file_size_limit_is_checked_before_reading() {
    let dir = std::env::temp_dir().join(format!("rtprof-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("small.nff");
    let text = format!("{}s 0 0 0 1\n", view(4, 4));
    // 2 + 12 + 9 + 9 + 9 + 9 + 15 lines of the view block, 10 for the sphere: 75 bytes.
    assert_eq!(text.len(), 75);
    std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
    let at_limit = Limits {
        max_file_bytes: 75,
        ..Limits::default()
    };
    assert!(load_nff_with_limits(&path, &at_limit).is_ok());
    let below = Limits {
        max_file_bytes: 74,
        ..Limits::default()
    };
    match load_nff_with_limits(&path, &below) {
        Err(e @ LoadError::TooLarge { .. }) => {
            let m = e.to_string();
            assert!(
                m.contains("75 bytes") && m.contains("limit of 74 bytes"),
                "{m}"
            );
            assert!(
                m.contains("max_file_bytes") && m.contains("small.nff"),
                "{m}"
            );
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    // Text handed to the parser directly obeys the same limit.
    expect_error(parse_with(&text, &below), 1, &["max_file_bytes"]);
    assert!(parse_with(&text, &at_limit).is_ok());
    std::fs::remove_dir_all(&dir).ok();
}
