//! `sample.c` (Alexander Enzmann): a small scene exercising the library's tessellated
//! primitives: three interlocking tori (smooth triangles), a cone, and a disc
//! (polygons); one light. The SPD ignores the size factor, so only 1 is accepted.
//!
//! Primitives: 3 tori × 288 patches (polygonalization 3: 12 × 12 cells of two
//! triangles), 1 cone, 16 disc triangles (polygonalization 4) = 881.

use crate::output::Output;

/// Primitives (the size factor is ignored).
pub fn primitive_count(_n: u32) -> u64 {
    3 * 288 + 1 + 16
}

/// Writes the scene (the size factor is ignored).
pub fn generate(out: &mut Output, _n: u32) {
    let cyan = [0.0, 1.0, 1.0];
    // The C's names: "Yellow" is (1, 0, 1) and "Magenta" (1, 1, 0).
    let yellow = [1.0, 0.0, 1.0];
    let magenta = [1.0, 1.0, 0.0];
    let red = [1.0, 0.0, 0.0];
    out.background([0.8, 0.8, 0.8]);
    out.viewpoint(
        [0.0, 5.0, -5.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        45.0,
        1.0,
        0.001,
        512,
        512,
    );
    out.light([-10.0, 20.0, -20.0, 1.0]);
    out.color(cyan, 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);
    out.torus([-1.0, 0.0, 0.0], [1.0, 1.0, -0.5], 2.0, 0.5);
    out.color(magenta, 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);
    out.torus([0.0, 0.0, 0.0], [0.0, 1.0, -0.5], 2.0, 0.5);
    out.color(yellow, 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);
    out.torus([1.0, 0.0, 0.0], [-1.0, 1.0, -0.5], 2.0, 0.5);
    out.color(red, 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);
    out.cylcone([0.0, -2.0, 0.0, 2.0], [0.0, 2.0, 0.0, 0.1]);
    out.set_polygonalization(4, 1);
    out.color(red, 0.1, 0.7, 0.0, 0.7, 10.0, 0.0, 1.0);
    out.disc([0.0, -2.0, 0.0], [0.0, 1.0, 0.0], 0.0, 4.0);
}
