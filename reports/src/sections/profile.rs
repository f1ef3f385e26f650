//! The profile sections: the flat profile and call graph, the calls and self-time
//! charts, the flamegraphs and the Amdahl table.

use crate::charts::short_name;
use crate::document::{
    Block, Builder, Cell, Column, Flamegraph, Inline, Preformatted, Section, Table, Tone,
};
use crate::format;
use crate::results::{FlatRow, Profile, ProfileResult, ProfileView, Timer};

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
            Inline::text("Sampled profile of "),
            Inline::strong(&p.scene),
            Inline::text(format!(
                " at {}: the baseline{best} in the layout of gprof.",
                format::size(p.width, p.height)
            )),
        ],
    });
    if let Some(text) = headline(&p.baseline) {
        s.blocks.push(Block::text(text));
    }
    for profile in profiles(p) {
        s.blocks
            .push(Block::heading(format!("Flat profile: {}", profile.variant)));
        s.blocks.push(Block::text(sampling_text(profile)));
        if profile.flat.is_empty() {
            s.blocks.push(Block::empty(
                "The flat profile has no rows (no samples landed in the tracer).",
            ));
        } else {
            s.blocks.push(Block::Table(
                flat_table(&profile.flat, profile.renders).caption(format!(
                    "Flat profile of {}, {}, in the layout of table 6",
                    p.scene, profile.variant
                )),
            ));
        }
        s.blocks
            .push(flat_text_block(b, &profile.flat_text, "flat profile"));
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
    for profile in profiles(p) {
        let Some(native) = &profile.second_view else {
            continue;
        };
        s.blocks.push(Block::heading(format!(
            "Native symbols: {} (what the compiler made of the code)",
            profile.variant
        )));
        s.blocks.push(Block::text(
            "The same samples attributed to the functions the binary's debug info names at each sample. Inlining decides what shows here: a test inlined into its caller is counted as the caller. The phase view above does not depend on it.",
        ));
        s.blocks.push(Block::Table(
            flat_table(&native.flat, profile.renders).caption(format!(
                "Native flat profile of {}, {}",
                p.scene, profile.variant
            )),
        ));
        s.blocks
            .push(flat_text_block(b, &native.flat_text, "native flat profile"));
    }
    if p.best.is_none() {
        s.blocks.push(Block::empty(
            "Only the baseline was profiled (no best variant).",
        ));
    }
    s
}

/// A flamegraph file as a block with its title and caption.
fn flame_block(b: &mut Builder, svg: &str, title: String, caption: String) -> Block {
    let visual = b.flamegraph(svg, &title);
    Block::Flamegraph(Flamegraph {
        title,
        caption: Some(caption),
        visual,
    })
}

/// A flat profile's gprof-layout text, folded away, or a note that it is missing.
fn flat_text_block(b: &Builder, path: &str, what: &str) -> Block {
    match b.text_file(path) {
        Ok(text) => Block::Preformatted(Preformatted {
            text,
            file: Some(path.to_string()),
            folded: Some(format!("gprof-layout {what} text ({path})")),
            print_lines: None,
        }),
        Err(reason) => Block::note(Tone::Bad, format!("{what} text missing: {path} ({reason})")),
    }
}

/// The bottleneck by self time (the work that costs by itself: what making it free
/// would buy) and, when another, the largest share with everything it calls, saying
/// that share is mostly the work it calls.
fn headline(profile: &Profile) -> Option<String> {
    let top = profile.bottleneck()?;
    let interval = top
        .self_interval
        .map(|[lo, hi]| {
            format!(
                " (95 % interval {}–{})",
                format::fixed(lo, 1),
                format::percent(hi, 1)
            )
        })
        .unwrap_or_default();
    let limit = 1.0 / (1.0 - top.percent / 100.0).max(1e-9);
    let mut text = format!(
        "Bottleneck of the {}: {} takes {}{interval} of the time itself; if it became free, the whole render would run {} faster.",
        profile.variant,
        top.name,
        format::percent(top.percent, 1),
        format::speedup(limit),
    );
    if let Some(parent) = profile.largest_inclusive().filter(|p| p.name != top.name) {
        let share = parent.inclusive_percent.unwrap_or(parent.percent);
        text += &format!(
            " {} holds more, {} with everything it calls, but only {} itself: the rest is the work it calls.",
            parent.name,
            format::percent(share, 1),
            format::percent(parent.percent, 1)
        );
    }
    Some(text)
}

/// What a profile's function identities are, in a sentence.
fn view_text(view: ProfileView) -> &'static str {
    match view {
        ProfileView::Phases => {
            "Rows are the tracer's phases (camera ray, traversal, each primitive's test, shading, …), recorded by the tracer as it runs and read at each sample, so an inlined test is still its test."
        }
        ProfileView::Native => {
            "Rows are native symbols from the binary's debug info (what the compiler made of the code: inlined functions may be credited to their callers)."
        }
    }
}

/// How a profile was sampled: samples taken and asked, renders, rate, per sample, timer.
fn sampling_text(profile: &Profile) -> String {
    let sampled = profile.samples as f64 * profile.seconds_per_sample;
    let mut text = format!(
        "{} samples at {} of CPU each ({} sampled",
        format::count(profile.samples),
        format::seconds(profile.seconds_per_sample),
        format::seconds(sampled),
    );
    if let Some(asked) = profile.samples_asked {
        text += &format!("; {} asked", format::count(asked));
    }
    if let Some(cpu) = profile.cpu_seconds.filter(|c| *c > 0.0) {
        text += &format!(
            "; effective rate {} samples per CPU second",
            format::fixed(profile.samples as f64 / cpu, 0)
        );
    }
    text += "). ";
    if let Some(timer) = profile.timer {
        text += &format!("{}. ", timer_sentence(timer));
    }
    text += &match profile.renders {
        Some(n) => format!(
            "{} sampled; calls are per render (exact, from the counters; identical for every render), blank where not counted. Shares carry their 95 % sampling interval; rows whose interval reaches 0 are marked as noise. ",
            format::plural(n as usize, "render"),
        ),
        None => "Calls are exact, from the counters, over all sampled renders (a results file from before rtprof.results/3). ".to_string(),
    };
    text += view_text(profile.view);
    text
}

/// Which timer sent the samples and what that means for the rate.
fn timer_sentence(timer: Timer) -> &'static str {
    match timer {
        Timer::PerfCpuClock => {
            "Sampled with perf cpu-clock (a perf_event_open timer on each rendering thread, driven by high-resolution timers: it delivers the rate asked)"
        }
        Timer::Setitimer => {
            "Sampled with setitimer (ITIMER_PROF, which fires on the kernel's tick: it delivers at most about the tick rate, whatever is asked)"
        }
    }
}

/// A share with its 95 % interval, or "noise" when the interval reaches 0.
fn share_cell(percent: f64, interval: Option<[f64; 2]>, noise: bool) -> Cell {
    let cell = Cell::number(format::percent(percent, 2), percent);
    match interval {
        Some([lo, hi]) if noise => {
            Cell::number(format!("noise (≤ {})", format::percent(hi, 2)), percent)
                .tone(Tone::Muted)
                .hover(format!(
                    "95 % interval {} to {}",
                    format::percent(lo, 2),
                    format::percent(hi, 2)
                ))
        }
        Some([lo, hi]) => cell.detail(format!("{}–{}", format::fixed(lo, 2), format::fixed(hi, 2))),
        None => cell,
    }
}

/// The flat profile, largest self time first, with the cumulative time gprof prints,
/// the inclusive share and the 95 % intervals. `renders` is how many renders the
/// samples cover (calls are per render); `None`: calls cover them all.
fn flat_table(flat: &[FlatRow], renders: Option<u64>) -> Table {
    let mut t = Table::new(vec![
        Column::number("self %"),
        Column::number("inclusive %"),
        Column::number("cumulative s"),
        Column::number("self s"),
        Column::number(if renders.is_some() {
            "calls per render"
        } else {
            "calls"
        }),
        Column::number("self per call"),
        Column::number("total per call"),
        Column::text("name").grow(),
    ])
    .sortable();
    let mut rows: Vec<_> = flat.iter().collect();
    rows.sort_by(|a, b| b.self_seconds.total_cmp(&a.self_seconds));
    let mut cumulative = 0.0;
    // Per-call times divide the sampled seconds by every sampled call.
    let sampled_calls = |calls: Option<u64>| calls.map(|c| c.saturating_mul(renders.unwrap_or(1)));
    for row in rows {
        if row.self_seconds.is_finite() {
            cumulative += row.self_seconds;
        }
        let per_call = |s: f64| {
            let calls = sampled_calls(row.calls);
            let value = format::per_call_value(s, calls);
            match format::per_call(s, calls) {
                Some(text) => Cell::number(text, value),
                None => Cell::number("", -1.0),
            }
        };
        t.rows.push(vec![
            share_cell(row.percent, row.self_interval, row.noise),
            match row.inclusive_percent {
                Some(p) => share_cell(p, row.inclusive_interval, false),
                None => Cell::number("", -1.0),
            },
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
        let views = std::iter::once((profile.view, &profile.flame_svg))
            .chain(profile.second_view.iter().map(|v| (v.view, &v.flame_svg)));
        for (view, svg) in views {
            let title = format!(
                "Flamegraph of {}, {} ({})",
                p.scene,
                profile.variant,
                match view {
                    ProfileView::Phases => "phases",
                    ProfileView::Native => "native symbols",
                }
            );
            s.blocks
                .push(flame_block(b, svg, title, view_text(view).to_string()));
        }
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
            s.blocks.push(flame_block(b, diff, title, format!(
                "Frames of the {to} profile, coloured by the change from baseline: red grew, blue shrank. Frames that vanished are not drawn here: see the next graph."
            )));
            if let Some(shrunk) = &p.diff_shrunk_flame_svg {
                let title = format!(
                    "What shrank or vanished in {}, {} to {to}",
                    p.scene, p.baseline.variant
                );
                s.blocks.push(flame_block(b, shrunk, title, format!(
                    "Frames of the baseline profile, coloured by the change to {to}: blue shrank or vanished, red grew."
                )));
            }
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
        "The whole run's speed-up if one function became 2×, 10× or infinitely faster: alone (its self time) and with everything it calls (its inclusive time). Rows are the functions with the most inclusive time, leaving out what stands for the whole render (threads' roots such as `sample row`, frames on at least 99.5 % of the samples). The first row can be a caller whose share is the work it calls; the headline's bottleneck is the most time in one function itself.",
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
            Column::number("self share"),
            Column::number("alone 2×"),
            Column::number("alone free"),
            Column::number("inclusive share"),
            Column::number("with callees 2×"),
            Column::number("with callees 10×"),
            Column::number("with callees free"),
        ])
        .sortable();
        let limit =
            |x: f64| Cell::number(format::speedup(x), if x.is_finite() { x } else { f64::MAX });
        for a in &profile.amdahl {
            let mut row = vec![
                Cell::text(short_name(&a.name)).code().hover(&a.name),
                Cell::number(format::percent(a.fraction * 100.0, 1), a.fraction),
                Cell::number(format::speedup(a.speedup_2x), a.speedup_2x),
                limit(a.speedup_limit),
            ];
            match &a.inclusive {
                Some(i) => row.extend([
                    Cell::number(format::percent(i.fraction * 100.0, 1), i.fraction),
                    Cell::number(format::speedup(i.speedup_2x), i.speedup_2x),
                    Cell::number(format::speedup(i.speedup_10x), i.speedup_10x),
                    limit(i.speedup_limit),
                ]),
                None => row.extend((0..4).map(|_| Cell::dash())),
            }
            t.rows.push(row);
        }
        s.blocks.push(Block::Table(t));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sample results' baseline profile, its timer set to `timer`.
    fn profile_with(timer: Option<Timer>) -> Profile {
        let results = testkit::sample::sample_results();
        let mut profile = results
            .profile
            .map(|p| p.baseline)
            .unwrap_or_else(|| panic!("the sample results have no profile"));
        profile.timer = timer;
        profile
    }

    #[test]
    fn the_sampling_text_names_the_timer_when_the_file_does() {
        let perf = sampling_text(&profile_with(Some(Timer::PerfCpuClock)));
        assert!(perf.contains("Sampled with perf cpu-clock ("), "{perf}");
        let setitimer = sampling_text(&profile_with(Some(Timer::Setitimer)));
        assert!(
            setitimer.contains("Sampled with setitimer ("),
            "{setitimer}"
        );
        // Older files do not say: neither is claimed.
        let unknown = sampling_text(&profile_with(None));
        assert!(!unknown.contains("Sampled with"), "{unknown}");
    }
}
