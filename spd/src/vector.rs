//! The SPD's vector and matrix library (`libvec.c`, `def.h` macros), in f64.
//!
//! Points are row vectors multiplied on the left of a row-major 4×4 matrix, as in the
//! C (`p' = p · M`, translation in row 3). Every function keeps the C's order of
//! floating-point operations, so the generated numbers are the C's bit for bit (up to
//! the C library's transcendental functions).

/// `COORD3`: x, y, z.
pub type Coord3 = [f64; 3];

/// `COORD4`: x, y, z and w (a radius for spheres and cone ends).
pub type Coord4 = [f64; 4];

/// `MATRIX`: row major, `m[row][column]`.
pub type Matrix = [[f64; 4]; 4];

/// `X_AXIS`, `Y_AXIS`, `Z_AXIS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

/// `PI` of `def.h` (3.141592653589793: the same double).
pub const PI: f64 = std::f64::consts::PI;

/// `EPSILON` of `def.h` (non-Mac builds).
pub const EPSILON: f64 = 1.0e-8;

/// `EPSILON2` of `def.h` (non-Mac builds).
pub const EPSILON2: f64 = 1.0e-6;

/// The identity matrix (`IdentityTx`).
pub const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The x, y, z of a `COORD4`.
pub fn xyz(v: Coord4) -> Coord3 {
    [v[0], v[1], v[2]]
}

/// `DOT_PRODUCT`.
pub fn dot(a: Coord3, b: Coord3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `DOT4`.
pub fn dot4(a: Coord4, b: Coord4) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// `CROSS`.
pub fn cross(a: Coord3, b: Coord3) -> Coord3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `ADD3_COORD3`.
pub fn add(a: Coord3, b: Coord3) -> Coord3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `SUB3_COORD3`.
pub fn sub(a: Coord3, b: Coord3) -> Coord3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `lib_normalize_vector`: scales `v` to unit length unless it is zero; returns the
/// length it had.
pub fn normalize(v: &mut Coord3) -> f64 {
    let divisor = dot(*v, *v).sqrt();
    if divisor > 0.0 {
        v[0] /= divisor;
        v[1] /= divisor;
        v[2] /= divisor;
    }
    divisor
}

/// `lib_create_rotate_matrix`: rotation about one axis by `angle` radians.
pub fn rotate_matrix(axis: Axis, angle: f64) -> Matrix {
    let mut mx = [[0.0; 4]; 4];
    let (cosine, sine) = (angle.cos(), angle.sin());
    match axis {
        Axis::X => {
            mx[0][0] = 1.0;
            mx[1][1] = cosine;
            mx[2][2] = cosine;
            mx[1][2] = sine;
            mx[2][1] = -sine;
        }
        Axis::Y => {
            mx[1][1] = 1.0;
            mx[0][0] = cosine;
            mx[2][2] = cosine;
            mx[2][0] = sine;
            mx[0][2] = -sine;
        }
        Axis::Z => {
            mx[2][2] = 1.0;
            mx[0][0] = cosine;
            mx[1][1] = cosine;
            mx[0][1] = sine;
            mx[1][0] = -sine;
        }
    }
    mx[3][3] = 1.0;
    mx
}

/// `lib_create_axis_rotate_matrix`: rotation by `angle` radians about the unit `axis`.
pub fn axis_rotate_matrix(axis: Coord3, angle: f64) -> Matrix {
    let (cosine, sine) = (angle.cos(), angle.sin());
    let one_minus_cosine = 1.0 - cosine;
    let [x, y, z] = axis;
    [
        [
            x * x + (1.0 - x * x) * cosine,
            x * y * one_minus_cosine + z * sine,
            x * z * one_minus_cosine - y * sine,
            0.0,
        ],
        [
            x * y * one_minus_cosine - z * sine,
            y * y + (1.0 - y * y) * cosine,
            y * z * one_minus_cosine + x * sine,
            0.0,
        ],
        [
            x * z * one_minus_cosine + y * sine,
            y * z * one_minus_cosine - x * sine,
            z * z + (1.0 - z * z) * cosine,
            0.0,
        ],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// `lib_create_translate_matrix`.
pub fn translate_matrix(v: Coord3) -> Matrix {
    let mut mx = IDENTITY;
    mx[3][0] = v[0];
    mx[3][1] = v[1];
    mx[3][2] = v[2];
    mx
}

/// `lib_create_scale_matrix`.
pub fn scale_matrix(v: Coord3) -> Matrix {
    let mut mx = [[0.0; 4]; 4];
    mx[0][0] = v[0];
    mx[1][1] = v[1];
    mx[2][2] = v[2];
    mx[3][3] = 1.0;
    mx
}

/// `lib_create_canonical_matrix`: the transform taking the canonical frame (origin at
/// 0, up along +Z) to the frame at `origin` with `up` (a unit vector), and its inverse.
/// Returns `(forward, inverse)`: `forward` maps the frame to canonical coordinates.
pub fn canonical_matrices(origin: Coord3, up: Coord3) -> (Matrix, Matrix) {
    let to_origin = translate_matrix([-origin[0], -origin[1], -origin[2]]);
    // Exact comparison as in the C: only the poles use the fixed X axis.
    let mut axis = if up[2].abs() == 1.0 {
        [1.0, 0.0, 0.0]
    } else {
        [-up[1], up[0], 0.0]
    };
    normalize(&mut axis);
    let angle = up[2].acos();
    let forward = multiply(&to_origin, &axis_rotate_matrix(axis, -angle));
    let inverse = multiply(&axis_rotate_matrix(axis, angle), &translate_matrix(origin));
    (forward, inverse)
}

/// `lib_matrix_multiply`: `a · b`.
pub fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + a[i][3] * b[3][j];
        }
    }
    m
}

/// `lib_transpose_matrix`.
pub fn transpose(m: &Matrix) -> Matrix {
    let mut t = [[0.0; 4]; 4];
    for (i, row) in m.iter().enumerate() {
        for (j, &cell) in row.iter().enumerate() {
            t[j][i] = cell;
        }
    }
    t
}

/// `lib_transform_vector`: `v · M` without the translation.
pub fn transform_vector(v: Coord3, m: &Matrix) -> Coord3 {
    [
        v[0] * m[0][0] + v[1] * m[1][0] + v[2] * m[2][0],
        v[0] * m[0][1] + v[1] * m[1][1] + v[2] * m[2][1],
        v[0] * m[0][2] + v[1] * m[1][2] + v[2] * m[2][2],
    ]
}

/// `lib_transform_normal`: `v · Mᵀ` (the caller passes the inverse transform).
pub fn transform_normal(v: Coord3, m: &Matrix) -> Coord3 {
    [
        v[0] * m[0][0] + v[1] * m[0][1] + v[2] * m[0][2],
        v[0] * m[1][0] + v[1] * m[1][1] + v[2] * m[1][2],
        v[0] * m[2][0] + v[1] * m[2][1] + v[2] * m[2][2],
    ]
}

/// `lib_transform_point`: `v · M` with the translation (w taken as 1, no divide).
pub fn transform_point(v: Coord3, m: &Matrix) -> Coord3 {
    [
        v[0] * m[0][0] + v[1] * m[1][0] + v[2] * m[2][0] + m[3][0],
        v[0] * m[0][1] + v[1] * m[1][1] + v[2] * m[2][1] + m[3][1],
        v[0] * m[0][2] + v[1] * m[1][2] + v[2] * m[2][2] + m[3][2],
    ]
}

/// `lib_transform_coord`: the homogeneous `v · M`.
pub fn transform_coord(v: Coord4, m: &Matrix) -> Coord4 {
    let mut r = [0.0; 4];
    for (j, cell) in r.iter_mut().enumerate() {
        *cell = v[0] * m[0][j] + v[1] * m[1][j] + v[2] * m[2][j] + v[3] * m[3][j];
    }
    r
}

/// `det3x3` of `libvec.c` (arguments by columns, as there).
#[allow(clippy::too_many_arguments)]
fn det3x3(a1: f64, a2: f64, a3: f64, b1: f64, b2: f64, b3: f64, c1: f64, c2: f64, c3: f64) -> f64 {
    a1 * (b2 * c3 - b3 * c2) - b1 * (a2 * c3 - a3 * c2) + c1 * (a2 * b3 - a3 * b2)
}

/// The 16 entries named as in `libvec.c`: `a` is column 0, `b` column 1, …; the digit
/// is the row plus one.
struct Entries {
    a: [f64; 4],
    b: [f64; 4],
    c: [f64; 4],
    d: [f64; 4],
}

impl Entries {
    fn of(m: &Matrix) -> Self {
        Self {
            a: [m[0][0], m[1][0], m[2][0], m[3][0]],
            b: [m[0][1], m[1][1], m[2][1], m[3][1]],
            c: [m[0][2], m[1][2], m[2][2], m[3][2]],
            d: [m[0][3], m[1][3], m[2][3], m[3][3]],
        }
    }
}

/// `lib_matrix_det4x4`.
pub fn determinant(m: &Matrix) -> f64 {
    let Entries { a, b, c, d } = Entries::of(m);
    let [a1, a2, a3, a4] = a;
    let [b1, b2, b3, b4] = b;
    let [c1, c2, c3, c4] = c;
    let [d1, d2, d3, d4] = d;
    a1 * det3x3(b2, b3, b4, c2, c3, c4, d2, d3, d4)
        - b1 * det3x3(a2, a3, a4, c2, c3, c4, d2, d3, d4)
        + c1 * det3x3(a2, a3, a4, b2, b3, b4, d2, d3, d4)
        - d1 * det3x3(a2, a3, a4, b2, b3, b4, c2, c3, c4)
}

/// `adjoint` of `libvec.c`.
fn adjoint(m: &Matrix) -> Matrix {
    let Entries { a, b, c, d } = Entries::of(m);
    let [a1, a2, a3, a4] = a;
    let [b1, b2, b3, b4] = b;
    let [c1, c2, c3, c4] = c;
    let [d1, d2, d3, d4] = d;
    let mut out = [[0.0; 4]; 4];
    out[0][0] = det3x3(b2, b3, b4, c2, c3, c4, d2, d3, d4);
    out[1][0] = -det3x3(a2, a3, a4, c2, c3, c4, d2, d3, d4);
    out[2][0] = det3x3(a2, a3, a4, b2, b3, b4, d2, d3, d4);
    out[3][0] = -det3x3(a2, a3, a4, b2, b3, b4, c2, c3, c4);
    out[0][1] = -det3x3(b1, b3, b4, c1, c3, c4, d1, d3, d4);
    out[1][1] = det3x3(a1, a3, a4, c1, c3, c4, d1, d3, d4);
    out[2][1] = -det3x3(a1, a3, a4, b1, b3, b4, d1, d3, d4);
    out[3][1] = det3x3(a1, a3, a4, b1, b3, b4, c1, c3, c4);
    out[0][2] = det3x3(b1, b2, b4, c1, c2, c4, d1, d2, d4);
    out[1][2] = -det3x3(a1, a2, a4, c1, c2, c4, d1, d2, d4);
    out[2][2] = det3x3(a1, a2, a4, b1, b2, b4, d1, d2, d4);
    out[3][2] = -det3x3(a1, a2, a4, b1, b2, b4, c1, c2, c4);
    out[0][3] = -det3x3(b1, b2, b3, c1, c2, c3, d1, d2, d3);
    out[1][3] = det3x3(a1, a2, a3, c1, c2, c3, d1, d2, d3);
    out[2][3] = -det3x3(a1, a2, a3, b1, b2, b3, d1, d2, d3);
    out[3][3] = det3x3(a1, a2, a3, b1, b2, b3, c1, c2, c3);
    out
}

/// `lib_invert_matrix`: the inverse, or the identity for a (nearly) singular matrix as
/// in the C.
pub fn invert(m: &Matrix) -> Matrix {
    let mut out = adjoint(m);
    let det = determinant(m);
    if det.abs() < EPSILON {
        return IDENTITY;
    }
    for row in &mut out {
        for cell in row {
            *cell /= det;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Matrix, b: &Matrix) -> bool {
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn rotations_and_inverse() {
        let r = multiply(&rotate_matrix(Axis::X, 0.3), &rotate_matrix(Axis::Y, -1.1));
        let t = multiply(&r, &translate_matrix([1.0, -2.0, 3.0]));
        let s = multiply(&scale_matrix([2.0, 2.0, 2.0]), &t);
        assert!(close(&multiply(&s, &invert(&s)), &IDENTITY));
        // A rotation about +Z by 90 degrees takes +X to +Y (row vectors).
        let p = transform_point([1.0, 0.0, 0.0], &rotate_matrix(Axis::Z, PI / 2.0));
        assert!((p[0]).abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15);
        // The axis form agrees with the single-axis form.
        assert!(close(
            &axis_rotate_matrix([0.0, 0.0, 1.0], 0.7),
            &rotate_matrix(Axis::Z, 0.7)
        ));
        assert!(close(&transpose(&transpose(&s)), &s));
    }

    #[test]
    fn canonical_matrices_are_inverse_and_map_up_to_z() {
        let mut up = [1.0, 1.0, -0.5];
        normalize(&mut up);
        let (forward, inverse) = canonical_matrices([-1.0, 0.0, 0.0], up);
        assert!(close(&multiply(&forward, &inverse), &IDENTITY));
        let z = transform_vector(up, &forward);
        assert!(z[0].abs() < 1e-12 && z[1].abs() < 1e-12 && (z[2] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn normalize_leaves_zero_alone() {
        let mut v = [0.0; 3];
        assert_eq!(normalize(&mut v), 0.0);
        assert_eq!(v, [0.0; 3]);
        let mut w = [3.0, 4.0, 0.0];
        assert_eq!(normalize(&mut w), 5.0);
        assert_eq!(w, [0.6, 0.8, 0.0]);
    }
}
