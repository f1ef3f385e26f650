//! The BVH quality section: for each scene the suite studied, every build strategy's
//! tree, the metrics that predict its cost (SAH cost, end-point overlap), what a
//! counted render measured and the time, the shape of the trees, and a sentence saying
//! whether the metrics predicted the measurement. Omitted when no scene has the study.

use crate::charts;
use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{BvhQuality, SceneResult};

pub fn bvh_quality(b: &mut Builder) -> Option<Section> {
    let scenes: Vec<&SceneResult> = b
        .results()
        .scenes
        .iter()
        .filter(|s| !s.bvh_quality.is_empty())
        .collect();
    if scenes.is_empty() {
        return None;
    }
    let mut s = b.section("bvh-quality", None);
    // A table of every scene and variant: the HTML's (the PDF keeps the opening).
    s.html_only = true;
    s.text("Each build strategy's tree: its size and shape, the surface area heuristic's cost and the end-point overlap (both with an interior node costing 0.5 and a primitive test 1; lower predicts a cheaper traversal), the nodes, leaves and tests per ray the SAH model predicts against what a counted render measured, and the time of a timed render with the tree.");
    // Scenes with one tree (the bvh variant's, on frames too large to render again)
    // share one table; those with both builders get their comparison.
    let (compared, single): (Vec<&SceneResult>, Vec<&SceneResult>) =
        scenes.into_iter().partition(|s| s.bvh_quality.len() > 1);
    if !single.is_empty() {
        s.blocks.push(Block::subheading("The bvh variant's tree"));
        if let Some(sentence) = spread_sentence(&single) {
            s.text(sentence);
        }
        s.blocks.push(Block::Table(single_table(&single)));
    }
    for scene in compared {
        s.blocks.push(Block::Heading {
            level: 2,
            text: scene.name.clone(),
            detail: counted_size(&scene.bvh_quality),
            anchor: Some(format!("bvh-quality-{}", crate::slug(&scene.name))),
        });
        if let Some(sentence) = prediction_sentence(&scene.name, &scene.bvh_quality) {
            s.text(sentence);
        }
        s.blocks.push(Block::Table(trees_table(&scene.bvh_quality)));
        if let Some(chart) = charts::bvh_histograms(scene) {
            let id = format!("{}-{}", chart.id, crate::slug(&scene.name));
            let figure = b.figure_at(id, chart, 6.0);
            s.blocks.push(figure);
        }
    }
    Some(s)
}

/// The size of the counted renders, when they share one.
fn counted_size(trees: &[BvhQuality]) -> Option<String> {
    let first = trees.first()?;
    trees
        .iter()
        .all(|t| (t.width, t.height) == (first.width, first.height))
        .then(|| format!("counted at {}", format::size(first.width, first.height)))
}

/// Which build the metrics favour and whether the measurement agrees: the build with
/// the lowest SAH cost against each other one, on EPO, nodes per ray and time.
fn prediction_sentence(scene: &str, trees: &[BvhQuality]) -> Option<String> {
    let best = trees
        .iter()
        .min_by(|a, b| a.sah_cost.total_cmp(&b.sah_cost))?;
    let others: Vec<&BvhQuality> = trees.iter().filter(|t| !std::ptr::eq(*t, best)).collect();
    if others.is_empty() {
        return Some(format!(
            "On {scene} only {} was built: nothing to compare its SAH cost of {} with.",
            best.builder,
            format::significant(best.sah_cost)
        ));
    }
    let mut sentences = Vec::new();
    for other in others {
        sentences.push(compare(scene, best, other));
    }
    Some(sentences.join(" "))
}

/// How two figures compare as printed: figures that print the same are the same to
/// the reader, whatever their last bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Printed {
    Lower,
    Same,
    Higher,
}

fn printed(a: f64, b: f64, text: fn(f64) -> String) -> Printed {
    if text(a) == text(b) {
        Printed::Same
    } else if a < b {
        Printed::Lower
    } else {
        Printed::Higher
    }
}

/// One comparison: `best` has the SAH cost no higher than `other`'s; the EPO, the
/// measured nodes per ray and the time either follow it or not. Figures that print the
/// same are called the same, never "lower" or "faster".
fn compare(scene: &str, best: &BvhQuality, other: &BvhQuality) -> String {
    let pair = |a: f64, b: f64, text: fn(f64) -> String| match printed(a, b, text) {
        Printed::Same => text(a),
        _ => format!("{} against {}", text(a), text(b)),
    };
    let sig: fn(f64) -> String = format::significant;
    let secs: fn(f64) -> String = format::seconds;
    let sah = printed(best.sah_cost, other.sah_cost, sig);
    let epo = printed(best.epo, other.epo, sig);
    let epo_pair = pair(best.epo, other.epo, sig);
    let mut text = if sah == Printed::Same {
        let epo_text = match epo {
            Printed::Same => format!(" and the same EPO ({epo_pair})"),
            Printed::Lower => format!(", and {} has the lower EPO ({epo_pair})", best.builder),
            Printed::Higher => format!(", and {} has the lower EPO ({epo_pair})", other.builder),
        };
        format!(
            "On {scene}, {} and {} have the same SAH cost ({}){epo_text}",
            best.builder,
            other.builder,
            sig(best.sah_cost)
        )
    } else {
        let sah_pair = pair(best.sah_cost, other.sah_cost, sig);
        let (b, o) = (&best.builder, &other.builder);
        match epo {
            Printed::Lower => format!(
                "On {scene}, {b} has the lower SAH cost ({sah_pair}) and the lower EPO ({epo_pair}) than {o}"
            ),
            Printed::Same => format!(
                "On {scene}, {b} has the lower SAH cost ({sah_pair}) than {o} and the same EPO ({epo_pair})"
            ),
            Printed::Higher => format!(
                "On {scene}, {b} has the lower SAH cost ({sah_pair}) than {o}, but not the lower EPO ({epo_pair})"
            ),
        }
    };
    let nodes = printed(
        best.measured_nodes_per_ray,
        other.measured_nodes_per_ray,
        sig,
    );
    let time = printed(best.trace_seconds, other.trace_seconds, secs);
    let nodes_text = match nodes {
        Printed::Same => format!(
            "as many nodes per ray ({})",
            sig(best.measured_nodes_per_ray)
        ),
        order => format!(
            "{} nodes per ray ({})",
            if order == Printed::Lower {
                "fewer"
            } else {
                "more"
            },
            pair(
                best.measured_nodes_per_ray,
                other.measured_nodes_per_ray,
                sig
            )
        ),
    };
    let time_text = match time {
        Printed::Same => format!("as fast ({})", secs(best.trace_seconds)),
        order => format!(
            "{} ({})",
            if order == Printed::Lower {
                "faster"
            } else {
                "slower"
            },
            pair(best.trace_seconds, other.trace_seconds, secs)
        ),
    };
    if sah == Printed::Same {
        return format!(
            "{text}; {} visits {nodes_text} and traces {time_text}: the metrics do not tell the two apart.",
            best.builder
        );
    }
    text += &match (nodes, time) {
        (Printed::Lower, Printed::Lower) => format!(
            "; it also visits {nodes_text} and traces {time_text}: the metrics predict the measurement."
        ),
        (Printed::Higher, Printed::Higher) => format!(
            "; yet it visits {nodes_text} and traces {time_text}: here the metrics do not predict the measurement."
        ),
        (Printed::Lower, _) => format!(
            "; it visits {nodes_text}, but traces {time_text}: here the metrics do not predict the time."
        ),
        (_, Printed::Lower) => format!(
            "; it traces {time_text}, but visits {nodes_text}: here the metrics do not predict the nodes visited."
        ),
        _ => format!(
            "; it visits {nodes_text} and traces {time_text}: the measurement does not follow the metrics."
        ),
    };
    text
}

/// Every build of one scene's tree.
fn trees_table(trees: &[BvhQuality]) -> Table {
    let mut t = Table::new(vec![
        Column::text("builder"),
        Column::number("nodes"),
        Column::number("leaves"),
        Column::number("bytes"),
        Column::number("max depth"),
        Column::number("max leaf"),
        Column::number("SAH cost"),
        Column::number("EPO"),
        Column::number("nodes per ray").detail("predicted"),
        Column::number("nodes per ray").detail("measured"),
        Column::number("measured ÷ predicted"),
        Column::number("tests per ray").detail("measured (predicted)"),
        Column::number("trace time"),
    ])
    .dense();
    for tree in trees {
        let ratio = tree.measured_nodes_per_ray / tree.predicted_nodes_per_ray;
        t.rows.push(vec![
            Cell::text(&tree.builder).code(),
            Cell::count(tree.nodes),
            Cell::count(tree.leaves),
            Cell::number(format::bytes(tree.bytes), tree.bytes as f64),
            Cell::count(u64::from(tree.max_depth)),
            Cell::count(u64::from(tree.max_leaf_size)),
            Cell::number(format::significant(tree.sah_cost), tree.sah_cost),
            Cell::number(format::significant(tree.epo), tree.epo),
            Cell::number(
                format::significant(tree.predicted_nodes_per_ray),
                tree.predicted_nodes_per_ray,
            ),
            Cell::number(
                format::significant(tree.measured_nodes_per_ray),
                tree.measured_nodes_per_ray,
            ),
            Cell::number(format::speedup(ratio), ratio).tone(if ratio.is_finite() {
                Tone::Neutral
            } else {
                Tone::Muted
            }),
            Cell::number(
                format::significant(tree.measured_tests_per_ray),
                tree.measured_tests_per_ray,
            )
            .detail(format!(
                "({})",
                format::significant(tree.predicted_tests_per_ray)
            ))
            .hover(format!(
                "leaves per ray: {} measured, {} predicted",
                format::significant(tree.measured_leaves_per_ray),
                format::significant(tree.predicted_leaves_per_ray)
            )),
            Cell::number(format::seconds(tree.trace_seconds), tree.trace_seconds),
        ]);
    }
    t
}

/// How far the measured boxes per ray stray from the prediction across `scenes`.
fn spread_sentence(scenes: &[&SceneResult]) -> Option<String> {
    let ratios: Vec<(f64, &str)> = scenes
        .iter()
        .filter_map(|s| {
            let t = s.bvh_quality.first()?;
            let r = t.measured_nodes_per_ray / t.predicted_nodes_per_ray;
            r.is_finite().then_some((r, s.name.as_str()))
        })
        .collect();
    let low = ratios.iter().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let high = ratios.iter().max_by(|a, b| a.0.total_cmp(&b.0))?;
    Some(format!(
        "On {} scenes the bvh variant's own tree, counted at the scene's frame: the boxes a ray tested were {} ({}) to {} ({}) the number the SAH model predicts for random lines through the root box; eye rays that miss the scene test only the root, and rays that start on a surface or stop at a hit test fewer or more.",
        ratios.len(),
        format::speedup(low.0),
        low.1,
        format::speedup(high.0),
        high.1
    ))
}

/// One row per scene with one tree: its size, metrics, boxes per ray and time.
fn single_table(scenes: &[&SceneResult]) -> Table {
    let columns = vec![
        Column::text("scene"),
        Column::text("frame"),
        Column::number("nodes"),
        Column::number("bytes"),
        Column::number("max depth"),
        Column::number("SAH cost"),
        Column::number("EPO"),
        Column::number("nodes per ray").detail("predicted"),
        Column::number("nodes per ray").detail("measured"),
        Column::number("measured ÷ predicted"),
        Column::number("trace time"),
    ];
    let mut t = Table::new(columns).sortable().dense();
    for scene in scenes {
        let Some(q) = scene.bvh_quality.first() else {
            continue;
        };
        let ratio = q.measured_nodes_per_ray / q.predicted_nodes_per_ray;
        t.rows.push(vec![
            Cell::text(&scene.name),
            Cell::text(format::size(q.width, q.height)),
            Cell::count(q.nodes),
            Cell::number(format::bytes(q.bytes), q.bytes as f64),
            Cell::count(u64::from(q.max_depth)),
            Cell::number(format::fixed(q.sah_cost, 2), q.sah_cost),
            Cell::number(format::fixed(q.epo, 2), q.epo),
            Cell::number(
                format::fixed(q.predicted_nodes_per_ray, 1),
                q.predicted_nodes_per_ray,
            ),
            Cell::number(
                format::fixed(q.measured_nodes_per_ray, 1),
                q.measured_nodes_per_ray,
            ),
            Cell::number(format::speedup(ratio), ratio),
            Cell::number(format::seconds(q.trace_seconds), q.trace_seconds),
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::sample::sample_results;

    fn a_tree() -> BvhQuality {
        sample_results()
            .scenes
            .iter()
            .flat_map(|s| s.bvh_quality.iter())
            .next()
            .cloned()
            .unwrap()
    }

    #[test]
    fn two_equal_trees_are_called_the_same_never_lower() {
        let a = a_tree();
        let mut b = a.clone();
        b.builder = "midpoint".into();
        let said = compare("balls", &a, &b);
        assert!(said.contains("have the same SAH cost"), "{said}");
        assert!(said.contains("the same EPO"), "{said}");
        assert!(said.contains("as many nodes per ray"), "{said}");
        assert!(said.contains("as fast"), "{said}");
        assert!(!said.contains("against"), "{said}");
        assert!(!said.contains("lower"), "{said}");
    }

    #[test]
    fn differing_trees_are_compared_with_both_figures() {
        let a = a_tree();
        let mut b = a.clone();
        b.builder = "midpoint".into();
        b.sah_cost = a.sah_cost * 1.5;
        b.epo = a.epo * 1.5;
        b.measured_nodes_per_ray = a.measured_nodes_per_ray * 1.5;
        b.trace_seconds = a.trace_seconds * 1.5;
        let said = compare("balls", &a, &b);
        assert!(said.contains("has the lower SAH cost ("), "{said}");
        assert!(said.contains(&format!(
            "{} against {}",
            format::significant(a.sah_cost),
            format::significant(b.sah_cost)
        )));
        assert!(
            said.ends_with("the metrics predict the measurement."),
            "{said}"
        );
    }
}
