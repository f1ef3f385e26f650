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

/// The profile chapter: the baseline's profile of the suite's profile scene (the
/// thesis's SPD rings by default): its finding, the flat profile in the phases view,
/// the calls and self-time charts, the flamegraph and the differential one, and the
/// Amdahl table. Everything else a profile holds is in [`profile_details`].
pub fn profile(b: &mut Builder) -> Section {
    let mut s = b.section(
        "profile",
        Some("table 6 (gprof flat profile of SPD rings, 640x480, Core i5-4570) and fig. 53 (call tree)"),
    );
    let Some(p) = &b.results().profile else {
        return s.empty("No profile in this run: the suite ran without profiling, or the profile failed (see Failures).");
    };
    if let Some(text) = headline(&p.baseline) {
        s.blocks.push(Block::text(text));
    }
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text("Sampled profile of "),
            Inline::strong(&p.scene),
            Inline::text(format!(
                " at {}, baseline, in the layout of gprof; the call graph, the native symbols{} are in ",
                format::size(p.width, p.height),
                p.best.as_ref().map_or_else(String::new, |x| format!(
                    " and the best variant ({})",
                    x.variant
                )),
            )),
            Inline::Link {
                text: "the appendix".to_string(),
                target: "profile-details".to_string(),
            },
            Inline::text("."),
        ],
    });
    if let Some(warning) = sample_warning(&p.baseline) {
        s.blocks.push(Block::note(Tone::Warning, warning));
    }
    let mut flat = b.section("profile-flat", None);
    flat.blocks.push(Block::text(sampling_text(&p.baseline)));
    flat.blocks.extend(flat_blocks(b, &p.scene, &p.baseline));
    s.absorb(flat);
    s.absorb(profile_charts(b));
    s.absorb(flamegraphs(b));
    s.absorb(amdahl(b));
    s
}

/// The profile's detail, for the appendix: the call graphs, the best variant's flat
/// profile, the native-symbol views and their flamegraphs, the best variant's Amdahl
/// table. `None` without a profile.
pub fn profile_details(b: &mut Builder) -> Option<Section> {
    let p = b.results().profile.as_ref()?;
    let mut s = b.section("profile-details", None);
    s.text(format!(
        "The rest of the profile of {} at {}: the call graphs in gprof's layout, the profile of the best variant, and the same samples by native symbol.",
        p.scene,
        format::size(p.width, p.height)
    ));
    for profile in profiles(p) {
        s.blocks.push(Block::heading(format!(
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
    if let Some(best) = &p.best {
        s.blocks
            .push(Block::heading(format!("Flat profile: {}", best.variant)));
        s.blocks.push(Block::text(sampling_text(best)));
        s.blocks.extend(flat_blocks(b, &p.scene, best));
        s.blocks.extend(amdahl_blocks(&p.scene, best));
    } else {
        s.blocks.push(Block::empty(
            "Only the baseline was profiled (no best variant).",
        ));
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
            "The same samples attributed to the functions the binary's debug info names at each sample. Inlining decides what shows here: a test inlined into its caller is counted as the caller. The phase view does not depend on it. Rows marked as rtprof's phase markers are the profiler's own instrumentation, which an unprofiled render does not run; `Counter::` rows are the operations themselves (the maths is written as methods of the counter trait, whose tally is a no-op when not counting); rows whose share is within sampling noise are left out (they are in the file).",
        ));
        s.blocks.push(Block::Table(
            native_table(&native.flat, profile.renders).caption(format!(
                "Native flat profile of {}, {}",
                p.scene, profile.variant
            )),
        ));
        s.blocks
            .push(flat_text_block(b, &native.flat_text, "native flat profile"));
        let title = format!(
            "Flamegraph of {}, {} (native symbols)",
            p.scene, profile.variant
        );
        s.blocks.push(flame_block(
            b,
            &native.flame_svg,
            title,
            view_text(ProfileView::Native).to_string(),
        ));
    }
    if let (Some(shrunk), Some(best)) = (&p.diff_shrunk_flame_svg, &p.best) {
        let title = format!(
            "What shrank or vanished in {}, {} to {}",
            p.scene, p.baseline.variant, best.variant
        );
        s.blocks.push(flame_block(b, shrunk, title, format!(
            "Frames of the baseline profile, coloured by the change to {}: blue shrank or vanished, red grew.",
            best.variant
        )));
    }
    Some(s)
}

/// A profile's flat table (or why there is none) and its gprof-layout text.
fn flat_blocks(b: &Builder, scene: &str, profile: &Profile) -> Vec<Block> {
    let table = if profile.flat.is_empty() {
        Block::empty("The flat profile has no rows (no samples landed in the tracer).")
    } else {
        Block::Table(flat_table(&profile.flat, profile.renders).caption(format!(
            "Flat profile of {scene}, {}, in the layout of table 6",
            profile.variant
        )))
    };
    vec![
        table,
        flat_text_block(b, &profile.flat_text, "flat profile"),
    ]
}

/// Fewer samples than this make a profile's shares too coarse to rank close rows.
pub const ENOUGH_SAMPLES: u64 = 2_000;

/// A warning when a profile is short of samples or got far fewer than it asked,
/// with the widest 95 % interval of its shares.
pub fn sample_warning(profile: &Profile) -> Option<String> {
    let asked = profile.samples_asked.unwrap_or(profile.samples);
    let short = profile.samples < ENOUGH_SAMPLES;
    let starved = asked > 0 && (profile.samples as f64) < 0.5 * asked as f64;
    if !short && !starved {
        return None;
    }
    let mut text = format!(
        "Few samples: {} of the {} asked",
        format::count(profile.samples),
        format::count(asked)
    );
    text += if starved {
        " (the timer delivered fewer than half: a tick-driven timer or a busy machine)."
    } else {
        "."
    };
    let widest = profile
        .flat
        .iter()
        .filter_map(|row| row.self_interval.map(|[lo, hi]| (hi - lo) / 2.0))
        .fold(f64::NAN, f64::max);
    if widest.is_finite() {
        text += &format!(
            " The shares' 95 % intervals are up to ±{} points wide: read rows closer than that as equal.",
            format::fixed(widest, 1)
        );
    }
    Some(text)
}

/// A flamegraph file as a block with its title and caption.
pub(crate) fn flame_block(b: &mut Builder, svg: &str, title: String, caption: String) -> Block {
    let visual = b.flamegraph(svg, &title);
    Block::Flamegraph(Flamegraph {
        title,
        caption: Some(caption),
        visual,
    })
}

/// A flat profile's gprof-layout text, folded away, or a note that it is missing.
pub(crate) fn flat_text_block(b: &Builder, path: &str, what: &str) -> Block {
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

/// The flamegraphs part of the profile chapter: the baseline's phases, and the
/// differential graph to the best variant.
pub fn flamegraphs(b: &mut Builder) -> Section {
    let mut s = b.section(
        "flamegraphs",
        Some("no counterpart (the thesis used gprof's call tree, fig. 53)"),
    );
    let Some(p) = &b.results().profile else {
        return s.empty("No profile in this run, so no flamegraphs.");
    };
    s.text("Each box is a function; its width is its share of the samples, the boxes above it are its callees. In the HTML report, hover a frame for its name and share, click to zoom.");
    let title = format!("Flamegraph of {}, {}", p.scene, p.baseline.variant);
    s.blocks.push(flame_block(
        b,
        &p.baseline.flame_svg,
        title,
        view_text(p.baseline.view).to_string(),
    ));
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
                "Frames of the {to} profile, coloured by the change from baseline: red grew, blue shrank. Frames that vanished are in the appendix's graph of what shrank."
            )));
        }
        (None, _) => s.blocks.push(Block::empty(
            "No differential flamegraph: only one variant was profiled.",
        )),
    }
    s
}

/// The Amdahl part of the profile chapter: the baseline's table.
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
    s.blocks.extend(amdahl_blocks(&p.scene, &p.baseline));
    s
}

/// One profile's Amdahl table, under a heading naming it.
fn amdahl_blocks(scene: &str, profile: &Profile) -> Vec<Block> {
    let mut blocks = vec![Block::subheading(format!(
        "Amdahl's law: {scene} · {}",
        profile.variant
    ))];
    if profile.amdahl.is_empty() {
        blocks.push(Block::empty("The profile has no Amdahl rows."));
        return blocks;
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
    let limit = |x: f64| Cell::number(format::speedup(x), if x.is_finite() { x } else { f64::MAX });
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
    blocks.push(Block::Table(t));
    blocks
}

/// Native symbols that are rtprof's own instrumentation (the phase markers the
/// profile reads), not the tracer's work: an unprofiled render does not run them.
pub const INSTRUMENTATION: [&str; 2] = ["PhaseGuard", "enter_phase"];

/// Whether a native symbol is rtprof's own instrumentation (see [`INSTRUMENTATION`]).
pub fn is_instrumentation(name: &str) -> bool {
    INSTRUMENTATION.iter().any(|mark| name.contains(mark))
}

/// The native flat profile without the rows within sampling noise (their count in
/// the caption's last row), rtprof's own instrumentation labelled.
fn native_table(flat: &[FlatRow], renders: Option<u64>) -> Table {
    let kept: Vec<FlatRow> = flat.iter().filter(|r| !r.noise).cloned().collect();
    let left_out = flat.len() - kept.len();
    let mut t = flat_table(&kept, renders);
    for row in &mut t.rows {
        let Some(name) = row.last_mut() else {
            continue;
        };
        if is_instrumentation(&name.text) {
            name.detail = Some("rtprof's phase markers (only when profiling)".to_string());
            name.tone = Tone::Muted;
        } else if name.text.contains("Counter::") {
            // The maths the tracer does is written as methods of the counter trait
            // (uncounted: no tally), so debug info names them after it.
            name.detail = Some("the operation itself, written in the counter trait".to_string());
        }
    }
    if left_out > 0 {
        let columns = t.columns.len() as u32;
        t.rows.push(vec![
            Cell::text(format!(
                "{} more {} within sampling noise (in the file)",
                left_out,
                if left_out == 1 { "row" } else { "rows" }
            ))
            .tone(Tone::Muted)
            .span(columns),
        ]);
    }
    t
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
