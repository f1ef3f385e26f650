//! Render time against primitive count, and the ray statistics of the SPD scenes.

use super::access;
use super::summary::scene_line;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{SceneResult, VariantResult};

pub fn time_vs_primitives(b: &mut Builder) -> Section {
    let mut s = b.section(
        "time-vs-primitives",
        Some("fig. 47 and 48 (box plots of render time per primitive count)"),
    );
    let r = b.results();
    s.text("Tracing time of the test-bench families against their number of primitives.");
    match b.chart("time-vs-primitives", 12.0) {
        Some(figure) => s.blocks.push(figure),
        None => s.blocks.push(Block::empty(
            "No test-bench scene (balls, cylinder or both with 1 to 7 primitives) ran with baseline.",
        )),
    }
    if r.scenes.is_empty() {
        return s;
    }
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::text("family"),
        Column::number("primitives"),
        Column::text("size"),
        Column::number("baseline time").detail("[95 % interval]"),
        Column::number("peak memory").detail("scene + structure + image"),
        Column::text("fastest variant").grow(),
    ])
    .sortable()
    .caption("Scenes by family and primitive count");
    let mut scenes: Vec<&SceneResult> = r.scenes.iter().collect();
    scenes.sort_by_key(|s| (s.family, s.primitives));
    for scene in scenes {
        let fastest = access::fastest(scene);
        t.rows.push(vec![
            Cell::text(&scene.name),
            Cell::text(scene.family.name()),
            Cell::count(scene.primitives),
            Cell::text(format::size(scene.width, scene.height)),
            match access::reference(r, scene) {
                Some(v) => Cell::estimate(v.time.median, v.time.low, v.time.high),
                None => Cell::dash(),
            },
            match &scene.memory {
                Some(m) => {
                    Cell::number(format::bytes(m.peak_bytes), m.peak_bytes as f64).hover(format!(
                        "scene {}, structure {}, framebuffer {}",
                        format::bytes(m.scene_bytes),
                        format::bytes(m.accelerator_bytes),
                        format::bytes(m.framebuffer_bytes)
                    ))
                }
                None => Cell::dash(),
            },
            match fastest {
                Some(v) => Cell::number(
                    format!("{} ({})", v.variant, format::seconds(v.time.median)),
                    v.time.median,
                ),
                None => Cell::dash(),
            },
        ]);
    }
    s.blocks.push(Block::Table(t));
    s
}

/// Ray counters and their column names.
const RAY_KINDS: [(&str, &str); 6] = [
    ("rays.primary", "primary rays"),
    ("rays.primary_hit", "hits"),
    ("rays.shadow", "shadow rays"),
    ("rays.shadow_blocked", "blocked"),
    ("rays.reflection", "reflection rays"),
    ("rays.refraction", "refraction rays"),
];

pub fn spd(b: &mut Builder) -> Section {
    let mut s = b.section(
        "spd",
        Some("ch. 8.1: SPD rings, about 1.0056e6 intersection calls and 4.22e9 sphere and cylinder tests"),
    );
    let scenes: Vec<&SceneResult> = b
        .results()
        .scenes
        .iter()
        .filter(|s| access::is_spd(s))
        .collect();
    if scenes.is_empty() {
        return s.empty("No SPD scene ran in this suite (add them with --scenes ../shared/spd).");
    }
    s.text("Exact ray and intersection counts of each SPD scene, per variant.");
    if scenes.iter().any(|s| s.name.ends_with("-small")) {
        s.text(
            "The suite runs each SPD scene twice: NAME at the SPD's own frame with its procedure \
             (corner rays) and accelerated variants only, and NAME-small on a small frame with \
             every variant, because brute force tests every primitive against every ray.",
        );
    }
    for scene in scenes {
        s.blocks.push(Block::Heading {
            level: 2,
            text: scene.name.clone(),
            detail: Some(scene_line(scene)),
            anchor: None,
        });
        if let Some(m) = &scene.memory {
            s.text(memory_line(m));
        }
        if let (Some(published), Some(v)) = (&scene.published, scene.variants.first()) {
            s.blocks.push(Block::Table(published_table(published, v)));
        }
        if scene.variants.is_empty() {
            s.blocks.push(Block::empty("No variant ran on this scene."));
            continue;
        }
        let mut columns = vec![Column::text("variant")];
        columns.extend(RAY_KINDS.iter().map(|(_, name)| Column::number(*name)));
        columns.extend([
            Column::number("rays per pixel"),
            Column::number("intersection tests"),
            Column::number("tests per ray"),
            Column::number("BVH nodes"),
        ]);
        let mut t = Table::new(columns).sortable().dense();
        let pixels = u64::from(scene.width) * u64::from(scene.height);
        for v in &scene.variants {
            t.rows.push(spd_row(v, pixels));
        }
        s.blocks.push(Block::Table(t));
    }
    s
}

/// Where the scene's memory went.
fn memory_line(m: &crate::results::MemoryUse) -> String {
    let bvh = match m.bvh_bytes_per_primitive {
        Some(per) => format!(" (BVH: {per:.0} bytes a primitive)"),
        None => String::new(),
    };
    format!(
        "Memory: peak {} = scene {} + acceleration structure {}{bvh} + framebuffer {}.",
        format::bytes(m.peak_bytes),
        format::bytes(m.scene_bytes),
        format::bytes(m.accelerator_bytes),
        format::bytes(m.framebuffer_bytes)
    )
}

/// The variant's ray counts against the published ones.
fn published_table(p: &crate::results::PublishedRays, v: &VariantResult) -> Table {
    let mut t = Table::new(vec![
        Column::text("ray count"),
        Column::number(format!("rtprof ({})", v.variant)),
        Column::number("published"),
        Column::number("difference"),
    ])
    .caption(format!(
        "Against the published figures ({}; a classical tracer is within {}).",
        p.source,
        format::percent(p.tolerance * 100.0, 0)
    ));
    let rows = [
        ("eye rays", "rays.primary", p.primary),
        ("eye rays that hit", "rays.primary_hit", p.primary_hit),
        ("reflection rays", "rays.reflection", p.reflection),
        ("refraction rays", "rays.refraction", p.refraction),
        ("shadow rays", "rays.shadow", p.shadow),
    ];
    for (label, key, published) in rows {
        let measured = v.counts.get(key).copied().unwrap_or(0);
        let difference = if published > 0 {
            let d = measured as f64 / published as f64 - 1.0;
            let tone = if d.abs() <= p.tolerance {
                Tone::Good
            } else {
                Tone::Bad
            };
            Cell::number(format::signed_percent(d * 100.0, 1), d).tone(tone)
        } else if measured == 0 {
            Cell::text("equal").tone(Tone::Good)
        } else {
            Cell::text("none published").tone(Tone::Bad)
        };
        t.rows.push(vec![
            Cell::text(label),
            Cell::count(measured),
            Cell::count(published),
            difference,
        ]);
    }
    t
}

fn spd_row(v: &VariantResult, pixels: u64) -> Vec<Cell> {
    let get = |k: &str| v.counts.get(k).copied().unwrap_or(0);
    let rays =
        get("rays.primary") + get("rays.shadow") + get("rays.reflection") + get("rays.refraction");
    let tests: u64 = v
        .counts
        .iter()
        .filter(|(k, _)| k.starts_with("tests.") && k.ends_with(".tests"))
        .map(|(_, n)| *n)
        .sum();
    let ratio = |a: u64, b: u64, decimals: usize| {
        if b > 0 {
            let x = a as f64 / b as f64;
            Cell::number(format::fixed(x, decimals), x)
        } else {
            Cell::dash()
        }
    };
    let mut row = vec![Cell::text(v.variant.as_str())];
    row.extend(RAY_KINDS.iter().map(|(key, _)| Cell::count(get(key))));
    row.push(ratio(rays, pixels, 2));
    if v.variant.counts_its_work() {
        row.push(Cell::count(tests));
        row.push(ratio(tests, rays, 1));
    } else {
        // Embree's tests happen inside the library, uncounted: not zero.
        row.push(Cell::text("not counted").tone(Tone::Muted));
        row.push(Cell::dash().tone(Tone::Muted));
    }
    row.push(match v.counts.get("accel.nodes_visited") {
        Some(n) if *n > 0 => Cell::count(*n),
        _ => Cell::dash().tone(Tone::Muted),
    });
    row
}
