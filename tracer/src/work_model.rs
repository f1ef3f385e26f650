//! The work of a render for the roofline model: its floating-point operations and the
//! bytes of scene and structure records it reads, both from the exact counts.
//!
//! Flops ([`FLOP_TABLE`]): each counted vector operation is its single-precision
//! arithmetic (a dot product is 3 multiplies and 2 adds: 5), a BVH box test its slab
//! arithmetic. The scalar arithmetic around them (a discriminant, a comparison) is not
//! counted (the counting layer's convention), nor are comparisons and min/max: the
//! figure is a lower bound of the arithmetic the processor does.
//!
//! Bytes ([`bytes_touched`]): every primitive test reads its primitive's record, every
//! BVH box test half a 64-byte node pair, every leaf primitive its 8-byte reference,
//! every SIMD lane its lane of the batch; nothing is assumed to stay in a cache, so the
//! figure is what the render asks of memory, an upper bound of the traffic from DRAM.

use crate::counter::{COUNTERS, Counts, Stat};
use crate::scene::Scene;

/// Flops of one occurrence of each counted operation, and why.
pub const FLOP_TABLE: &[(Stat, u64, &str)] = &[
    (Stat::Add, 3, "3 adds"),
    (Stat::Sub, 3, "3 subtractions"),
    (Stat::Scale, 3, "3 multiplies"),
    (Stat::Dot, 5, "3 multiplies, 2 adds"),
    (Stat::Cross, 9, "6 multiplies, 3 subtractions"),
    (
        Stat::Normalize,
        10,
        "a dot product (5), a square root, a division and 3 multiplies",
    ),
    (Stat::Sqrt, 1, "one square root"),
    (
        Stat::Pow,
        1,
        "one power, counted as one operation like the root",
    ),
    (
        Stat::NodesVisited,
        12,
        "slab test: 6 subtractions, 6 multiplies (the min/max not counted)",
    ),
];

/// The floating-point operations of a render with `counts` ([`FLOP_TABLE`]).
pub fn flops(counts: &Counts) -> u64 {
    FLOP_TABLE
        .iter()
        .map(|&(stat, flops, _)| {
            let def = COUNTERS.iter().find(|def| def.stat == Some(stat));
            def.map_or(0, |def| (def.value)(counts) * flops)
        })
        .sum()
}

/// Bytes of one node of a BVH (half of a 64-byte pair).
const NODE_BYTES: u64 = 32;
/// Bytes of one primitive reference in a BVH leaf.
const PRIM_REF_BYTES: u64 = 8;
/// Bytes of one SIMD lane: a sphere lane holds 5 floats, a cylinder lane 9, a triangle
/// lane 18 (its plane's normal and point, three edge functions) and its owner's
/// 8-byte reference.
const SPHERE_LANE_BYTES: u64 = 20;
const CYLINDER_LANE_BYTES: u64 = 36;
const TRIANGLE_LANE_BYTES: u64 = 80;

/// The bytes a render with `counts` reads from the records of `scene` and its
/// structure (module doc). `simd`: the spheres and cylinders were tested in lanes.
pub fn bytes_touched(counts: &Counts, scene: &Scene, simd: bool) -> u64 {
    let t = &counts.tests;
    let planar = |outline: &crate::primitives::PlanarOutline| {
        std::mem::size_of_val(outline.vertices.as_slice()) + 8 * outline.vertices.len()
    };
    let mean = |total: usize, n: usize| total.checked_div(n).unwrap_or(0) as u64;
    let polygon = mean(
        scene
            .polygons
            .iter()
            .map(|p| std::mem::size_of_val(p) + planar(&p.outline))
            .sum(),
        scene.polygons.len(),
    );
    let patch = mean(
        scene
            .patches
            .iter()
            .map(|p| {
                std::mem::size_of_val(p)
                    + planar(&p.outline)
                    + std::mem::size_of_val(p.normals.as_slice())
            })
            .sum(),
        scene.patches.len(),
    );
    let size = |bytes: usize| bytes as u64;
    let curved = if simd {
        // The lanes issued, each as wide as its kind's lane (split by the tests).
        let (spheres, cylinders, triangles) = (t.sphere.tests, t.cylinder.tests, t.triangle.tests);
        let lanes = counts.accel.lanes_issued;
        let active = (spheres + cylinders + triangles).max(1);
        lanes
            * (spheres * SPHERE_LANE_BYTES
                + cylinders * CYLINDER_LANE_BYTES
                + triangles * TRIANGLE_LANE_BYTES)
            / active
    } else {
        t.sphere.tests * size(std::mem::size_of::<crate::primitives::Sphere>())
            + t.cylinder.tests * size(std::mem::size_of::<crate::primitives::Cylinder>())
    };
    let records = curved
        + t.cone.tests * size(std::mem::size_of::<crate::primitives::Cone>())
        + t.polygon.tests * polygon
        + t.patch.tests * patch;
    let tree = if counts.accel.nodes_visited > 0 {
        let tested = t.sphere.tests + t.cylinder.tests + t.cone.tests + t.polygon.tests;
        counts.accel.nodes_visited * NODE_BYTES + (tested + t.patch.tests) * PRIM_REF_BYTES
    } else {
        0
    };
    records + tree
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{OpCounts, RayCounts};

    #[test]
    fn flops_follow_the_table() {
        // 2 dots (10), 1 cross (9), 1 normalize (10), 3 box tests (36).
        let mut counts = Counts::from_parts(&[0; crate::counter::STAT_COUNT], RayCounts::default());
        counts.ops = OpCounts {
            dot: 2,
            cross: 1,
            normalize: 1,
            ..counts.ops
        };
        counts.accel.nodes_visited = 3;
        assert_eq!(flops(&counts), 10 + 9 + 10 + 36);
    }

    #[test]
    fn every_vector_operation_has_a_flop_count() {
        for def in crate::counter::COUNTERS
            .iter()
            .filter(|d| d.key.starts_with("ops."))
        {
            let stat = def.stat;
            assert!(
                FLOP_TABLE.iter().any(|&(s, _, _)| Some(s) == stat),
                "{} has no flops",
                def.key
            );
        }
    }

    #[test]
    fn bytes_count_records_nodes_references_and_lanes() {
        let scene = crate::nff::parse_nff(
            "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 4 4\n\
             f 1 1 1 1 0 1 0 1\ns 0 0 0 1\n",
            "one.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let mut counts = Counts::from_parts(&[0; crate::counter::STAT_COUNT], RayCounts::default());
        counts.tests.sphere.tests = 10;
        let sphere = std::mem::size_of::<crate::primitives::Sphere>() as u64;
        assert_eq!(bytes_touched(&counts, &scene, false), 10 * sphere);
        counts.accel.nodes_visited = 4;
        assert_eq!(
            bytes_touched(&counts, &scene, false),
            10 * sphere + 4 * 32 + 10 * 8
        );
        let mut lanes = Counts::from_parts(&[0; crate::counter::STAT_COUNT], RayCounts::default());
        lanes.tests.sphere.tests = 3;
        lanes.accel.lanes_issued = 8;
        assert_eq!(bytes_touched(&lanes, &scene, true), 8 * 20);
        // Two triangle lanes beside the three spheres: the 8 lanes split 3 : 2.
        lanes.tests.triangle.tests = 2;
        assert_eq!(
            bytes_touched(&lanes, &scene, true),
            8 * (3 * 20 + 2 * 80) / 5
        );
    }
}
