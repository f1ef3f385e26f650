//! The images section: for a few scenes, every variant's image above its difference
//! heat map, then the scene's gray histograms.

use super::GRID_COLUMNS;
use crate::charts;
use crate::document::{Block, Builder, ImageGrid, Section, Tile, Tone, Visual};
use crate::format;
use crate::gallery;
use crate::results::{SceneResult, VariantResult};

pub fn images(b: &mut Builder) -> Section {
    let mut s = b.section(
        "images",
        Some("fig. 35-37 (gray histograms) and fig. 42-45 (image comparisons)"),
    );
    let r = b.results();
    if r.scenes.iter().all(|s| s.variants.is_empty()) {
        return s.empty("No images: no scene produced a result.");
    }
    s.text("For each scene: one column per variant, its image above its difference heat map against baseline (the brighter, the larger the difference), then the gray-level histograms (log scale; the tall bar is usually the background).");
    let omitted = gallery::omitted_scenes(r);
    if !omitted.is_empty() {
        s.blocks.push(Block::note(
            Tone::Muted,
            format!(
                "Shown: the scene with the largest difference and the largest scenes. The images of the other {} ({}) are in images/ next to this report; the variants table has their metrics.",
                omitted.len(),
                omitted.join(", ")
            ),
        ));
    }
    for scene in gallery::showcase_scenes(r) {
        s.blocks.push(Block::heading(&scene.name));
        let columns = scene.variants.len().min(GRID_COLUMNS);
        for chunk in scene.variants.chunks(GRID_COLUMNS) {
            s.blocks
                .push(Block::ImageGrid(grid(b, scene, chunk, columns)));
        }
        match charts::scene_histograms(r, scene) {
            Some(chart) => {
                let id = format!("{}-{}", chart.id, crate::slug(&scene.name));
                let figure = b.figure_at(id, chart, 6.0);
                s.blocks.push(figure);
            }
            None => s.blocks.push(Block::empty(
                "No histogram: baseline has no gray histogram for this scene.",
            )),
        }
    }
    if let Some(figure) = b.chart("histogram", 9.0) {
        s.blocks
            .push(Block::heading("The largest difference of the run"));
        s.blocks.push(figure);
    }
    s
}

/// Two rows of `columns`: the variants' images, then their heat maps.
fn grid(
    b: &mut Builder,
    scene: &SceneResult,
    variants: &[VariantResult],
    columns: usize,
) -> ImageGrid {
    let size = (scene.width, scene.height);
    let mut images = Vec::with_capacity(variants.len());
    let mut heat_maps = Vec::with_capacity(variants.len());
    for v in variants {
        let (caption, tone) = match &v.quality {
            Some(q) => {
                let band = q.band;
                (
                    format!(
                        "{} · RMS {} ({})",
                        v.variant,
                        format::fixed(q.rms, 1),
                        band.name()
                    ),
                    Tone::of_band(band),
                )
            }
            None => (v.variant.to_string(), Tone::Neutral),
        };
        images.push(Tile {
            visual: b.picture(
                v.image.as_deref(),
                &format!("{} {}", scene.name, v.variant),
                size,
            ),
            caption,
            tone,
        });
    }
    for v in variants {
        let visual = if v.variant.is_reference() {
            Visual::Placeholder {
                text: "reference image: no heat map".to_string(),
            }
        } else {
            match &v.heat_map {
                Some(path) => b.picture(
                    Some(path),
                    &format!("{} {} difference", scene.name, v.variant),
                    size,
                ),
                None => Visual::Missing {
                    text: "no heat map recorded".to_string(),
                },
            }
        };
        let caption = match visual {
            Visual::Placeholder { .. } => String::new(),
            _ => format!("{} − baseline", v.variant),
        };
        heat_maps.push(Tile {
            visual,
            caption,
            tone: Tone::Neutral,
        });
    }
    ImageGrid::from_rows(columns, Vec::new(), vec![images, heat_maps])
}
