//! `tree.c`: a tree by Aono and Kunii's method (IEEE CG&A, May 1984): every branch a
//! cone capped by a sphere, splitting in two at fixed angles and contractions; a
//! square field below, seven lights. No random numbers.
//!
//! Size factor n: 2ⁿ⁺¹ − 1 branches, each a cone and a sphere, plus the field:
//! primitives = 2·(2ⁿ⁺¹ − 1) + 1. n = 11 (default): 4095 spheres, 4095 cones.

use crate::output::Output;
use crate::vector::{Axis, IDENTITY, Matrix, PI, multiply, rotate_matrix, transform_point};

/// Branching angles (degrees), contractions, diameter ratio, divergence (degrees)
/// and width-to-height ratio of the branches.
const BR_ANGLE_0: f64 = 40.0;
const BR_ANGLE_1: f64 = 25.0;
const BR_CONTR_0: f64 = 0.65;
const BR_CONTR_1: f64 = 0.70;
const BR_DIAMETER: f64 = 0.67;
const DIV_ANGLE: f64 = 140.0;
const WIDTH_HEIGHTH_RATIO: f64 = 0.15;

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    2 * ((1u64 << (n + 1)) - 1) + 1
}

/// `grow_tree`: the branch along +Z of `cur_mx`, then its two children.
fn grow_tree(out: &mut Output, rst: &[Matrix; 2], cur_mx: &Matrix, scale: f64, depth: u32) {
    let b = transform_point([0.0, 0.0, 0.0], cur_mx);
    let base = [b[0], b[1], b[2], scale * WIDTH_HEIGHTH_RATIO];
    let a = transform_point([0.0, 0.0, 1.0], cur_mx);
    let apex = [a[0], a[1], a[2], base[3] * BR_DIAMETER];
    out.cylcone(base, apex);
    out.sphere(apex);
    if depth > 0 {
        for branch in rst {
            grow_tree(
                out,
                rst,
                &multiply(branch, cur_mx),
                scale * BR_DIAMETER,
                depth - 1,
            );
        }
    }
}

/// `create_tree`: the two branch matrices (rotate, contract, move up one unit), then
/// the tree from the identity.
fn create_tree(out: &mut Output, n: u32) {
    let rst: [Matrix; 2] = std::array::from_fn(|i| {
        let (branch_angle, divergence, contraction) = if i == 0 {
            (BR_ANGLE_0, 90.0, BR_CONTR_0)
        } else {
            (BR_ANGLE_1, DIV_ANGLE + 90.0, BR_CONTR_1)
        };
        let rx = rotate_matrix(Axis::X, branch_angle * PI / 180.0);
        let rz = rotate_matrix(Axis::Z, divergence * PI / 180.0);
        let mut st = IDENTITY;
        st[0][0] = contraction;
        st[1][1] = contraction;
        st[2][2] = contraction;
        st[3][2] = 1.0;
        multiply(&multiply(&rx, &rz), &st)
    });
    grow_tree(out, &rst, &IDENTITY, 1.0, n);
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [4.5, 0.4, 2.0],
        [0.0, 0.0, 1.5],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        1.0,
        512,
        512,
    );
    for light in [
        [-5.0, 5.0, 50.0],
        [30.0, -30.0, 30.0],
        [-40.0, -30.0, 20.0],
        [10.0, 30.0, 40.0],
        [-30.0, 40.0, 10.0],
        [50.0, 25.0, 20.0],
        [-10.0, -60.0, 30.0],
    ] {
        out.light([light[0], light[1], light[2], 1.0]);
    }
    out.color([0.2, 0.7, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    out.polygon(&[
        [50.0, 50.0, 0.0],
        [-50.0, 50.0, 0.0],
        [-50.0, -50.0, 0.0],
        [50.0, -50.0, 0.0],
    ]);
    out.color([0.55, 0.4, 0.2], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    create_tree(out, n);
}
