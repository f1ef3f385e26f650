//! The sample's consistency: the figures it claims agree with each other and with the schema.

use super::*;

#[test]
fn sample_variant_names_are_tracer_variants() {
    for v in SAMPLE_VARIANTS {
        assert_eq!(variant_name(v).as_str(), v);
    }
}

#[test]
fn sample_is_consistent_and_round_trips() {
    let r = sample_results();
    assert!(r.scenes.len() >= 6);
    for scene in &r.scenes {
        let base = r.baseline(scene).expect("baseline");
        for v in &scene.variants {
            assert_eq!(v.histogram.len(), 256);
            let sum: u64 = v.histogram.iter().sum();
            assert_eq!(sum, u64::from(scene.width) * u64::from(scene.height));
            let ratio = base.time.median / v.time.median;
            assert!(
                v.speedup.is_some_and(|s| (ratio - s).abs() < 1e-9),
                "{}/{}",
                scene.name,
                v.variant
            );
            assert!(v.time.low <= v.time.median && v.time.median <= v.time.high);
            assert_eq!(v.quality.is_none(), v.variant.is_reference());
        }
        assert_eq!(scene.hardware.is_none(), scene.spd);
    }
    // Without serde_json's `float_roundtrip` feature a float may come back one ulp
    // off: integers and strings must match exactly, floats to 1e-12.
    let text = serde_json::to_string(&r).expect("serialize");
    let back = Results::from_json(&text).expect("parse");
    assert_eq!(back.scenes.len(), r.scenes.len());
    for (a, b) in r.scenes.iter().zip(&back.scenes) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.hardware.is_some(), b.hardware.is_some());
        for (x, y) in a.variants.iter().zip(&b.variants) {
            assert!(x.counts == y.counts && x.histogram == y.histogram && x.image == y.image);
            assert!((x.time.median - y.time.median).abs() <= 1e-12 * x.time.median.abs());
        }
    }
    assert!(back.failures == r.failures && back.machine == r.machine);
    let models = |r: &Results| -> Vec<results::HwFigures> {
        r.hardware
            .iter()
            .flat_map(|h| h.ops.iter().chain(&h.blocks))
            .map(|row| row.model)
            .collect()
    };
    assert_eq!(models(&back), models(&r));
}

#[test]
fn the_machine_figures_are_consistent() {
    let r = sample_results();
    let peak = r.peak.as_ref().expect("peak");
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    for scene in &r.scenes {
        for v in &scene.variants {
            let e = v.efficiency.as_ref().expect("efficiency");
            assert!(close(
                e.achieved_gflops,
                e.flops as f64 / v.time.median / 1e9
            ));
            assert!(close(
                e.arithmetic_intensity,
                e.flops as f64 / e.bytes_moved as f64
            ));
            let roof = peak
                .roof(CodeKind::of_variant(&v.variant), e.arithmetic_intensity)
                .gflops;
            assert_eq!(e.roof_gflops, Some(roof));
            let fraction = e.fraction_of_roof.expect("fraction");
            assert!(fraction < 0.8, "{}/{}: {fraction}", scene.name, v.variant);
            let rates = v.ray_rates.as_ref().expect("ray rates");
            let sum = rates.eye_fraction
                + rates.secondary_fraction
                + rates.shadow_fraction
                + rates.other_fraction;
            assert!(close(sum, 1.0), "{sum}");
            assert_eq!(v.lane_utilization.is_some(), v.variant == "simd");
        }
        for tree in &scene.bvh_quality {
            assert_eq!(tree.depth_histogram.iter().sum::<u64>(), tree.leaves);
            assert_eq!(tree.leaf_size_histogram.iter().sum::<u64>(), tree.leaves);
            assert_eq!(tree.depth_histogram.len(), tree.max_depth as usize + 1);
        }
        for maps in &scene.pixel_maps {
            let v = scene
                .variants
                .iter()
                .find(|v| v.variant == maps.variant)
                .expect("the variant of the maps");
            for m in maps.maps.iter().filter(|m| m.key.starts_with("tests.")) {
                assert_eq!(Some(&m.sum), v.counts.get(&m.key));
                assert!(
                    m.min as f64 <= m.mean && m.mean <= m.max as f64,
                    "{}",
                    m.key
                );
            }
        }
    }
    let rings = r.scenes.iter().find(|s| s.name == "rings").expect("rings");
    assert_eq!(rings.bvh_quality.len(), 2);
    assert_eq!(rings.pixel_maps.len(), 3);
}
