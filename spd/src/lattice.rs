//! `lattice.c` (Antonio Costa): a cubic lattice of shiny spheres joined to their
//! neighbours by matte cylinders, red along X, green along Y, blue along Z; six
//! lights. Every primitive is preceded by its own `f` line, as in the C.
//!
//! Size factor n: spheres = (n + 1)³, cylinders = 3·n·(n + 1)²; primitives =
//! (n + 1)²·(4n + 1). n = 12 (default): 2197 + 6084 = 8281.

use crate::output::Output;

/// Sphere radius and cylinder radius, in lattice cells.
const RADIUS1: f64 = 1.0 / 4.0;
const RADIUS2: f64 = 1.0 / 16.0;

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    let n = u64::from(n);
    (n + 1).pow(3) + 3 * n * (n + 1).pow(2)
}

/// Writes the scene at size factor `n`.
pub fn generate(out: &mut Output, n: u32) {
    let sf = f64::from(n);
    let inv_factor = 1.0 / sf;
    let radius1 = RADIUS1 / sf;
    let radius2 = RADIUS2 / sf;
    // Cylinders stop just inside the spheres.
    let delta = (radius1 * (1.0 - (RADIUS2 / RADIUS1).sqrt())) * 0.99;

    out.background([0.078, 0.361, 0.753]);
    let middle = (f64::from(n >> 1) + 0.5) * inv_factor;
    out.viewpoint(
        [middle, 1.0, 1.0 - 1.0 / f64::from(n << 1)],
        [middle, -1.0, -1.0 - 1.0 / f64::from(n << 1)],
        [0.2, 1.0, 0.0],
        60.0,
        1.0,
        0.0,
        512,
        512,
    );
    let lscale = 1.0 / 6.0f64.sqrt();
    for light in [
        [2.0, 0.5, 0.5],
        [-1.0, 0.5, 0.5],
        [0.5, 2.0, 0.5],
        [0.5, -1.0, 0.5],
        [0.5, 0.5, 2.0],
        [0.5, 0.5, -1.0],
    ] {
        out.light([light[0], light[1], light[2], lscale]);
    }
    for x in 0..=n {
        let x0 = f64::from(x) / sf;
        for y in 0..=n {
            let y0 = f64::from(y) / sf;
            for z in 0..=n {
                let z0 = f64::from(z) / sf;
                out.color([0.9, 0.9, 0.9], 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 0.0);
                out.sphere([x0, y0, z0, radius1]);
                if x != n {
                    out.color([0.9, 0.1, 0.1], 0.1, 0.99, 0.0, 0.0, 0.0, 0.0, 0.0);
                    out.cylcone(
                        [x0 + delta, y0, z0, radius2],
                        [x0 + inv_factor - delta, y0, z0, radius2],
                    );
                }
                if y != n {
                    out.color([0.1, 0.9, 0.1], 0.1, 0.99, 0.0, 0.0, 0.0, 0.0, 0.0);
                    out.cylcone(
                        [x0, y0 + delta, z0, radius2],
                        [x0, y0 + inv_factor - delta, z0, radius2],
                    );
                }
                if z != n {
                    out.color([0.1, 0.1, 0.9], 0.1, 0.99, 0.0, 0.0, 0.0, 0.0, 0.0);
                    out.cylcone(
                        [x0, y0, z0 + delta, radius2],
                        [x0, y0, z0 + inv_factor - delta, radius2],
                    );
                }
            }
        }
    }
}
