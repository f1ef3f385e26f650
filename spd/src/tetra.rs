//! `tetra.c`: a Sierpinski tetrahedron, each tetrahedron replaced by 4 half-size ones
//! at its corners, down to the size factor's depth; one light. Mostly background.
//!
//! Size factor n: 4ⁿ⁻¹ tetrahedra of 4 triangles: triangles = 4ⁿ. n = 6 (default):
//! 4096; n = 10: 1,048,576.

use crate::output::Output;
use crate::vector::{Coord3, Coord4};

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    4u64.pow(n)
}

/// The cube corners (x, y, z signs) with x·y·z = 1, in the C's loop order: the
/// corners of a tetrahedron inscribed in the cube.
const CORNERS: [[f64; 3]; 4] = [
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, 1.0],
];

/// `create_tetra`: the tetrahedron in the cube of half side `center[3]` at `center`,
/// or its 4 sub-tetrahedra.
fn create_tetra(out: &mut Output, depth: u32, center: Coord4) {
    if depth <= 1 {
        let obj_pt: [Coord3; 4] = CORNERS.map(|d| {
            [
                center[0] + d[0] * center[3],
                center[1] + d[1] * center[3],
                center[2] + d[2] * center[3],
            ]
        });
        // Faces 0 1 2, 3 2 1, 2 3 0, 1 0 3 (odd faces reversed).
        for num_face in 0..4 {
            let mut order = [num_face % 4, (num_face + 1) % 4, (num_face + 2) % 4];
            if num_face % 2 == 1 {
                order.swap(0, 2);
            }
            out.polygon(&order.map(|i| obj_pt[i]));
        }
    } else {
        for d in CORNERS {
            let sub_center = [
                center[0] + d[0] * center[3] / 2.0,
                center[1] + d[1] * center[3] / 2.0,
                center[2] + d[2] * center[3] / 2.0,
                center[3] / 2.0,
            ];
            create_tetra(out, depth - 1, sub_center);
        }
    }
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [1.022846, -3.177154, -2.174512],
        [-0.004103, -0.004103, 0.216539],
        [-0.816497, -0.816497, 0.816497],
        45.0,
        1.0,
        1.0,
        512,
        512,
    );
    out.light([2.0, -18.0, -5.0, 1.0]);
    out.color([1.0, 0.2, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    create_tetra(out, n, [0.0, 0.0, 0.0, 1.0]);
}
