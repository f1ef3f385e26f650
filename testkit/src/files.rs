//! The files a sample run refers to: 1x1 PNG images, gprof-layout texts and small
//! flamegraph SVGs, so that a report of the sample can embed them.

use std::path::Path;

use results::{Profile, Results};

use crate::sample::sample_results;

/// A valid 1x1 8-bit grayscale PNG (one mid-gray pixel).
pub const TINY_PNG: [u8; 67] = [
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
    0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a, 0x7e, 0x9b,
    0x55, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68, 0x00, 0x00, 0x00,
    0x82, 0x00, 0x81, 0x77, 0xcd, 0x72, 0xb6, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae,
    0x42, 0x60, 0x82,
];

/// A valid NumPy file: one `<u8` value, 0, in a 1x1 array.
pub const TINY_NPY: [u8; 136] = {
    let header =
        *b"\x93NUMPY\x01\x00\x76\x00{'descr': '<u8', 'fortran_order': False, 'shape': (1, 1), }";
    let mut out = [b' '; 136];
    let mut i = 0;
    while i < header.len() {
        out[i] = header[i];
        i += 1;
    }
    out[127] = b'\n';
    let mut j = 128;
    while j < 136 {
        out[j] = 0;
        j += 1;
    }
    out
};

/// Every relative path the results refer to: images, texts and SVGs.
pub fn referenced_files(results: &Results) -> Vec<String> {
    let mut paths = Vec::new();
    for scene in &results.scenes {
        for v in &scene.variants {
            paths.extend(v.image.iter().cloned());
            paths.extend(v.heat_map.iter().cloned());
        }
        if let Some(hw) = &scene.hardware {
            paths.extend(hw.emulator_image.iter().cloned());
            paths.extend(hw.software_image.iter().cloned());
        }
        for maps in &scene.pixel_maps {
            paths.push(format!("{}/pixel-stats.json", maps.directory));
            for map in &maps.maps {
                paths.push(format!("{}/{}", maps.directory, map.npy));
                paths.push(format!("{}/{}", maps.directory, map.png));
            }
        }
    }
    if let Some(p) = &results.profile {
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            paths.push(profile.flat_text.clone());
            paths.push(profile.callgraph_text.clone());
            paths.push(profile.flame_svg.clone());
        }
        paths.extend(p.diff_flame_svg.iter().cloned());
    }
    paths
}

/// A gprof-layout flat profile text of `profile`.
fn flat_text(profile: &Profile) -> String {
    let mut out = String::from(
        "Flat profile:\n\nEach sample counts as 0.001 seconds.\n  %   cumulative   self              self     total\n time   seconds   seconds    calls  ms/call  ms/call  name\n",
    );
    let mut cumulative = 0.0;
    for row in &profile.flat {
        cumulative += row.self_seconds;
        let calls = row.calls.map_or_else(String::new, |c| c.to_string());
        out += &format!(
            "{:6.2} {:9.2} {:8.2} {:>12} {:>8} {:>8}  {}\n",
            row.percent, cumulative, row.self_seconds, calls, "", "", row.name
        );
    }
    out
}

/// A gprof-layout call graph text (a short one).
fn callgraph_text(profile: &Profile) -> String {
    let mut out = String::from("Call graph\n\nindex % time    self  children    called     name\n");
    for (i, row) in profile.flat.iter().enumerate() {
        out += &format!(
            "[{}] {:8.1} {:8.2} {:8.2} {:>12}     {} [{}]\n-----------------------------------------------\n",
            i + 1,
            row.percent,
            row.self_seconds,
            (row.total_seconds - row.self_seconds).max(0.0),
            row.calls.map_or_else(String::new, |c| c.to_string()),
            row.name,
            i + 1
        );
    }
    out
}

/// A small flamegraph-like SVG of `profile`'s flat rows.
fn flame_svg(title: &str, rows: &[(String, f64)]) -> String {
    let mut out = format!(
        "<?xml version=\"1.0\" standalone=\"no\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1000\" height=\"{}\" viewBox=\"0 0 1000 {}\"><rect width=\"100%\" height=\"100%\" fill=\"#f8f8f0\"/><text x=\"500\" y=\"20\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"15\">{}</text>",
        60 + rows.len() * 18,
        60 + rows.len() * 18,
        title
    );
    let mut x = 0.0;
    for (i, (name, percent)) in rows.iter().enumerate() {
        let width = 10.0 * percent;
        let y = 30 + (rows.len() - i) * 18;
        out += &format!(
            "<g><title>{name} ({percent:.1} %)</title><rect x=\"{x:.1}\" y=\"{y}\" width=\"{width:.1}\" height=\"16\" fill=\"rgb(230,{},50)\"/><text x=\"{:.1}\" y=\"{}\" font-family=\"monospace\" font-size=\"11\">{}</text></g>",
            100 + (i * 11) % 120,
            x + 3.0,
            y + 12,
            name.rsplit("::").next().unwrap_or(name)
        );
        x += width * 0.3;
    }
    out += "</svg>\n";
    out
}

/// Writes the files [`sample_results`] refers to under `dir`: a valid 1x1 PNG for every
/// image, gprof texts and small flamegraph SVGs.
pub fn write_sample_files(dir: &Path) -> std::io::Result<()> {
    let results = sample_results();
    let write = |rel: &str, bytes: &[u8]| -> std::io::Result<()> {
        let path = dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(path, bytes)
    };
    for rel in referenced_files(&results) {
        if rel.ends_with(".png") {
            write(&rel, &TINY_PNG)?;
        } else if rel.ends_with(".npy") {
            write(&rel, &TINY_NPY)?;
        } else if rel.ends_with("pixel-stats.json") {
            write(&rel, b"{}\n")?;
        }
    }
    if let Some(p) = &results.profile {
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            write(&profile.flat_text, flat_text(profile).as_bytes())?;
            write(&profile.callgraph_text, callgraph_text(profile).as_bytes())?;
            let rows: Vec<(String, f64)> = profile
                .flat
                .iter()
                .map(|r| (r.name.clone(), r.percent))
                .collect();
            let title = format!("Flame Graph: {} {}", p.scene, profile.variant);
            write(&profile.flame_svg, flame_svg(&title, &rows).as_bytes())?;
        }
        if let Some(diff) = &p.diff_flame_svg {
            let rows: Vec<(String, f64)> = p
                .baseline
                .flat
                .iter()
                .map(|r| (r.name.clone(), r.percent))
                .collect();
            let title = format!("Differential flame graph: {} baseline to bvh", p.scene);
            write(diff, flame_svg(&title, &rows).as_bytes())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_files_cover_every_reference() {
        let dir = std::env::temp_dir().join(format!("rtprof-sample-{}", std::process::id()));
        write_sample_files(&dir).expect("write");
        for rel in referenced_files(&sample_results()) {
            assert!(dir.join(&rel).is_file(), "{rel}");
        }
        let png = std::fs::read(dir.join("images/balls4-baseline.png")).expect("png");
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
