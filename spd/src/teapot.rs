//! `teapot.c`: the Utah teapot's 32 Bézier patches (bottom included) tessellated into
//! smooth triangles (`pp 3`), on a checkerboard meshed to the same degree; two lights.
//! The teapot should be rendered double sided (its lid gap shows back faces).
//!
//! Size factor n: each patch is an n × n mesh of two triangles per cell; triangles with
//! two vertices on the lid or bottom cusp (on the Z axis) are dropped, 8n of them (the
//! 4 lid-top and 4 bottom patches lose one row each). Patches = 64n² − 8n, checker
//! squares = n²: primitives = 65n² − 8n. n = 6 (default): 2256 patches, 36 squares.

use crate::output::Output;
use crate::teapot_data::{PATCHES, VERTS};
use crate::vector::{
    Coord3, Coord4, Matrix, cross, dot4, multiply, normalize, transform_coord, transpose,
};

/// Primitives at size factor `n`.
pub fn primitive_count(n: u32) -> u64 {
    let n = u64::from(n);
    65 * n * n - 8 * n
}

/// The Bézier basis matrix.
const MS: Matrix = [
    [-1.0, 3.0, -3.0, 1.0],
    [3.0, -6.0, 3.0, 0.0],
    [-3.0, 3.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 0.0],
];

/// `check_for_cusp`: a triangle with two or more vertices on the Z axis (within
/// 0.0001) is degenerate (false); one such vertex gets the axis normal, up at the lid
/// and down at the bottom.
fn check_for_cusp(vert: &[Coord3; 3], norm: &mut [Coord3; 3]) -> bool {
    let on_axis: Vec<usize> = (0..3)
        .rev()
        .filter(|&i| vert[i][0].abs() <= 0.0001 && vert[i][1].abs() <= 0.0001)
        .collect();
    match on_axis.as_slice() {
        [] => true,
        [nv] => {
            norm[*nv] = if vert[*nv][2] > 1.5 {
                [0.0, 0.0, 1.0]
            } else {
                [0.0, 0.0, -1.0]
            };
            true
        }
        _ => false,
    }
}

/// `points_from_basis`: the points at parameters (s[i], t[i]) of the patch with
/// geometry matrices `mgm` (x, y, z), and their normals (t tangent × s tangent).
fn points_from_basis(s: &[f64; 3], t: &[f64; 3], mgm: &[Matrix; 3]) -> ([Coord3; 3], [Coord3; 3]) {
    let mut vert = [[0.0; 3]; 3];
    let mut norm = [[0.0; 3]; 3];
    for num_vert in 0..3 {
        let (sxyz, txyz) = (s[num_vert], t[num_vert]);
        // Power vectors (s³ s² s 1) and their derivatives.
        let mut sp: Coord4 = [0.0; 4];
        let mut tp: Coord4 = [0.0; 4];
        let mut dsp: Coord4 = [0.0; 4];
        let mut dtp: Coord4 = [0.0; 4];
        let (mut sval, mut tval) = (1.0, 1.0);
        let (mut dsval, mut dtval) = (0.0, 0.0);
        for p in (0..4).rev() {
            sp[p] = sval;
            tp[p] = tval;
            sval *= sxyz;
            tval *= txyz;
            if p == 3 {
                dsp[p] = 0.0;
                dtp[p] = 0.0;
                dsval = 1.0;
                dtval = 1.0;
            } else {
                dsp[p] = dsval * (3 - p) as f64;
                dtp[p] = dtval * (3 - p) as f64;
                dsval *= sxyz;
                dtval *= txyz;
            }
        }
        let mut sdir = [0.0; 3];
        let mut tdir = [0.0; 3];
        for i in 0..3 {
            vert[num_vert][i] = dot4(transform_coord(sp, &mgm[i]), tp);
            sdir[i] = dot4(transform_coord(dsp, &mgm[i]), tp);
            tdir[i] = dot4(transform_coord(sp, &mgm[i]), dtp);
        }
        norm[num_vert] = cross(tdir, sdir);
        normalize(&mut norm[num_vert]);
    }
    (vert, norm)
}

/// `output_teapot`.
fn output_teapot(out: &mut Output, n: u32) {
    out.color([1.0, 0.5, 0.1], 0.0, 0.75, 0.25, 0.25, 37.0, 0.0, 0.0);
    let mst = transpose(&MS);
    let sf = f64::from(n);
    for patch in &PATCHES {
        // M · G · Mᵀ for x, y, z.
        let mgm: [Matrix; 3] = std::array::from_fn(|i| {
            let g: Matrix = std::array::from_fn(|r| {
                std::array::from_fn(|c| VERTS[usize::from(patch[r * 4 + c])][i])
            });
            multiply(&multiply(&MS, &g), &mst)
        });
        for sstep in 0..n {
            for tstep in 0..n {
                for num_tri in 0..2 {
                    let mut s = [0.0; 3];
                    let mut t = [0.0; 3];
                    for num_vert in 0..3 {
                        let corner = (num_vert + num_tri * 2) % 4;
                        // Corners 1 and 2 are one step further in s, 2 and 3 in t.
                        s[num_vert] = f64::from(sstep + u32::from(corner / 2 != 0)) / sf;
                        t[num_vert] = f64::from(tstep + u32::from(corner % 3 != 0)) / sf;
                    }
                    let (vert, mut norm) = points_from_basis(&s, &t, &mgm);
                    if check_for_cusp(&vert, &mut norm) {
                        out.patch_triangle(&vert, &norm);
                    }
                }
            }
        }
    }
}

/// `loc_to_square`: checkerboard square (`sstep`, `tstep`) of an n × n board over
/// [-4, 4]².
fn loc_to_square(sstep: u32, tstep: u32, n: u32) -> [Coord3; 4] {
    let sf = f64::from(n);
    std::array::from_fn(|i| {
        // Vertices 0 and 3 are at the low x, 1 and 2 at the high; 0 and 1 at the low y.
        let x = 4.0 * (2.0 * f64::from(sstep + u32::from(i % 3 != 0)) / sf - 1.0);
        let y = 4.0 * (2.0 * f64::from(tstep + u32::from(i / 2 != 0)) / sf - 1.0);
        [x, y, 0.0]
    })
}

/// `output_checkerboard`: the white squares, then the grey ones.
fn output_checkerboard(out: &mut Output, n: u32) {
    for (color, parity) in [([1.0, 1.0, 1.0], 1), ([0.5, 0.5, 0.5], 0)] {
        out.color(color, 0.0, 0.5, 0.5, 0.5, 30.0, 0.0, 0.0);
        for sstep in 0..n {
            for tstep in 0..n {
                if (sstep + tstep) % 2 == parity {
                    out.polygon(&loc_to_square(sstep, tstep, n));
                }
            }
        }
    }
}

/// Writes the scene at size factor `n` (1 works though the SPD warns it is
/// unsupported: it has more degenerate triangles, which are dropped).
pub fn generate(out: &mut Output, n: u32) {
    out.background([0.078, 0.361, 0.753]);
    out.viewpoint(
        [4.86, 7.2, 5.4],
        [0.0; 3],
        [0.0, 0.0, 1.0],
        45.0,
        1.0,
        1.0,
        512,
        512,
    );
    out.light([-3.1, 9.8, 12.1, 1.0]);
    out.light([11.3, 5.1, 8.8, 1.0]);
    output_checkerboard(out, n);
    output_teapot(out, n);
}
