//! One sample of a finished job's per-pixel maps, for the page's hover read-out: the
//! value of every map of every variant at an image pixel, written by
//! `reports::format` (the maps are NumPy arrays beside their pictures).

use std::path::Path;

use reports::format;
use serde::Serialize;

use crate::error::ApiError;
use crate::store::safe_join;

/// What a pixel holds, as the page shows it.
#[derive(Clone, Debug, Serialize)]
pub struct PixelValues {
    /// "pixel (12, 34), sample (12, 34)".
    pub position: String,
    pub variants: Vec<PixelVariant>,
}

/// One variant's maps at the pixel: `[key, value with its unit]`.
#[derive(Clone, Debug, Serialize)]
pub struct PixelVariant {
    pub variant: String,
    pub values: Vec<[String; 2]>,
}

/// The maps of scene `scene` (its index in the run) at pixel (`x`, `y`) of its image.
pub fn at(
    results: &results::Results,
    dir: &Path,
    scene: usize,
    x: u32,
    y: u32,
) -> Result<PixelValues, ApiError> {
    let s = results.scenes.get(scene).ok_or_else(|| {
        ApiError::invalid(format!(
            "scene {scene}: the run has {}",
            format::plural(results.scenes.len(), "scene")
        ))
    })?;
    if x >= s.width || y >= s.height {
        return Err(ApiError::invalid(format!(
            "pixel ({x}, {y}) is outside the {} image",
            format::size(s.width, s.height)
        )));
    }
    if s.pixel_maps.is_empty() {
        return Err(ApiError::invalid(format!(
            "{} has no per-pixel maps: run the job with pixel_maps",
            s.name
        )));
    }
    let mut sample = (0, 0);
    let mut variants = Vec::new();
    for set in &s.pixel_maps {
        // The samples cover the image (SPD corner sampling has one more row and
        // column than pixels): the sample under the pixel, scaled.
        let column = (u64::from(x) * u64::from(set.columns) / u64::from(s.width)) as usize;
        let row = (u64::from(y) * u64::from(set.rows) / u64::from(s.height)) as usize;
        sample = (column, row);
        let mut values = Vec::new();
        for map in &set.maps {
            let rel = format!("{}/{}", set.directory.trim_end_matches('/'), map.npy);
            let path = safe_join(dir, rel.trim_start_matches('/'))?;
            let bytes = std::fs::read(&path)
                .map_err(|e| ApiError::internal(format!("cannot read {rel}: {e}")))?;
            let array = reports::npy::read_npy(&bytes)
                .map_err(|e| ApiError::internal(format!("{rel}: {e}")))?;
            let value = array
                .values
                .get(row * array.columns + column)
                .copied()
                .filter(|_| row < array.rows && column < array.columns)
                .unwrap_or(f64::NAN);
            let text = match map.dtype.contains('f') {
                true => format::quantity(value),
                false if value.is_finite() && value >= 0.0 => format::count(value as u64),
                false => format::DASH.to_string(),
            };
            let unit = match map.unit.is_empty() {
                true => String::new(),
                false => format!(" {}", map.unit),
            };
            values.push([map.key.clone(), format!("{text}{unit}")]);
        }
        variants.push(PixelVariant {
            variant: set.variant.to_string(),
            values,
        });
    }
    Ok(PixelValues {
        position: format!(
            "pixel ({}, {}), sample ({}, {})",
            format::count(u64::from(x)),
            format::count(u64::from(y)),
            format::count(sample.0 as u64),
            format::count(sample.1 as u64)
        ),
        variants,
    })
}
