//! `sombrero.c` (Alexander Enzmann): a height field of a damped cosine ripple,
//! written as triangles by the library's height-field output; one light.
//!
//! Size factor n: a w × w grid with w = 32·2ⁿ⁻¹, triangles = 2·(w − 1)².
//! n = 1 (default): 1922; n = 6: 2,093,058.

use crate::output::Output;

/// The C's truncated π in the ripple (not the exact constant: the heights must be the
/// C's).
#[allow(clippy::approx_constant)]
const RIPPLE_PI: f64 = 3.14159265358;

/// Grid side at size factor `n`.
fn width(n: u32) -> usize {
    32 << (n - 1)
}

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    let w = width(n) as u64;
    2 * (w - 1) * (w - 1)
}

/// `create_sombrero`: the heights over x0..x1 (columns), y0..y1 (rows), stored as f32
/// as in the C. x and y advance by accumulation with a step of range / count (the
/// last sample falls short of x1, as in the C).
fn create_sombrero(
    width: usize,
    height: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
) -> Vec<Vec<f32>> {
    let (a_const, b_const, c_const) = (1.0, 1.0, 3.0);
    let two_pi_a = 2.0 * RIPPLE_PI * a_const;
    let deltax = (x1 - x0) / width as f64;
    let deltay = (y1 - y0) / height as f64;
    let mut data = Vec::with_capacity(height);
    let mut y = y0;
    for _ in 0..height {
        let mut row = Vec::with_capacity(width);
        let mut x = x0;
        for _ in 0..width {
            let d = (x * x + y * y).sqrt();
            row.push((c_const * (two_pi_a * d).cos() * (-b_const * d).exp() / 3.0) as f32);
            x += deltax;
        }
        data.push(row);
        y += deltay;
    }
    data
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.set_polygonalization(3, 3);
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [0.0, 5.0, -8.0],
        [0.0; 3],
        [0.0, 0.0, 1.0],
        40.0,
        1.0,
        0.01,
        512,
        512,
    );
    out.light([10.0, 10.0, -10.0, 1.0]);
    out.color([1.0, 0.1, 0.1], 0.1, 0.8, 0.0, 0.5, 40.0, 0.0, 1.0);
    let w = width(n);
    let data = create_sombrero(w, w, -4.0, 4.0, -4.0, 4.0);
    out.height_field(&data, -4.0, 4.0, -3.0, -4.0, 4.0);
}
