//! The renderer: eye rays in parallel over sample rows (rayon), per-row counters summed
//! in row order after the loop, so counts and images are identical for any thread count.

use crate::accel::Intersector;
use crate::camera::{Camera, Sampling};
use crate::color::Rgb;
use crate::counter::{Counter, Counts, RayCounts};
use crate::nff::Limits;
use crate::scene::Scene;
use crate::shading::{Shader, ShadingMode};
use rayon::prelude::*;

/// What to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    pub sampling: Sampling,
    pub mode: ShadingMode,
}

impl RenderOptions {
    /// Options at the scene's own resolution, pixel-centre sampling, colour.
    pub fn for_scene(scene: &Scene) -> Self {
        Self {
            width: scene.view.width,
            height: scene.view.height,
            sampling: Sampling::PixelCenters,
            mode: ShadingMode::Color,
        }
    }

    /// Number of sample rows the render walks (the progress total).
    pub fn sample_rows(&self) -> u64 {
        match self.sampling {
            Sampling::PixelCenters => u64::from(self.height),
            Sampling::SpdCorners => u64::from(self.height) + 1,
        }
    }
}

/// Why a render could not start.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RenderError {
    #[error("invalid camera: {0}")]
    Camera(String),
    #[error("{0}")]
    Size(String),
}

/// A floating-point framebuffer, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Rgb>,
}

impl Frame {
    /// The pixels as interleaved 8-bit RGB.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.to_rgb8()).collect()
    }

    /// Whether every channel of every pixel is finite.
    pub fn is_finite(&self) -> bool {
        self.pixels.iter().all(|p| p.is_finite())
    }
}

/// A finished render: the image, the operation counter and the ray counts.
#[derive(Clone, Debug)]
pub struct Rendered<C> {
    pub frame: Frame,
    pub counter: C,
    pub rays: RayCounts,
}

impl<C: Counter> Rendered<C> {
    /// Every count, or `None` for an uncounted render.
    pub fn counts(&self) -> Option<Counts> {
        self.counter
            .totals()
            .map(|t| Counts::from_parts(&t, self.rays))
    }
}

/// Renders `scene` with `accel` in the current rayon pool. `progress` is called with 1
/// after each finished sample row (from worker threads).
pub fn render<C: Counter, I: Intersector>(
    scene: &Scene,
    accel: &I,
    options: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Rendered<C>, RenderError> {
    Limits::default()
        .check_size(u64::from(options.width), u64::from(options.height))
        .map_err(RenderError::Size)?;
    let mut counter = C::default();
    let camera = Camera::perspective(
        &scene.view,
        options.width,
        options.height,
        options.sampling,
        &mut counter,
    )
    .map_err(RenderError::Camera)?;
    let shader = Shader::new(scene, accel, options.mode);
    let (columns, rows) = camera.grid();

    let traced: Vec<(Vec<Rgb>, C, RayCounts)> = (0..rows)
        .into_par_iter()
        .map(|row| {
            let mut c = C::default();
            let mut rays = RayCounts::default();
            let samples = (0..columns)
                .map(|column| {
                    let ray = camera.ray(column, row, &mut c);
                    shader.primary(&ray, &mut c, &mut rays)
                })
                .collect();
            progress(1);
            (samples, c, rays)
        })
        .collect();

    let mut ray_counts = RayCounts::default();
    let mut samples = Vec::with_capacity(columns as usize * rows as usize);
    for (row, c, rays) in traced {
        counter.merge(&c);
        ray_counts.merge(&rays);
        samples.extend(row);
    }
    let pixels = match options.sampling {
        Sampling::PixelCenters => samples,
        Sampling::SpdCorners => average_corners(&samples, options.width, options.height),
    };
    Ok(Rendered {
        frame: Frame {
            width: options.width,
            height: options.height,
            pixels,
        },
        counter,
        rays: ray_counts,
    })
}

/// Each pixel the mean of its four corner samples ((W+1)×(H+1) grid).
fn average_corners(samples: &[Rgb], width: u32, height: u32) -> Vec<Rgb> {
    let stride = width as usize + 1;
    let at = |x: usize, y: usize| samples[y * stride + x];
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height as usize {
        for x in 0..width as usize {
            let sum = at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1);
            pixels.push(sum * 0.25);
        }
    }
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_average_is_the_mean_of_four() {
        // 2x1 image from a 3x2 corner grid.
        let s: Vec<Rgb> = [0.0, 4.0, 8.0, 4.0, 8.0, 12.0]
            .iter()
            .map(|&v| Rgb::gray(v))
            .collect();
        let p = average_corners(&s, 2, 1);
        assert_eq!(p, vec![Rgb::gray(4.0), Rgb::gray(8.0)]);
    }
}
