//! The SPD's transform stack (`libtx.c`): a current transform plus saved copies.
//!
//! Each operation pre-multiplies the current matrix (`current = op · current`), so with
//! row vectors the last operation given is the first applied to a point, as in
//! OpenGL-style modelling. The NFF output applies the current transform to the
//! primitives itself (NFF has no transforms): points through the matrix, radii by the
//! X scale factor (which assumes uniform scaling, as the C says).

use crate::vector::{
    Axis, Coord3, EPSILON, IDENTITY, Matrix, multiply, rotate_matrix, scale_matrix,
    translate_matrix,
};

/// `CurrentTx` and `TxStack`.
#[derive(Clone, Debug)]
pub struct TransformStack {
    current: Matrix,
    saved: Vec<Matrix>,
}

impl Default for TransformStack {
    fn default() -> Self {
        Self {
            current: IDENTITY,
            saved: Vec::new(),
        }
    }
}

impl TransformStack {
    /// `lib_tx_active`: whether the current transform differs from the identity.
    pub fn active(&self) -> bool {
        self.current.iter().enumerate().any(|(i, row)| {
            row.iter()
                .enumerate()
                .any(|(j, &cell)| (cell - if i == j { 1.0 } else { 0.0 }).abs() > EPSILON)
        })
    }

    /// `lib_get_current_tx`.
    pub fn current(&self) -> &Matrix {
        &self.current
    }

    /// `lib_tx_push`: saves the current transform.
    pub fn push(&mut self) {
        self.saved.push(self.current);
    }

    /// `lib_tx_pop`: restores the last saved transform. Popping an empty stack leaves
    /// the current transform as it is (the C only complains on stderr).
    pub fn pop(&mut self) {
        if let Some(matrix) = self.saved.pop() {
            self.current = matrix;
        }
    }

    /// `lib_tx_rotate`: rotation about `axis` by `angle` radians.
    pub fn rotate(&mut self, axis: Axis, angle: f64) {
        self.current = multiply(&rotate_matrix(axis, angle), &self.current);
    }

    /// `lib_tx_scale`.
    pub fn scale(&mut self, factors: Coord3) {
        self.current = multiply(&scale_matrix(factors), &self.current);
    }

    /// `lib_tx_translate`.
    pub fn translate(&mut self, offset: Coord3) {
        self.current = multiply(&translate_matrix(offset), &self.current);
    }

    /// `trans[U_SCALEX]` of `lib_tx_unwind` on the current transform: the length of the
    /// first row of the upper 3×3 after dividing by the homogeneous entry. (The C
    /// gives up on a singular matrix and leaves the value undefined; the length is
    /// still the natural answer there, and no SPD program builds one.)
    pub fn scale_x(&self) -> f64 {
        let m = &self.current;
        let w = if m[3][3] != 0.0 { m[3][3] } else { 1.0 };
        let row = [m[0][0] / w, m[0][1] / w, m[0][2] / w];
        (row[0] * row[0] + row[1] * row[1] + row[2] * row[2]).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vector::transform_point;

    #[test]
    fn last_operation_applies_first() {
        let mut tx = TransformStack::default();
        assert!(!tx.active());
        tx.push();
        tx.translate([1.0, 0.0, 0.0]);
        tx.scale([2.0, 2.0, 2.0]);
        assert!(tx.active());
        // Scale first, then translate.
        assert_eq!(
            transform_point([1.0, 1.0, 1.0], tx.current()),
            [3.0, 2.0, 2.0]
        );
        assert_eq!(tx.scale_x(), 2.0);
        tx.pop();
        assert!(!tx.active());
        // Extra pops are harmless.
        tx.pop();
        assert!(!tx.active());
    }

    #[test]
    fn rotation_keeps_scale() {
        let mut tx = TransformStack::default();
        tx.rotate(Axis::X, 0.5);
        tx.scale([0.75, 0.75, 0.75]);
        assert!((tx.scale_x() - 0.75).abs() < 1e-15);
    }
}
