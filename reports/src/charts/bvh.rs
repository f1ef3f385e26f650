//! The shape of a scene's BVHs: leaves per depth and leaves per primitive count, one
//! bar per build strategy side by side, in two panels. A deeper or lopsided tree, or
//! fuller leaves, show here before they show in the time.

use plotters::prelude::*;

use super::Chart;
use super::bars::Slots;
use super::frame::render;
use super::marks::{Key, keyed};
use super::scale::{Axis, Ticks};
use super::style::{PALETTE, WIDTH};
use crate::results::{BvhQuality, SceneResult};

/// Height of the two-panel chart, pixels.
const HEIGHT: u32 = 300;

/// A histogram of a build: its bins.
type Histogram = fn(&BvhQuality) -> &[u64];

fn by_depth(t: &BvhQuality) -> &[u64] {
    &t.depth_histogram
}

fn by_size(t: &BvhQuality) -> &[u64] {
    &t.leaf_size_histogram
}

/// The two histograms of every build of `scene`'s BVH; `None` without builds or when
/// every histogram is empty.
pub fn bvh_histograms(scene: &SceneResult) -> Option<Chart> {
    let trees = &scene.bvh_quality;
    let largest = |h: Histogram| {
        trees
            .iter()
            .flat_map(|t| h(t).iter().copied())
            .max()
            .unwrap_or(0)
    };
    if largest(by_depth) == 0 && largest(by_size) == 0 {
        return None;
    }
    let panels: [(Histogram, &'static str); 2] = [
        (by_depth, "depth of the leaf (root: 0)"),
        (by_size, "primitives in the leaf"),
    ];
    let names: Vec<&str> = trees.iter().map(|t| t.builder.as_str()).collect();
    Some(render(
        "bvh-histograms",
        format!("Shape of the BVHs of {}", scene.name),
        format!(
            "Leaves of each build of {}'s BVH ({}) by depth and by the primitives they hold.",
            scene.name,
            names.join(", ")
        ),
        (WIDTH, HEIGHT),
        move |canvas| {
            let titles = ["Leaves per depth", "Leaves per size"].map(str::to_string);
            canvas.panels(&titles, |i, panel| {
                let (histogram, axis_title) = panels[i];
                let bins = trees.iter().map(|t| histogram(t).len()).max().unwrap_or(1);
                let top = largest(histogram).max(1) as f64 * 1.1;
                let x = Axis::linear(-0.5, bins as f64 - 0.5, Ticks::Whole, axis_title, 46);
                let y = Axis::linear(0.0, top, Ticks::Numbers, "leaves", 56);
                let mut plot = panel.plot(x, y)?;
                let slots = Slots {
                    groups: trees.len(),
                    span: 0.8,
                    gap: 0.04,
                };
                for (g, tree) in trees.iter().enumerate() {
                    let colour = PALETTE[g % PALETTE.len()];
                    let values = histogram(tree)
                        .iter()
                        .enumerate()
                        .map(|(bin, n)| (bin, *n as f64));
                    let anno = plot.columns(slots, g, values, 0.0, colour)?;
                    keyed(anno, &tree.builder, Key::Box(colour));
                }
                // One legend serves both panels: the right one's, over the thin tail of
                // large leaves.
                if i + 1 == panels.len() {
                    plot.legend(SeriesLabelPosition::UpperRight)?;
                }
                Ok(())
            })
        },
    ))
}
