//! `gears.c`: an n × n × n block of meshing gears over a reflective square, five
//! lights. Each gear face is one concave 144-vertex polygon; the tooth sides are
//! rectangles. Some gears transmit (refraction).
//!
//! Size factor n: n³ gears of 2 faces + 144 rectangles each, plus the floor:
//! polygons = 146·n³ + 1. n = 4 (default): 9345.

use crate::output::Output;
use crate::vector::{Axis, Coord3, PI, add, rotate_matrix, transform_vector};

/// Teeth per gear (a multiple of 4).
const TEETH: usize = 36;
/// Radius ratios of the teeth tips and roots (the tips slightly short of 1 so that
/// meshing gears do not touch).
const OUTER_EDGE_RATIO: f64 = 0.995;
const INNER_EDGE_RATIO: f64 = 0.9;
const EDGE_DIFF: f64 = 1.0 - INNER_EDGE_RATIO;
/// Ratio of gear thickness to width.
const DEPTH_RATIO: f64 = 0.1;

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    146 * u64::from(n).pow(3) + 1
}

/// `create_tooth`: the 4 outline points of one tooth.
fn create_tooth(
    gear_angle: f64,
    tooth_angle: f64,
    center: Coord3,
    outer: Coord3,
    inner: Coord3,
) -> [Coord3; 4] {
    let point =
        |angle: f64, p: Coord3| add(transform_vector(p, &rotate_matrix(Axis::Z, angle)), center);
    [
        point(gear_angle - 0.19 * tooth_angle, outer),
        point(gear_angle + 0.19 * tooth_angle, outer),
        point(gear_angle + 0.3 * tooth_angle, inner),
        point(gear_angle + 0.7 * tooth_angle, inner),
    ]
}

/// `create_gear`: top face, tooth sides, bottom face.
fn create_gear(
    out: &mut Output,
    center: Coord3,
    offset_angle: f64,
    outer_radius: f64,
    inner_radius: f64,
    thickness: f64,
) {
    let mut outer_pt = [outer_radius, 0.0, 0.0];
    let mut inner_pt = [inner_radius, 0.0, 0.0];
    let tooth_angle = 2.0 * PI / TEETH as f64;
    let mut gear_pts = [[0.0; 3]; 4 * TEETH];
    for (num_teeth, tooth) in gear_pts.chunks_exact_mut(4).enumerate() {
        let gear_angle = offset_angle + 2.0 * PI * num_teeth as f64 / TEETH as f64;
        tooth.copy_from_slice(&create_tooth(
            gear_angle,
            tooth_angle,
            center,
            outer_pt,
            inner_pt,
        ));
    }
    out.polygon(&gear_pts);
    for num_side in 0..4 * TEETH {
        let next_side = (num_side + 1) % (4 * TEETH);
        let mut side = [
            gear_pts[num_side],
            gear_pts[num_side],
            gear_pts[next_side],
            gear_pts[next_side],
        ];
        side[1][2] -= thickness;
        side[2][2] -= thickness;
        out.polygon(&side);
    }
    outer_pt[2] = -thickness;
    inner_pt[2] = -thickness;
    for (num_teeth, tooth) in gear_pts.chunks_exact_mut(4).enumerate() {
        let gear_angle = offset_angle - 2.0 * PI * num_teeth as f64 / TEETH as f64;
        tooth.copy_from_slice(&create_tooth(
            gear_angle,
            -tooth_angle,
            center,
            outer_pt,
            inner_pt,
        ));
    }
    out.polygon(&gear_pts);
}

/// `FRACTION`: the part after the decimal point (toward zero).
fn fraction(a: f64) -> f64 {
    a - a.trunc()
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [-1.1, -2.1, 2.6],
        [0.0; 3],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        1.0,
        512,
        512,
    );
    for light in [
        [2.0, 4.0, 4.0],
        [-2.0, 4.0, 3.0],
        [2.0, -2.5, 2.5],
        [-1.0, -4.0, 2.0],
        // Just behind the eye.
        [-1.111, -2.121, 2.626],
    ] {
        out.light([light[0], light[1], light[2], 1.0]);
    }
    out.color([1.0, 0.85, 0.7], 0.0, 0.3, 0.6, 0.3, 37.0, 0.0, 0.0);
    out.polygon(&[
        [2.0, 2.0, 0.0],
        [-2.0, 2.0, 0.0],
        [-2.0, -2.0, 0.0],
        [2.0, -2.0, 0.0],
    ]);

    let sf = f64::from(n);
    let outer_radius = 1.0 / (sf - (sf - 1.0) * EDGE_DIFF / 2.0);
    let zero_pt = [-1.0 + outer_radius, -1.0 + outer_radius, 1.0];
    let offset = [
        outer_radius * (2.0 - EDGE_DIFF),
        outer_radius * (2.0 - EDGE_DIFF),
        -1.0 / sf,
    ];
    let mut center = [0.0; 3];
    for iz in 0..n {
        center[2] = zero_pt[2] + f64::from(iz) * offset[2];
        for iy in 0..n {
            center[1] = zero_pt[1] + f64::from(iy) * offset[1];
            for ix in 0..n {
                center[0] = zero_pt[0] + f64::from(ix) * offset[0];
                // Pseudo-random gear colour, brightest channel scaled to 1.
                let mut color = [
                    0.01 + fraction(f64::from(ix * 3 + iy * 2 + iz + 1) * 5.0 / 7.0),
                    0.01 + fraction(f64::from(iy * 3 + iz * 2 + ix + 1) * 3.0 / 7.0),
                    0.01 + fraction(f64::from(iz * 3 + ix * 2 + iy + 1) * 2.0 / 7.0),
                ];
                let color_scale = color[0].max(color[1]).max(color[2]);
                for c in &mut color {
                    *c /= color_scale;
                }
                if (ix * 4 + iy * 2 + iz) % 5 == 0 {
                    out.color(color, 0.0, 0.2, 0.0, 0.0, 0.0, 0.8, 1.1);
                } else {
                    out.color(color, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
                }
                let angle = PI * f64::from((ix + iy + iz) % 2) / TEETH as f64;
                let thickness = DEPTH_RATIO.min(1.0 / (2.0 * sf));
                create_gear(
                    out,
                    center,
                    angle,
                    OUTER_EDGE_RATIO * outer_radius,
                    (1.0 - EDGE_DIFF) * outer_radius,
                    thickness,
                );
            }
        }
    }
}
