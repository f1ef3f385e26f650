//! `rtprof record --baseline DIR`: the differential flamegraphs from an earlier record
//! (its directory: its folded stacks and record.json) to this one, as `rtprof profile`
//! draws them between two variants: what grew, drawn on this run, and what shrank or
//! vanished, drawn on the baseline. The baseline is read before the program runs, so
//! a wrong directory costs nothing.

use std::path::{Path, PathBuf};

use analysis::profile::folded::{DiffSide, differential_svgs};

use crate::error::RunError;
use crate::staging::save;

/// An earlier record to compare this one with.
#[derive(Clone, Debug)]
pub struct Baseline {
    pub dir: PathBuf,
    /// Its name in the titles: the directory's.
    pub label: String,
    /// Its folded stacks (`folded-P.txt`).
    pub folded: String,
    /// Its CPU seconds (record.json).
    pub cpu_seconds: f64,
}

/// Reads the baseline record in `dir`: its one `folded-*.txt` and record.json.
pub fn read_baseline(dir: &Path) -> Result<Baseline, RunError> {
    let bad = |why: String| {
        RunError::Input(format!(
            "--baseline {}: {why} (give the directory of an earlier `rtprof record`)",
            dir.display()
        ))
    };
    let entries = std::fs::read_dir(dir).map_err(|e| bad(e.to_string()))?;
    let mut folded: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("folded-") && n.ends_with(".txt"))
        })
        .collect();
    folded.sort();
    let [file] = folded.as_slice() else {
        return Err(bad(format!("{} folded-*.txt files, not one", folded.len())));
    };
    let text =
        std::fs::read_to_string(file).map_err(|e| bad(format!("{}: {e}", file.display())))?;
    let json_path = dir.join("record.json");
    let json: serde_json::Value = std::fs::read(&json_path)
        .map_err(|e| e.to_string())
        .and_then(|b| serde_json::from_slice(&b).map_err(|e| e.to_string()))
        .map_err(|e| bad(format!("{}: {e}", json_path.display())))?;
    let cpu_seconds = json["cpu_seconds"]
        .as_f64()
        .filter(|s| s.is_finite() && *s >= 0.0)
        .ok_or_else(|| bad(format!("{} has no cpu_seconds", json_path.display())))?;
    let label = dir.file_name().map_or_else(
        || dir.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    Ok(Baseline {
        dir: dir.to_path_buf(),
        label,
        folded: text,
        cpu_seconds,
    })
}

/// Folded stacks with their outermost frame (the program's name, the root every stack
/// of a record has) renamed to `root`: two builds of one tracer compare frame by frame
/// even when their executables are named apart.
fn rerooted(folded: &str, root: &str) -> String {
    folded
        .lines()
        .map(|line| match line.split_once(';') {
            Some((_, rest)) => format!("{root};{rest}\n"),
            None => match line.rsplit_once(' ') {
                Some((_, count)) => format!("{root} {count}\n"),
                None => format!("{line}\n"),
            },
        })
        .collect()
}

/// Writes `flame-diff-BASE-NAME.svg` (what grew) and `…-shrunk.svg` (what shrank)
/// from the baseline to this run; returns their names.
pub fn save_record_differential(
    out: &Path,
    name: &str,
    folded: &str,
    cpu_seconds: f64,
    label: &str,
    baseline: &Baseline,
) -> Result<(String, String), RunError> {
    let before = rerooted(&baseline.folded, name);
    let svgs = differential_svgs(
        &DiffSide {
            folded: &before,
            label: &baseline.label,
            seconds_per_render: baseline.cpu_seconds,
            unit: "run",
        },
        &DiffSide {
            folded,
            label,
            seconds_per_render: cpu_seconds,
            unit: "run",
        },
        name,
    )
    .map_err(|e| RunError::Profile(e.to_string()))?;
    let stem = format!(
        "flame-diff-{}-{}",
        results::slug(&baseline.label),
        results::slug(label)
    );
    let grown = save(out, &format!("{stem}.svg"), svgs.grown.as_bytes())?;
    let shrunk = save(out, &format!("{stem}-shrunk.svg"), svgs.shrunk.as_bytes())?;
    Ok((grown, shrunk))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rtprof-diff-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_baseline_is_read_and_drawn_against_this_run() {
        let base = scratch("base");
        std::fs::write(
            base.join("folded-old.txt"),
            "old;main;hot 90\nold;main;cold 10\n",
        )
        .unwrap();
        std::fs::write(base.join("record.json"), r#"{"cpu_seconds": 2.0}"#).unwrap();
        let b = read_baseline(&base).unwrap();
        assert_eq!(b.cpu_seconds, 2.0);
        // The program renamed: its root follows this run's.
        assert_eq!(
            rerooted(&b.folded, "new"),
            "new;main;hot 90\nnew;main;cold 10\n"
        );
        let out = scratch("out");
        let (grown, shrunk) = save_record_differential(
            &out,
            "new",
            "new;main;hot 40\nnew;main;cold 10\n",
            1.0,
            "r",
            &b,
        )
        .unwrap();
        let svg = std::fs::read_to_string(out.join(&grown)).unwrap();
        assert!(svg.contains("<svg") && svg.contains("hot"), "{svg}");
        // By hand: 2 s → 1 s per run, a 2.00× speed-up.
        assert!(
            svg.contains("per run") && svg.contains("2.00\u{d7}"),
            "{svg}"
        );
        assert!(out.join(&shrunk).is_file());
        std::fs::remove_dir_all(&base).ok();
        std::fs::remove_dir_all(&out).ok();
    }

    #[test]
    fn a_directory_that_is_no_record_is_refused() {
        let dir = scratch("empty");
        let e = read_baseline(&dir).unwrap_err().to_string();
        assert!(e.contains("0 folded-*.txt files"), "{e}");
        std::fs::write(dir.join("folded-x.txt"), "x 1\n").unwrap();
        let e = read_baseline(&dir).unwrap_err().to_string();
        assert!(e.contains("record.json"), "{e}");
        let e = read_baseline(Path::new("/nonexistent/r"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--baseline /nonexistent/r:"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
