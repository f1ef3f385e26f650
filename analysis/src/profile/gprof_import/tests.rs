//! The importer on real gprof output (tests/data/gprof: GNU gprof 2.40 on the `-pg`
//! builds of loops.c and names.cpp), on odd layouts, and on broken input.

use super::*;
use proptest::prelude::*;

const LOOPS_BRIEF: &str = include_str!("../../../tests/data/gprof/loops-b.txt");
const LOOPS_FULL: &str = include_str!("../../../tests/data/gprof/loops-full.txt");
const NAMES_BRIEF: &str = include_str!("../../../tests/data/gprof/names-b.txt");

fn entry<'a>(graph: &'a CallGraph, name: &str) -> &'a CallGraphEntry {
    graph
        .entries
        .iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no entry {name}"))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn pairs(calls: &[(&str, &str, u64)]) -> BTreeMap<(String, String), u64> {
    calls
        .iter()
        .map(|&(caller, callee, n)| ((caller.to_owned(), callee.to_owned()), n))
        .collect()
}

#[test]
fn flat_profile_of_gprof_b_keeps_its_rows_counts_and_unit() {
    let imported = parse(LOOPS_BRIEF).unwrap();
    let flat = imported.flat.as_ref().unwrap();
    assert_eq!(flat.origin, Origin::Gprof);
    assert_eq!(flat.unit, "us/call");
    assert!(close(flat.seconds_per_sample, 0.01));
    assert!(close(flat.total_seconds, 0.33));
    assert_eq!((flat.samples, flat.renders), (33, 1));
    let rows: Vec<(&str, Option<u64>)> = flat
        .rows
        .iter()
        .map(|r| (r.name.as_str(), r.calls))
        .collect();
    // gprof's order and loops.c's counts (main is not listed: no time, not counted).
    assert_eq!(
        rows,
        [
            ("g", Some(3000)),
            ("odd", Some(500)),
            ("fact", Some(100)),
            ("even", Some(600)),
            ("f", Some(1000)),
        ]
    );
    let g = &flat.rows[0];
    assert!(close(g.percent, 36.42) && close(g.self_seconds, 0.12));
    assert!(close(g.cumulative_seconds, 0.12));
    assert_eq!(
        (g.self_per_call, g.total_per_call),
        (Some(40.06), Some(40.06))
    );
    assert_eq!((g.self_samples, g.inclusive_samples), (12, 12));
    // f: no time itself; its children's from its call graph entry (0.12 s, 36.4 %).
    let f = &flat.rows[4];
    assert!(f.noise && close(f.self_seconds, 0.0));
    assert!(close(f.children_seconds, 0.12) && close(f.inclusive_percent, 36.4));
    assert_eq!(f.inclusive_samples, 12);
    assert!(f.self_interval.low == 0.0 && f.self_interval.high > 0.0);
    assert!(!f.root && !g.root);
    assert_eq!(imported.calls()["even"], 600);
}

#[test]
fn call_graph_of_gprof_b_keeps_gprofs_exact_counts_and_cycles() {
    let imported = parse(LOOPS_BRIEF).unwrap();
    let graph = imported.call_graph.as_ref().unwrap();
    assert_eq!(graph.origin, Origin::Gprof);
    assert!(close(graph.total_seconds, 0.33));
    assert_eq!(graph.total_samples, 33);
    let indexes: Vec<usize> = graph.entries.iter().map(|e| e.index).collect();
    assert_eq!(indexes, [1, 2, 3, 4, 5, 6, 7]);
    // loops.c: main -> f 1000, f -> g 3 each, main -> even 100, even <-> odd 500
    // each way, main -> fact 100 and fact -> fact 4 a round.
    assert_eq!(
        imported.arc_calls(),
        pairs(&[
            ("main", "even", 100),
            ("main", "f", 1000),
            ("main", "fact", 100),
            ("f", "g", 3000),
            ("odd", "even", 500),
            ("fact", "fact", 400),
            ("even", "odd", 500),
        ])
    );
    let main = entry(graph, "main");
    assert!(main.parents.is_empty() && main.calls.is_none());
    assert!(close(main.percent, 100.0) && close(main.children_seconds, 0.33));
    let cycle = entry(graph, "<cycle 1 as a whole>");
    assert!(cycle.whole_cycle && cycle.cycle == Some(1) && cycle.index == 2);
    assert_eq!((cycle.calls, cycle.self_calls), (Some(100), Some(1000)));
    let members: Vec<(&str, Option<u64>)> = cycle
        .children
        .iter()
        .map(|m| (m.name.as_str(), m.calls))
        .collect();
    assert_eq!(members, [("odd", Some(500)), ("even", Some(600))]);
    let even = entry(graph, "even");
    assert_eq!(
        (even.cycle, even.calls, even.self_calls),
        (Some(1), Some(600), None)
    );
    // Its caller within the cycle carries no times; main's line carries 0.14 s.
    assert_eq!(even.parents[0].name, "odd");
    assert!(close(even.parents[0].self_seconds, 0.0));
    assert_eq!(
        (even.parents[1].name.as_str(), even.parents[1].index),
        ("main", 1)
    );
    assert!(close(even.parents[1].self_seconds, 0.14));
    assert_eq!(even.parents[1].samples, 14);
    let fact = entry(graph, "fact");
    assert_eq!(
        (fact.cycle, fact.calls, fact.self_calls),
        (None, Some(100), Some(400))
    );
    // The flat profile's root is gprof's spontaneous main (not a flat row here).
    assert!(imported.flat.unwrap().rows.iter().all(|r| !r.root));
}

#[test]
fn gprof_with_explanations_reads_as_gprof_b() {
    // The same gmon.out printed with and without -b: the same profile.
    assert_eq!(parse(LOOPS_FULL).unwrap(), parse(LOOPS_BRIEF).unwrap());
}

#[test]
fn demangled_cpp_names_with_spaces_parentheses_and_templates() {
    let imported = parse(NAMES_BRIEF).unwrap();
    let flat = imported.flat.as_ref().unwrap();
    let dot = "double rt::dot<double>(rt::Vec<double> const&, rt::Vec<double> const&)";
    let trace = "(anonymous namespace)::trace(std::vector<rt::Sphere, std::allocator<rt::Sphere> > const&, int)";
    let call = "rt::Sphere::operator()(int) const";
    let intersect = "rt::Sphere::intersect(rt::Vec<double> const&) const";
    let destructor = "std::_Vector_base<rt::Sphere, std::allocator<rt::Sphere> >::~_Vector_base()";
    let names: Vec<&str> = flat.rows.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, [dot, intersect, call, trace, destructor]);
    assert!(close(flat.rows[0].percent, 100.15)); // gprof's rounding, as printed
    let graph = imported.call_graph.as_ref().unwrap();
    // gprof skips indexes it does not print: [12] follows [5].
    assert_eq!(entry(graph, destructor).index, 12);
    assert_eq!(
        imported.arc_calls(),
        pairs(&[
            ("main", trace, 3000),
            ("main", destructor, 1),
            (intersect, dot, 21000),
            (call, intersect, 21000),
            (trace, call, 21000),
        ])
    );
    // A root: main, spontaneous, calling others; the dot product holds all the time.
    assert!(entry(graph, "main").parents.is_empty());
    let row = flat.rows.iter().find(|r| r.name == trace).unwrap();
    assert!(close(row.inclusive_percent, 100.0) && row.calls == Some(3000));
}

#[test]
fn imported_call_graph_prints_as_gprof_and_reads_back_the_same() {
    let imported = parse(LOOPS_BRIEF).unwrap();
    let graph = imported.call_graph.unwrap();
    let text = graph.to_text();
    // gprof's own lines for the cycle, fact's self-calls and the arcs.
    for line in [
        "[2]     42.4    0.14    0.00     100+1000    <cycle 1 as a whole> [2]\n",
        "                0.09    0.00     500             odd <cycle 1> [5]\n",
        "                0.14    0.00     100/100         even <cycle 1> [7]\n",
        "                0.00    0.12    1000/1000        f [4]\n",
        "                                 400             fact [6]\n",
        "[6]     21.2    0.07    0.00     100+400     fact [6]\n",
        "                                 500             odd <cycle 1> [5]\n",
    ] {
        assert!(text.contains(line), "no {line:?} in\n{text}");
    }
    assert!(text.contains("\n\x0c\nIndex by function name\n"));
    let back = parse(&text).unwrap().call_graph.unwrap();
    assert_eq!(back.entries, graph.entries);
    assert!(close(back.total_seconds, graph.total_seconds));
    assert_eq!(back.total_samples, graph.total_samples);
}

#[test]
fn flat_profile_alone_and_call_graph_alone() {
    let flat_only: String = LOOPS_BRIEF
        .split("\t\t\tCall graph")
        .next()
        .unwrap()
        .to_owned();
    let imported = parse(&flat_only).unwrap();
    assert!(imported.call_graph.is_none());
    let flat = imported.flat.unwrap();
    // Without a call graph, f's children come from total per call x calls:
    // 120.19 us x 1000 = 0.12019 s.
    let f = flat.rows.iter().find(|r| r.name == "f").unwrap();
    assert!((f.children_seconds - 0.12019).abs() < 1e-9);

    let graph_only = LOOPS_BRIEF.split('\x0c').nth(1).unwrap();
    let imported = parse(graph_only).unwrap();
    assert!(imported.flat.is_none());
    assert_eq!(imported.calls()["g"], 3000);
    assert_eq!(imported.call_graph.unwrap().total_samples, 33);
}

#[test]
fn odd_but_valid_layouts() {
    // A name that starts with a digit after blank call columns, a count wider than
    // its column, `(index)` for a function gprof does not list, and "s/call".
    let text = [
        "Flat profile:".to_owned(),
        String::new(),
        "Each sample counts as 0.01 seconds.".to_owned(),
        "  %   cumulative   self              self     total           ".to_owned(),
        " time   seconds   seconds    calls   s/call   s/call  name    ".to_owned(),
        format!(
            "{:6.2} {:9.2} {:8.2} {:8} {:8} {:8}  3d_render",
            60.0, 0.03, 0.03, "", "", ""
        ),
        format!(
            "{:6.2} {:9.2} {:8.2} {:8} {:8.2} {:8.2}  many",
            40.0, 0.05, 0.02, 123_456_789, 0.0, 0.0
        ),
        String::new(),
        "index % time    self  children    called     name".to_owned(),
        format!(
            "{:6} {:5} {:7.2} {:7.2} {:7}/{:<7}     main (9)",
            "", "", 0.02, 0.0, 123_456_789, 123_456_789
        ),
        format!(
            "{:<6} {:5.1} {:7.2} {:7.2} {:7} {:7} many [1]",
            "[1]", 40.0, 0.02, 0.0, 123_456_789, ""
        ),
        "-".repeat(47),
    ]
    .join("\n");
    let text = text.as_str();
    let imported = parse(text).unwrap();
    let flat = imported.flat.as_ref().unwrap();
    assert_eq!(flat.unit, " s/call");
    assert_eq!(flat.rows[0].name, "3d_render");
    assert_eq!(flat.rows[0].calls, None);
    assert_eq!(flat.rows[1].calls, Some(123_456_789));
    let many = &imported.call_graph.as_ref().unwrap().entries[0];
    assert_eq!(many.calls, Some(123_456_789));
    assert_eq!(
        (many.parents[0].name.as_str(), many.parents[0].index),
        ("main", 9)
    );
}

#[test]
fn broken_input_names_the_line() {
    let line_of = |text: &str| match parse(text) {
        Err(GprofImportError::Line { line, problem }) => (line, problem),
        other => panic!("expected a line error, got {other:?}"),
    };
    // Line 6 is g's row: its percent is not a number.
    let (line, problem) = line_of(&LOOPS_BRIEF.replacen(" 36.42", " 3x.42", 1));
    assert_eq!(line, 6, "{problem}");
    assert!(problem.contains("% time"), "{problem}");
    let number_of = |start: &str| {
        LOOPS_BRIEF
            .lines()
            .position(|l| l.starts_with(start))
            .unwrap()
            + 1
    };
    // main's [1] line.
    let (line, problem) = line_of(&LOOPS_BRIEF.replacen("[1]    100.0", "[1]    10o.0", 1));
    assert_eq!(line, number_of("[1] "), "{problem}");
    // An arc without its index: main's line for f, the one after even's.
    let f_line = number_of("[1] ") + 2;
    assert!(
        LOOPS_BRIEF
            .lines()
            .nth(f_line - 1)
            .unwrap()
            .ends_with(" f [4]")
    );
    let (line, problem) = line_of(&LOOPS_BRIEF.replacen("f [4]\n", "f\n", 1));
    assert_eq!(line, f_line, "{problem}");
    assert!(problem.contains("[index]"), "{problem}");
    // A count that is not one.
    let (line, _) = line_of(&LOOPS_BRIEF.replacen("1000/1000", "1000/x", 1));
    assert_eq!(line, f_line);
    // Headings missing: the section's title line.
    let (line, problem) = line_of("Flat profile:\n\nnothing here\n");
    assert_eq!(line, 1, "{problem}");
    // An entry without its own line.
    let (_, problem) = line_of(
        "index % time    self  children    called     name\n\
         \x20               0.00    0.12    1000/1000        main [1]\n\
         -----------------------------------------------\n",
    );
    assert!(problem.contains("without its [index] line"), "{problem}");
    // gprof -T.
    let (line, problem) =
        line_of("\n\nindex  %time    self descendents  called+self    name    index\n");
    assert_eq!(line, 3);
    assert!(problem.contains("-T"), "{problem}");
    // rtprof's own sampled call graph: its arc counts are samples.
    let sampled = crate::profile::gprof::tests::graph_of(
        &crate::profile::gprof::tests::three_functions(),
        &CallCounts::new(),
    )
    .to_text();
    let (line, problem) = line_of(&sampled);
    assert_eq!(line, 6, "{problem}");
    assert!(problem.contains("rtprof's sampled call graph"), "{problem}");
    assert_eq!(parse("hello\n"), Err(GprofImportError::NothingFound));
    assert_eq!(parse(""), Err(GprofImportError::NothingFound));
}

#[test]
fn read_names_the_file_and_line() {
    let dir = std::env::temp_dir().join(format!("rtprof-gprof-import-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("gprof.txt");
    std::fs::write(&path, LOOPS_BRIEF.replacen(" 36.42", " 3x.42", 1)).unwrap();
    let message = read(&path).unwrap_err().to_string();
    assert_eq!(
        message,
        format!("{}:6: % time is not a number: \"3x.42\"", path.display())
    );
    std::fs::write(&path, LOOPS_BRIEF).unwrap();
    assert_eq!(read(&path).unwrap(), parse(LOOPS_BRIEF).unwrap());
    let missing = read(&dir.join("none.txt")).unwrap_err().to_string();
    assert!(missing.starts_with("cannot read "), "{missing}");
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #[test]
    fn truncated_input_never_panics(cut in 0usize..8000, which in 0usize..3) {
        let text = [LOOPS_BRIEF, LOOPS_FULL, NAMES_BRIEF][which];
        let mut end = cut.min(text.len());
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        let _ = parse(&text[..end]);
    }

    #[test]
    fn damaged_input_never_panics(
        which in 0usize..3,
        edits in proptest::collection::vec((0usize..8000, any::<char>()), 1..20),
    ) {
        let mut text: Vec<char> = [LOOPS_BRIEF, LOOPS_FULL, NAMES_BRIEF][which].chars().collect();
        for (at, c) in edits {
            let at = at % text.len();
            text[at] = c;
        }
        let text: String = text.into_iter().collect();
        if let Ok(imported) = parse(&text) {
            // Whatever reads back also prints.
            let _ = imported.call_graph.map(|g| g.to_text());
            let _ = imported.flat.map(|f| f.to_text());
        }
    }

    #[test]
    fn random_lines_never_panic(lines in proptest::collection::vec("[ -~\t\x0c]{0,80}", 0..30)) {
        let mut text = String::from("Flat profile:\nEach sample counts as 0.01 seconds.\n time   seconds   seconds    calls  us/call  us/call  name\n");
        text.push_str(&lines.join("\n"));
        text.push_str("\nindex % time    self  children    called     name\n");
        text.push_str(&lines.join("\n"));
        let _ = parse(&text);
    }
}
