//! `balls.c`, the sphereflake: a sphere with 9 spheres of a third its radius on its
//! surface, each of those with 9 more, and so on; a square floor polygon below, three
//! lights.
//!
//! Size factor n (the recursion depth): spheres = 1 + 9 + … + 9ⁿ = (9ⁿ⁺¹ − 1) / 8,
//! plus 1 polygon. n = 4 (default): 7381 spheres; n = 6: 597,871.

use crate::output::Output;
use crate::vector::{
    Axis, Coord3, Coord4, IDENTITY, Matrix, PI, axis_rotate_matrix, cross, dot, normalize,
    rotate_matrix, transform_coord,
};

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    (9u64.pow(n + 1) - 1) / 8 + 1
}

/// `create_objset`: the 9 directions of the child spheres around +Z.
fn create_objset() -> [Coord4; 9] {
    let dist = 1.0 / 2.0f64.sqrt();
    let mut trio_dir: [Coord4; 3] = [
        [dist, dist, 0.0, 0.0],
        [dist, 0.0, -dist, 0.0],
        [0.0, dist, -dist, 0.0],
    ];
    let mut axis = [1.0, -1.0, 0.0];
    normalize(&mut axis);
    let mx = axis_rotate_matrix(axis, (2.0 / 6.0f64.sqrt()).asin());
    for dir in &mut trio_dir {
        *dir = transform_coord(*dir, &mx);
    }
    let mut objset = [[0.0; 4]; 9];
    for num_set in 0..3 {
        let mx = rotate_matrix(Axis::Z, f64::from(num_set) * 2.0 * PI / 3.0);
        for (num_vert, dir) in trio_dir.iter().enumerate() {
            objset[num_set as usize * 3 + num_vert] = transform_coord(*dir, &mx);
        }
    }
    objset
}

/// `output_object`: the sphere `center` (w = radius), then its children along
/// `direction` (w = the child radius ratio).
fn output_object(
    out: &mut Output,
    objset: &[Coord4; 9],
    depth: u32,
    center: Coord4,
    direction: Coord4,
) {
    out.sphere(center);
    if depth == 0 {
        return;
    }
    // The C's tolerance: child directions may be slightly short of unit length.
    let mx: Matrix = if direction[2] >= 0.9999 {
        IDENTITY
    } else if direction[2] <= -0.9999 {
        rotate_matrix(Axis::Y, PI)
    } else {
        let z_axis: Coord3 = [0.0, 0.0, 1.0];
        let dir = [direction[0], direction[1], direction[2]];
        let mut axis = cross(z_axis, dir);
        normalize(&mut axis);
        axis_rotate_matrix(axis, dot(z_axis, dir).acos())
    };
    let scale = center[3] * (1.0 + direction[3]);
    for set in objset {
        let mut child_pt = transform_coord(*set, &mx);
        child_pt[0] = child_pt[0] * scale + center[0];
        child_pt[1] = child_pt[1] * scale + center[1];
        child_pt[2] = child_pt[2] * scale + center[2];
        child_pt[3] = center[3] * direction[3];
        let child_dir = [
            (child_pt[0] - center[0]) / scale,
            (child_pt[1] - center[1]) / scale,
            (child_pt[2] - center[2]) / scale,
            direction[3],
        ];
        output_object(out, objset, depth - 1, child_pt, child_dir);
    }
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    let radius = 1.0;
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [2.1, 1.3, 1.7],
        [0.0; 3],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        0.01,
        512,
        512,
    );
    for light in [[4.0, 3.0, 2.0], [1.0, -4.0, 4.0], [-3.0, 1.0, 5.0]] {
        out.light([light[0], light[1], light[2], 1.0]);
    }
    out.color([1.0, 0.75, 0.33], 0.2, 0.8, 0.0, 0.0, 0.0, 0.0, 1.0);
    let b = [12.0 * radius, 12.0 * radius, -radius / 2.0];
    out.polygon(&[
        [b[0], b[1], b[2]],
        [-b[0], b[1], b[2]],
        [-b[0], -b[1], b[2]],
        [b[0], -b[1], b[2]],
    ]);
    out.color([1.0, 0.9, 0.7], 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 1.0);
    let objset = create_objset();
    output_object(
        out,
        &objset,
        n,
        [0.0, 0.0, 0.0, radius / 2.0],
        [0.0, 0.0, 1.0, 1.0 / 3.0],
    );
}
