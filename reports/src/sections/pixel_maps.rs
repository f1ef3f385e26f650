//! The per-pixel maps section: for each scene with maps, the variants' false-colour
//! maps side by side (one column per variant, one row per counter: time, primitive
//! tests of each kind tested, BVH nodes, shadow rays, ray-tree depth), and a sentence
//! on the busiest pixel and the clock. The pictures are the runner's, legend drawn in;
//! a missing file costs its tile only. Omitted when no scene has maps.

use crate::document::{Block, Builder, ImageGrid, Section, Tile, Tone, Visual};
use crate::format;
use crate::pixel_maps::picture_size;
use crate::results::{PixelMap, Results, SceneResult, VariantPixelMaps};

/// Maps are embedded up to this wide: the width the runner draws a small map at, so
/// its legend keeps the size it was drawn at; larger maps shrink to it (the captions
/// carry the legend's figures).
const MAP_WIDTH: u32 = crate::pixel_maps::MIN_WIDTH;

/// The counters shown, in row order, with their row labels; the primitive tests of
/// each kind come after the time, one row per kind (see [`rows`]).
const FIXED_ROWS: [(&str, &str); 4] = [
    ("time.ns", "time"),
    ("accel.nodes_visited", "BVH nodes"),
    ("rays.shadow", "shadow rays"),
    ("ray_tree.depth", "ray-tree depth"),
];

pub fn pixel_maps(b: &mut Builder) -> Option<Section> {
    let r = b.results();
    let scenes: Vec<&SceneResult> = r
        .scenes
        .iter()
        .filter(|s| !s.pixel_maps.is_empty())
        .collect();
    if scenes.is_empty() {
        return None;
    }
    let mut s = b.section("pixel-maps", None);
    s.text("Where in the picture the work goes: one false-colour map per counter and variant, each sample's value from a counted render (the time: from uncounted ones), on the viridis scale from the map's minimum to its maximum as its legend shows. Rows: the tracing time, the primitive tests of each kind the scene has, the BVH nodes visited, the shadow rays and the depth the ray tree reached. The raw values are NumPy arrays beside each picture.");
    for scene in scenes {
        let maps = ordered(r, scene);
        s.blocks.push(Block::Heading {
            level: 2,
            text: scene.name.clone(),
            detail: maps
                .first()
                .map(|m| format!("{} samples", format::size(m.columns, m.rows))),
            anchor: Some(format!("pixel-maps-{}", crate::slug(&scene.name))),
        });
        if let Some(sentence) = busiest_pixel(&scene.name, &maps) {
            s.text(sentence);
        }
        for (key, label) in rows(&maps) {
            let tiles = maps
                .iter()
                .map(|m| tile(b, scene, m, &key, &label))
                .collect();
            s.blocks.push(Block::ImageGrid(
                ImageGrid::from_rows(maps.len(), vec![label], vec![tiles]).wide(),
            ));
        }
    }
    Some(s)
}

/// The scene's maps in the suite's variant order (the reference first).
fn ordered<'a>(r: &Results, scene: &'a SceneResult) -> Vec<&'a VariantPixelMaps> {
    let mut maps: Vec<&VariantPixelMaps> = scene.pixel_maps.iter().collect();
    let place = |m: &VariantPixelMaps| {
        r.suite
            .variants
            .iter()
            .position(|v| *v == m.variant)
            .unwrap_or(usize::MAX)
    };
    // Stable: variants outside the suite's list keep the file's order, last.
    maps.sort_by_key(|m| (!m.variant.is_reference(), place(m)));
    maps
}

/// A map of `key` that counted something, if the variant has one.
fn find<'a>(maps: &'a VariantPixelMaps, key: &str) -> Option<&'a PixelMap> {
    maps.maps.iter().find(|m| m.key == key && m.sum > 0)
}

/// The rows shown: counter key and label, for the counters some variant has a map of.
fn rows(maps: &[&VariantPixelMaps]) -> Vec<(String, String)> {
    let mut tests: Vec<String> = Vec::new();
    for m in maps.iter().flat_map(|v| &v.maps) {
        let tested = m.key.starts_with("tests.") && m.key.ends_with(".tests") && m.sum > 0;
        if tested && !tests.contains(&m.key) {
            tests.push(m.key.clone());
        }
    }
    let (time, rest) = FIXED_ROWS.split_at(1);
    let fixed = |rows: &[(&str, &str)]| -> Vec<(String, String)> {
        rows.iter()
            .map(|(k, label)| ((*k).to_string(), (*label).to_string()))
            .collect()
    };
    let mut all = fixed(time);
    all.extend(tests.into_iter().map(|k| {
        let label = format!("{} tests", kind_of(&k));
        (k, label)
    }));
    all.extend(fixed(rest));
    all.retain(|(key, _)| maps.iter().any(|m| find(m, key).is_some()));
    all
}

/// The primitive kind of a test counter: `tests.sphere.tests` is `sphere`.
fn kind_of(key: &str) -> &str {
    key.split('.').nth(1).unwrap_or(key)
}

/// One variant's map of `key`, or a note that it has none.
fn tile(
    b: &mut Builder,
    scene: &SceneResult,
    maps: &VariantPixelMaps,
    key: &str,
    label: &str,
) -> Tile {
    let Some(map) = find(maps, key) else {
        return Tile {
            visual: Visual::Placeholder {
                text: format!("no {label} with {}", maps.variant),
            },
            caption: String::new(),
            tone: Tone::Neutral,
        };
    };
    let path = if maps.directory.is_empty() {
        map.png.clone()
    } else {
        format!("{}/{}", maps.directory.trim_end_matches('/'), map.png)
    };
    let alt = format!("{} {} {}", scene.name, maps.variant, map.key);
    let size = picture_size(maps.columns, maps.rows);
    Tile {
        visual: b.picture_within(Some(&path), &alt, size, MAP_WIDTH),
        caption: format!(
            "{} · {}, {} (min {}, max {}, mean {})",
            maps.variant,
            map.key,
            map.unit,
            value(map, map.min as f64),
            value(map, map.max as f64),
            value(map, map.mean)
        ),
        tone: Tone::Neutral,
    }
}

/// A value of a map as its unit reads: times in their unit, counts grouped.
fn value(map: &PixelMap, v: f64) -> String {
    if map.key == "time.ns" {
        format::seconds(v * 1e-9)
    } else if v.fract() == 0.0 || v >= 999.5 {
        format::count(v.round() as u64)
    } else {
        format::significant(v)
    }
}

/// The busiest pixel's tests of the most tested kind with each variant, and what the
/// clock of the time maps can resolve.
fn busiest_pixel(scene: &str, maps: &[&VariantPixelMaps]) -> Option<String> {
    let reference = maps.first()?;
    let most_tested = reference
        .maps
        .iter()
        .filter(|m| m.key.starts_with("tests.") && m.sum > 0)
        // Reversed: of equal maxima, max_by_key keeps the last, i.e. the first listed.
        .rev()
        .max_by_key(|m| m.max)?;
    let busiest: Vec<(u64, &str)> = maps
        .iter()
        .filter_map(|m| Some((find(m, &most_tested.key)?.max, m.variant.as_str())))
        .collect();
    let ((count, variant), rest) = busiest.split_first()?;
    let mut text = format!(
        "On {scene} the busiest pixel makes {} {} tests with {variant}",
        format::count(*count),
        kind_of(&most_tested.key)
    );
    let rest: Vec<String> = rest
        .iter()
        .map(|(n, v)| format!("{} with {v}", format::count(*n)))
        .collect();
    if !rest.is_empty() {
        text += &format!(", against {}", format::join_list(&rest));
    }
    text += ".";
    let resolution = reference.clock_resolution_ns;
    let time = find(reference, "time.ns").filter(|_| resolution.is_finite() && resolution > 0.0);
    if let Some(time) = time {
        let ticks = time.mean / resolution;
        text += &format!(
            " The time maps' clock ticks every {}; {}'s mean pixel takes {}, about {} ticks",
            format::seconds(resolution * 1e-9),
            reference.variant,
            format::seconds(time.mean * 1e-9),
            format::count(ticks.round() as u64)
        );
        text += if ticks < 10.0 {
            ": too coarse to tell most pixels apart."
        } else {
            "."
        };
    }
    Some(text)
}
