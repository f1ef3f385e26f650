//! Edge maps and how well two of them agree: the structure of a picture (where its
//! silhouettes, horizons and shadow borders are) apart from its tones.
//!
//! An edge map is Canny's without the hysteresis: the luma smoothed by a Gaussian (so
//! that pixel noise is not taken for edges), its Sobel gradient, thinned to the
//! maxima across each edge (non-maximum suppression), and kept where the gradient is
//! strong for *this* picture: a fraction of its own 99th percentile, above an absolute
//! floor and above what the picture's own noise gives. The threshold is relative so
//! that a global tone change (a gain, a gamma, other light intensities), which scales
//! gradients, keeps the same edges; it rises with the noise (Canny's rule) so that a
//! path tracer's noisy picture has the edges of its converged one, not thousands more.
//!
//! Agreement is the boundary F-measure of the Berkeley segmentation benchmark
//! (Martin, Fowlkes & Malik, PAMI 2004): precision is the share of one map's edge
//! pixels that lie within a small distance of the other's, recall the converse, F their
//! harmonic mean. The tolerance absorbs the pixel that anti-aliasing or a tone change
//! moves an edge by. Each share is corrected for chance as Cohen's kappa is,
//! `(observed - chance) / (1 - chance)`, chance being what edges scattered at random
//! near each edge pixel would score: without it a picture dense with edges (a
//! fractal, gears, noise) "matches" any other, even itself moved or mirrored.

use super::RgbImage;
use crate::timing::quantile_of_sorted;

/// Gaussian smoothing before the gradient, in pixels: removes pixel noise (a path
/// tracer's, dithering) while keeping edges a few pixels apart distinct.
const EDGE_BLUR_SIGMA: f64 = 1.5;

/// An edge pixel's gradient is at least this fraction of the picture's 99th-percentile
/// gradient. The percentile, not the maximum, so that one hot pixel does not set it.
const EDGE_RELATIVE_THRESHOLD: f64 = 0.2;

/// ... and at least this many luma levels per pixel, so that a nearly flat picture
/// (8-bit quantization steps, a faint gradient) has no edges at all. After the blur a
/// step of h levels peaks at 0.24 h levels per pixel: a step of 9 levels or more can be
/// an edge, one of 8 or less cannot (the tests check both).
const EDGE_MIN_GRADIENT: f64 = 2.0;

/// ... and at least this many times the gradient that the picture's own pixel noise
/// gives (estimated from the picture): a noise gradient's magnitude is Rayleigh
/// distributed, exceeded 4 standard deviations out with probability exp(-8) = 3e-4.
const EDGE_NOISE_MULTIPLE: f64 = 4.0;

/// Two edges match when they lie within this many pixels (Chebyshev distance) of
/// each other: the Berkeley benchmark's tolerance is about 1 % of the diagonal, 2 to 4
/// pixels on its pictures; 2 here, since a tone change moves an edge by a pixel at most.
const MATCH_RADIUS: usize = 2;

/// The window (a square of 2 × 8 + 1 pixels) around an edge pixel in which chance is
/// judged: the other map's nearby edges are taken as scattered at random within it.
/// Larger than the match tolerance, so that a true match still counts (a straight edge
/// and its tolerance band fill 5 / 17 of the window), and small enough that edges
/// clustered in one part of the picture are judged by their own density: a fractal
/// moved by 8 pixels scored 0.70 with chance taken over the whole picture, 0.03 with
/// this window.
const CHANCE_RADIUS: usize = 8;

/// The edge pixels of a picture, row by row.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EdgeMap {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) edges: Vec<bool>,
}

impl EdgeMap {
    /// The edges of `img`'s Rec. 601 luma (see the module documentation).
    pub(crate) fn of(img: &RgbImage) -> EdgeMap {
        let (width, height) = (img.width as usize, img.height as usize);
        let luma: Vec<f64> = img
            .data
            .chunks_exact(3)
            .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
            .collect();
        let smooth = gaussian_blur(&luma, width, height, EDGE_BLUR_SIGMA);
        let gradient = sobel(&smooth, width, height);
        let magnitudes: Vec<f64> = gradient.iter().map(|&(gx, gy)| gx.hypot(gy)).collect();
        let noise_floor = EDGE_NOISE_MULTIPLE * noise_sigma(&luma, width, height) * gradient_gain();
        let threshold = (EDGE_RELATIVE_THRESHOLD * quantile(&magnitudes, 0.99))
            .max(EDGE_MIN_GRADIENT)
            .max(noise_floor);
        EdgeMap {
            width,
            height,
            edges: thin(&gradient, width, height)
                .iter()
                .map(|&m| m >= threshold)
                .collect(),
        }
    }

    pub(crate) fn count(&self) -> u64 {
        self.edges.iter().filter(|&&e| e).count() as u64
    }

    /// Every pixel within `radius` (Chebyshev distance) of an edge: a square
    /// dilation, done as a row pass and a column pass.
    fn dilated(&self, radius: usize) -> Vec<bool> {
        let (w, h) = (self.width, self.height);
        let mut rows = vec![false; w * h];
        for y in 0..h {
            let row = &self.edges[y * w..][..w];
            for x in 0..w {
                let (lo, hi) = (x.saturating_sub(radius), (x + radius).min(w - 1));
                rows[y * w + x] = row[lo..=hi].iter().any(|&e| e);
            }
        }
        let mut out = vec![false; w * h];
        for y in 0..h {
            let (lo, hi) = (y.saturating_sub(radius), (y + radius).min(h - 1));
            for x in 0..w {
                out[y * w + x] = (lo..=hi).any(|yy| rows[yy * w + x]);
            }
        }
        out
    }
}

/// How well two edge maps of the same size agree, each share corrected for chance
/// (0 = no better than chance, 1 = every edge matched).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Agreement {
    /// Of `a`'s edges, the chance-corrected share near one of `b`'s.
    pub(crate) precision: f64,
    /// Of `b`'s edges, the chance-corrected share near one of `a`'s.
    pub(crate) recall: f64,
    /// Harmonic mean of the two; 1 when neither map has an edge (nothing disagrees),
    /// 0 when only one has none.
    pub(crate) f: f64,
}

/// The agreement of `a` (the picture) with `b` (the reference): see the module
/// documentation. Both maps must have the same size.
pub(crate) fn agreement(a: &EdgeMap, b: &EdgeMap) -> Agreement {
    match (a.count(), b.count()) {
        (0, 0) => {
            return Agreement {
                precision: 1.0,
                recall: 1.0,
                f: 1.0,
            };
        }
        (0, _) | (_, 0) => {
            return Agreement {
                precision: 0.0,
                recall: 0.0,
                f: 0.0,
            };
        }
        _ => {}
    }
    let near_a = a.dilated(MATCH_RADIUS);
    let near_b = b.dilated(MATCH_RADIUS);
    let (w, h) = (a.width, a.height);
    let precision = corrected_share(&a.edges, &near_b, w, h);
    let recall = corrected_share(&b.edges, &near_a, w, h);
    let f = if precision + recall > 0.0 {
        2.0 * precision * recall / (precision + recall)
    } else {
        0.0
    };
    Agreement {
        precision,
        recall,
        f,
    }
}

/// The share of `edges` inside `near`, as kappa: `(observed - chance) / (1 - chance)`,
/// clamped at 0 (worse than chance is no agreement). Chance is local: for each edge
/// pixel, the share of `near` in the window of [`CHANCE_RADIUS`] around it, so that
/// edges clustered in one part of a picture (a fractal in the middle of a flat floor)
/// are held to their own density, not the picture's average. When chance explains
/// every match, 1 if every edge matched and 0 if not.
fn corrected_share(edges: &[bool], near: &[bool], width: usize, height: usize) -> f64 {
    // Summed-area table of `near`, one row and column of zeros in front.
    let mut table = vec![0u32; (width + 1) * (height + 1)];
    for y in 0..height {
        let mut row = 0;
        for x in 0..width {
            row += u32::from(near[y * width + x]);
            table[(y + 1) * (width + 1) + x + 1] = table[y * (width + 1) + x + 1] + row;
        }
    }
    let (mut total, mut hits, mut chance) = (0.0, 0.0, 0.0);
    for y in 0..height {
        for x in 0..width {
            if !edges[y * width + x] {
                continue;
            }
            let (x0, x1) = (
                x.saturating_sub(CHANCE_RADIUS),
                (x + CHANCE_RADIUS + 1).min(width),
            );
            let (y0, y1) = (
                y.saturating_sub(CHANCE_RADIUS),
                (y + CHANCE_RADIUS + 1).min(height),
            );
            let at = |xx: usize, yy: usize| f64::from(table[yy * (width + 1) + xx]);
            let inside = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
            total += 1.0;
            hits += f64::from(u8::from(near[y * width + x]));
            chance += inside / ((x1 - x0) * (y1 - y0)) as f64;
        }
    }
    if total - chance <= 0.0 {
        // Chance explains any match (edges denser than the tolerance everywhere): no
        // evidence either way, so agreement only if nothing contradicts it.
        return if hits == total { 1.0 } else { 0.0 };
    }
    ((hits - chance) / (total - chance)).max(0.0)
}

/// A separable Gaussian blur (kernel to 3 sigma, normalized), edges clamped.
pub(crate) fn gaussian_blur(plane: &[f64], width: usize, height: usize, sigma: f64) -> Vec<f64> {
    let radius = (3.0 * sigma).ceil() as usize;
    let mut kernel: Vec<f64> = (0..=2 * radius)
        .map(|i| {
            let d = i as f64 - radius as f64;
            (-d * d / (2.0 * sigma * sigma)).exp()
        })
        .collect();
    let sum: f64 = kernel.iter().sum();
    kernel.iter_mut().for_each(|k| *k /= sum);
    let clamp = |i: usize, n: usize| i.saturating_sub(radius).min(n - 1);
    let mut rows = vec![0.0; plane.len()];
    for y in 0..height {
        for x in 0..width {
            rows[y * width + x] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * plane[y * width + clamp(x + k, width)])
                .sum();
        }
    }
    let mut out = vec![0.0; plane.len()];
    for y in 0..height {
        for x in 0..width {
            out[y * width + x] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * rows[clamp(y + k, height) * width + x])
                .sum();
        }
    }
    out
}

/// Sobel gradient, divided by 8 so that it is in levels per pixel (a ramp of slope s
/// gives s), edges clamped: `(gx, gy)` per pixel.
fn sobel(plane: &[f64], width: usize, height: usize) -> Vec<(f64, f64)> {
    let at = |x: usize, y: usize, dx: isize, dy: isize| {
        let xx = (x as isize + dx).clamp(0, width as isize - 1) as usize;
        let yy = (y as isize + dy).clamp(0, height as isize - 1) as usize;
        plane[yy * width + xx]
    };
    let mut out = Vec::with_capacity(plane.len());
    for y in 0..height {
        for x in 0..width {
            let gx = (at(x, y, 1, -1) + 2.0 * at(x, y, 1, 0) + at(x, y, 1, 1))
                - (at(x, y, -1, -1) + 2.0 * at(x, y, -1, 0) + at(x, y, -1, 1));
            let gy = (at(x, y, -1, 1) + 2.0 * at(x, y, 0, 1) + at(x, y, 1, 1))
                - (at(x, y, -1, -1) + 2.0 * at(x, y, 0, -1) + at(x, y, 1, -1));
            out.push((gx / 8.0, gy / 8.0));
        }
    }
    out
}

/// Canny's non-maximum suppression: a pixel stays a candidate only where its gradient
/// magnitude is a maximum across the edge (against its two neighbours along the
/// gradient's direction, rounded to 0, 45, 90 or 135 degrees), so an edge is a line
/// one or two pixels wide however soft it is; elsewhere the magnitude becomes 0.
fn thin(gradient: &[(f64, f64)], width: usize, height: usize) -> Vec<f64> {
    let magnitude = |x: isize, y: isize| {
        if x < 0 || y < 0 || x >= width as isize || y >= height as isize {
            return 0.0;
        }
        let (gx, gy) = gradient[y as usize * width + x as usize];
        gx.hypot(gy)
    };
    let mut out = Vec::with_capacity(gradient.len());
    for y in 0..height as isize {
        for x in 0..width as isize {
            let (gx, gy) = gradient[y as usize * width + x as usize];
            let m = gx.hypot(gy);
            // The direction across the edge, folded into [0, 180) degrees.
            let angle = gy.atan2(gx).to_degrees().rem_euclid(180.0);
            let (dx, dy) = match angle {
                a if !(22.5..157.5).contains(&a) => (1, 0),
                a if a < 67.5 => (1, 1),
                a if a < 112.5 => (0, 1),
                _ => (-1, 1),
            };
            let is_max = m >= magnitude(x + dx, y + dy) && m >= magnitude(x - dx, y - dy);
            out.push(if is_max { m } else { 0.0 });
        }
    }
    out
}

/// Standard deviation of a picture's pixel noise, by Immerkær's estimator ("Fast Noise
/// Variance Estimation", CVIU 1996): the mean absolute response to the difference of
/// two Laplacians, which cancels smooth shading, times sqrt(pi / 2) / 6. Edges add a
/// little; a clean render estimates at a level or two.
fn noise_sigma(plane: &[f64], width: usize, height: usize) -> f64 {
    if width < 3 || height < 3 {
        return 0.0;
    }
    let at = |x: usize, y: usize| plane[y * width + x];
    let mut sum = 0.0;
    for y in 1..height - 1 {
        for x in 1..width - 1 {
            let corners = at(x - 1, y - 1) + at(x + 1, y - 1) + at(x - 1, y + 1) + at(x + 1, y + 1);
            let sides = at(x, y - 1) + at(x - 1, y) + at(x + 1, y) + at(x, y + 1);
            sum += (corners - 2.0 * sides + 4.0 * at(x, y)).abs();
        }
    }
    (std::f64::consts::PI / 2.0).sqrt() * sum / (6.0 * ((width - 2) * (height - 2)) as f64)
}

/// The standard deviation of one gradient component (blurred, Sobel / 8) that white
/// noise of standard deviation 1 gives: the L2 norm of the filters' impulse response,
/// computed on an impulse rather than by hand.
fn gradient_gain() -> f64 {
    let size = 2 * (3.0 * EDGE_BLUR_SIGMA).ceil() as usize + 5;
    let mut impulse = vec![0.0; size * size];
    impulse[(size / 2) * size + size / 2] = 1.0;
    let response = sobel(
        &gaussian_blur(&impulse, size, size, EDGE_BLUR_SIGMA),
        size,
        size,
    );
    response.iter().map(|&(gx, _)| gx * gx).sum::<f64>().sqrt()
}

/// The `q` quantile of `values` (the workspace's one quantile, `timing`'s); 0 for none.
fn quantile(values: &[f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    quantile_of_sorted(&sorted, q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_metrics::test_scenes::{uniform, with_noise};
    use crate::prng::SplitMix64;

    /// A picture split into a dark left and a bright right part at column `split`.
    fn step(width: u32, height: u32, split: u32, dark: u8, bright: u8) -> RgbImage {
        let data = (0..height)
            .flat_map(|_| (0..width).flat_map(move |x| [if x < split { dark } else { bright }; 3]))
            .collect();
        RgbImage::new(width, height, data).expect("valid image")
    }

    fn edge_columns(map: &EdgeMap) -> Vec<usize> {
        (0..map.width)
            .filter(|&x| (0..map.height).any(|y| map.edges[y * map.width + x]))
            .collect()
    }

    #[test]
    fn a_step_has_a_thin_edge_along_its_border_only() {
        let map = EdgeMap::of(&step(20, 10, 10, 20, 200));
        // The border lies between columns 9 and 10, whose gradients are equal but for
        // rounding: one line, one pixel wide, in every row.
        assert_eq!(edge_columns(&map), [9]);
        assert_eq!(map.count(), 10);
    }

    #[test]
    fn flat_and_nearly_flat_pictures_have_no_edges() {
        assert_eq!(EdgeMap::of(&uniform(12, 9, [255; 3])).count(), 0);
        assert_eq!(EdgeMap::of(&step(20, 10, 10, 100, 108)).count(), 0);
        assert_eq!(edge_columns(&EdgeMap::of(&step(20, 10, 10, 100, 109))), [9]);
    }

    #[test]
    fn noise_raises_the_threshold_above_its_own_gradients() {
        // ±40 levels of uniform noise (standard deviation 23) on a 100-level step: the
        // border is still found, and next to nothing else.
        let noisy = with_noise(&step(64, 48, 32, 70, 170), 40, 9);
        let map = EdgeMap::of(&noisy);
        let near_border = (0..48)
            .flat_map(|y| (30..=33).map(move |x| (x, y)))
            .filter(|&(x, y)| map.edges[y * 64 + x])
            .count() as u64;
        assert!(near_border >= 40, "{near_border} of 48 rows found");
        assert!(
            map.count() - near_border <= 10,
            "{} stray edges",
            map.count() - near_border
        );
        assert_eq!(noise_sigma(&[0.0; 9], 3, 3), 0.0);
    }

    #[test]
    fn immerkaer_estimates_the_noise_of_a_flat_picture() {
        // Uniform noise in ±40: standard deviation 81 / sqrt(12) = 23.4 (its values
        // are 81 equally likely integers: sqrt((81^2 - 1) / 12)).
        let mut rng = SplitMix64::new(4);
        let plane: Vec<f64> = (0..200 * 200)
            .map(|_| rng.below(81) as f64 - 40.0)
            .collect();
        let sigma = noise_sigma(&plane, 200, 200);
        assert!((sigma / 23.38 - 1.0).abs() < 0.05, "{sigma}");
    }

    #[test]
    fn gradient_gain_matches_the_filters_norm() {
        // Pure Sobel/8 (no blur) would give sqrt(2 (1 + 4 + 1)) / 8 = 0.306; the blur at
        // sigma 1.5 averages about 2 sqrt(pi) 1.5 = 5.3 pixels per axis, so the gain
        // is much smaller, and positive.
        let g = gradient_gain();
        assert!(g > 0.01 && g < 0.1, "{g}");
    }

    #[test]
    fn sobel_of_a_ramp_is_its_slope() {
        let ramp: Vec<f64> = (0..5 * 4).map(|i| 3.0 * (i % 5) as f64).collect();
        let g = sobel(&ramp, 5, 4);
        // Inside, the central difference of slope 3; at the clamped borders half of it.
        assert_eq!(g[5 + 2], (3.0, 0.0));
        assert_eq!(g[5], (1.5, 0.0));
    }

    #[test]
    fn blur_keeps_flat_planes_and_the_mean() {
        let flat = vec![7.0; 30];
        assert!(
            gaussian_blur(&flat, 6, 5, 1.5)
                .iter()
                .all(|v| (v - 7.0).abs() < 1e-12)
        );
        let mut spike = vec![0.0; 21 * 21];
        spike[10 * 21 + 10] = 1.0;
        let blurred = gaussian_blur(&spike, 21, 21, 1.5);
        assert!((blurred.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn quantile_interpolates_and_takes_no_values() {
        let v: Vec<f64> = (1..=101).rev().map(f64::from).collect();
        assert_eq!(quantile(&v, 0.99), 100.0);
        assert_eq!(quantile(&[], 0.5), 0.0);
    }

    #[test]
    fn agreement_of_same_moved_and_missing_edges() {
        let a = EdgeMap::of(&step(40, 10, 20, 20, 200));
        let same = agreement(&a, &a);
        assert_eq!((same.precision, same.recall, same.f), (1.0, 1.0, 1.0));
        // One pixel over: within the tolerance.
        let near = agreement(&EdgeMap::of(&step(40, 10, 21, 20, 200)), &a);
        assert_eq!(near.f, 1.0);
        // Ten pixels over: no edge pixel within 2 of the other's.
        let far = agreement(&EdgeMap::of(&step(40, 10, 30, 20, 200)), &a);
        assert_eq!(far.f, 0.0);
        let flat = EdgeMap::of(&uniform(40, 10, [9; 3]));
        assert_eq!(agreement(&flat, &a).f, 0.0);
        assert_eq!(agreement(&a, &flat).f, 0.0);
        assert_eq!(agreement(&flat, &flat).f, 1.0);
    }

    fn random_edges(width: usize, height: usize, seed: u64) -> EdgeMap {
        let mut rng = SplitMix64::new(seed);
        let edges = (0..width * height).map(|_| rng.below(20) == 0).collect();
        EdgeMap {
            width,
            height,
            edges,
        }
    }

    /// Two independent random maps, 1 pixel in 20 an edge: the 5x5 tolerance band of
    /// one covers 1 - 0.95^25 = 72 % of the picture, so about 72 % of the other's edges
    /// "match" by chance alone. Corrected, that is no agreement.
    #[test]
    fn chance_correction_discounts_random_matches() {
        let (a, b) = (random_edges(64, 64, 1), random_edges(64, 64, 2));
        let near_b = b.dilated(MATCH_RADIUS);
        let raw = a
            .edges
            .iter()
            .zip(&near_b)
            .filter(|&(&e, &n)| e && n)
            .count() as f64
            / a.count() as f64;
        assert!((raw - 0.72).abs() < 0.05, "raw share {raw}");
        let corrected = agreement(&a, &b);
        assert!(corrected.f < 0.05, "{corrected:?}");
        assert_eq!(agreement(&a, &a).f, 1.0);
    }

    /// Stripes 4 pixels apart: the tolerance band covers the whole picture, so no
    /// match can be told from chance. Nothing contradicts a map agreeing with itself,
    /// so it does (identical pictures must not come out different); the price is that
    /// the stripes moved by half a period agree as well: edges this dense cannot tell.
    #[test]
    fn maps_denser_than_the_tolerance_agree_when_nothing_contradicts() {
        let stripes = |offset: usize| EdgeMap {
            width: 32,
            height: 8,
            edges: (0..8)
                .flat_map(|_| (0..32).map(move |x: usize| (x + offset).is_multiple_of(4)))
                .collect(),
        };
        assert_eq!(agreement(&stripes(0), &stripes(0)).f, 1.0);
        assert_eq!(agreement(&stripes(2), &stripes(0)).f, 1.0);
    }
}
