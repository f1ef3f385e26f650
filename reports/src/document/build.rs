//! Builds the [`Document`] of some runs: the sections of [`SECTIONS`] in order, each
//! from its builder in [`crate::sections`], and the assets they embed.

use std::path::Path;

use super::assets::svg_size;
use super::{AssetKind, Assets, Block, Document, Figure, Image, Metadata, Section, Visual};
use crate::Run;
use crate::charts::{self, Chart};
use crate::gallery::{self, Picture};
use crate::sections;

/// Where a section stands: the main body, the appendix, or folded into a chapter of
/// the main body as one of its parts (a sub-heading with the section's id as anchor).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    Main,
    /// Inside the chapter with this id.
    Within(&'static str),
    Appendix,
}

/// The report's sections: id, heading and part, in order. The main body answers first
/// and then has four chapters (profile, variants, hardware, images); what supports
/// them (per-scene tables, rates, rooflines, maps, SPD statistics, benchmarks) is the
/// appendix. The comparison comes only with several runs, and first: a report of
/// several runs opens with what changed. The ray-rates, roofline, pixel-maps and
/// bvh-quality sections come only with results that hold their data.
pub const SECTIONS: [(&str, &str, Part); 28] = [
    ("comparison", "What changed between the runs", Part::Main),
    ("answers", "Answers", Part::Main),
    ("profile", "Profile: where the time goes", Part::Main),
    ("profile-flat", "Flat profile", Part::Within("profile")),
    (
        "profile-charts",
        "Calls and self time per function",
        Part::Within("profile"),
    ),
    ("flamegraphs", "Flamegraphs", Part::Within("profile")),
    (
        "amdahl",
        "Amdahl's law: what speeding up a function would give",
        Part::Within("profile"),
    ),
    (
        "variants",
        "Variants: what each optimization buys and costs",
        Part::Main,
    ),
    ("hardware", "Hardware: the FPGA pipeline", Part::Main),
    (
        "hardware-tables",
        "The model against tables 7 and 8",
        Part::Within("hardware"),
    ),
    (
        "hardware-synthesis",
        "The generated RTL through Yosys: cells, logic depth, clock",
        Part::Within("hardware"),
    ),
    (
        "hw-optimizations",
        "The thesis's optimizations in cycles and logic",
        Part::Within("hardware"),
    ),
    (
        "device-utilization",
        "Device utilization",
        Part::Within("hardware"),
    ),
    (
        "design-space",
        "Would it pay off: every design on every device",
        Part::Within("hardware"),
    ),
    (
        "sw-hw",
        "Software against hardware",
        Part::Within("hardware"),
    ),
    (
        "images",
        "Images: what the variants change in the picture",
        Part::Main,
    ),
    (
        "summary",
        "All findings, the machine and the scenes",
        Part::Appendix,
    ),
    (
        "variants-by-scene",
        "Variants scene by scene",
        Part::Appendix,
    ),
    (
        "profile-details",
        "Profile details: call graphs, native symbols, the best variant",
        Part::Appendix,
    ),
    (
        "ray-rates",
        "Rays per second and where the time goes",
        Part::Appendix,
    ),
    (
        "roofline",
        "Roofline: attained GFLOP/s against the machine's peaks",
        Part::Appendix,
    ),
    ("pixel-maps", "Per-pixel maps of the work", Part::Appendix),
    (
        "time-vs-primitives",
        "Render time against primitive count",
        Part::Appendix,
    ),
    ("spd", "SPD scene statistics", Part::Appendix),
    (
        "bvh-quality",
        "BVH quality: predicted against measured cost",
        Part::Appendix,
    ),
    (
        "criterion",
        "Micro-benchmarks: time and instructions",
        Part::Appendix,
    ),
    ("failures", "Failures", Part::Appendix),
    ("reproduce", "How to reproduce", Part::Appendix),
];

/// The heading of section `id` (the id itself when it is not one of [`SECTIONS`]).
pub fn heading_of(id: &str) -> &str {
    SECTIONS
        .iter()
        .find(|(sid, _, _)| *sid == id)
        .map_or(id, |(_, heading, _)| heading)
}

/// The part of the report section `id` stands in ([`Part::Main`] when it is not one of
/// [`SECTIONS`]).
pub fn part_of(id: &str) -> Part {
    SECTIONS
        .iter()
        .find(|(sid, _, _)| *sid == id)
        .map_or(Part::Main, |(_, _, part)| *part)
}

/// The study the report reproduces.
const THESIS: &str = "R. A. Herrera Guaitero, J. M. Gómez Cruz and D. A. Sáenz Rodelo, \"Síntesis de una escena mediante ray tracing en FPGA\", undergraduate thesis (Trabajo de Grado, Ingeniería Electrónica), Pontificia Universidad Javeriana, Bogotá, December 2019";

/// The document of `runs` (the first in detail); `None` without runs.
pub fn build(runs: &[Run]) -> Option<Document> {
    let main = runs.first()?;
    let mut b = Builder {
        runs,
        run: main,
        charts: charts::all(&main.results),
        assets: Assets::default(),
    };
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
    if !b.charts.is_empty() {
        let mut more = b.section("more-charts", None);
        more.heading = "More charts".to_string();
        for chart in std::mem::take(&mut b.charts) {
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
        assets: b.assets,
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

/// What the section builders share: the runs, the charts not yet placed, the assets.
pub struct Builder<'a> {
    pub runs: &'a [Run],
    /// The run shown in detail.
    pub run: &'a Run,
    charts: Vec<Chart>,
    assets: Assets,
}

impl<'a> Builder<'a> {
    /// The results of the run shown in detail.
    pub fn results(&self) -> &'a crate::results::Results {
        &self.run.results
    }

    /// An empty section `id` with its heading from [`SECTIONS`].
    pub fn section(&self, id: &str, thesis: Option<&str>) -> Section {
        Section {
            id: id.to_string(),
            heading: heading_of(id).to_string(),
            thesis: thesis.map(str::to_string),
            short: false,
            appendix: part_of(id) == Part::Appendix,
            html_only: false,
            blocks: Vec::new(),
        }
    }

    /// The figure of chart `id` of [`charts::all`], if the data made one (each chart is
    /// placed once).
    pub fn chart(&mut self, id: &str, max_height_cm: f64) -> Option<Block> {
        let at = self.charts.iter().position(|c| c.id == id)?;
        let chart = self.charts.remove(at);
        Some(self.figure(chart, max_height_cm))
    }

    /// A figure of any chart, anchored at the chart's id.
    pub fn figure(&mut self, chart: Chart, max_height_cm: f64) -> Block {
        self.figure_at(chart.id.to_string(), chart, max_height_cm)
    }

    /// A figure of a chart with its own anchor (a chart drawn once per scene).
    pub fn figure_at(&mut self, id: String, chart: Chart, max_height_cm: f64) -> Block {
        let (width, height) = chart_size(&chart);
        let asset = self.assets.add(AssetKind::Svg, chart.svg.into_bytes());
        Block::Figure(Figure {
            id,
            title: chart.title.clone(),
            caption: chart.caption,
            visual: Visual::Image(Image {
                asset,
                width,
                height,
                alt: chart.title,
                file: None,
            }),
            max_height_cm,
        })
    }

    /// A picture of the run (a PNG relative to its directory) as a thumbnail (see
    /// [`crate::gallery`]), or why it cannot be shown. `size` is the picture's size
    /// in pixels (its aspect ratio).
    pub fn picture(&mut self, rel: Option<&str>, alt: &str, size: (u32, u32)) -> Visual {
        self.picture_within(rel, alt, size, gallery::THUMBNAIL_WIDTH)
    }

    /// [`Builder::picture`] embedded up to `max_width` pixels wide rather than the
    /// thumbnail width (a picture with text drawn in, which shrinking would blur).
    pub fn picture_within(
        &mut self,
        rel: Option<&str>,
        alt: &str,
        size: (u32, u32),
        max_width: u32,
    ) -> Visual {
        let Some(rel) = rel else {
            return Visual::Missing {
                text: format!("no image recorded for {alt}"),
            };
        };
        match gallery::thumbnail_within(&self.run.base_dir, rel, max_width) {
            Picture::Png(bytes) => Visual::Image(Image {
                asset: self.assets.add(AssetKind::Png, bytes),
                width: f64::from(size.0.max(1)),
                height: f64::from(size.1.max(1)),
                alt: alt.to_string(),
                file: Some(rel.to_string()),
            }),
            Picture::Unusable(reason) => Visual::Missing {
                text: format!("image missing: {rel} ({reason})"),
            },
        }
    }

    /// A flamegraph SVG of the run, or why it cannot be shown.
    pub fn flamegraph(&mut self, rel: &str, title: &str) -> Visual {
        match read_text(&self.run.base_dir, rel) {
            Ok(svg) => {
                let (width, height) = svg_size(&svg).unwrap_or((1200.0, 600.0));
                Visual::Image(Image {
                    asset: self.assets.add(AssetKind::Svg, svg.into_bytes()),
                    width,
                    height,
                    alt: title.to_string(),
                    file: Some(rel.to_string()),
                })
            }
            Err(reason) => Visual::Missing {
                text: format!("flamegraph missing: {rel} ({reason})"),
            },
        }
    }

    /// A text file of the run, or why it cannot be read.
    pub fn text_file(&self, rel: &str) -> Result<String, String> {
        read_text(&self.run.base_dir, rel)
    }
}

/// A chart's size in pixels, as the chart carries it.
fn chart_size(chart: &Chart) -> (f64, f64) {
    (f64::from(chart.width), f64::from(chart.height))
}

fn read_text(base: &Path, rel: &str) -> Result<String, String> {
    std::fs::read(base.join(rel))
        .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
        .map_err(|e| e.kind().to_string())
}
