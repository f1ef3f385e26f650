//! The summary: headline findings, what ran on what, the scenes, and the runs when
//! there are several.

use super::access;
use crate::document::{Block, Builder, Cell, Column, Inline, Pair, Section, Table};
use crate::findings::{headline_findings, repeats_text};
use crate::format;
use crate::results::{Results, SceneResult, TimeCovers};

pub fn summary(b: &mut Builder) -> Section {
    let mut s = b.section(
        "summary",
        Some("the GUI's report (ch. 7): what ran, on what, and what it found"),
    );
    let main = b.run;
    let r = &main.results;
    if b.runs.len() > 1 {
        s.blocks.push(Block::Paragraph {
            content: vec![
                Inline::text("The sections below show run "),
                Inline::strong(&main.label),
                Inline::text(" in detail; "),
                Inline::Link {
                    text: "the comparison".to_string(),
                    target: "comparison".to_string(),
                },
                Inline::text(format!(" sets all {} runs side by side.", b.runs.len())),
            ],
        });
    }
    s.blocks.push(Block::heading("Findings beside the answers"));
    let findings = headline_findings(r);
    s.blocks.push(if findings.is_empty() {
        Block::empty(
            "No findings: the run has no profile, variants, hardware model or failures to speak of.",
        )
    } else {
        Block::List { items: findings }
    });
    s.blocks.push(Block::Pairs {
        pairs: run_pairs(&main.label, r),
    });
    s.blocks
        .push(Block::heading(format!("Scenes ({})", r.scenes.len())));
    if r.scenes.is_empty() {
        s.blocks.push(Block::empty("No scene ran (see Failures)."));
    } else {
        s.blocks.push(Block::Table(scenes_table(r)));
    }
    if b.runs.len() > 1 {
        s.blocks.push(Block::heading("Runs"));
        let mut t = Table::new(vec![
            Column::text("run"),
            Column::text("host"),
            Column::text("CPU").grow(),
            Column::number("cores"),
            Column::text("commit"),
            Column::text("created"),
            Column::number("scenes"),
        ]);
        for run in b.runs {
            let r = &run.results;
            t.rows.push(vec![
                Cell::text(&run.label),
                Cell::text(&r.machine.hostname),
                Cell::text(&r.machine.cpu_model),
                Cell::count(u64::from(r.machine.cores)),
                Cell::text(short_commit(&r.build.git_commit))
                    .code()
                    .hover(&r.build.git_commit),
                Cell::text(&r.created),
                Cell::count(r.scenes.len() as u64),
            ]);
        }
        s.blocks.push(Block::Table(t));
    }
    s
}

/// Machine, build and suite of a run, as key-value pairs (the summary's, and the
/// comparison's columns).
pub fn run_pairs(label: &str, r: &Results) -> Vec<Pair> {
    let m = &r.machine;
    let b = &r.build;
    let s = &r.suite;
    vec![
        Pair::new("Run", label),
        Pair::new("Created", &r.created),
        Pair::new(
            "Machine",
            format!(
                "{} · {} logical CPUs · {} · host {}",
                m.cpu_model, m.cores, m.os, m.hostname
            ),
        ),
        Pair::new(
            "Build",
            format!(
                "rtprof {} · {} · commit {} · {} profile",
                b.rtprof_version,
                b.rustc,
                short_commit(&b.git_commit),
                b.profile
            ),
        ),
        Pair::new(
            "Suite",
            format!(
                "{}{}: {} · {} · {} · timed on {} · {} wall time",
                s.name,
                if s.quick { " (quick)" } else { "" },
                format::plural(r.scenes.len(), "scene"),
                format::plural(s.variants.len(), "variant"),
                repeats_text(s),
                format::plural(s.threads as usize, "thread"),
                format::seconds(s.wall_seconds)
            ),
        ),
        Pair::new(
            "Variants",
            s.variants
                .iter()
                .map(|v| v.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        ),
        Pair::new(
            "Times",
            format!(
                "{}; {} bootstrap resamples for each 95 % interval",
                time_covers(s.timing.covers),
                s.timing.bootstrap_resamples
            ),
        ),
        Pair::new(
            "Failures",
            if r.failures.is_empty() {
                "none".to_string()
            } else {
                format!("{} (see Failures)", r.failures.len())
            },
        ),
        Pair::new("Schema", &r.schema),
    ]
}

/// A commit's first twelve characters.
pub fn short_commit(commit: &str) -> &str {
    commit.get(..12).unwrap_or(commit)
}

/// "1 sphere, 2 cylinders": the kinds of primitives a scene has.
pub fn kinds(scene: &SceneResult) -> String {
    scene
        .primitive_counts
        .iter()
        .filter(|(_, n)| **n > 0)
        .map(|(k, n)| format::kind_count(*n, k))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a time of the run covers, in words.
pub fn time_covers(covers: TimeCovers) -> &'static str {
    match covers {
        TimeCovers::Tracing => "tracing only (scene preparation and structure build apart)",
        TimeCovers::PreprocessingAndTracing => {
            "scene preparation, structure build and tracing together (an rtprof.results/1 file)"
        }
    }
}

/// "balls · 7 primitives (7 spheres) · 640×480 · builtin": a scene in one line.
pub fn scene_line(scene: &SceneResult) -> String {
    let kinds = kinds(scene);
    format!(
        "{} · {}{} · {} · {}{}{}",
        scene.family.name(),
        format::kind_count(scene.primitives, "primitives"),
        if kinds.is_empty() {
            String::new()
        } else {
            format!(" ({kinds})")
        },
        format::size(scene.width, scene.height),
        scene.source,
        if scene.spd { " · SPD sampling" } else { "" },
        scene.threads.map_or_else(String::new, |n| format!(
            " · {}",
            format::plural(n as usize, "thread")
        ))
    )
}

fn scenes_table(r: &Results) -> Table {
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::text("family"),
        Column::number("primitives"),
        Column::text("kinds"),
        Column::text("size"),
        Column::number("variants run"),
        Column::number("baseline time"),
        Column::text("source").grow(),
    ])
    .sortable();
    for scene in &r.scenes {
        let base = access::reference(r, scene);
        t.rows.push(vec![
            Cell::text(&scene.name),
            Cell::text(scene.family.name()),
            Cell::count(scene.primitives),
            Cell::text(kinds(scene)),
            Cell::text(format!(
                "{}{}",
                format::size(scene.width, scene.height),
                if scene.spd { " (SPD sampling)" } else { "" }
            )),
            Cell::count(scene.variants.len() as u64),
            match base {
                Some(v) => Cell::estimate(v.time.median, v.time.low, v.time.high),
                None => Cell::text("no baseline").tone(crate::document::Tone::Muted),
            },
            Cell::text(&scene.source),
        ]);
    }
    t
}
