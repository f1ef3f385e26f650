//! Cameras: eye rays from an NFF view.
//!
//! Perspective camera after the thesis's eq. 1-8: `w = normalize(at - from)`,
//! `u = normalize(w × up)` (right), `v = u × w` (up), square samples, image rows
//! from top to bottom. The sample pitch follows the NFF angle convention: the angle
//! spans from the centre of the top sample row to the centre of the bottom one, so
//! the extreme rows sit at ±tan(angle/2) and the pitch is `2 tan(angle/2) / (rows - 1)`.
//! With [`Sampling::PixelCenters`] the samples are the W×H pixel centres; with
//! [`Sampling::SpdCorners`] they are the (W+1)×(H+1) pixel corners of the SPD
//! procedure, and the corner rows span the angle.
//!
//! Two variants change the projection ([`Projection`]): `ortho` moves the origin over
//! the sample grid and keeps one direction for every ray (thesis 8.3.2: no per-ray
//! normalization); `bounded` walks the screen row by row, the row's base direction
//! `forward + y·up` computed once per row, so an eye ray costs one `scale`, one `add`
//! and one `normalize`, and its tests use the scene's precomputed eye offsets. The
//! perspective ray sums in the same order, so both give the same bits.

use crate::counter::{Counter, Stat};
use crate::nff::check_view_basis;
use crate::ray::Ray;
use crate::scene::View;
use crate::vec3::Vec3;
use glam::Vec4;

/// Where eye rays are shot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Sampling {
    /// One ray through each pixel centre (thesis).
    #[default]
    PixelCenters,
    /// One ray through each pixel corner, each pixel the mean of its four (SPD).
    SpdCorners,
}

impl Sampling {
    /// The sample grid (columns, rows) of a `width` × `height` image.
    pub fn grid(self, width: u32, height: u32) -> (u32, u32) {
        match self {
            Sampling::PixelCenters => (width, height),
            Sampling::SpdCorners => (width + 1, height + 1),
        }
    }
}

/// How eye rays leave the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Projection {
    /// Pinhole perspective from the NFF view (baseline).
    #[default]
    Perspective,
    /// Parallel rays along the view direction from a grid of origins (variant `ortho`).
    /// The grid covers what the perspective view shows at the look-at distance.
    Orthographic,
    /// Perspective walked row by row from a scene with eye offsets (variant `bounded`,
    /// see [`crate::variants::eye_space`]).
    EyeRows,
}

/// A camera: eye rays for every sample of the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    projection: Projection,
    eye: Vec3,
    forward: Vec3,
    /// Right vector scaled by the sample pitch.
    right: Vec3,
    /// Up vector scaled by the sample pitch.
    up: Vec3,
    columns: u32,
    rows: u32,
}

impl Camera {
    /// A perspective camera (see [`Camera::new`]).
    pub fn perspective<C: Counter>(
        view: &View,
        width: u32,
        height: u32,
        sampling: Sampling,
        c: &mut C,
    ) -> Result<Self, String> {
        Self::new(
            view,
            width,
            height,
            sampling,
            Projection::Perspective,
            None,
            c,
        )
    }

    /// Sets up the camera for a `width` × `height` image (counts one
    /// `calls.primary_ray_setup`). Fails when the view defines no basis. `ortho_focus`
    /// is the distance at which the orthographic grid spans what the perspective view
    /// spans (default `|at - from|`).
    pub fn new<C: Counter>(
        view: &View,
        width: u32,
        height: u32,
        sampling: Sampling,
        projection: Projection,
        ortho_focus: Option<f32>,
        c: &mut C,
    ) -> Result<Self, String> {
        check_view_basis(view)?;
        c.tally(Stat::PrimaryRaySetup);
        let (columns, rows) = sampling.grid(width, height);
        let view_dir = c.sub(view.at, view.from);
        let w = c.normalize(view_dir);
        let side = c.cross(w, view.up);
        let u = c.normalize(side);
        let v = c.cross(u, w);
        let half_span = (view.angle_deg.to_radians() * 0.5).tan();
        let mut pitch = 2.0 * half_span / (rows.max(2) - 1) as f32;
        if projection == Projection::Orthographic {
            // The grid spans, at the look-at distance, what the perspective view spans.
            pitch *= match ortho_focus {
                Some(focus) if focus > 0.0 && focus.is_finite() => focus,
                _ => {
                    let focus_sq = c.dot(view_dir, view_dir);
                    c.sqrt(focus_sq)
                }
            };
        }
        Ok(Self {
            projection,
            eye: view.from,
            forward: w,
            right: c.scale(u, pitch),
            up: c.scale(v, pitch),
            columns,
            rows,
        })
    }

    /// The sample grid: (columns, rows).
    pub fn grid(&self) -> (u32, u32) {
        (self.columns, self.rows)
    }

    /// The projection in use.
    pub fn projection(&self) -> Projection {
        self.projection
    }

    /// Grid coordinates of sample `(column, row)` relative to the centre, y up.
    #[inline(always)]
    fn offsets(&self, column: u32, row: u32) -> (f32, f32) {
        let x = column as f32 - (self.columns - 1) as f32 * 0.5;
        let y = (self.rows - 1) as f32 * 0.5 - row as f32;
        (x, y)
    }

    /// The eye ray through sample `(column, row)`, row 0 at the top. Perspective:
    /// two `scale`, two `add`, one `normalize`; orthographic: two `scale`, two `add`
    /// (the origin moves, the direction is fixed); camera space: use
    /// [`Camera::ray_from_eye`].
    #[inline]
    pub fn ray<C: Counter>(&self, column: u32, row: u32, c: &mut C) -> Ray {
        let (x, y) = self.offsets(column, row);
        let across = c.scale(self.right, x);
        let down = c.scale(self.up, y);
        match self.projection {
            Projection::Orthographic => {
                let origin = c.add(self.eye, across);
                Ray {
                    origin: c.add(origin, down),
                    dir: self.forward,
                }
            }
            Projection::Perspective | Projection::EyeRows => {
                let dir = c.add(self.forward, down);
                let dir = c.add(dir, across);
                Ray {
                    origin: self.eye,
                    dir: c.normalize(dir),
                }
            }
        }
    }

    /// The eye rays through samples `columns` of row `row` (at most `N`; the lanes
    /// beyond are unused), each [`Camera::ray`]'s bit for bit and counted as it counts,
    /// ray `i` on `counters[i]`. Computed across the rays, lane by lane, so that the
    /// square roots and divisions of the normalizations go four to an instruction
    /// (one after another they were most of the camera's share of the packet loop;
    /// lanes: 1.5 % fewer instructions in a tetra render, 2 % less time).
    #[inline]
    pub fn packet<C: Counter, const N: usize>(
        &self,
        columns: &[u32],
        row: u32,
        counters: &mut [C],
    ) -> [Ray; N] {
        if self.projection == Projection::Orthographic {
            return std::array::from_fn(|i| match (columns.get(i), counters.get_mut(i)) {
                (Some(&column), Some(c)) => self.ray(column, row, c),
                _ => Ray {
                    origin: self.eye,
                    dir: self.forward,
                },
            });
        }
        let (_, y) = self.offsets(0, row);
        // `forward + y·up`, the sum `ray` forms first: the same for the whole row.
        let base = Vec3(self.forward.0 + self.up.0 * y);
        for c in counters.iter_mut().take(columns.len().min(N)) {
            c.tally_n(Stat::Scale, 2);
            c.tally_n(Stat::Add, 2);
            c.tally(Stat::Normalize);
        }
        self.directions::<C, N>(columns, base).map(|dir| Ray {
            origin: self.eye,
            dir,
        })
    }

    /// [`Camera::packet`] for the bounded walk: [`Camera::ray_from_eye`] of each column
    /// of the row whose base direction is `row_base`, counted as it counts.
    #[inline]
    pub fn packet_from_eye<C: Counter, const N: usize>(
        &self,
        columns: &[u32],
        row_base: Vec3,
        counters: &mut [C],
    ) -> [Ray<true>; N] {
        for c in counters.iter_mut().take(columns.len().min(N)) {
            c.tally(Stat::Scale);
            c.tally(Stat::Add);
            c.tally(Stat::Normalize);
        }
        self.directions::<C, N>(columns, row_base).map(|dir| Ray {
            origin: self.eye,
            dir,
        })
    }

    /// The normalized directions `row_base + x·right` of `columns`, four lanes at a
    /// time: the operations of `scale`, `add` and `normalize` (glam's dot sums
    /// `(x² + y²) + z²`) in their order, so the same floats.
    #[inline(always)]
    fn directions<C: Counter, const N: usize>(&self, columns: &[u32], row_base: Vec3) -> [Vec3; N] {
        let centre = (self.columns - 1) as f32 * 0.5;
        let mut x = [0.0f32; N];
        for (x, &column) in x.iter_mut().zip(columns) {
            *x = column as f32 - centre;
        }
        let (base, right) = (row_base.to_array(), self.right.to_array());
        let mut out = [Vec3::ZERO; N];
        for (x, out) in x.chunks_exact(4).zip(out.chunks_exact_mut(4)) {
            let x = Vec4::from_slice(x);
            let d = [0, 1, 2].map(|axis| Vec4::splat(base[axis]) + Vec4::splat(right[axis]) * x);
            let length_sq = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
            let inv = Vec4::ONE / C::sqrt_kernel4(length_sq);
            let [x, y, z] = d.map(|d| (d * inv).to_array());
            for (i, out) in out.iter_mut().enumerate() {
                *out = Vec3::new(x[i], y[i], z[i]);
            }
        }
        let done = N / 4 * 4;
        for i in done..N {
            let d = Vec3(row_base.0 + self.right.0 * x[i]);
            // Counted by the caller: a counter of its own, dropped.
            out[i] = C::default().normalize(d);
        }
        out
    }

    /// The base direction of sample row `row`, `forward + y·up` (one `scale`, one
    /// `add`), for [`Camera::ray_from_eye`].
    #[inline]
    pub fn row_base<C: Counter>(&self, row: u32, c: &mut C) -> Vec3 {
        let (_, y) = self.offsets(0, row);
        let down = c.scale(self.up, y);
        c.add(self.forward, down)
    }

    /// The eye ray through sample `column` of the row whose base direction is
    /// `row_base`: one `scale`, one `add`, one `normalize`. Bit for bit the
    /// perspective ray of that sample.
    #[inline]
    pub fn ray_from_eye<C: Counter>(&self, column: u32, row_base: Vec3, c: &mut C) -> Ray<true> {
        let (x, _) = self.offsets(column, 0);
        let across = c.scale(self.right, x);
        let dir = c.add(row_base, across);
        Ray {
            origin: self.eye,
            dir: c.normalize(dir),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, NoCount};

    fn view(width: u32, height: u32) -> View {
        View {
            from: Vec3::new(0.0, -5.0, 0.0),
            at: Vec3::ZERO,
            up: Vec3::new(0.0, 0.0, 1.0),
            angle_deg: 90.0,
            hither: 0.0,
            width,
            height,
        }
    }

    #[test]
    fn extreme_sample_rows_span_the_nff_angle() {
        // 90°: the top row centre looks 45° up, the bottom row 45° down.
        let cam = Camera::perspective(&view(5, 5), 5, 5, Sampling::PixelCenters, &mut NoCount)
            .unwrap_or_else(|e| panic!("{e}"));
        let top = cam.ray(2, 0, &mut NoCount).dir.to_array();
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert!(
            (top[1] - h).abs() < 1e-6 && (top[2] - h).abs() < 1e-6,
            "{top:?}"
        );
        let centre = cam.ray(2, 2, &mut NoCount).dir.to_array();
        assert_eq!(centre, [0.0, 1.0, 0.0]);
        // Right is view direction × up = +y × +z = +x.
        let right = cam.ray(4, 2, &mut NoCount).dir.to_array();
        assert!(
            (right[0] - h).abs() < 1e-6 && right[2].abs() < 1e-6,
            "{right:?}"
        );
    }

    #[test]
    fn spd_corners_are_one_more_per_side_and_span_the_angle() {
        let cam = Camera::perspective(&view(4, 4), 4, 4, Sampling::SpdCorners, &mut NoCount)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(cam.grid(), (5, 5));
        let corner = cam.ray(0, 0, &mut NoCount).dir.to_array();
        // Top-left corner: (-1, 1, 1)/sqrt3 in (x, z, y) terms.
        let s = 1.0 / 3f32.sqrt();
        assert!(
            (corner[0] + s).abs() < 1e-6
                && (corner[1] - s).abs() < 1e-6
                && (corner[2] - s).abs() < 1e-6
        );
    }

    #[test]
    fn counts_one_setup_and_fixed_ops_per_ray() {
        let mut c = Count::default();
        let cam = Camera::perspective(&view(8, 8), 8, 8, Sampling::PixelCenters, &mut c)
            .unwrap_or_else(|e| panic!("{e}"));
        let setup = c;
        cam.ray(3, 4, &mut c);
        assert_eq!(setup.get(Stat::PrimaryRaySetup), 1);
        assert_eq!(c.get(Stat::Scale) - setup.get(Stat::Scale), 2);
        assert_eq!(c.get(Stat::Add) - setup.get(Stat::Add), 2);
        assert_eq!(c.get(Stat::Normalize) - setup.get(Stat::Normalize), 1);
    }

    #[test]
    fn orthographic_rays_are_parallel_and_never_normalized() {
        let v = view(9, 9);
        let mut c = Count::default();
        let cam = Camera::new(
            &v,
            9,
            9,
            Sampling::PixelCenters,
            Projection::Orthographic,
            None,
            &mut c,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let setup = c;
        let corner = cam.ray(0, 0, &mut c);
        let centre = cam.ray(4, 4, &mut c);
        assert_eq!(c.get(Stat::Normalize), setup.get(Stat::Normalize));
        assert_eq!(corner.dir, centre.dir);
        assert_eq!(centre.origin.to_array(), [0.0, -5.0, 0.0]);
        // 90° at look-at distance 5: the extreme sample rows sit at ±5.
        let o = corner.origin.to_array();
        assert!(
            (o[0] + 5.0).abs() < 1e-5 && (o[2] - 5.0).abs() < 1e-5,
            "{o:?}"
        );
    }

    #[test]
    fn row_walk_gives_the_perspective_rays_bit_for_bit_with_fewer_ops() {
        let v = view(7, 5);
        let cam = Camera::new(
            &v,
            7,
            5,
            Sampling::PixelCenters,
            Projection::EyeRows,
            None,
            &mut NoCount,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let mut c = Count::default();
        for row in 0..5 {
            let base = cam.row_base(row, &mut c);
            for column in 0..7 {
                let walked = cam.ray_from_eye(column, base, &mut c);
                let plain = cam.ray(column, row, &mut NoCount);
                assert_eq!(walked.plain(), plain);
            }
        }
        // Per row one scale + one add; per ray one scale, one add, one normalize.
        assert_eq!(c.get(Stat::Scale), 5 + 35);
        assert_eq!(c.get(Stat::Add), 5 + 35);
        assert_eq!(c.get(Stat::Normalize), 35);
    }

    #[test]
    fn packets_of_eye_rays_are_each_rays_own_bit_for_bit_and_counted_alike() {
        let v = view(37, 11);
        for projection in [
            Projection::Perspective,
            Projection::Orthographic,
            Projection::EyeRows,
        ] {
            let cam = Camera::new(
                &v,
                37,
                11,
                Sampling::SpdCorners,
                projection,
                None,
                &mut NoCount,
            )
            .unwrap_or_else(|e| panic!("{e}"));
            let (columns, rows) = cam.grid();
            for row in 0..rows {
                let all: Vec<u32> = (0..columns).collect();
                for chunk in all.chunks(8) {
                    let mut lanes = [Count::default(); 8];
                    let packet: [Ray; 8] = cam.packet(chunk, row, &mut lanes);
                    let base = cam.row_base(row, &mut NoCount);
                    let from_eye: [Ray<true>; 8] =
                        cam.packet_from_eye(chunk, base, &mut [Count::default(); 8]);
                    for (i, &column) in chunk.iter().enumerate() {
                        let mut alone = Count::default();
                        let ray = cam.ray(column, row, &mut alone);
                        let bits = |r: Ray| r.dir.to_array().map(f32::to_bits);
                        assert_eq!(bits(packet[i]), bits(ray), "{projection:?} {column} {row}");
                        assert_eq!(packet[i].origin, ray.origin);
                        assert_eq!(lanes[i], alone);
                        if projection != Projection::Orthographic {
                            assert_eq!(bits(from_eye[i].plain()), bits(ray));
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn up_parallel_to_view_is_refused() {
        let mut v = view(8, 8);
        v.up = Vec3::new(0.0, 3.0, 0.0);
        assert!(Camera::perspective(&v, 8, 8, Sampling::PixelCenters, &mut NoCount).is_err());
    }
}
