//! Writes every chart of the synthetic sample run to SVG files, to look at them:
//! the charts of the report, each scene's histograms and each variant's small one.
//!
//! `cargo run -p reports --example chart_svgs -- OUT_DIR`

use std::path::PathBuf;

use reports::charts::{self, Chart};

fn main() -> std::io::Result<()> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "charts".into()));
    std::fs::create_dir_all(&dir)?;
    let write = |name: &str, c: &Chart| std::fs::write(dir.join(format!("{name}.svg")), &c.svg);
    let results = testkit::sample_results();
    for c in charts::all(&results) {
        write(c.id, &c)?;
    }
    for scene in &results.scenes {
        if let Some(c) = charts::scene_histograms(&results, scene) {
            write(&format!("scene-{}", scene.name), &c)?;
        }
        for v in &scene.variants {
            if let Some(c) = charts::variant_histogram(scene, v) {
                write(&format!("variant-{}-{}", scene.name, v.variant), &c)?;
            }
        }
    }
    Ok(())
}
