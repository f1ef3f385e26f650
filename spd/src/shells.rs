//! `shells.c`: a sea shell by Pickover's method (IEEE CG&A, November 1989), a spiral
//! of overlapping spheres growing exponentially; one light. Meant as a realistic yet
//! pathological scene (many overlapping, some tiny, primitives). The C's extra
//! options (alpha, beta, gamma, exponent) are kept at their defaults.
//!
//! Size factor n: steps = 180·2ⁿ, spheres = steps + 1 (i from −2·steps/3 to
//! steps/3). n = 5 (default): 5761 spheres; n = 13: 1,474,561.

use crate::output::Output;
use crate::vector::PI;

/// Shape parameters: gamma (0.01 to 3), alpha (> 1 − 1.1 is good), beta (about −2),
/// exponent constant `a` and relative size `k`.
const GAMMA: f64 = 1.0;
const ALPHA: f64 = 0.0;
const BETA: f64 = -2.0;
const A: f64 = 0.15;
const K: f64 = 1.0;

/// `steps` of the C: 180 · 2ⁿ.
fn steps(n: u32) -> i64 {
    180 * (1i64 << n)
}

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    let steps = steps(n);
    (steps / 3 + steps * 2 / 3 + 1) as u64
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [-6.0, -60.0, 35.0],
        [0.0, 8.0, -15.0],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        0.5,
        512,
        512,
    );
    out.light([-100.0, -100.0, 100.0, 1.0]);
    out.color([1.0, 0.8, 0.4], 0.0, 0.8, 0.2, 0.5, 10.0, 0.0, 1.0);
    let steps = steps(n);
    // The C's `(long)(180.0 * pow(2.0, n))` is exact: a power of two times 180.
    for i in -steps * 2 / 3..=steps / 3 {
        let angle = 3.0 * 6.0 * PI * i as f64 / steps as f64;
        let r = K * (A * angle).exp();
        let z = if ALPHA > 0.0 { ALPHA * angle } else { BETA * r };
        out.sphere([r * angle.sin(), r * angle.cos(), z, r / GAMMA]);
    }
}
