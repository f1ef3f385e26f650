//! Builds the [`Document`] of some runs: the sections of [`SECTIONS`](super::SECTIONS) in order, each
//! from its builder in [`crate::sections`], and the assets they embed.

use super::builder::Builder;
use super::{Document, Metadata};
use crate::Run;
use crate::sections;

/// The study the report reproduces.
const THESIS: &str = "R. A. Herrera Guaitero, J. M. Gómez Cruz and D. A. Sáenz Rodelo, \"Síntesis de una escena mediante ray tracing en FPGA\", undergraduate thesis (Trabajo de Grado, Ingeniería Electrónica), Pontificia Universidad Javeriana, Bogotá, December 2019";

/// The document of `runs` (the first in detail); `None` without runs.
pub fn build(runs: &[Run]) -> Option<Document> {
    let main = runs.first()?;
    let mut b = Builder::new(runs, main);
    let mut sections_out = Vec::new();
    if runs.len() > 1 {
        sections_out.push(sections::comparison::comparison(&mut b));
    }
    for section in [
        // The main body: the answers, then the four chapters.
        Some(sections::answers::answers(&mut b)),
        Some(sections::profile::profile(&mut b)),
        Some(sections::variants::variants(&mut b)),
        Some(sections::hardware::hardware(&mut b)),
        Some(sections::images::images(&mut b)),
        // The appendix.
        Some(sections::summary::summary(&mut b)),
        Some(sections::variants::variants_by_scene(&mut b)),
        sections::profile::profile_details(&mut b),
        sections::ray_rates::ray_rates(&mut b),
        sections::roofline::roofline(&mut b),
        sections::pixel_maps::pixel_maps(&mut b),
        Some(sections::scaling::time_vs_primitives(&mut b)),
        Some(sections::scaling::spd(&mut b)),
        sections::bvh_quality::bvh_quality(&mut b),
        Some(sections::benchmarks::criterion(&mut b)),
        Some(sections::closing::failures(&mut b)),
        Some(sections::closing::reproduce(&mut b)),
    ] {
        sections_out.extend(section);
    }
    // A chart no section placed (a new kind) is not lost.
    let unplaced = b.take_charts();
    if !unplaced.is_empty() {
        let mut more = b.section("more-charts", None);
        more.heading = "More charts".to_string();
        for chart in unplaced {
            let figure = b.figure(chart, 11.0);
            more.blocks.push(figure);
        }
        sections_out.push(more);
    }
    let r = &main.results;
    let labels: Vec<&str> = runs.iter().map(|run| run.label.as_str()).collect();
    Some(Document {
        title: "rtprof report".to_string(),
        metadata: Metadata {
            subtitle: "Profile, optimization variants and FPGA model of a Whitted ray tracer"
                .to_string(),
            byline: format!(
                "{} · {} · {} · {}",
                main.label,
                r.machine.cpu_model,
                r.created,
                if runs.len() > 1 {
                    format!("{} runs compared", runs.len())
                } else {
                    "one run".to_string()
                }
            ),
            // What the report is of: its scenes (a browser tab's title), or the runs
            // it compares.
            subject: if runs.len() > 1 {
                labels.join(" vs ")
            } else {
                subject_of(r)
            },
            reference: THESIS.to_string(),
            generator: format!("rtprof {}", r.build.rtprof_version),
        },
        notices: Vec::new(),
        sections: sections_out,
        assets: b.into_assets(),
    })
}

/// A single run's subject: its scenes ("balls3", "balls3, gears4 and tetra3"), or
/// their number when there are more than three.
fn subject_of(r: &crate::results::Results) -> String {
    let names: Vec<String> = r.scenes.iter().map(|s| s.name.clone()).collect();
    match names.len() {
        0 => "no scene".to_string(),
        1..=3 => crate::format::join_list(&names),
        n => crate::format::plural(n, "scene"),
    }
}
