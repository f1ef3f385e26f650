//! Per-pixel maps (`rtprof count SCENE --pixel-stats DIR`): a counted render and an
//! uncounted, timed one, both recording each sample (`RenderOptions::per_sample`),
//! turned into one map per counter: primitive tests by kind, BVH nodes and leaves
//! visited, shadow and secondary rays, dot products, the ray-tree depth reached and the
//! time per sample. Each map is written as raw values in NumPy's NPY format and as a
//! false-colour PNG with its legend, named after the counter
//! (`accel.nodes_visited.npy`, `accel.nodes_visited.png`), with `pixel-stats.json`
//! describing them all.

use std::path::Path;

use results::pixel_stats::{PIXEL_STATS_SCHEMA, PixelMap, PixelStats};
use tracer::counter::{COUNTERS, CounterDef, STAT_COUNT};
use tracer::{
    Count, Counter, NoCount, RenderOptions, Rendered, SampleStats, Sampling, VariantSet,
    render_variant_until,
};

use std::sync::atomic::AtomicBool;

use crate::error::RunError;
use crate::pool::thread_pool;
use crate::render_job::{RenderSettings, SceneRender};
use crate::render_setup::RenderSetup;
use crate::staging::save;
use tracer::image_io::encode_png_rgb8;

/// The counters mapped, when the render did any of that work (a map of zeros says
/// nothing): primitive tests by kind, the BVH's traversal, shadow rays and the
/// thesis's bottleneck, the dot product.
const MAPPED: [&str; 10] = [
    "tests.sphere.tests",
    "tests.cylinder.tests",
    "tests.cone.tests",
    "tests.polygon.tests",
    "tests.patch.tests",
    "tests.triangle.tests",
    "accel.nodes_visited",
    "accel.leaves_visited",
    "rays.shadow",
    "ops.dot",
];

/// One map's values, in the type its NPY file keeps.
#[derive(Clone, Debug, PartialEq)]
pub enum MapValues {
    Counts(Vec<u64>),
    Depth(Vec<u8>),
    Nanos(Vec<u32>),
}

impl MapValues {
    fn widened(&self) -> Vec<u64> {
        match self {
            MapValues::Counts(v) => v.clone(),
            MapValues::Depth(v) => v.iter().map(|&x| u64::from(x)).collect(),
            MapValues::Nanos(v) => v.iter().map(|&x| u64::from(x)).collect(),
        }
    }

    fn dtype(&self) -> &'static str {
        match self {
            MapValues::Counts(_) => "<u8",
            MapValues::Depth(_) => "|u1",
            MapValues::Nanos(_) => "<u4",
        }
    }
}

/// One map with what the legend and `pixel-stats.json` say of it.
#[derive(Clone, Debug, PartialEq)]
pub struct Map {
    pub key: String,
    pub description: String,
    pub unit: String,
    pub values: MapValues,
}

/// The maps of one render, before they are written.
#[derive(Clone, Debug, PartialEq)]
pub struct Maps {
    pub columns: u32,
    pub rows: u32,
    pub maps: Vec<Map>,
    /// Counts outside every sample, by key (non-zero only).
    pub frame_level: Vec<(String, u64)>,
}

/// The unit of one value of a counter's map: `tests per sample`.
fn unit_of(def: &CounterDef) -> String {
    let what = match def.key.split('.').next() {
        Some("tests") => "tests",
        Some("accel") if def.key.ends_with("leaves_visited") => "leaves",
        Some("accel") => "nodes",
        Some("rays") => "rays",
        _ => "operations",
    };
    format!("{what} per sample")
}

/// Uncounted renders timed for the time map: each sample keeps its fastest time, so
/// that a worker preempted or a page faulted in during one pass does not show as a
/// hot pixel.
pub const TIMED_PASSES: usize = 3;

/// The maps of a counted render's records (`counted`) and uncounted renders' (`timed`,
/// for the time per sample: each sample's least time) of the same scene, size and
/// variant; `totals` are the counted render's own counters.
pub fn maps_of(
    counted: &SampleStats,
    timed: &[SampleStats],
    totals: &[u64; STAT_COUNT],
) -> Result<Maps, RunError> {
    if let Some(other) = timed
        .iter()
        .find(|t| (t.columns, t.rows) != (counted.columns, counted.rows))
    {
        return Err(RunError::Input(format!(
            "pixel maps: the counted grid {}x{} differs from the timed {}x{}",
            counted.columns, counted.rows, other.columns, other.rows
        )));
    }
    let fastest: Vec<u32> = (0..counted.len())
        .map(|i| timed.iter().map(|t| t.nanos[i]).min().unwrap_or(0))
        .collect();
    let mut maps = Vec::new();
    for key in MAPPED {
        let Some(def) = COUNTERS.iter().find(|d| d.key == key) else {
            continue;
        };
        let Some(values) = counted.map(def) else {
            return Err(RunError::Input(
                "pixel maps need a counted render".to_string(),
            ));
        };
        if values.iter().any(|&v| v > 0) {
            maps.push(Map {
                key: key.to_string(),
                description: def.description.to_string(),
                unit: unit_of(def),
                values: MapValues::Counts(values),
            });
        }
    }
    maps.push(Map {
        key: "rays.secondary".to_string(),
        description: "reflection and refraction rays".to_string(),
        unit: "rays per sample".to_string(),
        values: MapValues::Counts(counted.secondary_rays()),
    });
    maps.push(Map {
        key: "ray_tree.depth".to_string(),
        description: "deepest ray-tree level reached (eye ray 1, 0 not traced)".to_string(),
        unit: "levels".to_string(),
        values: MapValues::Depth(counted.depth.clone()),
    });
    maps.push(Map {
        key: "time.ns".to_string(),
        description: format!(
            "tracing time of the sample, the least of {} uncounted renders",
            timed.len()
        ),
        unit: "ns per sample".to_string(),
        values: MapValues::Nanos(fastest),
    });
    let frame_level = counted
        .frame_level(totals)
        .map(|rest| {
            COUNTERS
                .iter()
                .filter_map(|d| {
                    let stat = d.stat?;
                    let v = rest[stat as usize];
                    (v > 0).then(|| (d.key.to_string(), v))
                })
                .collect()
        })
        .unwrap_or_default();
    Ok(Maps {
        columns: counted.columns,
        rows: counted.rows,
        maps,
        frame_level,
    })
}

/// Records the maps of `set` on `setup`'s scene: one counted render and
/// [`TIMED_PASSES`] uncounted ones, each keeping every sample's record.
pub fn record_maps(setup: &RenderSetup, set: &VariantSet) -> Result<Maps, RunError> {
    let options = RenderOptions {
        per_sample: true,
        ..*setup.options
    };
    let counted = setup
        .pool
        .install(|| render_variant_until::<Count>(setup.scene, &options, set, &|_| {}, setup.stop))
        .map_err(|e| RunError::render(setup.name, &e))?;
    record_maps_of(setup, set, &counted.rendered)
}

/// [`record_maps`] after its counted render: `counted` is a counted render of
/// `setup`'s scene with per-sample records (`rtprof count --pixel-stats` has made one
/// already); the timed renders run on `setup`'s pool.
pub fn record_maps_of(
    setup: &RenderSetup,
    set: &VariantSet,
    counted: &Rendered<Count>,
) -> Result<Maps, RunError> {
    let options = RenderOptions {
        per_sample: true,
        ..*setup.options
    };
    let fail = |e: tracer::RenderError| RunError::render(setup.name, &e);
    let missing = |what: &str| RunError::Render {
        context: setup.name.to_string(),
        message: format!("the counted render kept no {what}"),
    };
    let totals = counted.counter.totals().ok_or_else(|| missing("counts"))?;
    let samples = counted
        .samples
        .as_ref()
        .ok_or_else(|| missing("per-sample records"))?;
    let mut timed = Vec::with_capacity(TIMED_PASSES);
    for _ in 0..TIMED_PASSES {
        let run = setup
            .pool
            .install(|| {
                render_variant_until::<NoCount>(setup.scene, &options, set, &|_| {}, setup.stop)
            })
            .map_err(fail)?;
        timed.extend(run.rendered.samples);
    }
    maps_of(samples, &timed, &totals)
}

/// What `rtprof count --pixel-stats DIR` says of the maps written into `dir`.
pub fn written_line(stats: &PixelStats, dir: &Path) -> String {
    format!(
        "wrote {} per-pixel maps ({}x{} samples) to {}: {}",
        stats.maps.len(),
        stats.columns,
        stats.rows,
        dir.display(),
        stats
            .maps
            .iter()
            .map(|m| m.key.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// What `pixel-stats.json` records besides the maps.
pub struct MapsContext<'a> {
    pub scene: &'a str,
    pub variant: &'a str,
    pub sampling: Sampling,
    pub threads: usize,
    pub clock_resolution_ns: f64,
}

/// Writes every map (`KEY.npy`, `KEY.png`) and `pixel-stats.json` into `dir`
/// (created if needed); returns what the JSON holds.
pub fn write_maps(dir: &Path, maps: &Maps, context: &MapsContext) -> Result<PixelStats, RunError> {
    std::fs::create_dir_all(dir).map_err(|e| RunError::io("create", dir, &e))?;
    let (rows, columns) = (maps.rows as usize, maps.columns as usize);
    let mut summaries = Vec::new();
    for map in &maps.maps {
        let npy = format!("{}.npy", map.key);
        let png = format!("{}.png", map.key);
        let bytes = match &map.values {
            MapValues::Counts(v) => reports::npy::npy_bytes(rows, columns, v),
            MapValues::Depth(v) => reports::npy::npy_bytes(rows, columns, v),
            MapValues::Nanos(v) => reports::npy::npy_bytes(rows, columns, v),
        }
        .map_err(|e| RunError::Report(format!("{npy}: {e}")))?;
        save(dir, &npy, &bytes)?;
        let values = map.values.widened();
        let (min, max) = (
            values.iter().copied().min().unwrap_or(0),
            values.iter().copied().max().unwrap_or(0),
        );
        let sum: u64 = values.iter().sum();
        let legend = reports::pixel_maps::Legend {
            title: map.key.clone(),
            unit: map.unit.clone(),
            min: min as f64,
            max: max as f64,
        };
        let as_float: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        let image = reports::pixel_maps::false_colour(&as_float, maps.columns, maps.rows, &legend);
        let encoded = encode_png_rgb8(image.width(), image.height(), image.as_raw())
            .map_err(|e| RunError::Report(format!("{png}: {e}")))?;
        save(dir, &png, &encoded)?;
        summaries.push(PixelMap {
            key: map.key.clone(),
            description: map.description.clone(),
            unit: map.unit.clone(),
            npy,
            png,
            dtype: map.values.dtype().to_string(),
            sum,
            min,
            max,
            mean: sum as f64 / values.len().max(1) as f64,
        });
    }
    let stats = PixelStats {
        schema: PIXEL_STATS_SCHEMA.to_string(),
        scene: context.scene.to_string(),
        variant: context.variant.to_string(),
        sampling: match context.sampling {
            Sampling::PixelCenters => "pixel centres",
            Sampling::SpdCorners => "SPD corners",
        }
        .to_string(),
        columns: maps.columns,
        rows: maps.rows,
        threads: context.threads as u32,
        clock_resolution_ns: context.clock_resolution_ns,
        maps: summaries,
        frame_level: maps.frame_level.clone(),
    };
    let json = serde_json::to_string_pretty(&stats)
        .map_err(|e| RunError::Report(format!("pixel-stats.json: {e}")))?;
    save(dir, "pixel-stats.json", json.as_bytes())?;
    Ok(stats)
}

/// `rtprof count --pixel-stats DIR`: the per-pixel maps of the counted render
/// `counted` (its scene, variants and thread count) and of three timed ones, written
/// into `dir`; returns the line that says what was written. `settings` are the
/// render's; `variant` is the variant list as the user gave it.
pub fn write_maps_of_render(
    counted: &SceneRender<Count>,
    name: &str,
    variant: &str,
    settings: &RenderSettings,
    dir: &Path,
) -> Result<String, RunError> {
    let options = settings.options(&counted.scene, counted.mode);
    let pool = thread_pool(settings.threads)?;
    let never = AtomicBool::new(false);
    let setup = RenderSetup {
        scene: &counted.scene,
        name,
        options: &options,
        pool: &pool,
        counting_pool: &pool,
        stop: &never,
    };
    let maps = record_maps_of(&setup, &counted.variants, &counted.rendered)?;
    let context = MapsContext {
        scene: name,
        variant,
        sampling: options.sampling,
        threads: counted.threads,
        clock_resolution_ns: tracer::pixel_stats::clock_resolution().as_secs_f64() * 1e9,
    };
    let stats = write_maps(dir, &maps, &context)?;
    Ok(written_line(&stats, dir))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracer::{RayCounts, Stat};

    fn samples(tests: [u64; 2], nanos: [u32; 2]) -> SampleStats {
        let mut counts = vec![[0u64; STAT_COUNT]; 2];
        for (c, t) in counts.iter_mut().zip(tests) {
            c[Stat::SphereTest as usize] = t;
        }
        let eye = RayCounts {
            primary: 1,
            reflection: 1,
            ..RayCounts::default()
        };
        SampleStats {
            columns: 2,
            rows: 1,
            counts: Some(counts),
            rays: vec![
                eye,
                RayCounts {
                    primary: 1,
                    ..RayCounts::default()
                },
            ],
            depth: vec![2, 1],
            nanos: nanos.to_vec(),
        }
    }

    #[test]
    fn maps_keep_the_work_done_and_each_samples_least_time() {
        let counted = samples([3, 5], [900, 900]);
        let timed = [samples([0, 0], [10, 7]), samples([0, 0], [8, 9])];
        let mut totals = [0u64; STAT_COUNT];
        totals[Stat::SphereTest as usize] = 8;
        totals[Stat::PrimaryRaySetup as usize] = 1;
        let maps = maps_of(&counted, &timed, &totals).unwrap_or_else(|e| panic!("{e}"));
        let find = |key: &str| maps.maps.iter().find(|m| m.key == key).map(|m| &m.values);
        assert_eq!(
            find("tests.sphere.tests"),
            Some(&MapValues::Counts(vec![3, 5]))
        );
        assert_eq!(find("rays.secondary"), Some(&MapValues::Counts(vec![1, 0])));
        assert_eq!(find("ray_tree.depth"), Some(&MapValues::Depth(vec![2, 1])));
        assert_eq!(find("time.ns"), Some(&MapValues::Nanos(vec![8, 7])));
        // No map of work not done.
        assert_eq!(find("tests.cylinder.tests"), None);
        assert_eq!(find("accel.nodes_visited"), None);
        assert_eq!(
            maps.frame_level,
            vec![("calls.primary_ray_setup".to_string(), 1)]
        );
        // A timed grid of another size is refused.
        let mut other = samples([0, 0], [1, 1]);
        other.columns = 1;
        other.rows = 2;
        assert!(maps_of(&counted, &[other], &totals).is_err());
    }
}
