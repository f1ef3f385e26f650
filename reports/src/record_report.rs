//! The report of `rtprof record` (report.html, report.pdf): one recorded run of a
//! program rtprof did not write. Its first page answers "where does the time go" by
//! phase of ray tracing (the program's probe when it wrote one, else the phase rules)
//! and by function (the flat profile), each share with its 95 % interval; with a probe
//! file, the FPGA question for the program, its exact counts and its phases beside the
//! rules' ([`crate::record_probe`]); the program beside the thesis's table 6; then the
//! flamegraph, what the symbols and stacks covered per module, and the recording's
//! facts. Built as a [`Document`] like the suite's report, so the same renderers lay it
//! out.

use analysis::profile::amdahl::speedup;
use analysis::profile::flat::FlatProfile;
use analysis::profile::perf_data::coverage::ModuleCoverage;
use analysis::profile::phase_rules::{PhaseBreakdown, PhaseSource};
use analysis::profile::share_interval::ShareInterval;

use crate::document::{
    AssetKind, Assets, Block, Cell, Column, Document, Flamegraph, Image, Inline, Metadata, Pair,
    Section, Table, Tone, Visual, svg_size,
};
use crate::format;
use crate::record_probe::{
    ProbeReport, comparison_section, counts_section, fpga_section, table6_section,
};

/// Functions the first page lists by self time.
const FUNCTIONS_LISTED: usize = 15;
/// A phase share under which the answer does not name a second phase (percent).
const SECOND_PHASE_PERCENT: f64 = 10.0;

/// What a recorded run's report is made of: plain data the runner fills.
pub struct RecordReport<'a> {
    /// The program's short name (`rtiow`).
    pub program: &'a str,
    /// The command line as run.
    pub command: &'a str,
    /// How it ended: "exited with code 0", "was killed by signal SIGSEGV (11)".
    pub end: &'a str,
    pub success: bool,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
    pub samples: u64,
    pub frequency: u32,
    /// "frame pointers" or "DWARF unwinding".
    pub call_graph: &'a str,
    pub lost_samples: u64,
    pub processes: usize,
    pub flat: &'a FlatProfile,
    /// The phases by the phase rules (the report's phases unless the probe sampled).
    pub phases: &'a PhaseBreakdown,
    pub modules: &'a [ModuleCoverage],
    /// The flamegraph SVG and its file name beside the report.
    pub flamegraph: Option<(String, String)>,
    /// The files written beside the report.
    pub files: &'a [String],
    /// What the call stacks may get wrong (a frame-pointer recording with much time in
    /// libraries built without them).
    pub caveat: Option<String>,
    /// What the program's probe file gave, when it wrote one that could be read.
    pub probe: Option<ProbeReport<'a>>,
    /// Why the probe file the program wrote could not be read.
    pub probe_error: Option<&'a str>,
}

impl RecordReport<'_> {
    /// The phases the report shows: the probe's when it sampled any, else the rules'.
    pub fn shown_phases(&self) -> &PhaseBreakdown {
        self.probe
            .as_ref()
            .and_then(|p| p.phases)
            .unwrap_or(self.phases)
    }
}

/// `a – b` of an interval given in percent.
fn interval_text(i: ShareInterval) -> String {
    format!(
        "{} – {}",
        format::percent(i.low, 1),
        format::percent(i.high, 1)
    )
}

/// The report of a recorded run.
pub fn build(r: &RecordReport) -> Document {
    let mut assets = Assets::default();
    let mut sections = vec![where_the_time_goes(r)];
    if let Some(fpga) = r.probe.as_ref().and_then(|p| p.fpga) {
        sections.push(fpga_section(r.program, fpga));
    }
    sections.push(table6_section(
        r.program,
        r.shown_phases(),
        r.probe.as_ref(),
    ));
    if let Some(p) = &r.probe {
        sections.push(counts_section(p));
        if !p.comparison.is_empty() {
            sections.push(comparison_section(p.comparison));
        }
    }
    if let Some((svg, file)) = &r.flamegraph {
        let (width, height) = svg_size(svg).unwrap_or((1200.0, 600.0));
        let asset = assets.add(AssetKind::Svg, svg.clone().into_bytes());
        sections.push(section(
            "record-flamegraph",
            "Flamegraph",
            vec![Block::Flamegraph(Flamegraph {
                title: format!("{} (every sampled stack)", r.program),
                caption: Some(
                    "Each box a function on the stack, as wide as its share of the samples; \
                     callers below, callees above; inlined functions are boxes of their own."
                        .to_string(),
                ),
                visual: Visual::Image(Image {
                    asset,
                    width,
                    height,
                    alt: format!("flamegraph of {}", r.program),
                    file: Some(file.clone()),
                }),
            })],
        ));
    }
    sections.push(rules_section(r.phases));
    sections.push(coverage_section(r.modules));
    sections.push(recording_section(r));
    Document {
        title: format!("Where the time goes in {}", r.program),
        metadata: Metadata {
            subtitle: format!("rtprof record -- {}", r.command),
            byline: format!(
                "{} samples · {} of CPU · {}",
                format::count(r.samples),
                format::seconds(r.cpu_seconds),
                r.end
            ),
            subject: r.program.to_string(),
            reference: String::new(),
            generator: format!("rtprof {}", env!("CARGO_PKG_VERSION")),
        },
        notices: notices(r),
        sections,
        assets,
    }
}

fn section(id: &str, heading: &str, blocks: Vec<Block>) -> Section {
    Section {
        id: id.to_string(),
        heading: heading.to_string(),
        blocks,
        ..Section::default()
    }
}

/// What a reader must know first: a failed run, lost samples, few samples.
fn notices(r: &RecordReport) -> Vec<String> {
    let mut out = Vec::new();
    if !r.success {
        out.push(format!(
            "The program {}: this profile is of the part that ran.",
            r.end
        ));
    }
    if r.lost_samples > 0 {
        out.push(format!(
            "perf lost {} samples (its buffers were full): shares may be skewed.",
            format::count(r.lost_samples)
        ));
    }
    if let Some(caveat) = &r.caveat {
        let mut c = caveat.clone();
        if let Some(first) = c.get(..1) {
            let upper = first.to_uppercase();
            c.replace_range(..1, &upper);
        }
        out.push(format!("{c}."));
    }
    if let Some(e) = r.probe_error {
        out.push(format!(
            "The program's probe file could not be read ({e}): no exact counts and no probe \
             phases; the profile from perf's samples stands, with the phase rules' phases."
        ));
    }
    if r.samples < 100 {
        out.push(format!(
            "Only {}: every share below has a wide interval. Run longer or raise --freq.",
            format::plural(r.samples as usize, "sample")
        ));
    }
    out
}

/// The first page: the answer in words, then by phase and by function.
fn where_the_time_goes(r: &RecordReport) -> Section {
    let mut blocks = vec![Block::Paragraph { content: answer(r) }];
    blocks.push(Block::heading("By phase of ray tracing"));
    blocks.push(Block::Table(phase_table(r.shown_phases())));
    blocks.push(Block::heading("By function"));
    blocks.push(Block::Table(function_table(r.flat)));
    section("record-answer", "Where the time goes", blocks)
}

/// The answer in a sentence or two: the largest phase and the hottest function.
fn answer(r: &RecordReport) -> Vec<Inline> {
    let mut out = Vec::new();
    let phases = r.shown_phases();
    let classified: Vec<_> = phases
        .phases
        .iter()
        .filter(|p| !phases.is_rest(&p.phase))
        .collect();
    match classified.first() {
        Some(top) => {
            out.push(Inline::text(format!("Of {}'s CPU time, ", r.program)));
            out.push(Inline::strong(format!(
                "{} takes {}",
                top.phase,
                format::percent(100.0 * top.share, 1)
            )));
            out.push(Inline::text(format!(
                " (95 % interval {})",
                interval_text(top.interval.scaled(100.0))
            )));
            if let Some(second) = classified
                .get(1)
                .filter(|p| 100.0 * p.share >= SECOND_PHASE_PERCENT)
            {
                out.push(Inline::text(format!(
                    ", {} {}",
                    second.phase,
                    format::percent(100.0 * second.share, 1)
                )));
            }
            out.push(Inline::text(format!(
                ": made free, the whole run would be {} faster. ",
                format::speedup(speedup(top.share, f64::INFINITY))
            )));
        }
        None => out.push(Inline::text(match phases.source {
            PhaseSource::Rules => "No phase rule matched any sample (see the rules below). ",
            PhaseSource::Probe => "No sample fell in a phase the program marked. ",
        })),
    }
    if let Some(row) = r.flat.rows.iter().find(|row| !row.whole_run()) {
        out.push(Inline::text("The function with the most self time is "));
        out.push(Inline::code(row.name.clone()));
        out.push(Inline::text(format!(
            " ({} of the samples, {} with what it calls). ",
            format::percent(row.percent, 1),
            format::percent(row.inclusive_percent, 1)
        )));
    }
    out.push(Inline::text(match phases.source {
        PhaseSource::Rules => format!(
            "Phases by {}, which classified {} of {} samples.",
            phases.origin,
            format::percent(100.0 * phases.classified_share(), 1),
            format::count(phases.samples)
        ),
        PhaseSource::Probe => format!(
            "Phases by {}: {} of its {} samples fell in a phase the program marked.",
            phases.origin,
            format::percent(100.0 * phases.classified_share(), 1),
            format::count(phases.samples)
        ),
    }));
    out
}

fn phase_table(b: &PhaseBreakdown) -> Table {
    let mut t = Table::new(vec![
        Column::text("phase").grow(),
        Column::number("share").detail("95 % interval"),
        Column::number("CPU"),
        Column::number("samples"),
        Column::number("if free").detail("whole run"),
    ])
    .caption(match b.source {
        PhaseSource::Rules => {
            "A sample's phase is that of the innermost frame of its stack a rule matches; \
             \"if free\" is Amdahl's law: the whole run's speed-up if the phase took no time."
        }
        PhaseSource::Probe => {
            "A sample's phase is the innermost phase the program had marked when the probe's \
             sampler (inside the program, on each thread's CPU time) took it; \"if free\" is \
             Amdahl's law: the whole run's speed-up if the phase took no time."
        }
    });
    for p in &b.phases {
        let unclassified = b.is_rest(&p.phase);
        t.rows.push(vec![
            Cell::text(p.phase.clone()).tone(if unclassified {
                Tone::Muted
            } else {
                Tone::Neutral
            }),
            Cell::number(format::percent(100.0 * p.share, 1), p.share)
                .detail(interval_text(p.interval.scaled(100.0))),
            Cell::number(format::seconds(p.seconds), p.seconds),
            Cell::count(p.samples),
            if unclassified {
                Cell::dash()
            } else {
                let s = speedup(p.share, f64::INFINITY);
                Cell::number(format::speedup(s), s)
            },
        ]);
    }
    t
}

fn function_table(flat: &FlatProfile) -> Table {
    let mut t = Table::new(vec![
        Column::text("function").grow(),
        Column::number("self").detail("95 % interval"),
        Column::number("with callees").detail("95 % interval"),
        Column::number("self CPU"),
    ])
    .caption(format!(
        "The {} functions with the most self time (flat-*.txt has them all); inlined \
         functions are rows of their own.",
        FUNCTIONS_LISTED
    ));
    for row in flat.rows.iter().take(FUNCTIONS_LISTED) {
        t.rows.push(vec![
            Cell::text(row.name.clone()).code(),
            Cell::number(format::percent(row.percent, 1), row.percent)
                .detail(interval_text(row.self_interval)),
            Cell::number(
                format::percent(row.inclusive_percent, 1),
                row.inclusive_percent,
            )
            .detail(interval_text(row.inclusive_interval)),
            Cell::number(format::seconds(row.self_seconds), row.self_seconds),
        ]);
    }
    t
}

fn rules_section(b: &PhaseBreakdown) -> Section {
    let mut t = Table::new(vec![
        Column::number("rule"),
        Column::text("phase"),
        Column::number("samples"),
        Column::text("functions it matched (most samples first)").grow(),
    ])
    .caption(format!(
        "{}: a frame takes the first rule that matches it; patterns in phases-*.txt.",
        b.origin
    ));
    for r in b.rules.iter().filter(|r| r.samples > 0) {
        let functions: Vec<String> = r.functions.iter().take(4).map(|(f, _)| f.clone()).collect();
        t.rows.push(vec![
            Cell::number(r.rule.to_string(), r.rule as f64),
            Cell::text(r.phase.clone()),
            Cell::count(r.samples),
            Cell::text(functions.join(", ")).code(),
        ]);
    }
    let mut blocks = vec![Block::Table(t)];
    if b.unclassified > 0 {
        blocks.push(Block::text(format!(
            "No rule matched {} ({}). Their innermost frames: {}. A rules file \
             (`rtprof record --phases FILE`) gives them a phase.",
            format::plural(b.unclassified as usize, "sample"),
            format::percent(100.0 * (1.0 - b.classified_share()), 1),
            b.unclassified_frames
                .iter()
                .take(6)
                .map(|(f, n)| format!("{f} ({})", format::count(*n)))
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    section(
        "record-phase-rules",
        "What the phase rules classified",
        blocks,
    )
}

fn coverage_section(modules: &[ModuleCoverage]) -> Section {
    let total: u64 = modules.iter().map(|m| m.samples).sum();
    let mut t = Table::new(vec![
        Column::text("module").grow(),
        Column::number("samples"),
        Column::number("share"),
        Column::number("no symbol"),
        Column::number("no stack"),
        Column::number("cut short"),
    ])
    .caption(
        "Per module of each sample's innermost frame: the share of its samples no symbol \
         named, with no caller (no frame pointers), and with a stack the unwinder lost.",
    );
    let share_cell = |part: u64, of: u64| {
        let p = format::percent_of(part, of);
        let tone = if p >= 10.0 {
            Tone::Warning
        } else {
            Tone::Neutral
        };
        Cell::number(format::percent(p, 1), p).tone(tone)
    };
    for m in modules {
        t.rows.push(vec![
            Cell::text(m.module.clone()).code().hover(m.path.clone()),
            Cell::count(m.samples),
            Cell::number(
                format::percent(format::percent_of(m.samples, total), 1),
                m.samples as f64,
            ),
            share_cell(m.no_symbol, m.samples),
            share_cell(m.no_stack, m.samples),
            share_cell(m.cut_short, m.samples),
        ]);
    }
    let mut blocks = vec![Block::Table(t)];
    for m in modules {
        for advice in &m.advice {
            blocks.push(Block::note(
                Tone::Warning,
                format!("{}: {advice}", m.module),
            ));
        }
    }
    section("record-coverage", "Symbols and stacks per module", blocks)
}

fn recording_section(r: &RecordReport) -> Section {
    let pair = |key: &str, value: String| Pair {
        key: key.to_string(),
        value,
    };
    let blocks = vec![
        Block::Pairs {
            pairs: vec![
                pair("command", r.command.to_string()),
                pair("end", r.end.to_string()),
                pair(
                    "time",
                    format!(
                        "{} of CPU (the program and the processes it waited for), {} wall",
                        format::seconds(r.cpu_seconds),
                        format::seconds(r.wall_seconds)
                    ),
                ),
                pair(
                    "samples",
                    format!(
                        "{} ({} per CPU second; asked {} Hz), call stacks by {}",
                        format::count(r.samples),
                        format::count((r.samples as f64 / r.cpu_seconds.max(1e-9)).round() as u64),
                        format::count(u64::from(r.frequency)),
                        r.call_graph
                    ),
                ),
                pair("processes", r.processes.to_string()),
                pair("lost samples", format::count(r.lost_samples)),
                pair(
                    "probe",
                    match (&r.probe, r.probe_error) {
                        (Some(p), _) => format!(
                            "{} (written by the {} probe; {}; {})",
                            p.file,
                            p.writer,
                            format::plural(p.threads as usize, "thread"),
                            p.phases.map_or_else(
                                || "no phase samples".to_string(),
                                |b| format!("{} phase samples", format::count(b.samples))
                            ),
                        ),
                        (None, Some(e)) => format!("unreadable: {e}"),
                        (None, None) => "none written (the program has no probe)".to_string(),
                    },
                ),
            ],
        },
        Block::text(format!("Files beside this report: {}.", r.files.join(", "))),
    ];
    section("record-run", "The recording", blocks)
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::profile::flat::flat_profile;
    use analysis::profile::phase_rules::PhaseRules;
    use analysis::profile::tally::ProfileInput;
    use analysis::profile::{CallCounts, Stack, StackSamples};
    use std::collections::BTreeMap;

    /// The text of a paragraph block.
    fn paragraph(block: &Block) -> String {
        let Block::Paragraph { content } = block else {
            panic!("not a paragraph: {block:?}")
        };
        content
            .iter()
            .map(|i| match i {
                Inline::Text { text } | Inline::Strong { text } | Inline::Code { text } => {
                    text.as_str()
                }
                _ => "",
            })
            .collect()
    }

    #[test]
    fn with_the_probe_its_phases_lead_and_the_fpga_counts_and_table_6_follow() {
        use crate::record_fpga::tracer_fpga;
        use crate::record_probe::{CountRow, ProbeReport};
        use analysis::profile::phase_compare::{compare, intersection_time};
        let rules = PhaseRules::builtin().unwrap().classify(
            &StackSamples {
                stacks: vec![Stack {
                    frames: ["main", "bvh_node::hit", "sphere::hit"]
                        .map(String::from)
                        .to_vec(),
                    count: 10,
                }],
                seconds_per_sample: 0.01,
            },
            &BTreeMap::new(),
        );
        let probe_phases = PhaseBreakdown::from_counted(
            "the probe (the program's own phase marks)",
            &[("closest hit".into(), 75), ("shading".into(), 20)],
            5,
            0.004,
        );
        let comparison = compare(&probe_phases, &rules);
        let fpga = tracer_fpga(
            &[("sphere", 2_000_000)],
            intersection_time(&probe_phases),
            "the probe",
            0.4,
            2,
        );
        let counts =
            [("rays.primary", 1_000), ("tests.sphere.tests", 2_000_000)].map(|(k, v)| CountRow {
                key: k.into(),
                value: v,
                meaning: "m".into(),
            });
        let flat = flat_profile(&ProfileInput {
            samples: &StackSamples {
                stacks: Vec::new(),
                seconds_per_sample: 0.001,
            },
            calls: &CallCounts::new(),
            renders: 1,
        });
        let report = RecordReport {
            program: "rtiow",
            command: "./rtiow",
            end: "exited with code 0",
            success: true,
            cpu_seconds: 0.4,
            wall_seconds: 0.5,
            samples: 1000,
            frequency: 4000,
            call_graph: "frame pointers",
            lost_samples: 0,
            processes: 1,
            flat: &flat,
            phases: &rules,
            modules: &[],
            flamegraph: None,
            files: &[],
            caveat: None,
            probe: Some(ProbeReport {
                file: "probe.rtprof",
                writer: "c",
                threads: 1,
                counts: &counts,
                user_counters: &[],
                phases: Some(&probe_phases),
                comparison: &comparison,
                fpga: fpga.as_ref(),
            }),
            probe_error: None,
        };
        let doc = build(&report);
        let answer = paragraph(&doc.sections[0].blocks[0]);
        // By hand: closest hit 75 of 100 probe samples; free, 1 / 0.25 = 4x.
        assert!(answer.contains("closest hit takes 75.0 %"), "{answer}");
        assert!(answer.contains("4.00× faster"), "{answer}");
        assert!(answer.contains("Phases by the probe"), "{answer}");
        let ids: Vec<&str> = doc.sections.iter().map(|s| s.id.as_str()).collect();
        assert_eq!(
            ids,
            [
                "record-answer",
                "record-fpga",
                "record-table6",
                "record-counts",
                "record-phase-comparison",
                "record-phase-rules",
                "record-coverage",
                "record-run"
            ]
        );
        // The FPGA: 2,000,000 × 3 / 50 MHz = 0.12 s against 75 × 4 ms = 0.3 s: 2.5×.
        let fpga = paragraph(&doc.sections[1].blocks[0]);
        assert!(fpga.contains("would take 120 ms"), "{fpga}");
        assert!(fpga.contains("2.50× faster than one core"), "{fpga}");
        // An unreadable probe file is a notice; the report is still made.
        let doc = build(&RecordReport {
            probe: None,
            probe_error: Some("DIR/probe.rtprof: not a valid probe file: line 3 (byte 20): …"),
            ..report
        });
        assert!(doc.notices.iter().any(|n| n.contains("DIR/probe.rtprof")));
        assert!(answer_of(&doc).contains("Phases by rtprof's built-in phase rules"));
        assert!(crate::pdf::render(&doc).is_ok_and(|pdf| pdf.starts_with(b"%PDF")));
    }

    fn answer_of(doc: &Document) -> String {
        paragraph(&doc.sections[0].blocks[0])
    }

    #[test]
    fn the_first_page_answers_by_phase_and_by_function() {
        let samples = StackSamples {
            stacks: vec![
                Stack {
                    frames: ["main", "bvh_node::hit", "sphere::hit"]
                        .map(String::from)
                        .to_vec(),
                    count: 60,
                },
                Stack {
                    frames: ["main", "bvh_node::hit"].map(String::from).to_vec(),
                    count: 30,
                },
                Stack {
                    frames: ["main", "memcpy"].map(String::from).to_vec(),
                    count: 10,
                },
            ],
            seconds_per_sample: 0.001,
        };
        let phases = PhaseRules::builtin()
            .unwrap()
            .classify(&samples, &BTreeMap::new());
        let flat = flat_profile(&ProfileInput {
            samples: &samples,
            calls: &CallCounts::new(),
            renders: 1,
        });
        let doc = build(&RecordReport {
            program: "rtiow",
            command: "./rtiow",
            end: "exited with code 0",
            success: true,
            cpu_seconds: 0.1,
            wall_seconds: 0.11,
            samples: 100,
            frequency: 4000,
            call_graph: "frame pointers",
            lost_samples: 0,
            processes: 1,
            flat: &flat,
            phases: &phases,
            modules: &[],
            flamegraph: None,
            files: &[],
            caveat: None,
            probe: None,
            probe_error: None,
        });
        let first = &doc.sections[0];
        let answer = paragraph(&first.blocks[0]);
        // By hand: the sphere test 60 of 100 samples; free, 1 / 0.4 = 2.5x.
        assert!(answer.contains("sphere test takes 60.0 %"), "{answer}");
        assert!(answer.contains("traversal 30.0 %"), "{answer}");
        assert!(answer.contains("2.50× faster"), "{answer}");
        assert!(
            answer.contains("classified 90.0 % of 100 samples"),
            "{answer}"
        );
        let Block::Table(phase) = &first.blocks[2] else {
            panic!("no phase table")
        };
        assert_eq!(phase.rows.len(), 3, "sphere, traversal, unclassified");
        assert_eq!(
            phase.rows[2][0].text,
            analysis::profile::phase_rules::UNCLASSIFIED
        );
        // The HTML and the PDF both lay it out.
        let html = crate::html::render(&doc);
        assert!(html.contains("Where the time goes in rtiow"));
        assert!(crate::pdf::render(&doc).is_ok_and(|pdf| pdf.starts_with(b"%PDF")));
    }
}
