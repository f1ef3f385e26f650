//! Structural similarity (Wang, Bovik, Sheikh & Simoncelli 2004) of two grayscale images.
//!
//! Window: the paper's 11x11 circular-symmetric Gaussian, sigma 1.5, normalized to sum 1,
//! slid one pixel at a time over positions where it fits entirely (no padding, like the
//! reference `ssim_index.m`); the result is the mean of that local SSIM map. An image
//! narrower or shorter than 11 pixels is treated as one window with uniform weights.
//! K1 = 0.01, K2 = 0.03, L = 255.

const WINDOW: usize = 11;
const SIGMA: f64 = 1.5;
const C1: f64 = (0.01 * 255.0) * (0.01 * 255.0);
const C2: f64 = (0.03 * 255.0) * (0.03 * 255.0);

/// Weighted moments of a window: mean a, mean b, mean a², mean b², mean ab.
type Moments = [f64; 5];

/// Mean SSIM of two same-sized grayscale images, `width * height` bytes each.
pub(crate) fn mean_ssim(a: &[u8], b: &[u8], width: usize, height: usize) -> f64 {
    if width < WINDOW || height < WINDOW {
        let weight = 1.0 / a.len() as f64;
        let mut m = [0.0; 5];
        for (&x, &y) in a.iter().zip(b) {
            accumulate(&mut m, weight, f64::from(x), f64::from(y));
        }
        return local_ssim(m);
    }
    let kernel = gaussian_kernel();
    let out_width = width - WINDOW + 1;
    // Separable filtering: each input row is filtered horizontally once into a ring of
    // the last WINDOW rows, which is then filtered vertically, so memory is O(width).
    let mut ring = vec![[0.0; 5]; WINDOW * out_width];
    let mut total = 0.0;
    for row in 0..height {
        let slot = &mut ring[(row % WINDOW) * out_width..][..out_width];
        let (row_a, row_b) = (&a[row * width..][..width], &b[row * width..][..width]);
        for (x, m) in slot.iter_mut().enumerate() {
            *m = [0.0; 5];
            for (k, &g) in kernel.iter().enumerate() {
                accumulate(m, g, f64::from(row_a[x + k]), f64::from(row_b[x + k]));
            }
        }
        if row + 1 < WINDOW {
            continue;
        }
        let first_row = row + 1 - WINDOW;
        for x in 0..out_width {
            let mut m = [0.0; 5];
            for (k, &g) in kernel.iter().enumerate() {
                let h = ring[((first_row + k) % WINDOW) * out_width + x];
                for (acc, v) in m.iter_mut().zip(h) {
                    *acc += g * v;
                }
            }
            total += local_ssim(m);
        }
    }
    total / (out_width * (height - WINDOW + 1)) as f64
}

fn accumulate(m: &mut Moments, weight: f64, x: f64, y: f64) {
    m[0] += weight * x;
    m[1] += weight * y;
    m[2] += weight * x * x;
    m[3] += weight * y * y;
    m[4] += weight * x * y;
}

fn local_ssim([mean_a, mean_b, sq_a, sq_b, prod]: Moments) -> f64 {
    let var_a = sq_a - mean_a * mean_a;
    let var_b = sq_b - mean_b * mean_b;
    let cov = prod - mean_a * mean_b;
    ((2.0 * mean_a * mean_b + C1) * (2.0 * cov + C2))
        / ((mean_a * mean_a + mean_b * mean_b + C1) * (var_a + var_b + C2))
}

fn gaussian_kernel() -> [f64; WINDOW] {
    let centre = (WINDOW / 2) as f64;
    let mut kernel = [0.0; WINDOW];
    for (i, k) in kernel.iter_mut().enumerate() {
        let d = i as f64 - centre;
        *k = (-d * d / (2.0 * SIGMA * SIGMA)).exp();
    }
    let sum: f64 = kernel.iter().sum();
    kernel.map(|k| k / sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_is_normalized_and_symmetric() {
        let k = gaussian_kernel();
        assert!((k.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        for i in 0..WINDOW {
            assert_eq!(k[i], k[WINDOW - 1 - i]);
        }
        assert!(k[5] > k[4] && k[4] > k[0]);
    }

    #[test]
    fn small_image_uses_one_uniform_window() {
        // a = [0, 100], b = [0, 50]: means 50 and 25, variances 2500 and 625,
        // covariance mean(ab) - 50*25 = 2500 - 1250 = 1250.
        let expected = ((2.0 * 50.0 * 25.0 + C1) * (2.0 * 1250.0 + C2))
            / ((2500.0 + 625.0 + C1) * (2500.0 + 625.0 + C2));
        let got = mean_ssim(&[0, 100], &[0, 50], 2, 1);
        assert!((got - expected).abs() < 1e-12, "{got} vs {expected}");
    }

    #[test]
    fn constant_images_give_the_luminance_term_alone() {
        // Zero variances and covariance: every window gives
        // (2*100*110 + C1) C2 / ((100² + 110² + C1) C2) = (22000 + C1) / (22100 + C1).
        let (a, b) = (vec![100u8; 14 * 12], vec![110u8; 14 * 12]);
        let expected = (22000.0 + C1) / (22100.0 + C1);
        assert!((mean_ssim(&a, &b, 14, 12) - expected).abs() < 1e-12);
    }

    #[test]
    fn separable_ring_matches_direct_two_dimensional_windows() {
        let (width, height) = (15, 13);
        let a: Vec<u8> = (0..width * height).map(|i| (i * 37 % 251) as u8).collect();
        let b: Vec<u8> = (0..width * height).map(|i| (i * 11 % 241) as u8).collect();
        let g = gaussian_kernel();
        let mut total = 0.0;
        let positions = (width - WINDOW + 1) * (height - WINDOW + 1);
        for y0 in 0..=height - WINDOW {
            for x0 in 0..=width - WINDOW {
                let mut m = [0.0; 5];
                for dy in 0..WINDOW {
                    for dx in 0..WINDOW {
                        let i = (y0 + dy) * width + x0 + dx;
                        accumulate(&mut m, g[dy] * g[dx], f64::from(a[i]), f64::from(b[i]));
                    }
                }
                total += local_ssim(m);
            }
        }
        let direct = total / positions as f64;
        assert!((mean_ssim(&a, &b, width, height) - direct).abs() < 1e-9);
    }

    #[test]
    fn constant_images_of_equal_value_are_identical() {
        let a = vec![77u8; 20 * 15];
        assert!((mean_ssim(&a, &a, 20, 15) - 1.0).abs() < 1e-12);
    }
}
