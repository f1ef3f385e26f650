//! The per-pixel maps section: for each scene with maps, one figure per counter (time,
//! primitive tests of each kind tested, BVH nodes, shadow rays, ray-tree depth) with
//! the variants' false-colour maps side by side on one colour scale, the row's least
//! to greatest value, and that scale's values once, beside the maps; and a sentence on
//! the busiest pixel and the clock. The maps are drawn here from the raw values the
//! runner wrote (`.npy`), not taken from its pictures, each of which has its own scale.
//! A row whose values are all equal is left out, as are the maps a variant does not
//! have (it counted nothing there) and the files that cannot be read, each with one
//! sentence. Omitted when no scene has maps.

use std::path::Path;

use crate::charts::Chart;
use crate::document::{Block, Builder, Section};
use crate::format;
use crate::npy::read_npy;
use crate::pixel_maps::{Legend, RowMap, shared_range, shared_scale_row};
use crate::results::{PixelMap, Results, SceneResult, VariantPixelMaps};

/// The counters shown, in row order, with their row labels; the primitive tests of
/// each kind come after the time, one row per kind (see [`rows`]).
const FIXED_ROWS: [(&str, &str); 4] = [
    ("time.ns", "time"),
    ("accel.nodes_visited", "BVH nodes"),
    ("rays.shadow", "shadow rays"),
    ("ray_tree.depth", "ray-tree depth"),
];

/// The tallest a row of maps is set in the PDF, cm.
const ROW_HEIGHT_CM: f64 = 6.5;

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
    s.text("Where in the picture the work goes: one row of false-colour maps per counter, one map per variant, each sample's value from a counted render (the time: from uncounted ones). The maps of a row share one viridis scale, from the row's least value (dark purple) to its greatest (yellow), whose values stand once at the row's right: the same colour is the same value in every map of the row. Rows: the tracing time, the primitive tests of each kind the scene has, the BVH nodes visited, the shadow rays and the depth the ray tree reached. The raw values are NumPy arrays beside the report.");
    let base = b.run.base_dir.clone();
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
        let mut left_out = LeftOut::default();
        for (key, label) in rows(&maps) {
            match row(&base, &maps, &key, &label, &mut left_out) {
                Row::Drawn(row) => {
                    let id = format!(
                        "pixel-maps-{}-{}",
                        crate::slug(&scene.name),
                        crate::slug(&key)
                    );
                    if let Some(chart) = row_chart(&scene.name, &label, &row) {
                        s.blocks.push(b.figure_at(id, chart, ROW_HEIGHT_CM));
                    }
                }
                Row::Flat(value) => left_out.flat.push((label, value)),
                Row::Unreadable => {}
            }
        }
        for sentence in left_out.sentences() {
            s.text(sentence);
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

/// One variant's map of a row, read from its raw values.
struct RowEntry<'a> {
    variant: &'a str,
    map: &'a PixelMap,
    values: Vec<f64>,
}

/// A row ready to draw: the maps that could be read, their grid and shared range.
struct DrawnRow<'a> {
    entries: Vec<RowEntry<'a>>,
    grid: (u32, u32),
    range: (f64, f64),
}

enum Row<'a> {
    Drawn(DrawnRow<'a>),
    /// Every value of every variant's map is this one.
    Flat(f64),
    /// No map of the row could be read.
    Unreadable,
}

/// What a scene's rows left out, said once per scene.
#[derive(Default)]
struct LeftOut {
    /// Row label and the variants without a map of it.
    absent: Vec<(String, Vec<String>)>,
    /// Row label and the one value all its maps hold.
    flat: Vec<(String, f64)>,
    /// `variant's key` and why its values could not be read.
    unreadable: Vec<String>,
}

impl LeftOut {
    fn sentences(&self) -> Vec<String> {
        let mut out = Vec::new();
        if !self.absent.is_empty() {
            let parts: Vec<String> = self
                .absent
                .iter()
                .map(|(label, variants)| format!("no {label} with {}", format::join_list(variants)))
                .collect();
            out.push(format!(
                "Not drawn because not counted: {}.",
                format::join_list(&parts)
            ));
        }
        if !self.flat.is_empty() {
            let parts: Vec<String> = self
                .flat
                .iter()
                .map(|(label, value)| format!("the {label} is {} everywhere", plain(*value)))
                .collect();
            out.push(format!(
                "Not drawn because every sample of every variant holds the same value: {}.",
                format::join_list(&parts)
            ));
        }
        if !self.unreadable.is_empty() {
            out.push(format!(
                "Not drawn because the raw values could not be read: {}.",
                format::join_list(&self.unreadable)
            ));
        }
        out
    }
}

/// The row of `key`: each variant's map read from its `.npy` beside the results, on
/// the range of all of them.
fn row<'a>(
    base: &Path,
    maps: &[&'a VariantPixelMaps],
    key: &str,
    label: &str,
    left_out: &mut LeftOut,
) -> Row<'a> {
    let mut entries = Vec::new();
    let mut absent = Vec::new();
    for m in maps {
        let Some(map) = find(m, key) else {
            absent.push(m.variant.to_string());
            continue;
        };
        let rel = if m.directory.is_empty() {
            map.npy.clone()
        } else {
            format!("{}/{}", m.directory.trim_end_matches('/'), map.npy)
        };
        match read_values(base, &rel, (m.columns, m.rows)) {
            Ok(values) => entries.push(RowEntry {
                variant: m.variant.as_str(),
                map,
                values,
            }),
            Err(why) => left_out
                .unreadable
                .push(format!("{}'s {} ({rel}: {why})", m.variant, map.key)),
        }
    }
    if !absent.is_empty() {
        left_out.absent.push((label.to_string(), absent));
    }
    let Some(grid) = maps.first().map(|m| (m.columns, m.rows)) else {
        return Row::Unreadable;
    };
    let Some(range) = shared_range(entries.iter().map(|e| e.values.as_slice())) else {
        return Row::Unreadable;
    };
    if range.0 == range.1 {
        return Row::Flat(range.0);
    }
    Row::Drawn(DrawnRow {
        entries,
        grid,
        range,
    })
}

/// The values of the NPY file `rel` under `base`, which must be a `columns` x `rows`
/// map (rows first, as the runner writes it).
fn read_values(base: &Path, rel: &str, (columns, rows): (u32, u32)) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(base.join(rel)).map_err(|e| e.kind().to_string())?;
    let array = read_npy(&bytes).map_err(|e| e.to_string())?;
    if (array.rows, array.columns) != (rows as usize, columns as usize) {
        return Err(format!(
            "{} values, not the {}",
            format::size(array.columns as u32, array.rows as u32),
            format::size(columns, rows)
        ));
    }
    Ok(array.values)
}

/// The figure of a drawn row: the maps on their shared scale, each with its own mean
/// and maximum below it, titled by scene and counter, with what the maps count and the
/// scale's ends in the caption.
fn row_chart(scene: &str, label: &str, row: &DrawnRow<'_>) -> Option<Chart> {
    let first = row.entries.first()?;
    let key = first.map.key.as_str();
    let maps: Vec<RowMap<'_>> = row
        .entries
        .iter()
        .map(|e| {
            let numbers = e.values.iter().filter(|v| !v.is_nan());
            let (sum, count, max) = numbers
                .fold((0.0, 0usize, f64::NEG_INFINITY), |(s, n, m), v| {
                    (s + v, n + 1, m.max(*v))
                });
            RowMap {
                name: e.variant.to_string(),
                values: &e.values,
                note: format!(
                    "mean {}, max {}",
                    value(key, sum / count.max(1) as f64),
                    value(key, max)
                ),
            }
        })
        .collect();
    let legend = Legend {
        title: key.to_string(),
        unit: first.map.unit.clone(),
        min: row.range.0,
        max: row.range.1,
    };
    let (svg, (width, height)) = shared_scale_row(&maps, row.grid, &legend, &|v| value(key, v));
    let variants: Vec<String> = row.entries.iter().map(|e| e.variant.to_string()).collect();
    Some(Chart {
        id: "pixel-map",
        title: format!("{scene}: {label}"),
        caption: format!(
            "{} ({}, key {key}) with {}, on one colour scale from {} to {}.",
            capitalised(&first.map.description),
            first.map.unit,
            format::join_list(&variants),
            value(key, row.range.0),
            value(key, row.range.1)
        ),
        svg,
        width,
        height,
    })
}

/// `text` with its first letter in capitals.
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars
        .next()
        .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}

/// A value of a map of `key` as its unit reads: times (ns) in their unit, counts
/// grouped.
fn value(key: &str, v: f64) -> String {
    if key == "time.ns" {
        format::seconds(v * 1e-9)
    } else {
        plain(v)
    }
}

/// A count whole and grouped, any other value to three significant digits.
fn plain(v: f64) -> String {
    if v >= 0.0 && (v.fract() == 0.0 || v >= 999.5) {
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
