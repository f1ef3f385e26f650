//! The SPD outputs that NFF cannot express as curves and that the library therefore
//! tessellates even with `-c` (`libply.c`): the torus into smooth triangles (`pp 3`),
//! the disc into polygons, the height field into triangles.
//!
//! Angles step by accumulation (`u += delta_u`) as in the C, so the last vertices carry
//! the same round-off as the C's.

use crate::output::Output;
use crate::vector::{
    Coord3, EPSILON2, Matrix, PI, canonical_matrices, cross, normalize, transform_point,
    transform_vector,
};

/// `torus_evaluator`: the point at (`theta` around the tube, `phi` around the axis) of
/// a torus with major radius `r0` and minor radius `r1` about +Z, and its normal, both
/// taken through `trans`.
fn torus_point(trans: &Matrix, theta: f64, phi: f64, r0: f64, r1: f64) -> (Coord3, Coord3) {
    let vert = [
        (r0 + r1 * theta.sin()) * phi.cos(),
        (r0 + r1 * theta.sin()) * phi.sin(),
        r1 * theta.cos(),
    ];
    let v0 = [
        r1 * theta.cos() * phi.cos(),
        r1 * theta.cos() * phi.sin(),
        -r1 * theta.sin(),
    ];
    let v1 = [
        -(r0 + r1 * theta.sin()) * phi.sin(),
        (r0 + r1 * theta.sin()) * phi.cos(),
        0.0,
    ];
    let mut norm = cross(v0, v1);
    normalize(&mut norm);
    (transform_point(vert, trans), transform_vector(norm, trans))
}

/// `disc_evaluator`: the point at angle `theta`, radius `r + v`, through `trans`.
fn disc_point(trans: &Matrix, theta: f64, v: f64, r: f64) -> Coord3 {
    let vert = [(r + v) * theta.cos(), (r + v) * theta.sin(), 0.0];
    transform_point(vert, trans)
}

impl Output {
    /// `lib_output_torus` → `lib_output_polygon_torus`: `(4u)·(4v)` cells of two
    /// smooth triangles each. A zero `normal` writes nothing (the C exits).
    pub fn torus(&mut self, center: Coord3, normal: Coord3, iradius: f64, oradius: f64) {
        let mut normal = normal;
        if normalize(&mut normal) < EPSILON2 {
            return;
        }
        let (u_res, v_res) = self.resolution();
        let (_, imx) = canonical_matrices(center, normal);
        let delta_u = 2.0 * PI / f64::from(4 * u_res);
        let delta_v = 2.0 * PI / f64::from(4 * v_res);
        let mut vert = [[0.0; 3]; 3];
        let mut norm = [[0.0; 3]; 3];
        let mut u = 0.0;
        for _ in 0..4 * u_res {
            let mut v = 0.0;
            for _ in 0..4 * v_res {
                (vert[2], norm[2]) = torus_point(&imx, u, v, iradius, oradius);
                (vert[1], norm[1]) = torus_point(&imx, u, v + delta_v, iradius, oradius);
                (vert[0], norm[0]) = torus_point(&imx, u + delta_u, v + delta_v, iradius, oradius);
                self.patch_triangle(&vert, &norm);
                vert[1] = vert[0];
                norm[1] = norm[0];
                (vert[0], norm[0]) = torus_point(&imx, u + delta_u, v, iradius, oradius);
                self.patch_triangle(&vert, &norm);
                v += delta_v;
            }
            u += delta_u;
        }
    }

    /// `lib_output_disc` → `lib_output_polygon_disc`: `4u` quadrilaterals from the
    /// inner to the outer radius (triangles when the inner radius is 0: the polygon
    /// output drops the repeated centre). A zero `normal` writes nothing (the C exits).
    pub fn disc(&mut self, center: Coord3, normal: Coord3, iradius: f64, oradius: f64) {
        let mut norm = normal;
        if normalize(&mut norm) < EPSILON2 {
            return;
        }
        let (u_res, _) = self.resolution();
        let (_, imx) = canonical_matrices(center, norm);
        let delta_u = 2.0 * PI / f64::from(4 * u_res);
        let mut u = 0.0;
        for _ in 0..4 * u_res {
            let v = 0.0;
            let delta_v = oradius - iradius;
            let vert = [
                disc_point(&imx, u, v + delta_v, iradius),
                disc_point(&imx, u + delta_u, v + delta_v, iradius),
                disc_point(&imx, u + delta_u, v, iradius),
                disc_point(&imx, u, v, iradius),
            ];
            self.polygon(&vert);
            u += delta_u;
        }
    }

    /// `lib_output_height` → `lib_output_polygon_height`: a `width` × `height` grid of
    /// heights (`data[row][column]`, f32 as in the C) over x0..x1 (columns) and z0..z1
    /// (rows), written as two triangles per cell, y = y0 + height. Grids under 2×2 (or
    /// ragged rows) write nothing.
    pub fn height_field(&mut self, data: &[Vec<f32>], x0: f64, x1: f64, y0: f64, z0: f64, z1: f64) {
        let height = data.len();
        let width = data.first().map_or(0, Vec::len);
        if height < 2 || width < 2 || data.iter().any(|row| row.len() != width) {
            return;
        }
        let xdelta = (x1 - x0) / (width - 1) as f64;
        let zdelta = (z1 - z0) / (height - 1) as f64;
        let x = |j: usize| x0 + j as f64 * xdelta;
        let z = |i: usize| z0 + i as f64 * zdelta;
        let y = |i: usize, j: usize| y0 + f64::from(data[i][j]);
        for i in 0..height - 1 {
            for j in 0..width - 1 {
                let mut verts = [
                    [x(j), y(i, j), z(i)],
                    [x(j + 1), y(i + 1, j + 1), z(i + 1)],
                    [x(j + 1), y(i, j + 1), z(i)],
                ];
                self.polygon(&verts);
                verts[2] = verts[1];
                verts[1] = [x(j), y(i + 1, j), z(i + 1)];
                self.polygon(&verts);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn torus_cells_and_normals() {
        let mut out = Output::with_capacity(0);
        out.set_polygonalization(2, 1);
        out.torus([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 2.0, 0.5);
        let (text, counts) = out.finish();
        assert_eq!(counts.patches, 8 * 4 * 2);
        // First vertex: theta = 0, phi = pi/2 (v + delta_v), on the top of the tube.
        let first = text.lines().nth(2).unwrap_or("");
        let numbers: Vec<f64> = first.split(' ').filter_map(|t| t.parse().ok()).collect();
        assert_eq!(numbers.len(), 6, "{first}");
        assert!(
            (numbers[2] - 0.5).abs() < 1e-6 && (numbers[5] - 1.0).abs() < 1e-6,
            "{first}"
        );
        // Zero normal: nothing.
        let mut out = Output::with_capacity(0);
        out.torus([0.0; 3], [0.0; 3], 2.0, 0.5);
        assert_eq!(out.finish().1.total(), 0);
    }

    #[test]
    fn disc_with_no_hole_is_triangles() {
        let mut out = Output::with_capacity(0);
        out.set_polygonalization(4, 1);
        out.disc([0.0, -2.0, 0.0], [0.0, 1.0, 0.0], 0.0, 4.0);
        let (text, counts) = out.finish();
        assert_eq!(counts.polygons, 16);
        assert_eq!(text.matches("p 3\n").count(), 16);
    }

    #[test]
    fn height_field_two_triangles_per_cell() {
        let data = vec![vec![0.0f32, 1.0, 2.0], vec![0.5, 0.5, 0.5]];
        let mut out = Output::with_capacity(0);
        out.height_field(&data, -1.0, 1.0, 0.0, -1.0, 1.0);
        let (text, counts) = out.finish();
        assert_eq!(counts.polygons, 4);
        assert!(
            text.starts_with("p 3\n-1 0 -1\n0 0.5 1\n0 1 -1\np 3\n-1 0 -1\n-1 0.5 1\n0 0.5 1\n"),
            "{text}"
        );
        let mut out = Output::with_capacity(0);
        out.height_field(&[vec![1.0]], -1.0, 1.0, 0.0, -1.0, 1.0);
        out.height_field(&[vec![1.0, 2.0], vec![1.0]], -1.0, 1.0, 0.0, -1.0, 1.0);
        assert_eq!(out.finish().1.total(), 0);
    }
}
