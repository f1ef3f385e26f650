//! Writes the report of the synthetic sample run, to look at it: the sample's files,
//! made-up per-pixel maps (a pattern spread over each map's range, as NumPy arrays,
//! which the report draws, and drawn as the runner draws maps), `report.html` and
//! `report.pdf`.
//!
//! `cargo run -p reports --example sample_report -- OUT_DIR`

use std::path::PathBuf;

use reports::Run;
use reports::pixel_maps::{Legend, false_colour};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "sample-report".into()),
    );
    std::fs::create_dir_all(&dir)?;
    testkit::write_sample_files(&dir)?;
    let results = testkit::sample_results();
    for scene in &results.scenes {
        for maps in &scene.pixel_maps {
            let (columns, rows) = (maps.columns, maps.rows);
            for map in &maps.maps {
                // Concentric rings around the centre, from the map's minimum to its
                // maximum.
                let counts: Vec<u64> = (0..rows)
                    .flat_map(|y| (0..columns).map(move |x| (x, y)))
                    .map(|(x, y)| {
                        let dx = f64::from(x) - f64::from(columns) / 2.0;
                        let dy = f64::from(y) - f64::from(rows) / 2.0;
                        let wave = 0.5 + 0.5 * ((dx * dx + dy * dy).sqrt() / 9.0).sin();
                        map.min + (wave * wave * (map.max - map.min) as f64).round() as u64
                    })
                    .collect();
                let npy = reports::npy::npy_bytes(rows as usize, columns as usize, &counts)?;
                let npy_path = dir.join(&maps.directory).join(&map.npy);
                std::fs::create_dir_all(npy_path.parent().unwrap_or(&dir))?;
                std::fs::write(npy_path, npy)?;
                let values: Vec<f64> = counts.iter().map(|&v| v as f64).collect();
                let legend = Legend {
                    title: map.key.clone(),
                    unit: map.unit.clone(),
                    min: map.min as f64,
                    max: map.max as f64,
                };
                let path = dir.join(&maps.directory).join(&map.png);
                std::fs::create_dir_all(path.parent().unwrap_or(&dir))?;
                false_colour(&values, columns, rows, &legend).save(&path)?;
            }
        }
    }
    std::fs::write(
        dir.join("results.json"),
        serde_json::to_string_pretty(&results)?,
    )?;
    let run = Run {
        label: "sample".to_string(),
        results,
        base_dir: dir.clone(),
    };
    std::fs::write(
        dir.join("report.html"),
        reports::html::render_html(std::slice::from_ref(&run))?,
    )?;
    std::fs::write(dir.join("report.pdf"), reports::pdf::render_pdf(&[run])?)?;
    println!("{}", dir.display());
    Ok(())
}
