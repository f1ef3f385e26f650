//! A tracer definition (docs/tracers.md): how rtprof runs an outside renderer as a
//! variant. A TOML file gives its name, its command as a list of arguments with
//! placeholders (run without a shell), the scene format it reads, the image it writes,
//! where its time comes from, whether its picture is deterministic, and a time limit
//! per run. Everything is checked on load; a fault names `FILE:LINE:COLUMN`.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use toml::Spanned;

use crate::error::RunError;

/// The placeholders a command or an environment value may name, and what each becomes.
pub const PLACEHOLDERS: [(&str, &str); 10] = [
    (
        "rtprof",
        "this rtprof program (rtprof run as its users run it)",
    ),
    ("scene", "the scene file rtprof wrote for the program"),
    ("width", "the picture's width in pixels"),
    ("height", "the picture's height in pixels"),
    ("output", "the image file the program is to write"),
    ("threads", "the threads the run may use"),
    ("spp", "samples per pixel (path tracers)"),
    (
        "shading",
        "the shading asked of rtprof's variants: color, gray or diffuse-only",
    ),
    (
        "depth",
        "the ray-tree depth asked of rtprof's variants (the eye ray is 1)",
    ),
    (
        "workdir",
        "the run's own empty directory (also the program's working directory)",
    ),
];

/// Longest run allowed when a definition does not say, seconds.
pub const DEFAULT_TIME_LIMIT: f64 = 600.0;

/// The scene a program reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SceneFormat {
    /// NFF, as rtprof reads it (the scene written back by rtprof's NFF writer).
    Nff,
    /// POV-Ray's language, written by rtprof as the SPD's own POV-Ray output writes it.
    Pov,
    /// Tachyon's own scene language, written by rtprof's Tachyon writer with a camera
    /// that frames the picture rtprof renders at the run's size.
    Tachyon,
    /// None: the program draws a scene of its own (its picture is judged only against
    /// its own runs).
    Own,
}

/// The image a program writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ImageFormat {
    Ppm,
    Png,
    Tga,
}

impl ImageFormat {
    /// The file name extension (`{output}` ends with it).
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Ppm => "ppm",
            ImageFormat::Png => "png",
            ImageFormat::Tga => "tga",
        }
    }
}

/// Where the image comes out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ImageOutput {
    /// The file `{output}` names.
    #[default]
    File,
    /// The program's standard output.
    Stdout,
}

/// Where a run's time comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeSource {
    /// The whole process's wall time (start-up, parse, build, trace, write).
    Process,
    /// The program's own printout: the first capture group of `pattern` (a regular
    /// expression) in its standard output or error, in seconds times `scale`.
    Printout { pattern: String, scale: f64 },
    /// The probe's phases (docs/instrumenting.md): the CPU seconds the probe's samples
    /// give for the phases named (each phase's samples anywhere on a stack, all
    /// threads), summed.
    Probe { phases: Vec<String> },
}

impl TimeSource {
    /// Whether a time covers the whole process (start-up, parse and writing included).
    pub fn whole_process(&self) -> bool {
        matches!(self, TimeSource::Process)
    }

    /// What a time covers, for tables and the report.
    pub fn covers(&self) -> String {
        match self {
            TimeSource::Process => "the whole process".to_string(),
            TimeSource::Printout { pattern, .. } => format!("its own printout (`{pattern}`)"),
            TimeSource::Probe { phases } => format!("its probe's phases {}", phases.join(", ")),
        }
    }
}

/// A checked tracer definition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TracerDef {
    /// Its variant name (not one of rtprof's own variants).
    pub name: String,
    /// One line on what it is, for the report.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// The program and its arguments, placeholders unexpanded.
    pub command: Vec<String>,
    /// Variables set for it, placeholders unexpanded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub env: Vec<(String, String)>,
    pub scene: SceneFormat,
    pub image: ImageFormat,
    #[serde(default)]
    pub output: ImageOutput,
    pub time: TimeSource,
    /// Whether two runs draw the same picture (false for path tracers: Monte Carlo noise).
    pub deterministic: bool,
    /// Samples per pixel of the converged run a noisy picture is measured against.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub converged_spp: Option<u32>,
    /// Samples per pixel of its timed runs (`{spp}`) when the caller does not say.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spp: Option<u32>,
    /// What it draws differently from rtprof by design (light intensity, background…),
    /// for the report.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub conventions: String,
    /// Longest run, seconds; past it the run is stopped and recorded as failed.
    pub time_limit: f64,
    /// Where it was defined (a file, or `built-in`).
    pub file: String,
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDef {
    name: Spanned<String>,
    #[serde(default)]
    description: String,
    command: Spanned<Vec<Spanned<String>>>,
    #[serde(default)]
    env: BTreeMap<String, Spanned<String>>,
    scene: SceneFormat,
    image: ImageFormat,
    #[serde(default)]
    output: ImageOutput,
    time: Spanned<RawTime>,
    #[serde(default = "yes")]
    deterministic: bool,
    #[serde(default)]
    converged_spp: Option<Spanned<u32>>,
    #[serde(default)]
    spp: Option<Spanned<u32>>,
    #[serde(default)]
    conventions: String,
    #[serde(default)]
    time_limit: Option<Spanned<f64>>,
}

fn yes() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawTime {
    Named(String),
    Printout {
        pattern: String,
        #[serde(default = "one")]
        scale: f64,
    },
    Probe {
        probe_phases: Vec<String>,
    },
}

fn one() -> f64 {
    1.0
}

/// A fault at a byte offset of the file.
struct At {
    offset: usize,
    message: String,
}

impl TracerDef {
    /// Reads and checks the definition at `path`.
    pub fn load(path: &Path) -> Result<Self, RunError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| RunError::io("read tracer definition", path, &e))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parses and checks a definition (`file` names it in errors and in the record).
    pub fn parse(text: &str, file: &str) -> Result<Self, RunError> {
        let located = |offset: Option<usize>, message: String| {
            let file = match offset {
                Some(offset) => {
                    let (line, column) = crate::text_position::line_and_column(text, offset);
                    format!("{file}:{line}:{column}")
                }
                None => file.to_string(),
            };
            RunError::Definition { file, message }
        };
        let raw: RawDef = toml::from_str(text)
            .map_err(|e| located(e.span().map(|s| s.start), e.message().trim().to_string()))?;
        Self::check(raw, file).map_err(|at| located(Some(at.offset), at.message))
    }

    fn check(raw: RawDef, file: &str) -> Result<Self, At> {
        let at = |span: std::ops::Range<usize>, message: String| At {
            offset: span.start,
            message,
        };
        let name = raw.name.get_ref();
        if name.is_empty()
            || !name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b))
        {
            return Err(at(
                raw.name.span(),
                format!("name '{name}': use letters, digits, '-', '_' and '.' (it names files)"),
            ));
        }
        if tracer::VariantSet::parse(name).is_ok() {
            return Err(at(
                raw.name.span(),
                format!("name '{name}' is one of rtprof's own variants: choose another"),
            ));
        }
        let command: Vec<String> = raw
            .command
            .get_ref()
            .iter()
            .map(|a| a.get_ref().clone())
            .collect();
        if command.first().is_none_or(|p| p.trim().is_empty()) {
            return Err(at(
                raw.command.span(),
                "command is empty: give the program and its arguments, e.g. [\"tachyon\", \"{scene}\"]"
                    .into(),
            ));
        }
        for argument in raw.command.get_ref() {
            check_placeholders(argument.get_ref()).map_err(|m| at(argument.span(), m))?;
        }
        let mut env = Vec::new();
        for (key, value) in &raw.env {
            check_placeholders(value.get_ref()).map_err(|m| at(value.span(), m))?;
            env.push((key.clone(), value.get_ref().clone()));
        }
        let names = |p: &str| command.iter().any(|a| a.contains(&format!("{{{p}}}")));
        if raw.scene != SceneFormat::Own && !names("scene") {
            return Err(at(
                raw.command.span(),
                "the command never names {scene}: the program would not see the scene (or say scene = \"own\")".into(),
            ));
        }
        if raw.output == ImageOutput::File && !names("output") {
            return Err(at(
                raw.command.span(),
                "the command never names {output}, where the image goes (or say output = \"stdout\")".into(),
            ));
        }
        let time = match raw.time.get_ref() {
            RawTime::Named(n) if n == "process" => TimeSource::Process,
            RawTime::Named(other) => {
                return Err(at(
                    raw.time.span(),
                    format!(
                        "time = \"{other}\": use \"process\", {{ pattern = \"REGEX\", scale = 1.0 }} or {{ probe_phases = [\"trace\"] }}"
                    ),
                ));
            }
            RawTime::Printout { pattern, scale } => {
                let re = regex::Regex::new(pattern)
                    .map_err(|e| at(raw.time.span(), format!("time pattern: {e}")))?;
                if re.captures_len() < 2 {
                    return Err(at(
                        raw.time.span(),
                        "time pattern has no capture group: put the seconds in ( )".into(),
                    ));
                }
                if !(scale.is_finite() && *scale > 0.0) {
                    return Err(at(raw.time.span(), "time scale must be positive".into()));
                }
                TimeSource::Printout {
                    pattern: pattern.clone(),
                    scale: *scale,
                }
            }
            RawTime::Probe { probe_phases } => {
                if probe_phases.is_empty() {
                    return Err(at(
                        raw.time.span(),
                        "probe_phases is empty: name the phases the time covers".into(),
                    ));
                }
                TimeSource::Probe {
                    phases: probe_phases.clone(),
                }
            }
        };
        let positive = |v: &Option<Spanned<u32>>, what: &str| match v {
            Some(s) if *s.get_ref() == 0 => Err(at(s.span(), format!("{what} must be at least 1"))),
            _ => Ok(v.as_ref().map(|s| *s.get_ref())),
        };
        let converged_spp = positive(&raw.converged_spp, "converged_spp")?;
        let spp = positive(&raw.spp, "spp")?;
        if !raw.deterministic && converged_spp.is_none() {
            return Err(at(
                raw.name.span(),
                "a tracer that is not deterministic needs converged_spp: the samples per pixel of the run its pictures are measured against".into(),
            ));
        }
        if converged_spp.is_some() && !names("spp") {
            return Err(at(
                raw.command.span(),
                "converged_spp is set but the command never names {spp}".into(),
            ));
        }
        let time_limit = match &raw.time_limit {
            Some(limit) => {
                let seconds = *limit.get_ref();
                if !(seconds.is_finite() && seconds > 0.0 && seconds <= 86_400.0) {
                    return Err(at(
                        limit.span(),
                        "time_limit must be more than 0 and at most 86400 seconds".into(),
                    ));
                }
                seconds
            }
            None => DEFAULT_TIME_LIMIT,
        };
        Ok(TracerDef {
            name: name.clone(),
            description: raw.description,
            command,
            env,
            scene: raw.scene,
            image: raw.image,
            output: raw.output,
            time,
            deterministic: raw.deterministic,
            converged_spp,
            spp,
            conventions: raw.conventions,
            time_limit,
            file: file.to_string(),
        })
    }
}

/// Every `{name}` in `text` is a known placeholder; `{{` and `}}` are literal braces.
fn check_placeholders(text: &str) -> Result<(), String> {
    expand(text, &|_| Some(String::new())).map(|_| ())?;
    expand(text, &|name| {
        PLACEHOLDERS
            .iter()
            .any(|(known, _)| *known == name)
            .then(String::new)
    })
    .map(|_| ())
}

/// `text` with each `{name}` replaced by `value(name)`; `{{` and `}}` are literal
/// braces. An unknown name, or an unclosed brace, is an error naming it.
pub fn expand(text: &str, value: &dyn Fn(&str) -> Option<String>) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(['{', '}']) {
        out.push_str(&rest[..at]);
        let tail = &rest[at..];
        if let Some(after) = tail.strip_prefix("{{") {
            out.push('{');
            rest = after;
        } else if let Some(after) = tail.strip_prefix("}}") {
            out.push('}');
            rest = after;
        } else if let Some(after) = tail.strip_prefix('{') {
            let Some(end) = after.find('}') else {
                return Err(format!("unclosed '{{' in \"{text}\""));
            };
            let name = &after[..end];
            let known: Vec<&str> = PLACEHOLDERS.iter().map(|(n, _)| *n).collect();
            let replacement = value(name).ok_or_else(|| {
                format!(
                    "unknown placeholder {{{name}}} in \"{text}\" (known: {})",
                    known
                        .iter()
                        .map(|n| format!("{{{n}}}"))
                        .collect::<Vec<_>>()
                        .join(" ")
                )
            })?;
            out.push_str(&replacement);
            rest = &after[end + 1..];
        } else {
            return Err(format!(
                "a lone '}}' in \"{text}\" (write '}}}}' for a brace)"
            ));
        }
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TACHYON: &str = r#"
name = "tachyon"
command = ["tachyon", "{scene}", "-res", "{width}", "{height}", "-numthreads", "{threads}", "-o", "{output}"]
scene = "nff"
image = "tga"
time = { pattern = 'Ray Tracing Time:\s+([0-9.]+) seconds' }
"#;

    #[test]
    fn a_definition_reads_with_its_defaults() {
        let def = TracerDef::parse(TACHYON, "t.toml").unwrap();
        assert_eq!(def.name, "tachyon");
        assert_eq!(def.command.len(), 9);
        assert_eq!(def.scene, SceneFormat::Nff);
        assert_eq!(def.image, ImageFormat::Tga);
        assert_eq!(def.output, ImageOutput::File);
        assert!(def.deterministic);
        assert_eq!(def.time_limit, DEFAULT_TIME_LIMIT);
        assert!(matches!(def.time, TimeSource::Printout { scale, .. } if scale == 1.0));
    }

    /// The error of `text` (a definition), as the user sees it.
    fn fault(text: &str) -> String {
        TracerDef::parse(text, "my.toml").unwrap_err().to_string()
    }

    #[test]
    fn faults_name_file_line_and_column() {
        // An unknown placeholder: line 3 is `command`, column 40 its second argument.
        let bad = TACHYON.replace("\"{width}\"", "\"{wide}\"");
        let e = fault(&bad);
        assert!(e.starts_with("my.toml:3:"), "{e}");
        assert!(e.contains("unknown placeholder {wide}"), "{e}");
        // A field that does not exist.
        let e = fault(&format!("{TACHYON}colour = 1\n"));
        assert!(e.starts_with("my.toml:7:1"), "{e}");
        // A bad regular expression, on line 6.
        let e = fault(&TACHYON.replace("([0-9.]+)", "([0-9.]+"));
        assert!(e.starts_with("my.toml:6:"), "{e}");
        assert!(e.contains("time pattern"), "{e}");
    }

    #[test]
    fn a_definition_that_cannot_work_is_refused() {
        // rtprof's own variant name.
        assert!(fault(&TACHYON.replace("\"tachyon\"\n", "\"bvh\"\n")).contains("own variants"));
        // The scene never reaches the program.
        assert!(fault(&TACHYON.replace("\"{scene}\", ", "")).contains("never names {scene}"));
        // Nor does the output file.
        assert!(fault(&TACHYON.replace(", \"-o\", \"{output}\"", "")).contains("{output}"));
        // A pattern without the seconds captured.
        assert!(fault(&TACHYON.replace("([0-9.]+)", "[0-9.]+")).contains("no capture group"));
        // A noisy tracer with nothing to converge to.
        assert!(fault(&format!("{TACHYON}deterministic = false\n")).contains("converged_spp"));
        assert!(fault(&format!("{TACHYON}time_limit = 0\n")).contains("time_limit"));
        assert!(fault(&TACHYON.replace("[\"tachyon\", ", "[\"\", ")).contains("empty"));
    }

    #[test]
    fn placeholders_expand_and_braces_escape() {
        let value = |n: &str| match n {
            "width" => Some("64".to_string()),
            _ => None,
        };
        assert_eq!(expand("+W{width}", &value).unwrap(), "+W64");
        assert_eq!(expand("{{x}} {width}}}", &value).unwrap(), "{x} 64}");
        assert!(expand("{nope}", &value).unwrap_err().contains("{nope}"));
        assert!(expand("{width", &value).unwrap_err().contains("unclosed"));
        assert!(expand("a}b", &value).unwrap_err().contains("lone"));
    }
}
