//! The gprof tables' tests, and the sample profiles the other profile views' tests share.

use super::*;
use crate::profile::gprof_text::*;
use crate::profile::{CallCounts, Stack, StackSamples};

pub(crate) fn samples(stacks: &[(&[&str], u64)], seconds_per_sample: f64) -> StackSamples {
    StackSamples {
        stacks: stacks
            .iter()
            .map(|(frames, count)| Stack {
                frames: frames.iter().map(|f| f.to_string()).collect(),
                count: *count,
            })
            .collect(),
        seconds_per_sample,
    }
}

pub(crate) fn counts(pairs: &[(&str, u64)]) -> CallCounts {
    pairs
        .iter()
        .map(|(name, count)| (name.to_string(), *count))
        .collect()
}

pub(crate) fn close(actual: f64, expected: f64) -> bool {
    (actual - expected).abs() < 1e-9
}

/// main->a 30, main->a->b 50, main->c 20 samples of 10 ms: 1.00 s in all.
pub(crate) fn three_functions() -> StackSamples {
    samples(
        &[
            (&["main", "a"], 30),
            (&["main", "a", "b"], 50),
            (&["main", "c"], 20),
        ],
        0.01,
    )
}

/// main->trace->shade->trace->shade->sphere 10 samples, main->trace->shade 5.
pub(crate) fn recursive_tracer() -> StackSamples {
    samples(
        &[
            (&["main", "trace", "shade", "trace", "shade", "sphere"], 10),
            (&["main", "trace", "shade"], 5),
        ],
        0.01,
    )
}

/// The flat profile of one sampled render.
pub(crate) fn flat_of(samples: &StackSamples, calls: &CallCounts) -> FlatProfile {
    flat_profile(&ProfileInput {
        samples,
        calls,
        renders: 1,
    })
}

/// The call graph of one sampled render.
pub(crate) fn graph_of(samples: &StackSamples, calls: &CallCounts) -> CallGraph {
    call_graph(&ProfileInput {
        samples,
        calls,
        renders: 1,
    })
}

fn entry<'a>(graph: &'a CallGraph, name: &str) -> &'a CallGraphEntry {
    graph.entries.iter().find(|e| e.name == name).unwrap()
}

#[test]
fn recursion_counts_each_sample_once_and_forms_a_cycle() {
    let stacks = recursive_tracer();
    let flat = flat_of(&stacks, &CallCounts::new());
    let row = |name: &str| flat.rows.iter().find(|r| r.name == name).unwrap();
    // trace and shade are on the stack in all 15 samples: 15, not 10 * 2 + 5 = 25.
    assert!(close(
        row("trace").self_seconds + row("trace").children_seconds,
        0.15
    ));
    assert!(close(row("shade").self_seconds, 0.05) && close(row("shade").children_seconds, 0.10));

    let graph = graph_of(&stacks, &CallCounts::new());
    assert!(graph.entries.iter().all(|e| e.percent <= 100.0 + 1e-9));
    let cycle = entry(&graph, "<cycle 1 as a whole>");
    assert!(cycle.whole_cycle && cycle.cycle == Some(1) && cycle.index == 1);
    // Cycle: self = shade's 5 samples, children = sphere's 10.
    assert!(close(cycle.self_seconds, 0.05) && close(cycle.children_seconds, 0.10));
    let members: Vec<&str> = cycle.children.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(members, ["trace", "shade"]); // equal time: trace is nearer the root
    assert_eq!(cycle.parents.len(), 1);
    assert!(
        close(cycle.parents[0].self_seconds, 0.05)
            && close(cycle.parents[0].children_seconds, 0.10)
    );

    let trace = entry(&graph, "trace");
    assert_eq!(trace.cycle, Some(1));
    assert!(close(trace.percent, 100.0) && close(trace.children_seconds, 0.15));
    // main -> trace carries all 15 samples (outermost occurrence).
    let from_main = trace.parents.iter().find(|p| p.name == "main").unwrap();
    assert!(close(from_main.children_seconds, 0.15));
    let sphere = entry(&graph, "sphere");
    assert!(close(sphere.percent, 100.0 * 10.0 / 15.0) && sphere.cycle.is_none());
    let order: Vec<&str> = graph.entries.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(
        order,
        ["<cycle 1 as a whole>", "main", "trace", "shade", "sphere"]
    );

    let text = graph.to_text();
    assert!(
        text.contains("[1]    100.0    0.05    0.10                 <cycle 1 as a whole> [1]\n")
    );
    assert!(text.contains("[3]    100.0    0.00    0.15                 trace <cycle 1> [3]\n"));
    // shade's caller inside the cycle: sibling form, no times, the 15 samples that
    // entered shade from trace (cg_print.c: "%6.6s %5.5s %7.7s %7.7s %7lu %7.7s     ").
    assert!(text.contains(&format!(
        "{:6} {:5} {:7} {:7} {:7} {:7}     trace <cycle 1> [3]\n[4]",
        "", "", "", "", 15, ""
    )));
    // A child line: "%6.6s %5.5s %7.2f %7.2f %7lu/%-7lu     ", samples along the call
    // out of all that entered sphere.
    assert!(text.contains(&format!(
        "{:6} {:5} {:7.2} {:7.2} {:7}/{:<7}     sphere [5]\n",
        "", "", 0.10, 0.0, 10, 10
    )));
    // The cycle's entry starts with its own line (gprof lists no callers there) and
    // lists its members with their calls (0: not counted).
    assert!(text.contains(&format!(
        "called     name\n[1]    100.0    0.05    0.10                 <cycle 1 as a whole> [1]\n\
         {:6} {:5} {:7.2} {:7.2} {:7} {:7}     trace <cycle 1> [3]\n",
        "", "", 0.0, 0.15, 0, ""
    )));
}

#[test]
fn self_recursion_is_a_one_member_cycle() {
    let graph = graph_of(
        &samples(&[(&["main", "walk", "walk", "walk", "leaf"], 4)], 1.0),
        &CallCounts::new(),
    );
    let walk = entry(&graph, "walk");
    assert_eq!(walk.cycle, Some(1));
    assert!(close(walk.children_seconds, 4.0) && close(walk.percent, 100.0)); // not 12
    let cycle = entry(&graph, "<cycle 1 as a whole>");
    assert!(close(cycle.children_seconds, 4.0));
    assert!(entry(&graph, "main").cycle.is_none() && entry(&graph, "leaf").cycle.is_none());
}

#[test]
fn call_graph_text_matches_gprof_layout() {
    let graph = graph_of(
        &samples(&[(&["main", "foo"], 240)], 0.01),
        &counts(&[("foo", 1)]),
    );
    let text = graph.to_text();
    let expected = "\t\t     Call graph (explanation follows)\n\n\n\
granularity: each sample hit covers one call stack for 0.42% of 2.40 seconds\n\
1 render sampled; calls are per render, seconds for that render.\n\
On callers' and callees' lines `called` is samples, not calls (see below).\n\n\
index % time    self  children    called     name\n\
\x20                                                <spontaneous>\n\
[1]    100.0    0.00    2.40                 main [1]\n\
\x20               2.40    0.00     240/240         foo [2]\n\
-----------------------------------------------\n\
\x20               2.40    0.00     240/240         main [1]\n\
[2]    100.0    2.40    0.00       1         foo [2]\n\
-----------------------------------------------\n";
    assert!(text.starts_with(expected), "{text}");
    // The explanation, gprof's form feed, then the index: two names, one row, cells
    // of 26 characters.
    assert!(
        text.contains("not calls, which are not counted per call"),
        "{text}"
    );
    assert!(
        text.ends_with("\n\x0c\nIndex by function name\n\n   [2] foo                   [1] main\n"),
        "{text}"
    );
}

#[test]
fn a_recorded_run_s_graph_says_per_run_and_counts_samples_on_arcs() {
    let mut graph = graph_of(&three_functions(), &CallCounts::new());
    graph.origin = Origin::Recorded;
    let text = graph.to_text();
    assert!(
        text.contains(
            "1 run of the program sampled; seconds are per run, no calls counted.\n\
             On callers' and callees' lines"
        ),
        "{text}"
    );
    assert!(!text.contains("render"), "{text}");
    // main -> a: the 80 samples that flowed along the call, of the 80 that entered a.
    assert!(text.contains("     80/80          a [2]\n"), "{text}");
    // Samples on its arcs: gprof's importer refuses it, as it does a sampled graph.
    assert!(crate::profile::gprof_import::parse(&text).is_err());
}

#[test]
fn call_graph_says_renders_and_shows_calls_per_render() {
    let stacks = samples(&[(&["main", "foo"], 240)], 0.01);
    let graph = call_graph(&ProfileInput {
        samples: &stacks,
        calls: &counts(&[("foo", 7)]),
        renders: 5,
    });
    assert_eq!(graph.renders, 5);
    let text = graph.to_text();
    // Free text above the column headings, as gprof's granularity line.
    let renders_line = "5 renders sampled; calls are per render, seconds for all 5 renders.\n\
                            On callers' and callees' lines";
    assert!(text.contains(renders_line), "{text}");
    // The calls column holds the per-render count as given, not 7 x 5.
    assert!(text.contains("[2]    100.0    2.40    0.00       7         foo [2]\n"));
    let parsed = parse_call_graph_text(&text).unwrap();
    assert_eq!(parsed[1].called, Some(7));
    // renders 0 is read as 1.
    let zero = call_graph(&ProfileInput {
        samples: &stacks,
        calls: &CallCounts::new(),
        renders: 0,
    });
    assert_eq!(zero.renders, 1);
}

#[test]
fn index_fills_three_columns_downwards_and_keeps_long_names() {
    let names = ["a", "b", "c", "d", "a_rather_long_function_name"];
    let stacks: Vec<(&[&str], u64)> = names.iter().map(|n| (std::slice::from_ref(n), 1)).collect();
    let text = graph_of(&samples(&stacks, 1.0), &CallCounts::new()).to_text();
    let index = text.split("Index by function name\n\n").nth(1).unwrap();
    // Five names, two rows, filled down the columns: a, a_rather... | b, c | d.
    // All have 1 sample at depth 0, so entries are numbered by name too. The long
    // name pushes c one space past its own long cell.
    let expected = "   [1] a                     [3] b                     [5] d\n\
                        \x20  [2] a_rather_long_function_name    [4] c\n";
    assert_eq!(index, expected);
}

#[test]
fn call_graph_text_round_trips_through_parser() {
    let mut stacks = recursive_tracer();
    stacks.stacks.push(Stack {
        frames: vec!["main".into(), "a name with spaces".into()],
        count: 7,
    });
    let graph = graph_of(&stacks, &counts(&[("trace", 300), ("sphere", 12_345_678)]));
    let parsed = parse_call_graph_text(&graph.to_text()).unwrap();
    assert_eq!(parsed.len(), graph.entries.len());
    let to_printed = |x: f64, scale: f64| (x * scale).round() / scale;
    let by_index: HashMap<usize, &CallGraphEntry> =
        graph.entries.iter().map(|e| (e.index, e)).collect();
    for (entry, back) in graph.entries.iter().zip(&parsed) {
        assert_eq!(
            (back.index, &back.name, back.cycle, back.called),
            (entry.index, &entry.name, entry.cycle, entry.calls)
        );
        assert!(close(back.percent, to_printed(entry.percent, 10.0)));
        assert!(close(
            back.self_seconds,
            to_printed(entry.self_seconds, 100.0)
        ));
        assert!(close(
            back.children_seconds,
            to_printed(entry.children_seconds, 100.0)
        ));
        // A cycle's entry prints no callers (as gprof); its data keeps them.
        let no_parents = Vec::new();
        let parents = if entry.whole_cycle {
            &no_parents
        } else {
            &entry.parents
        };
        let lines = [(parents, &back.parents), (&entry.children, &back.children)];
        for (arcs, parsed_arcs) in lines {
            let arcs_back: Vec<&ParsedArc> = parsed_arcs
                .iter()
                .filter(|a| a.name != "<spontaneous>")
                .collect();
            assert_eq!(arcs_back.len(), arcs.len());
            for (arc, arc_back) in arcs.iter().zip(arcs_back) {
                assert_eq!(
                    (&arc_back.name, arc_back.index),
                    (&arc.name, Some(arc.index))
                );
                assert_eq!(arc_back.cycle, by_index[&arc.index].cycle);
                if let Some(own) = arc_back.self_seconds {
                    assert!(close(own, to_printed(arc.self_seconds, 100.0)));
                }
                // Every line has a count: samples (S/T) on callers and callees,
                // calls on a cycle's members.
                let called = arc_back.called.as_deref().unwrap_or("");
                let first = called.split('/').next().unwrap_or("");
                if entry.whole_cycle {
                    let calls = by_index[&arc.index].calls.unwrap_or(0);
                    assert_eq!(called, calls.to_string());
                } else {
                    assert_eq!(first, arc.samples.to_string(), "{called:?}");
                }
            }
        }
    }
    let main = parsed.iter().find(|e| e.name == "main").unwrap();
    assert_eq!(main.parents[0].name, "<spontaneous>");
    let shade = parsed.iter().find(|e| e.name == "shade").unwrap();
    // Sibling line: no times; sphere's line has them.
    assert_eq!(shade.parents[0].self_seconds, None);
    assert_eq!(
        shade
            .children
            .iter()
            .find(|c| c.name == "sphere")
            .unwrap()
            .self_seconds,
        Some(0.10)
    );
    let cycle = parsed
        .iter()
        .find(|e| e.cycle == Some(1) && e.name.starts_with("<cycle"))
        .unwrap();
    // Member lines carry the member's call count: trace 300.
    assert_eq!(
        cycle
            .children
            .iter()
            .find(|m| m.name == "trace")
            .unwrap()
            .called
            .as_deref(),
        Some("300")
    );
    let json = serde_json::to_string(&graph).unwrap();
    assert_eq!(serde_json::from_str::<CallGraph>(&json).unwrap(), graph);
}

#[test]
fn parsers_report_the_failing_line() {
    let text = flat_of(&three_functions(), &CallCounts::new()).to_text();
    let broken = text.replacen(" 50.00", " 5x.00", 1);
    assert!(matches!(
        parse_flat_text(&broken),
        Err(GprofParseError::Line { line: 7, .. })
    ));
    assert_eq!(
        parse_flat_text("nothing"),
        Err(GprofParseError::MissingHeader("flat profile"))
    );
    let graph = graph_of(&three_functions(), &CallCounts::new()).to_text();
    let broken = graph.replacen("[1]    100.0", "[1]    1o0.0", 1);
    assert!(matches!(
        parse_call_graph_text(&broken),
        Err(GprofParseError::Line { line: 10, .. })
    ));
    assert!(parse_call_graph_text("index % time\n                0.1").is_err());
}

#[test]
fn odd_input_does_not_panic() {
    let odd = samples(
        &[(&[], 3), (&["x"], u64::MAX), (&["x", "ü"], u64::MAX)],
        f64::NAN,
    );
    for (stacks, calls) in [
        (odd, counts(&[("x", 0)])),
        (samples(&[], 0.0), counts(&[("lonely", 2)])),
    ] {
        let flat = flat_of(&stacks, &calls);
        let graph = graph_of(&stacks, &calls);
        let _ = parse_flat_text(&flat.to_text());
        let _ = parse_call_graph_text(&graph.to_text());
    }
    let lonely = graph_of(&samples(&[], 0.0), &counts(&[("lonely", 2)]));
    assert_eq!(lonely.entries.len(), 1);
    assert!(lonely.to_text().contains("no time propagated"));
    assert!(
        flat_of(&samples(&[], 0.0), &CallCounts::new())
            .to_text()
            .contains(" no time accumulated")
    );
}
