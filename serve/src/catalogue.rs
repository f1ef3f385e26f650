//! The scenes a job can name: the built-in scenes, the generators (SPD databases at a
//! size factor, sphereflake, lattice) and the NFF files uploaded to this server; and
//! the variants and parts ([`Part`]) a job can ask for, the outside tracers loaded when
//! the server started (a job names one by its name, [`Catalogue::tracers_named`]), and
//! the rule of an upload's name ([`check_name`]). `GET /api/scenes` is this, as JSON.

use std::path::{Path, PathBuf};

use runner::outside::TracerDef;
use runner::scene_input::{SPD_PREFIX, SceneInput};
use serde::{Deserialize, Serialize};
use tracer::{Limits, VariantSet};

use crate::error::ApiError;

/// The prefix of an uploaded scene's id.
pub const UPLOAD_PREFIX: &str = "upload:";

/// Longest upload name.
const MAX_NAME: usize = 64;

/// An uploaded scene's name (its id after [`UPLOAD_PREFIX`]), a plain name: letters, digits, `-` and `_`, 1 to 64 of them, not starting with `-`.
pub fn check_name(name: &str) -> Result<(), ApiError> {
    let plain = !name.is_empty()
        && name.len() <= MAX_NAME
        && !name.starts_with('-')
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_');
    if plain {
        Ok(())
    } else {
        Err(ApiError::invalid(format!(
            "'{name}' is not a scene name: use 1 to {MAX_NAME} letters, digits, '-' or '_'"
        )))
    }
}

/// What a job runs besides the renders (the suite's parts).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Part {
    /// Every variant rendered, counted, timed and compared with baseline (always run).
    Render,
    /// The scene sampled: gprof-format profile and flamegraphs of baseline and the
    /// fastest variant whose picture stays visually identical.
    Profile,
    /// The FPGA pipeline model (time, fit) and its emulator's image.
    Hardware,
    /// Per-pixel maps of baseline, simd and bvh.
    PixelMaps,
    /// The embedded suite's CI-sized run (`rtprof suite --quick`): every scene and
    /// variant; the job's scene and variants are ignored.
    Suite,
}

impl Part {
    pub const ALL: [Part; 5] = [
        Part::Render,
        Part::Profile,
        Part::Hardware,
        Part::PixelMaps,
        Part::Suite,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Part::Render => "render",
            Part::Profile => "profile",
            Part::Hardware => "hardware",
            Part::PixelMaps => "pixel_maps",
            Part::Suite => "suite",
        }
    }

    /// What the page says of it.
    pub fn label(self) -> &'static str {
        match self {
            Part::Render => "render and compare: counts, times, images and their difference",
            Part::Profile => "profile: gprof flat profile, call graph, flamegraphs",
            Part::Hardware => "hardware: FPGA model time and fit, emulator image",
            Part::PixelMaps => "per-pixel maps of baseline, simd and bvh",
            Part::Suite => "the whole quick suite (every scene and variant; a few minutes)",
        }
    }
}

/// A scene a job can name as is.
#[derive(Clone, Debug, Serialize)]
pub struct SceneEntry {
    pub id: String,
    /// `builtin` or `uploaded`.
    pub group: &'static str,
    pub family: String,
    pub primitives: u64,
    /// "balls3 (test, 91 primitives)".
    pub label: String,
}

impl SceneEntry {
    pub fn new(id: String, group: &'static str, family: String, primitives: u64) -> Self {
        let label = format!(
            "{id} ({family}, {})",
            reports::page_values::primitives(primitives)
        );
        SceneEntry {
            id,
            group,
            family,
            primitives,
            label,
        }
    }
}

/// A scene generator: its id is `PREFIX:N`.
#[derive(Clone, Debug, Serialize)]
pub struct GeneratorEntry {
    pub prefix: String,
    pub label: String,
    pub parameter: &'static str,
    pub min: u32,
    pub max: u32,
    pub default: u32,
    pub summary: String,
    /// "size factor 1–9, default 3."
    pub range: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct VariantEntry {
    pub name: String,
    pub summary: String,
}

/// An outside tracer a job may run (docs/tracers.md): one of the definitions given when
/// the server started, shown as its definition says it.
#[derive(Clone, Debug, Serialize)]
pub struct OutsideEntry {
    /// What a job names it by (`tachyon`).
    pub name: String,
    /// Its variant in results (`tracer:tachyon`).
    pub variant: String,
    /// Its definition's one line on what it is.
    pub description: String,
    /// Where its definition came from (a file, or `built-in NAME.toml`).
    pub definition: String,
    /// Its command as the definition writes it (placeholders unexpanded), for reading.
    pub command: String,
    /// What its time covers ("the whole process", "its own printout (…)").
    pub time_covers: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct PartEntry {
    pub name: &'static str,
    pub label: &'static str,
}

/// An image-quality band (the thesis's table 2), so that the page names and explains
/// them as the reports do.
#[derive(Clone, Debug, Serialize)]
pub struct BandEntry {
    /// Its key in results.json (`visually_identical`).
    pub key: analysis::Band,
    /// Its name (`visually identical`).
    pub name: &'static str,
    /// The RMS where the next band starts (`null` for the last).
    pub upper_edge: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct LimitsEntry {
    pub max_side: u32,
    pub max_pixels: u64,
    pub max_upload_bytes: u64,
    /// The most worker threads a job may ask for (`runner::pool::max_threads`).
    pub max_threads: u16,
    /// The size and thread limits, said: "Image size: each side at most …".
    pub size_text: String,
    /// "Up to 64.0 MiB."
    pub upload_text: String,
}

/// Everything `GET /api/scenes` lists.
#[derive(Clone, Debug, Serialize)]
pub struct Listing {
    pub scenes: Vec<SceneEntry>,
    pub generators: Vec<GeneratorEntry>,
    pub variants: Vec<VariantEntry>,
    /// The outside tracers loaded at start (`rtprof serve --tracer FILE`, `--peers`).
    pub tracers: Vec<OutsideEntry>,
    pub parts: Vec<PartEntry>,
    pub bands: Vec<BandEntry>,
    pub limits: LimitsEntry,
}

/// The combinations the suite runs, offered beside the single variants.
const COMBINATIONS: [&str; 2] = ["bvh+simd", "bvh+simd+packets"];

/// The scene catalogue of one server: fixed names plus the uploads directory.
#[derive(Clone, Debug)]
pub struct Catalogue {
    uploads: PathBuf,
    max_upload_bytes: u64,
    /// The outside tracers' definitions, read and checked when the server started.
    tracers: Vec<TracerDef>,
}

/// Longest tracer name a refusal quotes back.
const QUOTED: usize = 80;

impl Catalogue {
    pub fn new(uploads: PathBuf, max_upload_bytes: u64) -> Self {
        Catalogue {
            uploads,
            max_upload_bytes,
            tracers: Vec::new(),
        }
    }

    /// The catalogue offering the outside tracers `defs` (loaded at start).
    pub fn with_tracers(mut self, defs: Vec<TracerDef>) -> Self {
        self.tracers = defs;
        self
    }

    /// The definitions of the tracers `names` asks for (each a loaded tracer's name, or
    /// `tracer:NAME`), in the catalogue's order. A request only ever selects among the
    /// definitions loaded at start: anything else (a path, a command, an unknown name)
    /// is refused with a 400 naming the tracers there are.
    pub fn tracers_named(&self, names: &[String]) -> Result<Vec<TracerDef>, ApiError> {
        let mut wanted: Vec<&str> = Vec::new();
        for asked in names {
            let name = asked.strip_prefix("tracer:").unwrap_or(asked);
            if !self.tracers.iter().any(|t| t.name == name) {
                return Err(self.unknown_tracer(asked));
            }
            if !wanted.contains(&name) {
                wanted.push(name);
            }
        }
        Ok(self
            .tracers
            .iter()
            .filter(|t| wanted.contains(&t.name.as_str()))
            .cloned()
            .collect())
    }

    fn unknown_tracer(&self, asked: &str) -> ApiError {
        let quoted: String = asked.chars().take(QUOTED).collect();
        let quoted = match quoted.len() < asked.len() {
            true => format!("{quoted}…"),
            false => quoted,
        };
        let looks_like_command = asked
            .chars()
            .any(|c| c.is_whitespace() || "/\\{}$;|&<>`'\"".contains(c));
        let why = match looks_like_command {
            true => "a job names an outside tracer by its name only: this server never runs a command or a path from a request".to_string(),
            false => "it is not one of the outside tracers this server loaded at start".to_string(),
        };
        let offered = match self.tracers.is_empty() {
            true => "none were given (start the server with --tracer FILE or --peers)".to_string(),
            false => format!(
                "it runs: {}",
                self.tracers
                    .iter()
                    .map(|t| t.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        ApiError::bad_request(format!("tracer '{quoted}': {why}; {offered}"))
    }

    /// Where uploaded scenes are kept.
    pub fn uploads_dir(&self) -> &Path {
        &self.uploads
    }

    pub fn max_upload_bytes(&self) -> u64 {
        self.max_upload_bytes
    }

    /// The file of the uploaded scene `name` (already checked to be a plain name).
    pub fn upload_path(&self, name: &str) -> PathBuf {
        self.uploads.join(format!("{name}.nff"))
    }

    /// Everything a job can name.
    pub fn listing(&self) -> Listing {
        let mut scenes: Vec<SceneEntry> = tracer::builtin_scenes::all()
            .map(|b| {
                SceneEntry::new(
                    b.name.to_string(),
                    "builtin",
                    b.family.to_string(),
                    b.primitives as u64,
                )
            })
            .collect();
        scenes.extend(self.uploaded());
        let mut generators: Vec<GeneratorEntry> = spd::PROGRAMS
            .iter()
            .map(|p| GeneratorEntry {
                prefix: format!("{SPD_PREFIX}{}", p.name),
                label: format!("SPD {}", p.name),
                parameter: "size factor",
                min: 1,
                max: p.max_size_factor,
                default: p.default_size_factor,
                summary: p.summary.to_string(),
                range: String::new(),
            })
            .collect();
        use tracer::generators::{MAX_LATTICE_SIDE, MAX_SPHEREFLAKE_DEPTH};
        generators.push(GeneratorEntry {
            prefix: "sphereflake".into(),
            label: "sphereflake".into(),
            parameter: "depth",
            min: 0,
            max: MAX_SPHEREFLAKE_DEPTH,
            default: 2,
            summary: "Haines's sphereflake without the ground: 1 + 9 + 81 + ... spheres".into(),
            range: String::new(),
        });
        generators.push(GeneratorEntry {
            prefix: "lattice".into(),
            label: "lattice".into(),
            parameter: "side",
            min: 1,
            max: MAX_LATTICE_SIDE,
            default: 3,
            summary: "N^3 spheres on a cubic lattice joined by 3 N^2 (N-1) cylinders".into(),
            range: String::new(),
        });
        for g in &mut generators {
            g.range = format!(
                "{} {}–{}, default {}.",
                g.parameter,
                reports::format::count(u64::from(g.min)),
                reports::format::count(u64::from(g.max)),
                reports::format::count(u64::from(g.default))
            );
        }
        let mut variants: Vec<VariantEntry> = tracer::Variant::ALL
            .iter()
            .filter(|v| v.available() && VariantSet::parse(v.name()).is_ok())
            .map(|v| VariantEntry {
                name: v.name().to_string(),
                summary: v.description().to_string(),
            })
            .collect();
        for combination in COMBINATIONS {
            if VariantSet::parse(combination).is_ok() {
                variants.push(VariantEntry {
                    name: combination.to_string(),
                    summary: format!("{combination} combined"),
                });
            }
        }
        let limits = Limits::default();
        let tracers = self
            .tracers
            .iter()
            .map(|t| OutsideEntry {
                name: t.name.clone(),
                variant: format!("tracer:{}", t.name),
                description: t.description.clone(),
                definition: t.file.clone(),
                command: t.command.join(" "),
                time_covers: t.time.covers(),
            })
            .collect();
        Listing {
            scenes,
            generators,
            variants,
            tracers,
            parts: Part::ALL
                .iter()
                .map(|p| PartEntry {
                    name: p.name(),
                    label: p.label(),
                })
                .collect(),
            bands: analysis::Band::ALL
                .iter()
                .map(|&key| BandEntry {
                    key,
                    name: key.name(),
                    upper_edge: key.upper_edge(),
                })
                .collect(),
            limits: LimitsEntry {
                max_side: limits.max_side,
                max_pixels: limits.max_pixels,
                max_upload_bytes: self.max_upload_bytes,
                max_threads: runner::pool::max_threads().0,
                size_text: format!(
                    "Image size: each side at most {} pixels, at most {} pixels in all. Threads of the timed renders: 1 to {}; leave empty for one (the untimed work uses every core).",
                    reports::format::count(u64::from(limits.max_side)),
                    reports::format::count(limits.max_pixels),
                    reports::format::count(u64::from(runner::pool::max_threads().0))
                ),
                upload_text: format!("Up to {}.", reports::format::bytes(self.max_upload_bytes)),
            },
        }
    }

    /// The uploaded scenes, by name (primitive counts from their parse).
    fn uploaded(&self) -> Vec<SceneEntry> {
        let Ok(entries) = std::fs::read_dir(&self.uploads) else {
            return Vec::new();
        };
        let mut names: Vec<String> = entries
            .filter_map(|e| e.ok())
            .filter_map(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                let stem = name.strip_suffix(".nff")?;
                check_name(stem).ok()?;
                Some(stem.to_string())
            })
            .collect();
        names.sort();
        names
            .into_iter()
            .filter_map(|name| {
                let path = self.upload_path(&name);
                let scene = tracer::load_nff_with_limits(&path, &Limits::default()).ok()?;
                Some(SceneEntry::new(
                    format!("{UPLOAD_PREFIX}{name}"),
                    "uploaded",
                    "other".into(),
                    scene.primitive_count() as u64,
                ))
            })
            .collect()
    }

    /// The suite entry of a scene id (a built-in name, a generator, or an uploaded
    /// scene's file). Never a path the request names: a job reads no file but the
    /// uploads.
    pub fn resolve(&self, id: &str) -> Result<String, ApiError> {
        if id.is_empty() {
            return Err(ApiError::invalid(
                "no scene: pick one of GET /api/scenes (e.g. balls3)",
            ));
        }
        if let Some(name) = id.strip_prefix(UPLOAD_PREFIX) {
            check_name(name)?;
            let path = self.upload_path(name);
            if !path.is_file() {
                return Err(ApiError::invalid(format!(
                    "no uploaded scene '{name}': upload it first (POST /api/scenes?name={name})"
                )));
            }
            return Ok(path.display().to_string());
        }
        let unknown = || {
            ApiError::invalid(format!(
                "unknown scene '{id}': GET /api/scenes lists the built-in scenes and generators"
            ))
        };
        if id.contains(['/', '\\']) || id.ends_with(".nff") {
            return Err(unknown());
        }
        // A base directory that cannot exist: a name is never read as a file.
        let nowhere = Path::new("/nonexistent/rtprof-serve");
        match SceneInput::parse(id, nowhere) {
            Ok(SceneInput::File(_)) => Err(unknown()),
            Ok(input) => Ok(input.to_string()),
            Err(e) => Err(ApiError::invalid(e.to_string())),
        }
    }
}
