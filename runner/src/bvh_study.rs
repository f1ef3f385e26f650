//! The BVH quality study of a scene: for each build strategy ([`BvhBuilder`]), the
//! tree's metrics (SAH cost, end-point overlap, shape) beside what a counted render
//! with it measured (boxes, leaves and tests per ray) and its trace time, so that the
//! report can show whether the metrics predict the cost.

use results::BvhQuality;
use tracer::{
    Bvh, BvhBuilder, Count, Counts, NoCount, RenderOptions, VariantSet, render_variant_until,
};

use crate::error::RunError;
use crate::render_setup::RenderSetup;
use crate::timing::{TimingPolicy, measure};

/// Per ray (every closest-hit and shadow query): boxes tested, leaves entered and
/// primitives tested.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PerRay {
    pub nodes: f64,
    pub leaves: f64,
    pub tests: f64,
}

impl PerRay {
    pub fn of(counts: &Counts) -> Self {
        let rays = counts.rays.total().max(1) as f64;
        Self {
            nodes: counts.accel.nodes_visited as f64 / rays,
            leaves: counts.accel.leaves_visited as f64 / rays,
            tests: counts.tests.total() as f64 / rays,
        }
    }
}

/// Studies the tree `builder` makes of `setup`'s scene: metrics, a counted render and
/// renders timed under `policy`.
pub fn study(
    setup: &RenderSetup,
    builder: BvhBuilder,
    policy: &TimingPolicy,
) -> Result<BvhQuality, RunError> {
    let options = RenderOptions {
        bvh_builder: builder,
        ..*setup.options
    };
    let set = VariantSet::parse("bvh")?;
    let fail = |e: tracer::RenderError| RunError::render(setup.name, &e);
    let counted = setup
        .pool
        .install(|| render_variant_until::<Count>(setup.scene, &options, &set, &|_| {}, setup.stop))
        .map_err(fail)?;
    let counts = counted.rendered.counts().ok_or_else(|| RunError::Render {
        context: setup.name.to_string(),
        message: "the counted render returned no counts".into(),
    })?;
    let timed = measure(policy, setup.stop, || {
        setup
            .pool
            .install(|| {
                render_variant_until::<NoCount>(setup.scene, &options, &set, &|_| {}, setup.stop)
            })
            .map_err(fail)
    })?;
    Ok(quality(setup, builder, &counts, timed.time.median))
}

/// The quality of the tree `builder` makes of `setup`'s scene, with what a render with
/// it counted (`counts`) and how long it traced (`seconds`): the suite's `bvh` variant
/// gives both for frames too large to render again.
pub fn quality(
    setup: &RenderSetup,
    builder: BvhBuilder,
    counts: &Counts,
    seconds: f64,
) -> BvhQuality {
    let bvh = Bvh::build_with(setup.scene, builder);
    let stats = bvh.stats();
    let epo = bvh.end_point_overlap();
    let shape = bvh.shape().clone();
    let measured = PerRay::of(counts);
    BvhQuality {
        builder: builder.name().to_string(),
        nodes: stats.nodes as u64,
        leaves: stats.leaves as u64,
        bytes: stats.bytes as u64,
        max_depth: stats.max_depth as u32,
        max_leaf_size: stats.max_leaf_size as u32,
        sah_cost: stats.sah_cost,
        epo,
        depth_histogram: shape.depth_histogram,
        leaf_size_histogram: shape.leaf_size_histogram,
        predicted_nodes_per_ray: stats.predicted_nodes_per_ray,
        measured_nodes_per_ray: measured.nodes,
        predicted_leaves_per_ray: stats.predicted_leaves_per_ray,
        measured_leaves_per_ray: measured.leaves,
        predicted_tests_per_ray: stats.predicted_tests_per_ray,
        measured_tests_per_ray: measured.tests,
        width: setup.options.width,
        height: setup.options.height,
        trace_seconds: seconds,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use tracer::{Sampling, ShadingMode};

    #[test]
    fn both_builders_are_studied_with_consistent_figures() {
        let scene = tracer::builtin_scenes::find("balls7")
            .unwrap_or_else(|| panic!("balls7 is built in"))
            .parse()
            .unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions::new(24, 18, Sampling::PixelCenters, ShadingMode::Color);
        let pool = crate::pool::thread_pool(Some(1)).unwrap_or_else(|e| panic!("{e}"));
        let stop = AtomicBool::new(false);
        let setup = RenderSetup {
            scene: &scene,
            name: "balls7",
            options: &options,
            pool: &pool,
            counting_pool: &pool,
            stop: &stop,
        };
        let policy = TimingPolicy::new(1, 0.0);
        for builder in BvhBuilder::ALL {
            let q = study(&setup, builder, &policy).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(q.builder, builder.name());
            // Every leaf appears once in each histogram.
            assert_eq!(q.depth_histogram.iter().sum::<u64>(), q.leaves);
            assert_eq!(q.leaf_size_histogram.iter().sum::<u64>(), q.leaves);
            // A binary tree: nodes = 2 leaves - 1.
            assert_eq!(q.nodes, 2 * q.leaves - 1);
            // The leaves hold every primitive once.
            let held: u64 = q
                .leaf_size_histogram
                .iter()
                .enumerate()
                .map(|(size, n)| size as u64 * n)
                .sum();
            assert_eq!(held, scene.primitive_count() as u64);
            assert!(
                q.measured_nodes_per_ray >= 1.0 && q.trace_seconds > 0.0,
                "{q:?}"
            );
        }
    }
}
