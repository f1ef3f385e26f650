//! The closing sections: what failed, and how to run it again.

use crate::document::{
    Block, Builder, Cell, Column, Inline, Pair, Preformatted, Section, Table, Tone,
};

pub fn failures(b: &mut Builder) -> Section {
    let mut s = b.section("failures", None);
    s.short = true;
    let failures = &b.results().failures;
    if failures.is_empty() {
        s.text("No failures: every scene and variant of the suite ran.");
        return s;
    }
    s.blocks.push(Block::note(
        Tone::Bad,
        format!(
            "{} of the run failed; the rest of the results stand.",
            if failures.len() == 1 {
                "1 part".to_string()
            } else {
                format!("{} parts", failures.len())
            }
        ),
    ));
    let mut t = Table::new(vec![Column::text("where"), Column::text("message").grow()]);
    for f in failures {
        t.rows
            .push(vec![Cell::text(f.place()), Cell::text(&f.message)]);
    }
    s.blocks.push(Block::Table(t));
    s
}

pub fn reproduce(b: &mut Builder) -> Section {
    let mut s = b.section("reproduce", None);
    s.short = true;
    for run in b.runs {
        let r = &run.results;
        s.blocks.push(Block::heading(&run.label));
        s.blocks.push(Block::text(format!(
            "On {} ({} logical CPUs, {}): check out the commit, build it as the run did ({}, {} build) and run the command.",
            r.machine.cpu_model, r.machine.cores, r.machine.os, r.build.rustc, r.build.profile
        )));
        s.blocks.push(Block::Preformatted(Preformatted {
            text: format!("git checkout {}\n{}", r.build.git_commit, r.command),
            file: None,
            folded: None,
            print_lines: None,
        }));
        s.blocks.push(Block::Pairs {
            pairs: vec![
                Pair::new("Commit", &r.build.git_commit),
                Pair::new(
                    "rtprof",
                    format!("{} ({})", r.build.rtprof_version, r.build.profile),
                ),
                Pair::new("Compiler", &r.build.rustc),
                Pair::new(
                    "Results",
                    format!("schema {}, created {}", r.schema, r.created),
                ),
                Pair::new("Files", format!("relative to {}", run.base_dir.display())),
            ],
        });
    }
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text("Rebuild this report from saved results with "),
            Inline::code("rtprof report results.json"),
            Inline::text("; give several files to compare machines."),
        ],
    });
    s
}
