//! `mount.c`: a fractal mountain (Carpenter's midpoint subdivision extended to a
//! square grid) with a pyramid of four glass spheres in front; one light.
//!
//! The heights come from [`gauss_rand`] seeded by the C's original hash of the grid
//! position (the "old, faulty" hash the SPD keeps so that the mountain is the one of
//! the 1987 IEEE CG&A article), so the mountain is the SPD's.
//!
//! Size factor n: a 2ⁿ × 2ⁿ grid, triangles = 2·4ⁿ, plus 4 spheres. n = 6 (default):
//! 8192 triangles; n = 10: 2,097,152.

use crate::output::Output;
use crate::random::gauss_rand;
use crate::vector::{
    Axis, Coord3, Coord4, PI, add, axis_rotate_matrix, normalize, rotate_matrix, transform_vector,
};

/// Fractal dimension (between 2 and 3): sets the variance of the heights.
const FRACTAL_DIMENSION: f64 = 2.2;
/// Added to every seed; another value makes another mountain.
const MOUNTAIN_NO: i64 = 21;
/// The C's rounded √2 for the centre point's rise (not the exact constant: the
/// heights must be the C's).
#[allow(clippy::approx_constant)]
const ROOT_2: f64 = 1.4142136;
/// Lower left corner and width of the mountain.
const X_CORNER: f64 = -1.0;
const Y_CORNER: f64 = -1.0;
const WIDTH: f64 = 2.0;

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    2 * 4u64.pow(n) + 4
}

/// `value << shift` in the C's `unsigned long`, for the hash: a negative shift (size
/// factors above 7) is undefined behaviour in C; on x86-64 the count is taken modulo
/// 64, which puts every bit of these small values above bit 15, so the term is 0 after
/// the hash's `& 0xffff`. Zero is therefore also what a 32-bit `long` would give.
fn shifted(value: u64, shift: i64) -> u64 {
    if (0..64).contains(&shift) {
        value << shift
    } else {
        0
    }
}

/// `hash_rand(A, B, C)`, the original (buggy) hash of `mount.c`.
fn hash_rand(a: u32, b: u32, c: u32) -> i64 {
    let (a, b, c) = (u64::from(a), u64::from(b), i64::from(c));
    let sum = shifted(a, 23 - c)
        .wrapping_add(shifted(b, 15 - c))
        .wrapping_add(shifted(a, 7 - c));
    (sum & 0xffff) as i64
}

/// `create_spheres`: a pyramid of 4 spheres of radius `center[3]` around `center`.
fn create_spheres(out: &mut Output, center: Coord4) {
    let mut axis = [1.0, 1.0, 0.0];
    normalize(&mut axis);
    let angle = (-1.0f64 / 3.0).acos();
    let pt: Coord3 = [0.0, 0.0, center[3] * (3.0f64 / 2.0).sqrt()];
    let top = add([center[0], center[1], center[2]], pt);
    out.sphere([top[0], top[1], top[2], center[3]]);
    let new_pt = transform_vector(pt, &axis_rotate_matrix(axis, angle));
    for i in 0..3 {
        let mx = rotate_matrix(Axis::Z, f64::from(i) * 2.0 * PI / 3.0);
        let p = add(
            transform_vector(new_pt, &mx),
            [center[0], center[1], center[2]],
        );
        out.sphere([p[0], p[1], p[2], center[3]]);
    }
}

/// Recursion state of `grow_mountain` that does not change.
struct Mountain {
    fnum_pts: f64,
    roughness: f64,
    size_factor: u32,
}

impl Mountain {
    /// The midpoint height offset at grid point (x, y) for a rise of `rise_height`.
    fn rise(&self, x: u32, y: u32, rise_height: f64) -> f64 {
        let seed = MOUNTAIN_NO + hash_rand(x, y, self.size_factor);
        rise_height * gauss_rand(seed)
    }

    /// `grow_mountain`: the square of side `width` (grid units) at (`ll_x`, `ll_y`)
    /// with corner heights lower left, lower right, upper right, upper left; split in
    /// four until one unit wide, then two triangles.
    #[allow(clippy::too_many_arguments)]
    fn grow(
        &self,
        out: &mut Output,
        width: u32,
        ll_x: u32,
        ll_y: u32,
        ll_fz: f64,
        lr_fz: f64,
        ur_fz: f64,
        ul_fz: f64,
    ) {
        if width == 1 {
            let l_fx = X_CORNER + f64::from(ll_x) * WIDTH / self.fnum_pts;
            let r_fx = X_CORNER + f64::from(ll_x + 1) * WIDTH / self.fnum_pts;
            let l_fy = Y_CORNER + f64::from(ll_y) * WIDTH / self.fnum_pts;
            let u_fy = Y_CORNER + f64::from(ll_y + 1) * WIDTH / self.fnum_pts;
            let corners = [
                [l_fx, l_fy, ll_fz],
                [r_fx, l_fy, lr_fz],
                [r_fx, u_fy, ur_fz],
                [l_fx, u_fy, ul_fz],
            ];
            for num_tri in 0..2 {
                let tri: [Coord3; 3] = std::array::from_fn(|v| corners[(v + num_tri * 2) % 4]);
                out.polygon(&tri);
            }
            return;
        }
        let half = width >> 1;
        let hside_length = f64::from(half) * WIDTH / self.fnum_pts;
        let rise_height = hside_length * self.roughness;
        let lower_fz = (ll_fz + lr_fz) / 2.0 + self.rise(ll_x + half, ll_y, rise_height);
        let right_fz = (lr_fz + ur_fz) / 2.0 + self.rise(ll_x + width, ll_y + half, rise_height);
        let upper_fz = (ur_fz + ul_fz) / 2.0 + self.rise(ll_x + half, ll_y + width, rise_height);
        let left_fz = (ul_fz + ll_fz) / 2.0 + self.rise(ll_x, ll_y + half, rise_height);
        let middle_fz = (ll_fz + lr_fz + ur_fz + ul_fz) / 4.0
            + self.rise(ll_x + half, ll_y + half, ROOT_2 * rise_height);
        self.grow(out, half, ll_x, ll_y, ll_fz, lower_fz, middle_fz, left_fz);
        self.grow(
            out,
            half,
            ll_x + half,
            ll_y,
            lower_fz,
            lr_fz,
            right_fz,
            middle_fz,
        );
        self.grow(
            out,
            half,
            ll_x + half,
            ll_y + half,
            middle_fz,
            right_fz,
            ur_fz,
            upper_fz,
        );
        self.grow(
            out,
            half,
            ll_x,
            ll_y + half,
            left_fz,
            middle_fz,
            upper_fz,
            ul_fz,
        );
    }
}

/// Writes the scene at size factor `n` (at most 31: the grid side is a u32).
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [-1.6, 1.6, 1.7],
        [0.0; 3],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        0.01,
        512,
        512,
    );
    out.light([-100.0, -100.0, 100.0, 1.0]);
    out.color([1.0, 1.0, 1.0], 0.0, 0.1, 0.1, 0.4, 6.7, 0.9, 1.5);
    create_spheres(out, [-0.8, 0.8, 1.0, 0.17]);
    out.color([0.5, 0.45, 0.35], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let num_pts = 1u32 << n.min(31);
    let ratio = 2.0 / (2.0f64.ln() / (FRACTAL_DIMENSION - 1.0)).exp();
    let mountain = Mountain {
        fnum_pts: f64::from(num_pts),
        roughness: (ratio * ratio - 1.0).sqrt(),
        size_factor: n,
    };
    mountain.grow(out, num_pts, 0, 0, 0.0, 0.0, 0.0, 0.0);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_matches_the_macro() {
        // ((A << 17) + (B << 9) + (A << 1)) & 0xffff at size factor 6.
        assert_eq!(hash_rand(32, 0, 6), ((32 << 17) + (32 << 1)) & 0xffff);
        assert_eq!(
            hash_rand(5, 7, 6),
            ((5 << 17) + (7 << 9) + (5 << 1)) & 0xffff
        );
        // Size factor 8: the last shift is negative and drops out.
        assert_eq!(hash_rand(5, 7, 8), ((5 << 15) + (7 << 7)) & 0xffff);
    }
}
