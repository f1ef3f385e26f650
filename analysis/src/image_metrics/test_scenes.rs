//! Synthetic but realistic pictures for the metrics' tests, drawn by hand (analysis
//! depends on no renderer): shaded spheres over a floor and a flat sky, and the
//! transformations an outside renderer's conventions or a broken run would apply.

use super::RgbImage;
use crate::prng::SplitMix64;

/// Spheres seen from the front: centre and radius as fractions of the picture, and
/// their colour. Placed off-centre so that no mirror image matches.
const SPHERES: [([f64; 3], [f64; 3]); 4] = [
    ([0.30, 0.40, 0.18], [200.0, 60.0, 50.0]),
    ([0.62, 0.55, 0.22], [70.0, 170.0, 80.0]),
    ([0.45, 0.74, 0.12], [60.0, 90.0, 200.0]),
    ([0.82, 0.28, 0.10], [220.0, 200.0, 60.0]),
];

/// Where the floor starts, as a fraction of the height.
const HORIZON: f64 = 0.78;

/// Samples per pixel along each axis: anti-aliased edges, as renderers draw them.
const SUPERSAMPLING: u32 = 4;

/// Four diffuse spheres with a highlight each, lit from the upper left, over a floor
/// that brightens towards the viewer and a flat sky of colour `sky`.
pub(crate) fn discs(width: u32, height: u32, sky: [u8; 3]) -> RgbImage {
    let scale = f64::from(width.min(height));
    let light = normalize([-0.5, -0.6, 0.62]);
    // The Blinn half vector between the light and the viewer (0, 0, 1).
    let half = normalize([light[0], light[1], light[2] + 1.0]);
    let shade = |px: f64, py: f64| -> [f64; 3] {
        for &([cx, cy, r], colour) in SPHERES.iter().rev() {
            let (dx, dy) = (
                (px - cx * f64::from(width)) / (r * scale),
                (py - cy * f64::from(height)) / (r * scale),
            );
            let d2 = dx * dx + dy * dy;
            if d2 < 1.0 {
                let n = [dx, dy, (1.0 - d2).sqrt()];
                let diffuse = 0.15 + 0.85 * dot(n, light).max(0.0);
                let highlight = 120.0 * dot(n, half).max(0.0).powi(40);
                return colour.map(|c| c * diffuse + highlight);
            }
        }
        let v = py / f64::from(height);
        if v >= HORIZON {
            let depth = (v - HORIZON) / (1.0 - HORIZON);
            [
                90.0 + 60.0 * depth,
                80.0 + 50.0 * depth,
                60.0 + 30.0 * depth,
            ]
        } else {
            sky.map(f64::from)
        }
    };
    let n = f64::from(SUPERSAMPLING * SUPERSAMPLING);
    let mut data = Vec::with_capacity(3 * (width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let mut sum = [0.0; 3];
            for sy in 0..SUPERSAMPLING {
                for sx in 0..SUPERSAMPLING {
                    let px = f64::from(x) + (f64::from(sx) + 0.5) / f64::from(SUPERSAMPLING);
                    let py = f64::from(y) + (f64::from(sy) + 0.5) / f64::from(SUPERSAMPLING);
                    for (s, v) in sum.iter_mut().zip(shade(px, py)) {
                        *s += v;
                    }
                }
            }
            data.extend(sum.map(|s| (s / n).round().clamp(0.0, 255.0) as u8));
        }
    }
    RgbImage::new(width, height, data).expect("valid image")
}

/// Each channel value plus independent uniform noise in `-amplitude..=amplitude`.
pub(crate) fn with_noise(img: &RgbImage, amplitude: i32, seed: u64) -> RgbImage {
    let mut rng = SplitMix64::new(seed);
    let span = (2 * amplitude + 1) as usize;
    map_values(img, |v| {
        (i32::from(v) + rng.below(span) as i32 - amplitude).clamp(0, 255) as u8
    })
}

/// Every value through `f`.
pub(crate) fn map_values(img: &RgbImage, mut f: impl FnMut(u8) -> u8) -> RgbImage {
    RgbImage::new(
        img.width,
        img.height,
        img.data.iter().map(|&v| f(v)).collect(),
    )
    .expect("valid image")
}

/// A display gamma applied on top: `255 (v / 255)^(1 / gamma)`.
pub(crate) fn gamma(img: &RgbImage, gamma: f64) -> RgbImage {
    map_values(img, |v| {
        (255.0 * (f64::from(v) / 255.0).powf(1.0 / gamma)).round() as u8
    })
}

/// Brighter lights: every value times `gain`, clipped at white.
pub(crate) fn gain(img: &RgbImage, gain: f64) -> RgbImage {
    map_values(img, |v| (f64::from(v) * gain).round().min(255.0) as u8)
}

/// Left and right swapped.
pub(crate) fn mirrored(img: &RgbImage) -> RgbImage {
    let row = 3 * img.width as usize;
    let data = img
        .data
        .chunks_exact(row)
        .flat_map(|r| {
            r.chunks_exact(3)
                .rev()
                .flatten()
                .copied()
                .collect::<Vec<_>>()
        })
        .collect();
    RgbImage::new(img.width, img.height, data).expect("valid image")
}

/// Top and bottom swapped.
pub(crate) fn upside_down(img: &RgbImage) -> RgbImage {
    let row = 3 * img.width as usize;
    let data = img
        .data
        .chunks_exact(row)
        .rev()
        .flatten()
        .copied()
        .collect();
    RgbImage::new(img.width, img.height, data).expect("valid image")
}

/// Moved `dx` pixels to the right, the uncovered columns repeating the first one.
pub(crate) fn shifted(img: &RgbImage, dx: u32) -> RgbImage {
    let (width, row) = (img.width as usize, 3 * img.width as usize);
    let data = img
        .data
        .chunks_exact(row)
        .flat_map(|r| {
            (0..width).flat_map(move |x| {
                let from = x.saturating_sub(dx as usize);
                r[3 * from..3 * from + 3].iter().copied()
            })
        })
        .collect();
    RgbImage::new(img.width, img.height, data).expect("valid image")
}

/// Independent uniform values in 0..=255: a picture of nothing.
pub(crate) fn noise(width: u32, height: u32, seed: u64) -> RgbImage {
    let mut rng = SplitMix64::new(seed);
    let data = (0..3 * width * height)
        .map(|_| rng.below(256) as u8)
        .collect();
    RgbImage::new(width, height, data).expect("valid image")
}

/// One flat colour.
pub(crate) fn uniform(width: u32, height: u32, rgb: [u8; 3]) -> RgbImage {
    let data = (0..width * height).flat_map(|_| rgb).collect();
    RgbImage::new(width, height, data).expect("valid image")
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let len = dot(v, v).sqrt();
    v.map(|c| c / len)
}
