//! The quality of a scene's BVH, per build strategy: the metrics that predict its cost
//! (SAH cost, end-point overlap), its shape, and what a counted render measured.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One BVH build of a scene and the counted render that used it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct BvhQuality {
    /// The build strategy: `binned_sah` (the `bvh` variant's) or `midpoint`.
    pub builder: String,
    pub nodes: u64,
    pub leaves: u64,
    pub bytes: u64,
    pub max_depth: u32,
    pub max_leaf_size: u32,
    /// Surface area heuristic cost (interior node 0.5, primitive test 1).
    pub sah_cost: f64,
    /// End-point overlap (Aila, Karras and Laine 2013), same cost weights.
    pub epo: f64,
    /// Leaves per depth (index 0: the root).
    pub depth_histogram: Vec<u64>,
    /// Leaves per primitive count (index 0: empty leaves).
    pub leaf_size_histogram: Vec<u64>,
    /// Per ray query, predicted by the SAH model and measured by the counted render.
    pub predicted_nodes_per_ray: f64,
    pub measured_nodes_per_ray: f64,
    pub predicted_leaves_per_ray: f64,
    pub measured_leaves_per_ray: f64,
    pub predicted_tests_per_ray: f64,
    pub measured_tests_per_ray: f64,
    /// Size of the counted render (the scene's frame).
    pub width: u32,
    pub height: u32,
    /// Seconds of one timed render with this tree (after a warm-up render).
    pub trace_seconds: f64,
}
