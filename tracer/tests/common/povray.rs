//! POV-Ray runs for the POV writer's ignored tests: render a POV-Ray file as
//! `scripts/povray-compare.sh` does, compare two pictures, and the SPD's file with its
//! textures as its NFF states them. Shared by tracer/tests/pov_writer_povray.rs (rtprof's
//! files written from the SPD's NFF files) and spd/tests/pov_povray.rs (written from the
//! scenes the `spd` crate generates), which includes this file by path (tracer's tests
//! cannot reach the spd crate). Self-contained: std, `image` and `flate2`.

use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The seven classic SPD scenes, whose POV-Ray files the SPD wrote.
pub const SCENES: [&str; 7] = [
    "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
];

/// The scenes whose SPD textures hold values the NFF `f` line cannot (see
/// [`as_its_nff_states`]).
pub const TEXTURES_BEYOND_NFF: [&str; 4] = ["balls", "gears", "mount", "rings"];

/// Picture width and height.
pub const SIZE: u32 = 128;

/// The SPD's POV-Ray file of scene `name` (`../shared/peers/povray/NAME.pov.gz` beside
/// the project), decompressed.
pub fn spd_pov_file(name: &str) -> String {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/peers/povray");
    let path = dir.join(format!("{name}.pov.gz"));
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text
}

/// The POV-Ray program: `POVRAY` or `povray` on PATH.
pub fn povray() -> String {
    std::env::var("POVRAY").unwrap_or_else(|_| "povray".to_string())
}

/// The SPD's file with every texture as its NFF `f` line states it: `ambient 0`, and the
/// Phong weight equal to the reflection weight (no highlight without reflection). The
/// SPD's layout is one finish value per line inside `#declare txtNNN = texture { ... }
/// // texture txtNNN`.
pub fn as_its_nff_states(spd: &str) -> String {
    let mut out = String::with_capacity(spd.len());
    let mut texture: Vec<&str> = Vec::new();
    let mut inside = false;
    for line in spd.lines() {
        if line.starts_with("#declare ") {
            inside = true;
        }
        if !inside {
            out.push_str(line);
            out.push('\n');
            continue;
        }
        texture.push(line);
        if line.starts_with("} // texture") {
            inside = false;
            let reflection = texture
                .iter()
                .find_map(|l| l.trim().strip_prefix("reflection "))
                .map(str::trim);
            for l in texture.drain(..) {
                let t = l.trim();
                if t.starts_with("ambient ") {
                    out.push_str("        ambient 0\n");
                } else if let Some(rest) = t.strip_prefix("phong ") {
                    let size = rest.split_once("phong_size").map_or("", |(_, s)| s.trim());
                    if let Some(weight) = reflection {
                        out.push_str(&format!("        phong {weight}  phong_size {size}\n"));
                    }
                } else {
                    out.push_str(l);
                    out.push('\n');
                }
            }
        }
    }
    out
}

/// Renders `pov` text as `scripts/povray-compare.sh` does: in `dir`, under a HOME whose
/// user povray.conf is empty, POVINI and POVRAYOPT unset, `+W +H -D +FN +WT1 -A`.
/// Returns the picture's bytes, RGB 8-bit, row by row.
pub fn render(povray: &str, dir: &Path, stem: &str, pov: &str) -> Vec<u8> {
    let input = dir.join(format!("{stem}.pov"));
    let output = dir.join(format!("{stem}.png"));
    std::fs::write(&input, pov).unwrap_or_else(|e| panic!("{}: {e}", input.display()));
    let result = Command::new(povray)
        .current_dir(dir)
        .env("HOME", dir.join("home"))
        .env_remove("POVINI")
        .env_remove("POVRAYOPT")
        .arg(format!("+I{stem}.pov"))
        .arg(format!("+O{stem}.png"))
        .arg(format!("+W{SIZE}"))
        .arg(format!("+H{SIZE}"))
        .args(["-D", "+FN", "+WT1", "-A"])
        .output()
        .unwrap_or_else(|e| panic!("{povray}: {e} (install Debian's povray or set POVRAY)"));
    let log = String::from_utf8_lossy(&result.stderr);
    assert!(
        result.status.success() && output.is_file(),
        "POV-Ray failed on {stem} ({}):\n{log}",
        result.status
    );
    assert!(!log.contains("Parse Error"), "{stem}:\n{log}");
    image::open(&output)
        .unwrap_or_else(|e| panic!("{}: {e}", output.display()))
        .to_rgb8()
        .into_raw()
}

/// Root mean square of the channel differences, 0-255 scale.
pub fn rms(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2))
        .sum();
    (sum / a.len() as f64).sqrt()
}

/// A fresh scratch directory with the empty user povray.conf.
pub fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-{tag}-{}", std::process::id()));
    let conf = dir.join("home/.povray/3.7");
    std::fs::create_dir_all(&conf).unwrap_or_else(|e| panic!("{}: {e}", conf.display()));
    std::fs::write(conf.join("povray.conf"), "").unwrap_or_else(|e| panic!("{e}"));
    dir
}
