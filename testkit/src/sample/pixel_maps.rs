//! The sample's per-pixel maps of `rings`: each map sums to its variant's count.

use super::scene_spec::SceneSpec;
use results::{PixelMap, VariantPixelMaps, VariantResult};

/// The variants whose per-pixel maps the sample has.
const MAPPED_VARIANTS: [&str; 3] = ["baseline", "bvh", "simd"];

/// The per-pixel maps of the variants of [`MAPPED_VARIANTS`] on an SPD scene (pixel
/// centres, one sample a pixel): each map sums to the variant's count, its files named
/// as the runner names them (not written).
pub(super) fn sample_pixel_maps(
    s: &SceneSpec,
    variants: &[VariantResult],
) -> Vec<VariantPixelMaps> {
    if !s.is_spd() {
        return Vec::new();
    }
    let samples = s.pixels();
    let lights = 3;
    variants
        .iter()
        .filter(|v| MAPPED_VARIANTS.contains(&v.variant.as_str()))
        .map(|v| {
            let get = |k: &str| v.counts.get(k).copied().unwrap_or(0);
            let tree = get("accel.nodes_visited") > 0;
            let map =
                |key: &str, description: &str, unit: &str, sum: u64, range: (u64, u64)| PixelMap {
                    key: key.to_string(),
                    description: description.to_string(),
                    unit: unit.to_string(),
                    npy: format!("{key}.npy"),
                    png: format!("{key}.png"),
                    dtype: match key {
                        "ray_tree.depth" => "|u1",
                        "time.ns" => "<u4",
                        _ => "<u8",
                    }
                    .to_string(),
                    sum,
                    min: range.0,
                    max: range.1,
                    mean: sum as f64 / samples as f64,
                };
            let mut maps = Vec::new();
            for (kind, n) in [
                ("sphere", s.spheres),
                ("cylinder", s.cylinders),
                ("polygon", s.polygons),
            ] {
                let key = format!("tests.{kind}.tests");
                let sum = get(&key);
                if sum == 0 {
                    continue;
                }
                // Brute force: every ray tests every primitive of the kind; the
                // busiest pixel traces its eye ray, two reflections and their shadows.
                let range = if tree {
                    (0, (sum / samples * 7).max(1))
                } else {
                    (n, n * (3 + 3 * lights))
                };
                maps.push(map(
                    &key,
                    &format!("{kind} intersection tests"),
                    "tests per sample",
                    sum,
                    range,
                ));
            }
            if tree {
                let nodes = get("accel.nodes_visited");
                let leaves = get("accel.leaves_visited");
                maps.push(map(
                    "accel.nodes_visited",
                    "BVH nodes visited",
                    "nodes per sample",
                    nodes,
                    (1, nodes / samples * 6),
                ));
                maps.push(map(
                    "accel.leaves_visited",
                    "BVH leaves visited",
                    "leaves per sample",
                    leaves,
                    (0, leaves / samples * 6),
                ));
            }
            maps.push(map(
                "rays.shadow",
                "shadow rays",
                "rays per sample",
                get("rays.shadow"),
                (0, 3 * lights),
            ));
            maps.push(map(
                "ops.dot",
                "dot products",
                "operations per sample",
                get("ops.dot"),
                (get("ops.dot") / samples / 4, get("ops.dot") / samples * 5),
            ));
            let secondary = get("rays.reflection") + get("rays.refraction");
            maps.push(map(
                "rays.secondary",
                "reflection and refraction rays",
                "rays per sample",
                secondary,
                (0, 2),
            ));
            maps.push(map(
                "ray_tree.depth",
                "deepest ray-tree level reached (eye ray 1, 0 not traced)",
                "levels",
                samples + secondary,
                (1, 3),
            ));
            // Two worker threads' time, nanoseconds.
            let nanos = (v.time.median * 2e9) as u64;
            maps.push(map(
                "time.ns",
                "tracing time of the sample, the least of 3 uncounted renders",
                "ns per sample",
                nanos,
                (nanos / samples / 5, nanos / samples * 8),
            ));
            VariantPixelMaps {
                variant: v.variant.clone(),
                directory: format!("pixel-maps/{}/{}", s.name, v.variant),
                columns: s.width,
                rows: s.height,
                clock_resolution_ns: 0.42,
                maps,
            }
        })
        .collect()
}
