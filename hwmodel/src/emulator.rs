//! Functional emulator of the thesis hardware (ch. 6): the 8-bit gray image the FPGA
//! would show, computed block by block in the arithmetic of the RTL's operators
//! ([`crate::float_policy`]: IEEE single precision, round to nearest even, subnormals
//! flushed like the Altera cores), so the emulator and the generated RTL can check
//! each other.
//!
//! - Primary ray (6.1.3): the scene block precomputes `ScanLine` (the direction to the
//!   top-left pixel centre), `PixelWidth` and `PixelHeight` (one pixel's step to the
//!   right and upwards); row `i` starts at `ScanLine − i·PixelHeight` and pixel `j` of
//!   it looks along `normalize(row base + j·PixelWidth)`. The geometry is the tracer's
//!   [`tracer::Camera`] with pixel-centre sampling (`w = normalize(at − from)`,
//!   `u = normalize(w × up)`, `v = u × w`, pitch `2·tan(angle/2)/(rows − 1)`), only
//!   walked incrementally, so a ray may differ from the software's in the last bit.
//! - Intersection test (6.1.4): `Voc = O − C`; sphere `a = 1`, `b = 2 R·Voc`,
//!   `c = Voc·Voc − r²`; cylinder `a = 1 − (R·V)²`, `b = 2(R·Voc − (R·V)(Voc·V))`,
//!   `c = Voc·Voc − (Voc·V)² − r²`; the selector picks by type; the quadratic solver
//!   gives the smaller positive root of `(−b ∓ √(b² − 4ac)) / 2a` (the near root if
//!   positive, else the far one), infinity when the discriminant is negative or no root
//!   is positive.
//! - Hit body (6.1.6): `P = O + d·R`, `m = (P − Cb)·V`; a cylinder's distance becomes
//!   infinity unless `0 < m < m max`.
//! - Minimum distance (6.1.5): a strictly smaller distance replaces the stored one, so
//!   the first primitive in memory wins ties.
//! - Shading (6.1.7): `L = light − P`, `N = P − C` (sphere) or `(P − Cb) − m·V`
//!   (cylinder), both normalized; gray = `N·L × 255` converted to 8 bits (round half
//!   away from zero, saturating: for `N·L` in (0, 1] the same bytes as
//!   [`tracer::Rgb::to_rgb8`]), the background where there is no hit or `N·L ≤ 0`.
//!
//! Every operation, its operands' order and every selection is the blocks' dataflow
//! graph's ([`crate::blocks`]), evaluated in [`crate::float_policy`]: the generated RTL
//! computes the same bits.
//!
//! Differences from the software's `--diffuse-only` render ([`tracer::ShadingMode::DiffuseOnly`]):
//! - Open cylinder ends. The hardware hands only the selected (smaller positive) root to
//!   the hit body. When that root misses the body (the ray passes the outer wall above
//!   or below the ends), the cylinder counts as missed even though the ray may go on to
//!   the inner wall through the open end. The software tries the far root too and shows
//!   that inner wall, shaded with the outward normal (diffuse-only never turns normals
//!   toward the viewer), so there it is either lit or background; the hardware shows
//!   whatever lies behind (background or another primitive).
//! - A ray parallel to a cylinder's axis (`a = 0`): the solver divides by zero and
//!   gets an infinity or NaN, neither of which counts as a positive distance; the
//!   software rejects `a ≤ 0` explicitly. Same result.
//! - Tangent rays (discriminant exactly 0) hit in the hardware and miss in the
//!   software: a set of measure zero.
//! - Rounding: the sphere and cylinder distances are the software's bit for bit (the
//!   `b = 2·half_b` form only scales by powers of two), but the incremental primary
//!   rays and `m = (P − Cb)·V` (the software uses `m = Voc·V + d·R·V`) can differ in
//!   the last bits, which moves a gray level by one now and then, or flips a grazing
//!   silhouette pixel (discriminant near 0, or m near 0 or m max) between hit and miss.

use crate::float_policy as fp;
use crate::hw_scene::{HwKind, HwPrimitive, HwScene};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use tracer::image_io::{ImageError, write_rgb8};

type V3 = [f32; 3];

fn add(a: V3, b: V3) -> V3 {
    [
        fp::add(a[0], b[0]),
        fp::add(a[1], b[1]),
        fp::add(a[2], b[2]),
    ]
}

fn sub(a: V3, b: V3) -> V3 {
    [
        fp::sub(a[0], b[0]),
        fp::sub(a[1], b[1]),
        fp::sub(a[2], b[2]),
    ]
}

fn scale(a: V3, s: f32) -> V3 {
    [fp::mul(a[0], s), fp::mul(a[1], s), fp::mul(a[2], s)]
}

/// `(x·x + y·y) + z·z`: the order glam's SSE dot product sums in, so the emulator and
/// the software round alike.
fn dot(a: V3, b: V3) -> f32 {
    let xy = fp::add(fp::mul(a[0], b[0]), fp::mul(a[1], b[1]));
    fp::add(xy, fp::mul(a[2], b[2]))
}

fn cross(a: V3, b: V3) -> V3 {
    let term = |i: usize, j: usize| fp::sub(fp::mul(a[i], b[j]), fp::mul(b[i], a[j]));
    [term(1, 2), term(2, 0), term(0, 1)]
}

/// `a · (1/√(a·a))`: the dot product, the inverse square root core, a scale (as the
/// software's counter normalizes: a reciprocal, then a scale).
fn normalize(a: V3) -> V3 {
    scale(a, fp::inv_sqrt(dot(a, a)))
}

/// A screen coordinate as the screen iterator's int-to-float converter gives it.
fn coordinate(i: u32) -> f32 {
    fp::from_int(i32::try_from(i).unwrap_or(i32::MAX))
}

/// The 0..1 → 0..255 conversion of the software's 8-bit output: clamp, scale, round.
pub fn to_gray8(value: f32) -> u8 {
    (value.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// An 8-bit grayscale image, row-major, top row first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HwImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u8>,
}

impl HwImage {
    /// The gray value at (`column`, `row`), row 0 at the top; `None` outside the image.
    pub fn gray_at(&self, column: u32, row: u32) -> Option<u8> {
        if column >= self.width || row >= self.height {
            return None;
        }
        let index = row as usize * self.width as usize + column as usize;
        self.pixels.get(index).copied()
    }

    /// The pixels as interleaved 8-bit RGB (three equal channels), for the image writers.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|&g| [g, g, g]).collect()
    }
}

/// Writes `image` to `path` as PNG or PPM (chosen by the extension), atomically.
pub fn write_image(image: &HwImage, path: &Path) -> Result<(), ImageError> {
    write_rgb8(path, image.width, image.height, &image.to_rgb8())
}

/// The primary-ray block's inputs, precomputed by the scene block for one screen size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimaryRays {
    pub observer: V3,
    /// Direction (unnormalized) to the centre of the top-left pixel.
    pub scan_line: V3,
    /// One pixel's step to the right.
    pub pixel_width: V3,
    /// One pixel's step upwards (rows go down, so row `i` subtracts `i` of them).
    pub pixel_height: V3,
}

impl PrimaryRays {
    /// The set-up for a `width` × `height` screen. A degenerate view (refused by
    /// [`HwScene::from_scene`]) gives NaN directions, which hit nothing.
    pub fn new(scene: &HwScene, width: u32, height: u32) -> Self {
        let forward = normalize(sub(scene.look_at, scene.eye));
        let right = normalize(cross(forward, scene.up));
        let up = cross(right, forward);
        let half_span = (scene.angle_deg.to_radians() * 0.5).tan();
        // The angle spans the centres of the extreme rows (one row: as if two).
        let pitch = 2.0 * half_span / (height.max(2) - 1) as f32;
        let pixel_width = scale(right, pitch);
        let pixel_height = scale(up, pitch);
        let left = -((width.max(1) - 1) as f32 * 0.5);
        let top = (height.max(1) - 1) as f32 * 0.5;
        let scan_line = add(
            add(forward, scale(pixel_height, top)),
            scale(pixel_width, left),
        );
        Self {
            observer: scene.eye,
            scan_line,
            pixel_width,
            pixel_height,
        }
    }

    /// The base direction of row `row` (row 0 at the top).
    pub fn row_base(&self, row: u32) -> V3 {
        sub(self.scan_line, scale(self.pixel_height, coordinate(row)))
    }

    /// The unit direction of pixel `column` of the row starting at `row_base`.
    pub fn direction(&self, row_base: V3, column: u32) -> V3 {
        normalize(add(row_base, scale(self.pixel_width, coordinate(column))))
    }
}

/// The quadratic's coefficients `(a, b, c)` for `primitive`, as the selector outputs
/// them (`voc = O − C`, `dir` of unit length).
pub fn quadratic_coefficients(primitive: &HwPrimitive, voc: V3, dir: V3) -> (f32, f32, f32) {
    let r_sq = fp::mul(primitive.radius, primitive.radius);
    let r_voc = dot(dir, voc);
    let voc_voc = dot(voc, voc);
    match primitive.kind {
        HwKind::Sphere => (1.0, fp::mul(2.0, r_voc), fp::sub(voc_voc, r_sq)),
        HwKind::Cylinder => {
            let r_v = dot(dir, primitive.axis);
            let voc_v = dot(voc, primitive.axis);
            (
                fp::sub(1.0, fp::mul(r_v, r_v)),
                fp::mul(2.0, fp::sub(r_voc, fp::mul(r_v, voc_v))),
                fp::sub(fp::sub(voc_voc, fp::mul(voc_v, voc_v)), r_sq),
            )
        }
    }
}

/// The quadratic solver as the hardware wires it: the roots `(−b ∓ √(b² − 4ac)) / 2a`,
/// then `near` if it is positive, else `far` if it is positive, else infinity. With
/// `a > 0` (always, up to rounding: `a = 1` for a sphere, `1 − (R·V)²` for a cylinder)
/// `near ≤ far`, so this is the smaller positive root. A negative discriminant needs no
/// test: its square root is NaN, NaN is not positive, and the result is infinity; roots
/// that are NaN (`a = 0`) are not positive either. The operations and their order are
/// the intersection block's graph ([`crate::blocks::intersection`]), so the RTL gives
/// the same bits.
pub fn smaller_positive_root(a: f32, b: f32, c: f32) -> f32 {
    let discriminant = fp::sub(fp::mul(b, b), fp::mul(fp::mul(a, c), 4.0));
    let root = fp::sqrt(discriminant);
    let two_a = fp::mul(a, 2.0);
    // `-b` is a sign flip on the wire, exact.
    let near = fp::div(fp::sub(-b, root), two_a);
    let far = fp::div(fp::add(-b, root), two_a);
    let far_or_none = fp::select(fp::lt(0.0, far), f32::INFINITY, far);
    fp::select(fp::lt(0.0, near), far_or_none, near)
}

/// What the hit body hands on for one primitive: distance (infinity on a miss), the
/// hit point and the axial coordinate m (zero for a sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyHit {
    pub distance: f32,
    pub point: V3,
    pub m: f32,
}

/// The intersection test and hit body of one primitive for the ray `origin + d·dir`.
pub fn intersect(primitive: &HwPrimitive, origin: V3, dir: V3) -> BodyHit {
    let voc = sub(origin, primitive.center);
    let (a, b, c) = quadratic_coefficients(primitive, voc, dir);
    let root = smaller_positive_root(a, b, c);
    let point = add(origin, scale(dir, root));
    let m = dot(sub(point, primitive.center), primitive.axis);
    // Only the selected root is bounded: a cylinder whose near wall lies beyond an end
    // is missed even if the ray would meet its inner wall (see the module doc).
    let inside_body = fp::lt(0.0, m) && fp::lt(m, primitive.m_max);
    let distance = match primitive.kind {
        HwKind::Sphere => root,
        HwKind::Cylinder if inside_body => root,
        HwKind::Cylinder => f32::INFINITY,
    };
    BodyHit { distance, point, m }
}

/// The minimum-distance block over the whole scene memory: the closest hit and its
/// primitive, `None` when every distance is infinite.
pub fn closest_hit(scene: &HwScene, origin: V3, dir: V3) -> Option<(&HwPrimitive, BodyHit)> {
    let mut best: Option<(&HwPrimitive, BodyHit)> = None;
    for primitive in &scene.primitives {
        let hit = intersect(primitive, origin, dir);
        let best_distance = best.map_or(f32::INFINITY, |(_, b)| b.distance);
        // Strictly smaller: the first primitive in memory wins ties.
        if fp::lt(hit.distance, best_distance) {
            best = Some((primitive, hit));
        }
    }
    best
}

/// The shading block: the Lambert term `N·L` of a hit, or `None` (background) unless
/// it is positive (`N·L = 0` is the silhouette; NaN is not positive).
pub fn diffuse(primitive: &HwPrimitive, hit: &BodyHit, light: V3) -> Option<f32> {
    let to_light = normalize(sub(light, hit.point));
    let radial = sub(hit.point, primitive.center);
    let normal = match primitive.kind {
        HwKind::Sphere => radial,
        HwKind::Cylinder => sub(radial, scale(primitive.axis, hit.m)),
    };
    let lambert = dot(normalize(normal), to_light);
    fp::lt(0.0, lambert).then_some(lambert)
}

/// The gray value of the pixel whose ray leaves the observer along `dir`: `N·L × 255`
/// converted to 8 bits, or the background.
pub fn pixel_gray(scene: &HwScene, dir: V3) -> u8 {
    let background = to_gray8(scene.background_gray);
    closest_hit(scene, scene.eye, dir)
        .and_then(|(primitive, hit)| diffuse(primitive, &hit, scene.light))
        .map_or(background, |lambert| fp::to_u8(fp::mul(lambert, 255.0)))
}

/// The image the hardware computes for `scene` on a `width` × `height` screen.
pub fn render(scene: &HwScene, width: u32, height: u32) -> HwImage {
    use rayon::prelude::*;
    let rays = PrimaryRays::new(scene, width, height);
    // The screen iterator's order (columns within rows, top row first); each pixel is
    // computed on its own, so the rows run in parallel (on the caller's rayon pool) and
    // the picture is the same on any number of threads.
    let pixels: Vec<u8> = (0..height)
        .into_par_iter()
        .flat_map_iter(|row| row_pixels(scene, &rays, row, width))
        .collect();
    HwImage {
        width,
        height,
        pixels,
    }
}

/// [`render`] that stops when `stop` is set (read before each row, so it ends within a
/// row's time): `None` then, never a partial image.
pub fn render_until(
    scene: &HwScene,
    width: u32,
    height: u32,
    stop: &AtomicBool,
) -> Option<HwImage> {
    use rayon::prelude::*;
    let rays = PrimaryRays::new(scene, width, height);
    // A relaxed load a row: nothing beside a row of closest-hit searches.
    let rows: Option<Vec<Vec<u8>>> = (0..height)
        .into_par_iter()
        .map(|row| {
            (!stop.load(Ordering::Relaxed)).then(|| row_pixels(scene, &rays, row, width).collect())
        })
        .collect();
    Some(HwImage {
        width,
        height,
        pixels: rows?.concat(),
    })
}

/// The gray values of row `row`, left to right.
fn row_pixels<'a>(
    scene: &'a HwScene,
    rays: &'a PrimaryRays,
    row: u32,
    width: u32,
) -> impl Iterator<Item = u8> + 'a {
    let row_base = rays.row_base(row);
    (0..width).map(move |column| pixel_gray(scene, rays.direction(row_base, column)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solver_picks_the_smaller_positive_root() {
        // (d - 2)(d - 5) = d² - 7d + 10.
        assert_eq!(smaller_positive_root(1.0, -7.0, 10.0), 2.0);
        // (d + 1)(d - 3): the origin is inside, the positive root is kept.
        assert_eq!(smaller_positive_root(1.0, -2.0, -3.0), 3.0);
        // Both behind.
        assert_eq!(smaller_positive_root(1.0, 7.0, 10.0), f32::INFINITY);
        // No real root.
        assert_eq!(smaller_positive_root(1.0, 0.0, 1.0), f32::INFINITY);
        // a = 0 (ray parallel to a cylinder axis): no positive distance.
        assert_eq!(smaller_positive_root(0.0, 2.0, -1.0), f32::INFINITY);
    }

    #[test]
    fn cylinder_seen_through_its_open_end_is_missed() {
        // Axis +z from z = 0 to 2, radius 1. The ray from (-1.1, 0, 2.2) along
        // (1, 0, -1)/√2 meets the outer wall above the top (m = 2.1) and the inner wall
        // at m = 0.1: the hardware bounds only the first and reports a miss.
        let cylinder = HwPrimitive::cylinder([0.0; 3], [0.0, 0.0, 1.0], 1.0, 2.0);
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let hit = intersect(&cylinder, [-1.1, 0.0, 2.2], [h, 0.0, -h]);
        assert_eq!(hit.distance, f32::INFINITY);
        // From the side at mid-height: wall at x = -1, d = 4, m = 1.
        let side = intersect(&cylinder, [-5.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        assert_eq!((side.distance, side.m), (4.0, 1.0));
    }

    /// A scene of `n` spheres in a row before the camera (every primary ray tests all).
    fn spheres(n: usize) -> HwScene {
        let mut scene = HwScene::from_scene(
            &tracer::parse_nff(
                "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\n\
             l 0 10 -10\nf 1 1 1 1 0 0 0 0\ns 0 0 0 1\n",
                "spheres.nff",
            )
            .unwrap(),
        )
        .unwrap();
        scene.primitives = (0..n)
            .map(|i| HwPrimitive::sphere([i as f32 * 0.01 - 2.0, 0.0, 0.0], 1.0))
            .collect();
        scene
    }

    #[test]
    fn render_until_gives_the_same_picture_and_stops_within_a_row() {
        let scene = spheres(3);
        let never = AtomicBool::new(false);
        assert_eq!(
            render_until(&scene, 24, 16, &never),
            Some(render(&scene, 24, 16))
        );
        assert_eq!(render_until(&scene, 24, 16, &AtomicBool::new(true)), None);
        // A frame of many seconds (500 spheres × 1,000 × 1,000 pixels: 5·10⁸ tests),
        // stopped after 0.2 s: it must end within a second of the flag, on a busy
        // machine too (a row here is about 1 ms of work).
        let big = spheres(500);
        let stop = AtomicBool::new(false);
        let (out, late) = std::thread::scope(|s| {
            let worker = s.spawn(|| render_until(&big, 1000, 1000, &stop));
            std::thread::sleep(std::time::Duration::from_millis(200));
            let raised = std::time::Instant::now();
            stop.store(true, Ordering::SeqCst);
            let out = worker.join().unwrap();
            (out, raised.elapsed())
        });
        assert_eq!(out, None, "the frame was stopped, not finished");
        assert!(late.as_secs_f64() < 1.0, "ended {late:?} after the flag");
    }

    #[test]
    fn gray_conversion_rounds_like_the_software() {
        assert_eq!(to_gray8(0.5), 128);
        assert_eq!(to_gray8(1.5), 255);
        assert_eq!(to_gray8(-0.2), 0);
        assert_eq!(to_gray8(100.0 / 255.0), 100);
    }
}
