//! The renderer: eye rays in parallel over sample rows (rayon), per-row counters summed
//! in row order after the loop, so counts and images are identical for any thread count.
//! Phases: each row is a `sample row` (a worker's root), eye-ray generation (and the
//! camera's set-up) `camera ray`, the framebuffer work after the loop `pixel fill`;
//! the shader and the intersectors mark the rest.
//!
//! With `checkerboard` (variant `pixel-avg`, thesis 8.3.5) only the samples with an even
//! `column + row` are traced; each other sample is the mean of its traced 4-neighbours
//! (two to four of them). The thesis's formula for the untraced pixel,
//! `(colour above - colour below) / 2`, is a difference, which is near zero (black)
//! wherever the picture is smooth; we read it as the neighbours' mean it describes in
//! words, and use all traced 4-neighbours rather than only the two vertical ones.
//!
//! A render can be stopped ([`render_until`]): each sample row first reads a stop flag
//! (one relaxed atomic load a row, nothing measurable beside a row's rays) and, once it
//! is set, the rows not yet started are skipped and the render returns
//! [`RenderError::Cancelled`] instead of a partial frame.

use crate::accel::{BvhBuilder, Intersector, PACKET};
use crate::camera::{Camera, Projection, Sampling};
use crate::color::Rgb;
use crate::counter::{Counter, Counts, Phase, RayCounts};
use crate::huge_pages;
use crate::nff::Limits;
use crate::pixel_stats::{SampleRows, SampleStats};
use crate::ray::Ray;
use crate::scene::Scene;
use crate::shading::{MAX_DEPTH, RayLog, Shader, ShadingMode};
use crate::variants::diffuse::DiffuseForm;
use crate::vec3::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The stop flag of a render nobody can stop ([`render`], [`crate::render_variant`]).
pub static NEVER_STOP: AtomicBool = AtomicBool::new(false);

/// What to render: the choices of whoever asks for the picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    pub sampling: Sampling,
    pub mode: ShadingMode,
    /// Maximum ray-tree depth, the eye ray being depth 1 (default [`MAX_DEPTH`], the
    /// SPD's 5); at most `limits.max_ray_depth`.
    pub max_depth: u32,
    /// Image size and depth limits checked before anything is allocated.
    pub limits: Limits,
    /// Record each sample's counts, rays, depth and time ([`Rendered::samples`], for
    /// the per-pixel maps). Costs a clock read and, when counting, a counter merge per
    /// sample.
    pub per_sample: bool,
    /// How the `bvh` variant builds its tree (default the binned SAH).
    pub bvh_builder: BvhBuilder,
}

/// How the renderer computes the picture: the choices of the variant set that the
/// renderer itself reads ([`crate::variants::render_variant`] makes it from the
/// [`VariantConfig`](crate::VariantConfig); the square root and the intersection
/// structure arrive as types, the counter and the intersector). The default is the
/// baseline's: perspective camera, Lambert diffuse, every sample traced.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct RenderMethod {
    pub projection: Projection,
    pub diffuse: DiffuseForm,
    /// Trace every other sample, fill the rest from neighbours (`pixel-avg`).
    pub checkerboard: bool,
    /// Distance at which the orthographic grid spans the perspective view (`ortho`;
    /// default `|at - from|`).
    pub ortho_focus: Option<f32>,
    /// Trace neighbouring eye rays of a row together, [`PACKET`] at a time (`packets`).
    pub packets: bool,
}

impl RenderOptions {
    /// Options at the scene's own resolution, pixel-centre sampling, colour.
    pub fn for_scene(scene: &Scene) -> Self {
        Self::new(
            scene.view.width,
            scene.view.height,
            Sampling::PixelCenters,
            ShadingMode::Color,
        )
    }

    /// Options for a size, sampling and shading mode, with the SPD's depth and the
    /// default limits.
    pub fn new(width: u32, height: u32, sampling: Sampling, mode: ShadingMode) -> Self {
        Self {
            width,
            height,
            sampling,
            mode,
            max_depth: MAX_DEPTH,
            limits: Limits::default(),
            per_sample: false,
            bvh_builder: BvhBuilder::BinnedSah,
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
    Size(crate::LimitError),
    #[error("{0}")]
    Depth(crate::LimitError),
    /// The intersection structure cannot be used (e.g. a variant this build lacks).
    #[error("{0}")]
    Accelerator(String),
    /// The stop flag was set during the render: the frame is incomplete and not returned.
    #[error("cancelled: the render was stopped on request before it finished")]
    Cancelled,
}

impl RenderError {
    /// The limit the render exceeded, when that is the error.
    pub fn limit(&self) -> Option<crate::Limit> {
        match self {
            RenderError::Size(e) | RenderError::Depth(e) => e.limit,
            _ => None,
        }
    }
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

    /// Bytes of the pixels (12 a pixel: three f32).
    pub fn memory_bytes(&self) -> usize {
        self.pixels.capacity() * std::mem::size_of::<Rgb>()
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
    /// Each sample's work, when [`RenderOptions::per_sample`] asked for it.
    pub samples: Option<SampleStats>,
}

impl<C: Counter> Rendered<C> {
    /// Every count, or `None` for an uncounted render.
    pub fn counts(&self) -> Option<Counts> {
        self.counter
            .totals()
            .map(|t| Counts::from_parts(&t, self.rays))
    }
}

/// Renders `scene` with `accel`, computing the picture by `method`: in the rayon pool
/// the caller runs in (`ThreadPool::install`), its sample rows in parallel, or outside
/// any pool on the calling thread, one row after another. `progress` is called with 1
/// after each finished sample row (from worker threads).
pub fn render<C: Counter, I: Intersector>(
    scene: &Scene,
    accel: &I,
    options: &RenderOptions,
    method: &RenderMethod,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Rendered<C>, RenderError> {
    render_until(scene, accel, options, method, progress, &NEVER_STOP)
}

/// [`render`] that stops when `stop` is set: each sample row reads the flag before it
/// starts, so the render ends within one row's time (per worker) of the request, with
/// [`RenderError::Cancelled`]; rows already traced are dropped, never returned.
pub fn render_until<C: Counter, I: Intersector>(
    scene: &Scene,
    accel: &I,
    options: &RenderOptions,
    method: &RenderMethod,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Result<Rendered<C>, RenderError> {
    let samples = SampleMemory::for_render(options)?;
    render_into(scene, accel, options, method, progress, stop, samples)
}

/// The memory a render writes its samples into, taken and first touched before the
/// render: its page faults (a 1024×1024 frame is 12 MiB) are setup, not tracing, as in
/// the outside programs rtprof is set against, which allocate their frames before their
/// clocks start. [`crate::variants`] takes it before its trace clock.
pub struct SampleMemory(Vec<Rgb>);

impl SampleMemory {
    /// The samples of `options`' render, all black, after its size and depth limits
    /// are checked (nothing is allocated for a render that would be refused).
    pub fn for_render(options: &RenderOptions) -> Result<SampleMemory, RenderError> {
        check_limits(options)?;
        let (columns, rows) = options.sampling.grid(options.width, options.height);
        let len = columns as usize * rows as usize;
        // Huge pages where allowed: a row's own vector, copied into the frame after the
        // loop, and the frame's 4 KiB page faults were the pixel fill's 6 % of a tetra
        // render.
        let mut samples: Vec<Rgb> = huge_pages::vec_with_capacity(len);
        samples.resize(len, Rgb::BLACK);
        Ok(SampleMemory(samples))
    }
}

/// The render's size and depth against its limits, before anything is allocated.
fn check_limits(options: &RenderOptions) -> Result<(), RenderError> {
    let limits = &options.limits;
    limits
        .check_size(u64::from(options.width), u64::from(options.height))
        .map_err(RenderError::Size)?;
    limits
        .check_ray_depth(options.max_depth)
        .map_err(RenderError::Depth)
}

/// [`render_until`] into memory taken beforehand ([`SampleMemory::for_render`] with the
/// same options).
pub fn render_into<C: Counter, I: Intersector>(
    scene: &Scene,
    accel: &I,
    options: &RenderOptions,
    method: &RenderMethod,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
    samples: SampleMemory,
) -> Result<Rendered<C>, RenderError> {
    // Checked again: memory taken for other options is fitted below.
    check_limits(options)?;
    let mut counter = C::default();
    let camera_phase = C::enter_phase(Phase::CameraRay);
    let camera = Camera::new(
        &scene.view,
        options.width,
        options.height,
        options.sampling,
        method.projection,
        method.ortho_focus,
        &mut counter,
    )
    .map_err(RenderError::Camera)?;
    drop(camera_phase);
    let shader = Shader::with_diffuse(scene, accel, options.mode, method.diffuse)
        .with_max_depth(options.max_depth);
    let (columns, rows) = camera.grid();
    let from_eye = method.projection == Projection::EyeRows;

    // Each row writes its samples straight into the frame (rows in parallel, each its
    // own slice).
    let (width, height) = (columns as usize, rows as usize);
    let SampleMemory(mut samples) = samples;
    // Memory taken for other options is fitted (never the case from `render_until`).
    samples.resize(width * height, Rgb::BLACK);
    let trace_row = |(row, out): (usize, &mut [Rgb])| {
        let row = row as u32;
        // Relaxed: the flag orders nothing else; a row started just before it is set
        // finishes, and the render then ends.
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let _phase = C::enter_phase(Phase::SampleRow);
        let mut c = C::default();
        let mut rays = RayLog::default();
        // The bounded walk: the row's base direction once, then one step per pixel.
        let row_base = from_eye.then(|| {
            let _phase = C::enter_phase(Phase::CameraRay);
            camera.row_base(row, &mut c)
        });
        let trace = |column: u32, c: &mut C, rays: &mut RayLog| {
            if let Some(base) = row_base {
                let ray = {
                    let _phase = C::enter_phase(Phase::CameraRay);
                    camera.ray_from_eye(column, base, c)
                };
                shader.primary_from_eye(&ray, c, rays)
            } else {
                let ray = {
                    let _phase = C::enter_phase(Phase::CameraRay);
                    camera.ray(column, row, c)
                };
                shader.primary(&ray, c, rays)
            }
        };
        let mut records = options
            .per_sample
            .then(|| SampleRows::with_capacity(columns as usize, C::ENABLED));
        if I::PACKETS && method.packets {
            let packets = PacketRow {
                camera: &camera,
                shader: &shader,
                row,
                row_base,
                columns,
                checkerboard: method.checkerboard,
            };
            packets.trace(&mut c, &mut rays, records.as_mut(), out);
        } else {
            for (column, sample) in (0..columns).zip(out.iter_mut()) {
                *sample = if method.checkerboard && (column + row) % 2 == 1 {
                    // Filled from the neighbours after the loop.
                    if let Some(records) = &mut records {
                        records.push_untraced();
                    }
                    Rgb::BLACK
                } else if let Some(records) = &mut records {
                    // Each sample on its own counter, then added to the row's.
                    let (mut own, mut own_rays) = (C::default(), RayLog::default());
                    let start = Instant::now();
                    let colour = trace(column, &mut own, &mut own_rays);
                    records.push(start.elapsed(), &own, &own_rays);
                    c.merge(&own);
                    rays.merge(&own_rays);
                    colour
                } else {
                    trace(column, &mut c, &mut rays)
                };
            }
        }
        progress(1);
        Some(TracedRow {
            counter: c,
            rays: rays.counts,
            records,
        })
    };
    // In the caller's pool, the rows in parallel; outside any pool, on the calling thread,
    // rather than in a global pool started behind the caller's back. A skipped row (the
    // stop flag) makes the whole collection `None`.
    let traced: Option<Vec<TracedRow<C>>> = if rayon::current_thread_index().is_some() {
        samples
            .par_chunks_mut(width)
            .enumerate()
            .map(trace_row)
            .collect()
    } else {
        samples
            .chunks_mut(width)
            .enumerate()
            .map(trace_row)
            .collect()
    };
    let traced = traced.ok_or(RenderError::Cancelled)?;

    let pixel_fill = C::enter_phase(Phase::PixelFill);
    let mut ray_counts = RayCounts::default();
    let mut records = options
        .per_sample
        .then(|| SampleStats::new(columns, rows, C::ENABLED));
    for row in traced {
        counter.merge(&row.counter);
        ray_counts.merge(&row.rays);
        if let (Some(all), Some(part)) = (&mut records, row.records) {
            all.append(part);
        }
    }
    if method.checkerboard {
        fill_checkerboard(&mut samples, columns as usize, rows as usize);
    }
    let pixels = match options.sampling {
        Sampling::PixelCenters => samples,
        Sampling::SpdCorners => average_corners(&samples, options.width, options.height),
    };
    drop(pixel_fill);
    Ok(Rendered {
        frame: Frame {
            width: options.width,
            height: options.height,
            pixels,
        },
        counter,
        rays: ray_counts,
        samples: records,
    })
}

/// A sample row traced in packets of [`PACKET`] neighbouring eye rays (`packets`).
struct PacketRow<'a, 's, I> {
    camera: &'a Camera,
    shader: &'a Shader<'s, I>,
    row: u32,
    /// The bounded walk's row direction, when the eye rays start at the origin.
    row_base: Option<Vec3>,
    columns: u32,
    checkerboard: bool,
}

impl<I: Intersector> PacketRow<'_, '_, I> {
    /// The row's samples, written into `samples` (untraced ones left as they are);
    /// each ray's work is counted on its own counter, then added to `c` and `rays`, and
    /// recorded per sample in `records` when asked (a packet's time shared equally
    /// among its rays, in column order).
    fn trace<C: Counter>(
        &self,
        c: &mut C,
        rays: &mut RayLog,
        records: Option<&mut SampleRows>,
        samples: &mut [Rgb],
    ) {
        let columns = self.columns as usize;
        let keep = records.is_some();
        let mut kept: Vec<Option<(Duration, C, RayLog)>> = if keep {
            (0..columns).map(|_| None).collect()
        } else {
            Vec::new()
        };
        // The traced columns: all, or with the checkerboard those of the row's parity
        // (computed, not collected: a vector of them cost a store per column).
        let (first, step) = if self.checkerboard {
            (self.row % 2, 2)
        } else {
            (0, 1)
        };
        let count = self.columns.saturating_sub(first).div_ceil(step);
        for start in (0..count).step_by(PACKET) {
            let n = (count - start).min(PACKET as u32) as usize;
            let columns_of: [u32; PACKET] =
                std::array::from_fn(|i| first + (start + i as u32) * step);
            let chunk = &columns_of[..n];
            let start = keep.then(Instant::now);
            let mut counters: [C; PACKET] = Default::default();
            let mut logs = [RayLog::default(); PACKET];
            let mut colours = [Rgb::BLACK; PACKET];
            let (cs, ls, out) = (&mut counters[..n], &mut logs[..n], &mut colours[..n]);
            if let Some(base) = self.row_base {
                let eye: [Ray<true>; PACKET] = {
                    let _phase = C::enter_phase(Phase::CameraRay);
                    self.camera.packet_from_eye(chunk, base, cs)
                };
                self.shader.primaries_from_eye(&eye[..n], cs, ls, out);
            } else {
                let plain: [Ray; PACKET] = {
                    let _phase = C::enter_phase(Phase::CameraRay);
                    self.camera.packet(chunk, self.row, cs)
                };
                self.shader.primaries(&plain[..n], cs, ls, out);
            }
            let share = start.map(|s| s.elapsed() / n as u32);
            for (i, &column) in chunk.iter().enumerate() {
                samples[column as usize] = colours[i];
                c.merge(&counters[i]);
                rays.merge(&logs[i]);
                if let Some(share) = share {
                    kept[column as usize] =
                        Some((share, std::mem::take(&mut counters[i]), logs[i]));
                }
            }
        }
        if let Some(records) = records {
            for sample in kept {
                match sample {
                    Some((time, counter, log)) => records.push(time, &counter, &log),
                    None => records.push_untraced(),
                }
            }
        }
    }
}

/// One sample row's counts, merged in row order after the parallel loop (its samples
/// are in the frame already).
struct TracedRow<C> {
    counter: C,
    rays: RayCounts,
    records: Option<SampleRows>,
}

/// Sets every odd (`column + row`) sample to the mean of its even 4-neighbours.
fn fill_checkerboard(samples: &mut [Rgb], columns: usize, rows: usize) {
    for row in 0..rows {
        for column in (1 - row % 2..columns).step_by(2) {
            let mut sum = Rgb::BLACK;
            let mut n = 0.0f32;
            let mut take = |x: usize, y: usize| {
                sum += samples[y * columns + x];
                n += 1.0;
            };
            if column > 0 {
                take(column - 1, row);
            }
            if column + 1 < columns {
                take(column + 1, row);
            }
            if row > 0 {
                take(column, row - 1);
            }
            if row + 1 < rows {
                take(column, row + 1);
            }
            if n > 0.0 {
                samples[row * columns + column] = sum * (1.0 / n);
            }
        }
    }
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
    fn sample_memory_holds_the_camera_grid_and_refuses_what_the_limits_refuse() {
        // Pixel centres: one sample a pixel; SPD corners: (W+1) x (H+1).
        let centres = RenderOptions::new(5, 3, Sampling::PixelCenters, ShadingMode::Color);
        let corners = RenderOptions::new(5, 3, Sampling::SpdCorners, ShadingMode::Color);
        for (options, len) in [(&centres, 15), (&corners, 24)] {
            let memory = SampleMemory::for_render(options).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(memory.0.len(), len);
            assert!(memory.0.iter().all(|&s| s == Rgb::BLACK));
        }
        // Beyond the largest side: refused before any allocation, as render_into does.
        let mut wide = centres;
        wide.limits.max_side = 4;
        assert!(matches!(
            SampleMemory::for_render(&wide),
            Err(RenderError::Size(_))
        ));
        let mut deep = centres;
        deep.max_depth = deep.limits.max_ray_depth + 1;
        assert!(matches!(
            SampleMemory::for_render(&deep),
            Err(RenderError::Depth(_))
        ));
    }

    #[test]
    fn checkerboard_fill_takes_the_mean_of_traced_neighbours() {
        // 3x3 grid: traced where column + row is even.
        //   1 . 3     (. = untraced; top middle = (1+3+5)/3 = 3,
        //   . 5 .      middle left = (1+5+7)/3 = 13/3, middle right = (3+5+9)/3,
        //   7 . 9      bottom middle = (7+9+5)/3 = 7)
        let g = |v: f32| Rgb::gray(v);
        let mut s = vec![
            g(1.0),
            g(0.0),
            g(3.0),
            g(0.0),
            g(5.0),
            g(0.0),
            g(7.0),
            g(0.0),
            g(9.0),
        ];
        fill_checkerboard(&mut s, 3, 3);
        let want = [1.0, 3.0, 3.0, 13.0 / 3.0, 5.0, 17.0 / 3.0, 7.0, 7.0, 9.0];
        for (got, want) in s.iter().zip(want) {
            assert!((got.luminance() - want).abs() < 1e-5, "{got:?} vs {want}");
        }
    }

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
