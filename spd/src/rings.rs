//! `rings.c`: objects made of 6 pentagonal rings (cylinders with spheres at the joints)
//! joining the edge midpoints of a dodecahedron, stacked in a pyramid seen from its
//! tip, with a wall behind for shadows; three lights.
//!
//! Size factor n: layers 1..n of d² objects, T = n(n + 1)(2n + 1)/6 objects of 30
//! cylinders and 30 spheres; primitives = 60·T + 1 (the wall). n = 7 (default):
//! 4200 spheres, 4200 cylinders.

use crate::output::Output;
use crate::vector::{Axis, Coord3, PI, add, rotate_matrix, transform_point};

/// Growth of the spacing from layer to layer (1: none).
const SPREAD_OUT: f64 = 1.0;

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    let n = u64::from(n);
    60 * (n * (n + 1) * (2 * n + 1) / 6) + 1
}

/// `create_dodec`: the 30 joint points (6 pentagons of 5) of one object, scaled to fit
/// a unit sphere with the tube radius `minor_radius`.
fn create_dodec(minor_radius: f64) -> [Coord3; 30] {
    let mut vertex = [[0.0; 3]; 30];
    let scale = 1.0 / (1.0 + minor_radius);
    // One pentagon in the XY plane, starting along +X.
    for (num_vertex, v) in vertex.iter_mut().take(5).enumerate() {
        let angle = num_vertex as f64 * 2.0 * PI / 5.0;
        *v = [scale * angle.cos(), scale * angle.sin(), 0.0];
    }
    // The angle between two adjacent dodecahedron faces.
    let x_rotation = 2.0 * ((PI / 3.0).cos() / (PI / 5.0).sin()).acos();
    let x_matrix = rotate_matrix(Axis::X, x_rotation);
    for num_pentagon in 1..6 {
        let z_rotation = PI * (2.0 * f64::from(num_pentagon - 1) + 1.0) / 5.0;
        let z_matrix = rotate_matrix(Axis::Z, z_rotation);
        for num_vertex in 0..5 {
            let temp = transform_point(vertex[num_vertex], &x_matrix);
            vertex[5 * num_pentagon as usize + num_vertex] = transform_point(temp, &z_matrix);
        }
    }
    vertex
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    let radius = 0.07412;
    let spread = 1.0 / (PI / 8.0).sin();
    let (y_diff, xz_diff) = if SPREAD_OUT <= spread {
        (spread / SPREAD_OUT, 1.0)
    } else {
        (1.0, SPREAD_OUT / spread)
    };
    out.background([0.078, 0.361, 0.753]);
    let from = [-1.0, -spread, 0.5];
    let at = [from[0], from[1] + 1.0, from[2]];
    out.viewpoint(from, at, [0.0, 0.0, 1.0], 45.0, 1.0, 1.0, 512, 512);
    for light in [
        [3.0, -spread, 3.0],
        [-4.0, -spread, 1.0],
        [2.0, -spread, -4.0],
    ] {
        out.light([light[0], light[1], light[2], 1.0]);
    }
    out.color([1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    // The wall just spans the 45 degree view, plus 1 %.
    let wy = y_diff * f64::from(n + 1);
    let wxz = 1.01 * (wy - from[1]) * (PI / 8.0).tan();
    out.polygon(&[
        [wxz + from[0], wy, wxz + from[2]],
        [-wxz + from[0], wy, wxz + from[2]],
        [-wxz + from[0], wy, -wxz + from[2]],
        [wxz + from[0], wy, -wxz + from[2]],
    ]);
    let ring_color: [Coord3; 6] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
    ];
    let dodec = create_dodec(radius);
    let mut offset = [0.0; 3];
    for num_depth in 0..n {
        offset[1] = y_diff * f64::from(num_depth + 1);
        for num_objz in 0..=num_depth {
            offset[2] = xz_diff * (2.0 * f64::from(num_objz) - f64::from(num_depth));
            for num_objx in 0..=num_depth {
                offset[0] = xz_diff * (2.0 * f64::from(num_objx) - f64::from(num_depth));
                for num_elem in 0..30 {
                    let base = add(dodec[num_elem], offset);
                    let prev_elem = if num_elem % 5 == 0 {
                        // A new ring: its colour.
                        out.color(ring_color[num_elem / 5], 0.0, 0.5, 0.2, 0.3, 37.0, 0.0, 0.0);
                        num_elem + 4
                    } else {
                        num_elem - 1
                    };
                    let apex = add(dodec[prev_elem], offset);
                    out.cylcone(
                        [base[0], base[1], base[2], radius],
                        [apex[0], apex[1], apex[2], radius],
                    );
                    out.sphere([base[0], base[1], base[2], radius]);
                }
            }
        }
    }
}
