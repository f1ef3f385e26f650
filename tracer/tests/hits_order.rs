//! `tests.<kind>.hits` counts every test that finds an intersection inside the ray's
//! range, so it cannot depend on the order of the primitives in the file (before, a test
//! counted a hit only when nearer than the closest so far: two files with the same
//! spheres in swapped order gave 2,619 and 3,534).

use tracer::render_variant;
use tracer::{Count, Counts, RenderOptions, Sampling, ShadingMode, VariantSet, parse_nff};

/// Overlapping rows of spheres, cylinders, cones and polygons one behind the other, with
/// a mirror so that secondary rays query them too.
fn primitives() -> Vec<String> {
    let mut lines = Vec::new();
    for k in 0..6 {
        let z = 2.0 * k as f32;
        let x = 0.3 * k as f32 - 0.7;
        lines.push(format!("s {x} 0.2 {z} 1"));
        lines.push(format!("c\n{x} -1.5 {z} 0.4\n{} 1.5 {z} 0.4", x + 0.5));
        lines.push(format!(
            "c\n{} -1 {} 0.6\n{} 1 {} 0.1",
            -x,
            z + 1.0,
            -x,
            z + 1.0
        ));
        lines.push(format!(
            "p 3\n{} -1 {z}\n{} -1 {z}\n{} 1 {}",
            x - 1.0,
            x + 1.0,
            x,
            z + 0.5
        ));
    }
    lines
}

fn scene_text(primitives: &[String]) -> String {
    format!(
        "v\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 24 24\n\
         b 0.1 0.1 0.1\nl 3 4 -6\nf 0.8 0.6 0.4 0.7 0.3 10 0 1\n{}\n",
        primitives.join("\n")
    )
}

fn counts(text: &str, variant: &str) -> Counts {
    let scene = parse_nff(text, "hits.nff").unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions::new(24, 24, Sampling::PixelCenters, ShadingMode::Color);
    let variants = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
    render_variant::<Count>(&scene, &options, &variants, &|_| {})
        .unwrap_or_else(|e| panic!("{variant}: {e}"))
        .rendered
        .counts()
        .unwrap_or_else(|| panic!("a counted render has counts"))
}

#[test]
fn hits_are_the_same_whatever_the_order_of_the_primitives() {
    let forward = primitives();
    let mut reversed = forward.clone();
    reversed.reverse();
    // A second permutation: every other primitive first.
    let (even, odd): (Vec<_>, Vec<_>) = forward.iter().enumerate().partition(|(i, _)| i % 2 == 0);
    let interleaved: Vec<String> = odd
        .into_iter()
        .chain(even)
        .map(|(_, l)| l.clone())
        .collect();
    for variant in ["baseline", "simd"] {
        let base = counts(&scene_text(&forward), variant);
        let t = &base.tests;
        // Order matters here: each eye ray meets several primitives of a kind.
        assert!(
            t.sphere.hits > base.rays.primary_hit / 4,
            "{variant}: {t:?}"
        );
        assert!(
            t.polygon.hits > 0 && t.cylinder.hits > 0 && t.cone.hits > 0,
            "{t:?}"
        );
        for (name, order) in [("reversed", &reversed), ("interleaved", &interleaved)] {
            let other = counts(&scene_text(order), variant);
            let o = &other.tests;
            let pairs = [
                ("sphere", t.sphere.hits, o.sphere.hits),
                ("cylinder", t.cylinder.hits, o.cylinder.hits),
                ("cone", t.cone.hits, o.cone.hits),
                ("polygon", t.polygon.hits, o.polygon.hits),
                ("plane", t.plane.hits, o.plane.hits),
            ];
            for (kind, a, b) in pairs {
                assert_eq!(a, b, "{variant}, {name} order: {kind} hits {a} against {b}");
            }
            assert_eq!(base.rays, other.rays, "{variant}, {name} order: ray counts");
        }
    }
}
