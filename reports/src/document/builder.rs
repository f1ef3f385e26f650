//! What the section builders share ([`Builder`]): the runs, the charts not yet placed
//! and the assets the sections embed (charts, pictures, flamegraphs). Its own file so
//! that the sections, which use it, and the document's assembly, which calls them, do
//! not import each other.

use std::path::Path;

use super::assets::svg_size;
use super::outline::{Part, heading_of, part_of};
use super::{AssetKind, Assets, Block, Figure, Image, Section, Visual};
use crate::Run;
use crate::charts::{self, Chart};
use crate::gallery::{self, Picture};

/// What the section builders share: the runs, the charts not yet placed, the assets.
pub struct Builder<'a> {
    pub runs: &'a [Run],
    /// The run shown in detail.
    pub run: &'a Run,
    charts: Vec<Chart>,
    assets: Assets,
}

impl<'a> Builder<'a> {
    /// A builder for `runs`, `run` shown in detail, with every chart its results make.
    pub(super) fn new(runs: &'a [Run], run: &'a Run) -> Self {
        Builder {
            runs,
            run,
            charts: charts::all(&run.results),
            assets: Assets::default(),
        }
    }

    /// The charts no section has placed, taken out of the builder.
    pub(super) fn take_charts(&mut self) -> Vec<Chart> {
        std::mem::take(&mut self.charts)
    }

    /// The assets the sections embedded.
    pub(super) fn into_assets(self) -> Assets {
        self.assets
    }

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
