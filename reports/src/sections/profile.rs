//! The profile sections: the flat profile and call graph, the calls and self-time
//! charts, the flamegraphs and the Amdahl table.

use crate::charts::short_name;
use crate::document::{
    Block, Builder, Cell, Column, Flamegraph, Inline, Preformatted, Section, Table, Tone,
};
use crate::format;
use crate::results::{Profile, ProfileResult};

/// Lines of a call graph a printed page shows before leaving the rest to the file.
const CALLGRAPH_PRINT_LINES: u32 = 160;

/// The profiles of a run: baseline, then the best variant if it was profiled.
fn profiles(p: &ProfileResult) -> impl Iterator<Item = &Profile> {
    std::iter::once(&p.baseline).chain(p.best.iter())
}

pub fn profile(b: &mut Builder) -> Section {
    let mut s = b.section(
        "profile",
        Some("table 6 (gprof flat profile of SPD rings, 640x480, Core i5-4570) and fig. 53 (call tree)"),
    );
    let Some(p) = &b.results().profile else {
        return s.empty("No profile in this run: the suite ran without profiling, or the profile failed (see Failures).");
    };
    let best = p.best.as_ref().map_or_else(String::new, |x| {
        format!(" and the best variant, {},", x.variant)
    });
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text("Sampled profile of the heaviest scene of the run, "),
            Inline::strong(&p.scene),
            Inline::text(format!(
                " at {}: the baseline{best} in the layout of gprof.",
                format::size(p.width, p.height)
            )),
        ],
    });
    for profile in profiles(p) {
        s.blocks
            .push(Block::heading(format!("Flat profile: {}", profile.variant)));
        s.blocks.push(Block::text(format!(
            "{} samples at {} each ({} sampled). Calls are exact, from the counters; blank where the function is not counted.",
            format::count(profile.samples),
            format::seconds(profile.seconds_per_sample),
            format::seconds(profile.samples as f64 * profile.seconds_per_sample),
        )));
        if profile.flat.is_empty() {
            s.blocks.push(Block::empty(
                "The flat profile has no rows (no samples landed in the tracer).",
            ));
        } else {
            s.blocks
                .push(Block::Table(flat_table(profile).caption(format!(
                    "Table 6 (thesis): flat profile of {}, {}",
                    p.scene, profile.variant
                ))));
        }
        s.blocks.push(match b.text_file(&profile.flat_text) {
            Ok(text) => Block::Preformatted(Preformatted {
                text,
                file: Some(profile.flat_text.clone()),
                folded: Some(format!(
                    "gprof-layout flat profile text ({})",
                    profile.flat_text
                )),
                print_lines: None,
            }),
            Err(reason) => Block::note(
                Tone::Bad,
                format!(
                    "flat profile text missing: {} ({reason})",
                    profile.flat_text
                ),
            ),
        });
        s.blocks.push(Block::subheading(format!(
            "Call graph: {} (fig. 53)",
            profile.variant
        )));
        s.blocks.push(match b.text_file(&profile.callgraph_text) {
            Ok(text) => Block::Preformatted(Preformatted {
                text,
                file: Some(profile.callgraph_text.clone()),
                folded: None,
                print_lines: Some(CALLGRAPH_PRINT_LINES),
            }),
            Err(reason) => Block::note(
                Tone::Bad,
                format!(
                    "call graph text missing: {} ({reason})",
                    profile.callgraph_text
                ),
            ),
        });
    }
    if p.best.is_none() {
        s.blocks.push(Block::empty(
            "Only the baseline was profiled (no best variant).",
        ));
    }
    s
}

/// The flat profile, largest self time first, with the cumulative time gprof prints.
fn flat_table(profile: &Profile) -> Table {
    let mut t = Table::new(vec![
        Column::number("% time"),
        Column::number("cumulative s"),
        Column::number("self s"),
        Column::number("calls"),
        Column::number("self per call"),
        Column::number("total per call"),
        Column::text("name").grow(),
    ])
    .sortable();
    let mut rows: Vec<_> = profile.flat.iter().collect();
    rows.sort_by(|a, b| b.self_seconds.total_cmp(&a.self_seconds));
    let mut cumulative = 0.0;
    for row in rows {
        if row.self_seconds.is_finite() {
            cumulative += row.self_seconds;
        }
        let per_call = |s: f64| {
            let value = format::per_call_value(s, row.calls);
            match format::per_call(s, row.calls) {
                Some(text) => Cell::number(text, value),
                None => Cell::number("", -1.0),
            }
        };
        t.rows.push(vec![
            Cell::number(format::fixed(row.percent, 2), row.percent),
            Cell::number(format::fixed(cumulative, 3), cumulative),
            Cell::number(format::fixed(row.self_seconds, 3), row.self_seconds),
            match row.calls {
                Some(c) => Cell::count(c),
                None => Cell::number("", -1.0),
            },
            per_call(row.self_seconds),
            per_call(row.total_seconds),
            Cell::text(&row.name).code().hover(&row.name),
        ]);
    }
    t
}

pub fn profile_charts(b: &mut Builder) -> Section {
    let mut s = b.section(
        "profile-charts",
        Some("fig. 51 (calls per function) and fig. 52 (self seconds per function)"),
    );
    if let Some(p) = &b.results().profile {
        s.blocks.push(Block::text(format!(
            "Exact calls and sampled self time of the functions of {}, baseline.",
            p.scene
        )));
    }
    let mut any = false;
    for id in ["calls", "self-seconds"] {
        if let Some(figure) = b.chart(id, 10.5) {
            s.blocks.push(figure);
            any = true;
        }
    }
    if !any {
        s.blocks
            .push(Block::empty(if b.results().profile.is_none() {
                "No profile in this run, so no calls or self-time charts."
            } else {
                "The profile has no counted calls or self time to chart."
            }));
    }
    s
}

pub fn flamegraphs(b: &mut Builder) -> Section {
    let mut s = b.section(
        "flamegraphs",
        Some("no counterpart (the thesis used gprof's call tree, fig. 53)"),
    );
    let Some(p) = &b.results().profile else {
        return s.empty("No profile in this run, so no flamegraphs.");
    };
    s.text("Each box is a function; its width is its share of the samples, the boxes above it are its callees. In the HTML report, hover a frame for its name and share, click to zoom.");
    for profile in profiles(p) {
        let title = format!("Flamegraph of {}, {}", p.scene, profile.variant);
        let visual = b.flamegraph(&profile.flame_svg, &title);
        s.blocks.push(Block::Flamegraph(Flamegraph {
            title,
            caption: None,
            visual,
        }));
    }
    match (&p.diff_flame_svg, &p.best) {
        (Some(diff), best) => {
            let to = best
                .as_ref()
                .map_or("the best variant", |x| x.variant.as_str());
            let title = format!(
                "Differential flamegraph of {}, {} to {to}",
                p.scene, p.baseline.variant
            );
            let visual = b.flamegraph(diff, &title);
            s.blocks.push(Block::Flamegraph(Flamegraph {
                title,
                caption: Some(format!(
                    "Frames of the {to} profile, coloured by the change from baseline: red grew, blue shrank."
                )),
                visual,
            }));
        }
        (None, _) => s.blocks.push(Block::empty(
            "No differential flamegraph: only one variant was profiled.",
        )),
    }
    s
}

pub fn amdahl(b: &mut Builder) -> Section {
    let mut s = b.section(
        "amdahl",
        Some(
            "ch. 8.1's conclusion that the intersection test is the bottleneck, made quantitative",
        ),
    );
    let Some(p) = &b.results().profile else {
        return s.empty("No profile in this run, so no Amdahl table.");
    };
    s.text(
        "The whole program's speed-up if one function alone became 2×, 10× or infinitely faster.",
    );
    for profile in profiles(p) {
        s.blocks
            .push(Block::heading(format!("{} · {}", p.scene, profile.variant)));
        if profile.amdahl.is_empty() {
            s.blocks
                .push(Block::empty("The profile has no Amdahl rows."));
            continue;
        }
        let mut t = Table::new(vec![
            Column::text("function").grow(),
            Column::number("share of time"),
            Column::number("whole program if 2× faster"),
            Column::number("if 10× faster"),
            Column::number("if free (limit)"),
        ])
        .sortable();
        for a in &profile.amdahl {
            t.rows.push(vec![
                Cell::text(short_name(&a.name)).code().hover(&a.name),
                Cell::number(format::percent(a.fraction * 100.0, 1), a.fraction),
                Cell::number(format::speedup(a.speedup_2x), a.speedup_2x),
                Cell::number(format::speedup(a.speedup_10x), a.speedup_10x),
                Cell::number(
                    format::speedup(a.speedup_limit),
                    if a.speedup_limit.is_finite() {
                        a.speedup_limit
                    } else {
                        f64::MAX
                    },
                ),
            ]);
        }
        s.blocks.push(Block::Table(t));
    }
    s
}
