//! `jacks.c`: recursive jacks (three crossed cylinders with spheres on the six ends),
//! a smaller jack in each of the 8 octants of every jack, down to the size factor's
//! depth; built with the transform stack ([`crate::transform_stack`]), one light.
//!
//! Size factor n: jacks = 1 + 8 + … + 8ⁿ⁻¹ = (8ⁿ − 1) / 7, each 3 cylinders and 6
//! spheres: primitives = 9·(8ⁿ − 1) / 7. n = 1 (default): 9; n = 7: 2,696,337.

use crate::output::Output;
use crate::vector::{Axis, PI};

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    9 * (8u64.pow(n) - 1) / 7
}

/// `make_jack_obj`: one jack in the current frame, scaled by 3/4 to keep copies apart.
fn make_jack_obj(out: &mut Output) {
    out.tx.push();
    out.tx.scale([0.75, 0.75, 0.75]);
    out.cylcone([-1.0, 0.0, 0.0, 0.1], [1.0, 0.0, 0.0, 0.1]);
    out.cylcone([0.0, -1.0, 0.0, 0.1], [0.0, 1.0, 0.0, 0.1]);
    out.cylcone([0.0, 0.0, -1.0, 0.1], [0.0, 0.0, 1.0, 0.1]);
    for center in [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, -1.0],
    ] {
        out.sphere([center[0], center[1], center[2], 0.2]);
    }
    out.tx.pop();
}

/// `make_rec_jack`: a jack, then half-size copies centred at (±½, ±½, ±½).
fn make_rec_jack(out: &mut Output, depth: u32, max_depth: u32) {
    make_jack_obj(out);
    if depth < max_depth {
        for i in [-0.5, 0.5] {
            for j in [-0.5, 0.5] {
                for k in [-0.5, 0.5] {
                    out.tx.push();
                    out.tx.translate([i, j, k]);
                    out.tx.scale([0.5, 0.5, 0.5]);
                    make_rec_jack(out, depth + 1, max_depth);
                    out.tx.pop();
                }
            }
        }
    }
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    out.set_polygonalization(2, 2);
    out.background([0.2, 0.05, 0.2]);
    out.viewpoint(
        [0.0, 0.0, -8.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        25.0,
        1.0,
        0.001,
        256,
        256,
    );
    out.light([-10.0, 3.0, -20.0, 1.0]);
    out.tx.push();
    out.tx.rotate(Axis::X, -30.0 * PI / 180.0);
    out.tx.rotate(Axis::Y, -20.0 * PI / 180.0);
    out.color([0.737, 0.561, 0.561], 0.1, 0.7, 0.7, 0.4, 20.0, 0.0, 1.0);
    make_rec_jack(out, 1, n);
    out.tx.pop();
}
