//! Validation of a results file on read: a results file is input like an NFF file.
//!
//! Every number a report computes with is checked to be finite and within a range a
//! real run can produce, every list is bounded (so the work of a report or the gate
//! is bounded whatever the file says), and every file the results reference stays
//! inside the results directory. An error names the place by its JSON path
//! (`scenes[3].variants[1].samples[7]`).

use std::collections::BTreeSet;
use std::fmt::Display;
use std::path::{Component, Path};

use crate::error::ResultsError;
use crate::hardware::{
    HardwareResult, HwErrors, HwFigures, HwRow, SceneHardware, SynthBlock, Synthesis,
};
use crate::schema::{
    AmdahlFigures, Band, Estimate, Failure, FlatRow, Profile, ProfileResult, Quality, Results,
    SceneResult, SuiteInfo, VariantResult,
};

/// The limits of a results file ([`crate::limits`]).
pub use crate::limits;

use limits::*;

/// A number as a message shows it: exponent form when very large or small.
fn shown(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// Walks a results value, keeping the JSON path of where it is.
struct Check {
    path: String,
}

type Checked = Result<(), ResultsError>;

impl Check {
    fn err(&self, message: impl Into<String>) -> ResultsError {
        ResultsError::invalid(self.path.trim_start_matches('.'), message)
    }

    /// Runs `f` one step deeper: `.field` or `[index]`.
    fn at(&mut self, step: impl Display, f: impl FnOnce(&mut Self) -> Checked) -> Checked {
        let len = self.path.len();
        self.path.push_str(&step.to_string());
        let r = f(self);
        self.path.truncate(len);
        r
    }

    fn field(&mut self, name: &str, f: impl FnOnce(&mut Self) -> Checked) -> Checked {
        self.at(format_args!(".{name}"), f)
    }

    /// Each element of a list of at most `max`, at `[i]`.
    fn each<T>(
        &mut self,
        name: &str,
        items: &[T],
        max: usize,
        mut f: impl FnMut(&mut Self, &T) -> Checked,
    ) -> Checked {
        self.field(name, |c| {
            if items.len() > max {
                return Err(c.err(format!(
                    "{} entries, more than the {max} a results file may hold",
                    items.len()
                )));
            }
            for (i, item) in items.iter().enumerate() {
                c.at(format_args!("[{i}]"), |c| f(c, item))?;
            }
            Ok(())
        })
    }

    fn number(&self, x: f64, unit: &str, low: f64, high: f64) -> Checked {
        if !x.is_finite() {
            Err(self.err(format!("{x} is not a finite number")))
        } else if x < low {
            Err(self.err(format!(
                "{}{unit} is below the plausible range (at least {}{unit})",
                shown(x),
                shown(low)
            )))
        } else if x > high {
            Err(self.err(format!(
                "{}{unit} is beyond the plausible range (at most {}{unit})",
                shown(x),
                shown(high)
            )))
        } else {
            Ok(())
        }
    }

    fn seconds(&mut self, name: &str, x: f64) -> Checked {
        self.field(name, |c| c.number(x, " s", 0.0, MAX_SECONDS))
    }

    fn ratio(&mut self, name: &str, x: f64) -> Checked {
        self.field(name, |c| c.number(x, "", 0.0, MAX_RATIO))
    }

    fn count(&mut self, name: &str, n: u64) -> Checked {
        self.field(name, |c| {
            if n > MAX_COUNT {
                Err(c.err(format!(
                    "{n} is beyond the exact range of counts (at most 2^53)"
                )))
            } else {
                Ok(())
            }
        })
    }

    fn text(&mut self, name: &str, s: &str, max: usize) -> Checked {
        self.field(name, |c| {
            if s.len() > max {
                Err(c.err(format!("{} bytes of text, more than {max}", s.len())))
            } else {
                Ok(())
            }
        })
    }

    /// A file the results reference: relative, without `..` or a root, so that it
    /// stays inside the results directory.
    fn file(&mut self, name: &str, path: &str) -> Checked {
        self.field(name, |c| {
            if path.is_empty() || path.len() > MAX_NAME {
                return Err(c.err(format!(
                    "a file path must have 1 to {MAX_NAME} bytes, not {}",
                    path.len()
                )));
            }
            // Backslashes and drive letters would leave the directory on Windows.
            if path.contains(['\\', '\0', ':']) {
                return Err(c.err(format!(
                    "file path '{}' has a character a portable relative path may not hold (\\, :, NUL)",
                    path.escape_debug()
                )));
            }
            let inside = Path::new(path)
                .components()
                .all(|part| matches!(part, Component::Normal(_) | Component::CurDir));
            if inside {
                Ok(())
            } else {
                Err(c.err(format!(
                    "file path '{}' leaves the results directory (it must be relative, without '..')",
                    path.escape_debug()
                )))
            }
        })
    }

    fn optional_file(&mut self, name: &str, path: Option<&str>) -> Checked {
        path.map_or(Ok(()), |p| self.file(name, p))
    }

    fn estimate(&mut self, name: &str, e: &Estimate, high: f64, unit: &str) -> Checked {
        self.field(name, |c| {
            for (part, x) in [("low", e.low), ("median", e.median), ("high", e.high)] {
                c.field(part, |c| c.number(x, unit, 0.0, high))?;
            }
            if e.low <= e.median && e.median <= e.high {
                Ok(())
            } else {
                Err(c.err(format!(
                    "the interval [{}, {}] does not hold its median {}",
                    e.low, e.high, e.median
                )))
            }
        })
    }

    fn size(&mut self, width: u32, height: u32) -> Checked {
        tracer::Limits::default()
            .check_size(u64::from(width), u64::from(height))
            .map_err(|e| self.err(e.to_string()))
    }

    fn band(&mut self, name: &str, band: Band, rms: f64) -> Checked {
        self.field(name, |c| {
            if Band::of(rms) == band {
                Ok(())
            } else {
                Err(c.err(format!(
                    "'{band}' is not the band of RMS {rms} ('{}')",
                    Band::of(rms)
                )))
            }
        })
    }
}

fn check_suite(c: &mut Check, s: &SuiteInfo) -> Checked {
    c.text("name", &s.name, MAX_NAME)?;
    c.field("threads", |c| {
        if (1..=MAX_THREADS).contains(&s.threads) {
            Ok(())
        } else {
            Err(c.err(format!("{} threads: 1 to {MAX_THREADS}", s.threads)))
        }
    })?;
    unique_variants(
        c,
        "variants",
        s.variants.iter().map(|v| v.as_str()),
        s.variants.len(),
    )?;
    c.field("timing", |c| {
        let t = &s.timing;
        c.seconds("min_seconds", t.min_seconds)?;
        c.field("max_repeats", |c| {
            if (1..=MAX_SAMPLES as u32).contains(&t.max_repeats) {
                Ok(())
            } else {
                Err(c.err(format!("{}: 1 to {MAX_SAMPLES}", t.max_repeats)))
            }
        })?;
        c.field("min_repeats", |c| {
            if (1..=MAX_SAMPLES as u32).contains(&t.min_repeats) {
                Ok(())
            } else {
                Err(c.err(format!("{}: 1 to {MAX_SAMPLES}", t.min_repeats)))
            }
        })?;
        c.field("bootstrap_resamples", |c| {
            if (1..=MAX_RESAMPLES).contains(&t.bootstrap_resamples) {
                Ok(())
            } else {
                Err(c.err(format!("{}: 1 to {MAX_RESAMPLES}", t.bootstrap_resamples)))
            }
        })?;
        c.field("confidence", |c| {
            if t.confidence > 0.0 && t.confidence < 1.0 {
                Ok(())
            } else {
                Err(c.err(format!("{} is not a confidence (0 to 1)", t.confidence)))
            }
        })
    })?;
    if let Some(shard) = s.shard {
        c.field("shard", |c| {
            if shard.index >= 1 && shard.index <= shard.count {
                Ok(())
            } else {
                Err(c.err(format!("shard {shard}: the index must be 1 to the count")))
            }
        })?;
    }
    c.seconds("wall_seconds", s.wall_seconds)
}

/// A list of variant names without repeats.
fn unique_variants<'a>(
    c: &mut Check,
    name: &str,
    names: impl Iterator<Item = &'a str>,
    len: usize,
) -> Checked {
    c.field(name, |c| {
        if len > MAX_VARIANTS {
            return Err(c.err(format!(
                "{len} variants, more than the {MAX_VARIANTS} a results file may hold"
            )));
        }
        let mut seen = BTreeSet::new();
        for (i, n) in names.enumerate() {
            if !seen.insert(n) {
                return c.at(format_args!("[{i}]"), |c| {
                    Err(c.err(format!("variant '{n}' appears twice")))
                });
            }
        }
        Ok(())
    })
}

fn check_quality(c: &mut Check, q: &Quality) -> Checked {
    c.field("rms", |c| c.number(q.rms, "", 0.0, MAX_RMS))?;
    c.band("band", q.band, q.rms)?;
    if let Some(p) = q.psnr {
        c.field("psnr", |c| c.number(p, " dB", 0.0, MAX_PSNR_DB))?;
    }
    c.field("ssim", |c| c.number(q.ssim, "", -1.0, 1.0))?;
    c.field("max_abs_diff", |c| {
        if q.max_abs_diff <= 255 {
            Ok(())
        } else {
            Err(c.err(format!("{} is beyond 255", q.max_abs_diff)))
        }
    })
}

fn check_counts(c: &mut Check, counts: &std::collections::BTreeMap<String, u64>) -> Checked {
    c.field("counts", |c| {
        if counts.len() > MAX_ROWS {
            return Err(c.err(format!("{} counters, more than {MAX_ROWS}", counts.len())));
        }
        for (key, &n) in counts {
            if key.len() > MAX_NAME {
                return Err(c.err(format!("a counter name of {} bytes", key.len())));
            }
            c.count(&format!("\"{}\"", key.escape_debug()), n)?;
        }
        Ok(())
    })
}

fn check_variant(c: &mut Check, v: &VariantResult, pixels: u64) -> Checked {
    c.estimate("time", &v.time, MAX_SECONDS, " s")?;
    c.each("samples", &v.samples, MAX_SAMPLES, |c, &x| {
        c.number(x, " s", 0.0, MAX_SECONDS)
    })?;
    if let Some(p) = v.preprocessing_seconds {
        c.seconds("preprocessing_seconds", p)?;
    }
    if let Some(s) = v.speedup {
        c.ratio("speedup", s)?;
    }
    check_counts(c, &v.counts)?;
    c.optional_file("image", v.image.as_deref())?;
    c.optional_file("heat_map", v.heat_map.as_deref())?;
    if let Some(q) = &v.quality {
        c.field("quality", |c| check_quality(c, q))?;
    }
    c.field("histogram", |c| {
        if !(v.histogram.is_empty() || v.histogram.len() == 256) {
            return Err(c.err(format!(
                "{} bins: a gray histogram has 256 (or none)",
                v.histogram.len()
            )));
        }
        // Saturating: a sum past u64 is over `pixels` anyway.
        let total = v.histogram.iter().fold(0u64, |a, &b| a.saturating_add(b));
        if total > pixels {
            return Err(c.err(format!(
                "{total} pixels counted, more than the image's {pixels}"
            )));
        }
        Ok(())
    })
}

fn check_scene_hardware(c: &mut Check, h: &SceneHardware) -> Checked {
    c.count("primitives", h.primitives)?;
    c.count("cycles", h.cycles)?;
    c.seconds("seconds", h.seconds)?;
    c.estimate("software_seconds", &h.software_seconds, MAX_SECONDS, " s")?;
    c.ratio("speedup", h.speedup)?;
    c.field("emulator_rms", |c| {
        c.number(h.emulator_rms, "", 0.0, MAX_RMS)
    })?;
    c.band("emulator_band", h.emulator_band, h.emulator_rms)?;
    c.optional_file("emulator_image", h.emulator_image.as_deref())?;
    c.optional_file("software_image", h.software_image.as_deref())
}

fn check_scene(c: &mut Check, s: &SceneResult) -> Checked {
    c.text("name", &s.name, MAX_NAME)?;
    c.text("source", &s.source, MAX_NAME)?;
    let max_primitives = tracer::Limits::default().max_primitives;
    c.field("primitives", |c| {
        if s.primitives <= max_primitives {
            Ok(())
        } else {
            Err(c.err(format!(
                "{} primitives, more than a scene may hold ({max_primitives})",
                s.primitives
            )))
        }
    })?;
    c.field("primitive_counts", |c| {
        if s.primitive_counts.len() > MAX_VARIANTS {
            return Err(c.err(format!("{} kinds", s.primitive_counts.len())));
        }
        for (kind, &n) in &s.primitive_counts {
            if kind.len() > MAX_NAME || n > max_primitives {
                return Err(c.err(format!(
                    "'{}': {n} is not a primitive count",
                    kind.escape_debug()
                )));
            }
        }
        Ok(())
    })?;
    c.size(s.width, s.height)?;
    unique_variants(
        c,
        "variants",
        s.variants.iter().map(|v| v.variant.as_str()),
        s.variants.len(),
    )?;
    let pixels = u64::from(s.width) * u64::from(s.height);
    c.each("variants", &s.variants, MAX_VARIANTS, |c, v| {
        check_variant(c, v, pixels)
    })?;
    if let Some(h) = &s.hardware {
        c.field("hardware", |c| check_scene_hardware(c, h))?;
    }
    Ok(())
}

fn check_flat_rows(c: &mut Check, rows: &[FlatRow]) -> Checked {
    c.each("flat", rows, MAX_ROWS, |c, r| {
        c.text("name", &r.name, MAX_NAME)?;
        c.field("percent", |c| c.number(r.percent, " %", 0.0, 100.0))?;
        c.seconds("self_seconds", r.self_seconds)?;
        c.seconds("total_seconds", r.total_seconds)?;
        if let Some(p) = r.inclusive_percent {
            c.field("inclusive_percent", |c| c.number(p, " %", 0.0, 100.0))?;
        }
        for (name, interval) in [
            ("self_interval", r.self_interval),
            ("inclusive_interval", r.inclusive_interval),
        ] {
            if let Some([lo, hi]) = interval {
                c.field(name, |c| {
                    c.number(lo, " %", 0.0, 100.0)?;
                    c.number(hi, " %", lo, 100.0)
                })?;
            }
        }
        r.calls.map_or(Ok(()), |n| c.count("calls", n))
    })
}

fn check_amdahl_figures(c: &mut Check, f: &AmdahlFigures) -> Checked {
    c.field("fraction", |c| c.number(f.fraction, "", 0.0, 1.0))?;
    c.ratio("speedup_2x", f.speedup_2x)?;
    c.ratio("speedup_10x", f.speedup_10x)?;
    c.ratio("speedup_limit", f.speedup_limit)
}

fn check_profile(c: &mut Check, p: &Profile) -> Checked {
    c.count("samples", p.samples)?;
    c.seconds("seconds_per_sample", p.seconds_per_sample)?;
    if let Some(n) = p.renders {
        c.count("renders", n)?;
    }
    if let Some(n) = p.samples_asked {
        c.count("samples_asked", n)?;
    }
    if let Some(s) = p.cpu_seconds {
        c.seconds("cpu_seconds", s)?;
    }
    check_flat_rows(c, &p.flat)?;
    c.file("flat_text", &p.flat_text)?;
    c.file("callgraph_text", &p.callgraph_text)?;
    c.file("flame_svg", &p.flame_svg)?;
    c.each("amdahl", &p.amdahl, MAX_ROWS, |c, r| {
        c.text("name", &r.name, MAX_NAME)?;
        check_amdahl_figures(
            c,
            &AmdahlFigures {
                fraction: r.fraction,
                speedup_2x: r.speedup_2x,
                speedup_10x: r.speedup_10x,
                speedup_limit: r.speedup_limit,
            },
        )?;
        match &r.inclusive {
            Some(f) => c.field("inclusive", |c| check_amdahl_figures(c, f)),
            None => Ok(()),
        }
    })?;
    if let Some(v) = &p.second_view {
        c.field("second_view", |c| {
            check_flat_rows(c, &v.flat)?;
            c.file("flat_text", &v.flat_text)?;
            c.file("callgraph_text", &v.callgraph_text)?;
            c.file("flame_svg", &v.flame_svg)
        })?;
    }
    c.each("exports", &p.exports, MAX_ROWS, |c, path| {
        c.file("path", path)
    })
}

fn check_profile_result(c: &mut Check, p: &ProfileResult) -> Checked {
    c.text("scene", &p.scene, MAX_NAME)?;
    c.size(p.width, p.height)?;
    c.field("baseline", |c| check_profile(c, &p.baseline))?;
    if let Some(best) = &p.best {
        c.field("best", |c| check_profile(c, best))?;
    }
    c.optional_file("diff_flame_svg", p.diff_flame_svg.as_deref())?;
    c.optional_file("diff_shrunk_flame_svg", p.diff_shrunk_flame_svg.as_deref())
}

/// An outside tracer recorded with perf: the report reads its flat profile and
/// flamegraph from the paths here, so each must stay inside the results directory.
fn check_outside_profile(c: &mut Check, p: &crate::OutsideProfile) -> Checked {
    c.text("scene", &p.scene, MAX_NAME)?;
    c.size(p.width, p.height)?;
    c.each("command", &p.command, MAX_ROWS, |c, arg| {
        c.text("arg", arg, MAX_TEXT)
    })?;
    c.count("samples", p.samples)?;
    c.seconds("cpu_seconds", p.cpu_seconds)?;
    c.seconds("wall_seconds", p.wall_seconds)?;
    c.text("call_graph", &p.call_graph, MAX_NAME)?;
    c.file("directory", &p.directory)?;
    c.field("profile", |c| {
        check_flat_rows(c, &p.profile.flat)?;
        c.file("flat_text", &p.profile.flat_text)?;
        c.file("callgraph_text", &p.profile.callgraph_text)?;
        c.file("flame_svg", &p.profile.flame_svg)
    })?;
    c.file("folded", &p.folded)?;
    c.each("files", &p.files, MAX_ROWS, |c, path| c.file("path", path))
}

fn check_figures(c: &mut Check, name: &str, f: &HwFigures) -> Checked {
    c.field(name, |c| {
        for (column, n) in f.columns() {
            c.count(column.key(), n)?;
        }
        Ok(())
    })
}

fn check_errors(c: &mut Check, e: &HwErrors) -> Checked {
    c.field("error_pct", |c| {
        for (column, x) in e.columns() {
            if let Some(x) = x {
                c.field(column.key(), |c| {
                    c.number(x, " %", -MAX_ERROR_PCT, MAX_ERROR_PCT)
                })?;
            }
        }
        Ok(())
    })
}

fn check_hw_row(c: &mut Check, r: &HwRow) -> Checked {
    c.text("name", &r.name, MAX_NAME)?;
    check_figures(c, "model", &r.model)?;
    if let Some(t) = &r.thesis {
        check_figures(c, "thesis", t)?;
    }
    r.error_pct.as_ref().map_or(Ok(()), |e| check_errors(c, e))
}

fn check_hardware(c: &mut Check, h: &HardwareResult) -> Checked {
    c.text("family", &h.family, MAX_NAME)?;
    c.each("ops", &h.ops, MAX_ROWS, check_hw_row)?;
    c.each("blocks", &h.blocks, MAX_ROWS, check_hw_row)?;
    c.each("devices", &h.devices, MAX_ROWS, |c, d| {
        c.text("device", &d.device, MAX_NAME)?;
        for (name, n) in [
            ("le", d.le),
            ("le_capacity", d.le_capacity),
            ("mult", d.mult),
            ("mult_capacity", d.mult_capacity),
            ("soft_mult_elements", d.soft_mult_elements),
            ("mem_bits", d.mem_bits),
            ("mem_capacity", d.mem_capacity),
        ] {
            c.count(name, n)?;
        }
        Ok(())
    })?;
    if let Some(s) = &h.synthesis {
        c.field("synthesis", |c| check_synthesis(c, s))?;
    }
    Ok(())
}

/// A synthesis: names and texts bounded, cells exact, times and clocks finite and
/// plausible.
fn check_synthesis(c: &mut Check, s: &Synthesis) -> Checked {
    for (name, text) in [
        ("design", &s.design),
        ("tool", &s.tool),
        ("flow", &s.flow),
        ("rtl_hash", &s.rtl_hash),
    ] {
        c.text(name, text, MAX_NAME)?;
    }
    c.seconds("seconds", s.seconds)?;
    for (name, x) in [
        ("clock_mhz", s.clock_mhz),
        ("level_ns", s.level_ns),
        ("register_ns", s.register_ns),
    ] {
        c.ratio(name, x)?;
    }
    c.count("max_levels", s.max_levels)?;
    let block = |c: &mut Check, b: &SynthBlock| -> Checked {
        for (name, text) in [
            ("name", &b.name),
            ("path_from", &b.path_from),
            ("path_to", &b.path_to),
        ] {
            c.text(name, text, MAX_NAME)?;
        }
        for (name, n) in [
            ("lut4", b.lut4),
            ("mult_lut4", b.mult_lut4),
            ("ff", b.ff),
            ("mem_bits", b.mem_bits),
            ("m9k", b.m9k),
            ("levels", b.levels),
        ] {
            c.count(name, n)?;
        }
        c.ratio("fmax_mhz", b.fmax_mhz)
    };
    c.each("blocks", &s.blocks, MAX_ROWS, block)?;
    c.field("total", |c| block(c, &s.total))
}

fn check_failure(c: &mut Check, f: &Failure) -> Checked {
    if let Some(scene) = &f.scene {
        c.text("scene", scene, MAX_NAME)?;
    }
    c.text("message", &f.message, MAX_TEXT)
}

impl Results {
    /// Checks the ranges, sizes and references of [`crate::validate`]; the error
    /// names the first value out of place by its JSON path.
    pub fn validate(&self) -> Result<(), ResultsError> {
        let c = &mut Check {
            path: String::new(),
        };
        c.text("created", &self.created, MAX_NAME)?;
        c.text("command", &self.command, MAX_TEXT)?;
        c.field("machine", |c| {
            let m = &self.machine;
            for (name, s) in [
                ("cpu_model", &m.cpu_model),
                ("os", &m.os),
                ("hostname", &m.hostname),
            ] {
                c.text(name, s, MAX_NAME)?;
            }
            c.field("cores", |c| {
                if m.cores <= MAX_THREADS {
                    Ok(())
                } else {
                    Err(c.err(format!("{} cores, more than {MAX_THREADS}", m.cores)))
                }
            })
        })?;
        c.field("build", |c| {
            let b = &self.build;
            for (name, s) in [
                ("rtprof_version", &b.rtprof_version),
                ("rustc", &b.rustc),
                ("git_commit", &b.git_commit),
                ("profile", &b.profile),
            ] {
                c.text(name, s, MAX_NAME)?;
            }
            Ok(())
        })?;
        c.field("suite", |c| check_suite(c, &self.suite))?;
        c.each("scenes", &self.scenes, MAX_SCENES, check_scene)?;
        // The gate pairs scenes by name and size: each may appear once.
        let mut seen = BTreeSet::new();
        for (i, s) in self.scenes.iter().enumerate() {
            if !seen.insert((&s.name, s.width, s.height)) {
                return c.at(format_args!("scenes[{i}]"), |c| {
                    Err(c.err(format!(
                        "scene '{}' at {}x{} appears twice",
                        s.name.escape_debug(),
                        s.width,
                        s.height
                    )))
                });
            }
        }
        if let Some(p) = &self.profile {
            c.field("profile", |c| check_profile_result(c, p))?;
        }
        if let Some(h) = &self.hardware {
            c.field("hardware", |c| check_hardware(c, h))?;
        }
        c.each(
            "outside_profiles",
            &self.outside_profiles,
            MAX_ROWS,
            check_outside_profile,
        )?;
        c.each("failures", &self.failures, MAX_ROWS, check_failure)?;
        // Criterion's estimates are nanoseconds.
        c.each("criterion", &self.criterion, MAX_ROWS, |c, e| {
            c.text("id", &e.id, MAX_NAME)?;
            c.estimate("mean", &e.mean, MAX_SECONDS * 1e9, " ns")?;
            c.estimate("median", &e.median, MAX_SECONDS * 1e9, " ns")?;
            e.measured
                .as_deref()
                .map_or(Ok(()), |m| c.text("measured", m, MAX_NAME))
        })?;
        c.each("instructions", &self.instructions, MAX_ROWS, |c, i| {
            c.text("id", &i.id, MAX_NAME)?;
            c.count("instructions", i.instructions)?;
            if let Some(n) = i.estimated_cycles {
                c.count("estimated_cycles", n)?;
            }
            i.measured
                .as_deref()
                .map_or(Ok(()), |m| c.text("measured", m, MAX_NAME))
        })
    }
}
