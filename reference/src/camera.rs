//! The pinhole camera in f64, by the tracer's rules (README, "SPD rules as
//! implemented"; the thesis's eq. 1-8).
//!
//! `w = normalize(at - from)` looks forward, `u = normalize(w × up)` right and
//! `v = u × w` up. Samples are square. The NFF angle spans from the centre of the top
//! sample row to the centre of the bottom one, so those rows look at `±tan(angle/2)` and
//! the sample pitch is `2 tan(angle/2) / (rows - 1)`. Sample `(column, row)`, row 0 at the
//! top, looks along `w + pitch (x u + y v)` with `x = column - (columns - 1)/2` and
//! `y = (rows - 1)/2 - row`. Pixel centres are a W×H grid; the SPD's corners a
//! (W+1)×(H+1) grid whose corner rows span the angle, each pixel the mean of its four.

use crate::ray::Ray;
use crate::scene::View;
use glam::DVec3;
use tracer::Sampling;

/// Eye rays through a grid of samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    forward: DVec3,
    /// Right, scaled by the sample pitch.
    right: DVec3,
    /// Up, scaled by the sample pitch.
    up: DVec3,
    columns: u32,
    rows: u32,
}

impl Camera {
    /// The camera for a `width` × `height` image; an error when the view has no
    /// direction or its up vector lies along it (sin² of their angle ≤ 1e-10, the
    /// parser's own limit).
    pub fn new(view: &View, width: u32, height: u32, sampling: Sampling) -> Result<Self, String> {
        let forward = view.at - view.from;
        if !(forward.length_squared() > 0.0) {
            return Err("'from' and 'at' are the same point: the view has no direction".into());
        }
        let side = forward.cross(view.up);
        if !(side.length_squared() > 1e-10 * forward.length_squared() * view.up.length_squared()) {
            return Err("the 'up' vector is parallel to the view direction (or zero)".into());
        }
        let (columns, rows) = match sampling {
            Sampling::PixelCenters => (width, height),
            Sampling::SpdCorners => (width + 1, height + 1),
        };
        let w = forward.normalize();
        let u = w.cross(view.up).normalize();
        let v = u.cross(w);
        let half_span = (view.angle_deg.to_radians() / 2.0).tan();
        let pitch = 2.0 * half_span / f64::from(rows.max(2) - 1);
        Ok(Self {
            eye: view.from,
            forward: w,
            right: pitch * u,
            up: pitch * v,
            columns,
            rows,
        })
    }

    /// The sample grid: (columns, rows).
    pub fn grid(&self) -> (u32, u32) {
        (self.columns, self.rows)
    }

    /// The eye ray through sample `(column, row)`, row 0 at the top.
    pub fn ray(&self, column: u32, row: u32) -> Ray {
        let x = f64::from(column) - f64::from(self.columns - 1) / 2.0;
        let y = f64::from(self.rows - 1) / 2.0 - f64::from(row);
        Ray::toward(self.eye, self.forward + x * self.right + y * self.up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> View {
        View {
            from: DVec3::new(0.0, -5.0, 0.0),
            at: DVec3::ZERO,
            up: DVec3::Z,
            angle_deg: 90.0,
        }
    }

    #[test]
    fn extreme_rows_span_the_nff_angle_and_right_is_forward_cross_up() {
        // 90° over 5 rows: the top row centre looks 45° up; +y × +z = +x is right.
        let cam =
            Camera::new(&view(), 5, 5, Sampling::PixelCenters).unwrap_or_else(|e| panic!("{e}"));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let top = cam.ray(2, 0).dir;
        assert!((top - DVec3::new(0.0, h, h)).length() < 1e-15, "{top}");
        assert_eq!(cam.ray(2, 2).dir, DVec3::Y);
        let right = cam.ray(4, 2).dir;
        assert!((right - DVec3::new(h, h, 0.0)).length() < 1e-15, "{right}");
        // Pitch tan 45° / 2 = 0.5: the sample right of centre looks along (0.5, 1, 0).
        let next = cam.ray(3, 2).dir;
        assert!((next - DVec3::new(0.5, 1.0, 0.0).normalize()).length() < 1e-15);
    }

    #[test]
    fn spd_corners_are_one_more_per_side_and_span_the_angle() {
        let cam =
            Camera::new(&view(), 4, 4, Sampling::SpdCorners).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(cam.grid(), (5, 5));
        let corner = cam.ray(0, 0).dir;
        let s = 1.0 / 3f64.sqrt();
        assert!((corner - DVec3::new(-s, s, s)).length() < 1e-15, "{corner}");
    }

    #[test]
    fn a_view_without_a_basis_is_refused() {
        let mut v = view();
        v.up = DVec3::new(0.0, 3.0, 0.0);
        assert!(Camera::new(&v, 4, 4, Sampling::PixelCenters).is_err());
        let mut v = view();
        v.at = v.from;
        assert!(Camera::new(&v, 4, 4, Sampling::PixelCenters).is_err());
    }
}
