//! The images chapter: which variants change the picture, and for a few scenes each
//! of those variants' image above its difference heat map, then the scene's gray
//! histograms. Variants that keep baseline's picture bit for bit are named, not shown.

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
    let (changed, same) = picture_changers(r);
    s.text(if changed.is_empty() {
        "Every variant renders baseline's picture bit for bit on every scene: there is nothing to show here.".to_string()
    } else {
        format!(
            "{} change the picture; {}. Below, for the scenes where the differences are largest and the largest scenes: baseline and each variant that changed the picture there, its image above its difference heat map against baseline (black: equal; white: the largest difference of that map, in gray levels under it), then the gray-level histograms (log scale; the tall bar is usually the background).",
            format::join_list(&changed),
            if same.is_empty() {
                "every variant changes it somewhere".to_string()
            } else {
                format!(
                    "{} render baseline's picture bit for bit on every scene, so they are not shown",
                    format::join_list(&same)
                )
            }
        )
    });
    if changed.is_empty() {
        return s;
    }
    let omitted = gallery::omitted_scenes(r);
    if !omitted.is_empty() {
        s.blocks.push(Block::note(
            Tone::Muted,
            format!(
                "Not shown: {} ({}); their images are in images/ next to this report and their metrics in the HTML report's per-scene tables.",
                format::plural(omitted.len(), "scene"),
                omitted.join(", ")
            ),
        ));
    }
    for scene in gallery::showcase_scenes(r) {
        let shown: Vec<VariantResult> = scene
            .variants
            .iter()
            .filter(|v| {
                v.variant.is_reference() || v.quality.as_ref().is_some_and(|q| q.max_abs_diff > 0)
            })
            .cloned()
            .collect();
        if shown.len() < 2 {
            continue;
        }
        s.blocks.push(Block::heading(&scene.name));
        let columns = shown.len().min(GRID_COLUMNS);
        for chunk in shown.chunks(GRID_COLUMNS) {
            s.blocks
                .push(Block::ImageGrid(grid(b, scene, chunk, columns)));
        }
        if let Some(chart) = charts::scene_histograms(r, scene) {
            let id = format!("{}-{}", chart.id, crate::slug(&scene.name));
            let figure = b.figure_at(id, chart, 6.0);
            s.blocks.push(figure);
        }
    }
    // The run's largest difference is the first scene shown above, with its
    // histograms: the chart of it alone would repeat them.
    let _ = b.chart("histogram", 9.0);
    s
}

/// The variants whose picture differs from the reference variant's on some scene, and
/// those whose pictures are all equal to it, in first-seen order.
pub fn picture_changers(r: &crate::results::Results) -> (Vec<String>, Vec<String>) {
    let mut changed: Vec<String> = Vec::new();
    let mut seen: Vec<String> = Vec::new();
    for v in r.scenes.iter().flat_map(|s| s.variants.iter()) {
        if v.variant.is_reference() {
            continue;
        }
        let name = v.variant.to_string();
        if !seen.contains(&name) {
            seen.push(name.clone());
        }
        if v.quality.as_ref().is_some_and(|q| q.max_abs_diff > 0) && !changed.contains(&name) {
            changed.push(name);
        }
    }
    let same = seen.into_iter().filter(|n| !changed.contains(n)).collect();
    (changed, same)
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
        // The reference variant has no difference to map: its tile stays empty.
        let visual = if v.variant.is_reference() {
            Visual::Empty
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
        let caption = match (&visual, &v.quality) {
            (Visual::Empty, _) => String::new(),
            (_, Some(q)) => format!(
                "{} − baseline · white = {} levels",
                v.variant, q.max_abs_diff
            ),
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
