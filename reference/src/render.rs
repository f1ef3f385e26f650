//! The reference render: every sample in f64, rows in parallel (rayon) when called
//! inside a pool, else one after another on the calling thread; each sample depends on
//! nothing but its ray, so the image is the same for any thread count. Each row first
//! reads a stop flag ([`render_until`]), as the tracer's renderer does.

use crate::camera::Camera;
use crate::error::ReferenceError;
use crate::scene::RefScene;
use crate::shading::{Color, Shader, Walk};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use tracer::{Frame, RenderOptions, Rgb, Sampling, Scene};

/// Renders `scene` as `options` ask (size, sampling, shading mode, depth; limits checked
/// first), converting it to f64 first. `progress` hears 1 after each sample row.
pub fn render(
    scene: &Scene,
    options: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Frame, ReferenceError> {
    render_converted(&RefScene::new(scene), options, progress)
}

/// [`render`] of a scene already converted (to time the conversion apart).
pub fn render_converted(
    scene: &RefScene,
    options: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Frame, ReferenceError> {
    render_walking(scene, options, Walk::Bvh, progress)
}

/// [`render_converted`] that stops when `stop` is set (read before each sample row):
/// it then returns [`ReferenceError::Cancelled`], never a partial frame.
pub fn render_until(
    scene: &RefScene,
    options: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Result<Frame, ReferenceError> {
    render_walking_until(scene, options, Walk::Bvh, progress, stop)
}

/// [`render_converted`] with the queries walking as `walk` says (the picture is the
/// same either way; the brute-force walk is the definition tests hold the BVH to).
pub fn render_walking(
    scene: &RefScene,
    options: &RenderOptions,
    walk: Walk,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Frame, ReferenceError> {
    render_walking_until(scene, options, walk, progress, &tracer::NEVER_STOP)
}

/// [`render_walking`] that stops when `stop` is set.
fn render_walking_until(
    scene: &RefScene,
    options: &RenderOptions,
    walk: Walk,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Result<Frame, ReferenceError> {
    let limits = &options.limits;
    limits
        .check_size(u64::from(options.width), u64::from(options.height))
        .map_err(ReferenceError::Limits)?;
    limits
        .check_ray_depth(options.max_depth)
        .map_err(ReferenceError::Limits)?;
    let camera = Camera::new(&scene.view, options.width, options.height, options.sampling)
        .map_err(ReferenceError::Camera)?;
    let shader = Shader::new(scene, options.mode, options.max_depth, walk);
    let (columns, rows) = camera.grid();
    let trace_row = |row: u32| {
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let samples: Vec<Color> = (0..columns)
            .map(|column| shader.primary(&camera.ray(column, row)))
            .collect();
        progress(1);
        Some(samples)
    };
    let traced: Option<Vec<Vec<Color>>> = if rayon::current_thread_index().is_some() {
        (0..rows).into_par_iter().map(trace_row).collect()
    } else {
        (0..rows).map(trace_row).collect()
    };
    let traced = traced.ok_or(ReferenceError::Cancelled)?;
    let samples: Vec<Color> = traced.into_iter().flatten().collect();
    let pixels = match options.sampling {
        Sampling::PixelCenters => samples,
        Sampling::SpdCorners => corner_means(&samples, options.width, options.height),
    };
    Ok(Frame {
        width: options.width,
        height: options.height,
        pixels: pixels.into_iter().map(to_rgb).collect(),
    })
}

/// Each pixel the mean of its four corner samples, from a (W+1)×(H+1) grid.
fn corner_means(samples: &[Color], width: u32, height: u32) -> Vec<Color> {
    let stride = width as usize + 1;
    let at = |x: usize, y: usize| samples.get(y * stride + x).copied().unwrap_or(DVec3::NAN);
    (0..height as usize)
        .flat_map(|y| (0..width as usize).map(move |x| (x, y)))
        .map(|(x, y)| (at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1)) / 4.0)
        .collect()
}

/// The f32 pixel nearest to an f64 colour.
fn to_rgb(c: Color) -> Rgb {
    Rgb::new(c.x as f32, c.y as f32, c.z as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_mean_is_the_mean_of_four() {
        // A 2x1 image from a 3x2 corner grid.
        let s: Vec<Color> = [0.0, 4.0, 8.0, 4.0, 8.0, 12.0]
            .iter()
            .map(|&v| DVec3::splat(v))
            .collect();
        assert_eq!(
            corner_means(&s, 2, 1),
            vec![DVec3::splat(4.0), DVec3::splat(8.0)]
        );
    }
}
