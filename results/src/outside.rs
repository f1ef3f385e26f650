//! An outside tracer's entry in results (docs/tracers.md): the definition it ran by,
//! the program that ran (so a rebuilt or replaced program is told apart), and how its
//! picture was judged; and its run recorded with perf on the suite's profile scene
//! where the suite asked ([`OutsideProfile`]).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What results record about a variant an outside program drew.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct OutsideTracer {
    /// Where its definition came from (a file, or `built-in NAME.toml`).
    pub definition: String,
    /// Its command, placeholders unexpanded.
    pub command: Vec<String>,
    /// The scene format it read (`nff`, `pov`, or `own`: a scene of its own).
    pub scene_format: String,
    /// What its time covers (`the whole process`, its own printout, its probe's phases).
    pub time_covers: String,
    /// Whether its time is the whole process's (start-up, parse and writing included):
    /// then rtprof's own whole process (`tracer:rtprof`) is what it is set against.
    #[serde(default)]
    pub whole_process: bool,
    /// Whether two runs draw the same picture.
    pub deterministic: bool,
    /// Samples per pixel of its timed runs.
    pub spp: u32,
    /// What it draws differently from rtprof by design, as its definition says.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub conventions: String,
    /// The program found on disk.
    #[serde(default)]
    pub program: Option<Program>,
    /// Whether its picture shows the scene rtprof drew, with the same conventions, other
    /// ones, or something else (then its time is no comparison: kept out of the means
    /// and the answers). Judged against the f64 reference's picture, else the reference
    /// variant's; `None` when neither is at its frame (a scene of its own).
    #[serde(default)]
    pub likeness: Option<analysis::Likeness>,
    /// A noisy (path-traced) picture against the same program's converged run.
    #[serde(default)]
    pub noise: Option<Noise>,
}

impl OutsideTracer {
    /// Whether its time may stand beside rtprof's: it drew the same scene (with any
    /// conventions), or nothing could say it did not.
    pub fn comparable(&self) -> bool {
        !matches!(self.likeness, Some(analysis::Likeness::Different { .. }))
    }
}

/// Monte Carlo noise of a picture against a converged run of the same program
/// (pbrt-v4's relMSE of linear values), and the efficiency 1 / (relMSE × time).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Noise {
    /// Samples per pixel of the converged run.
    pub converged_spp: u32,
    pub rel_mse: f64,
    pub mse: f64,
    /// `None` when relMSE or the time is zero (no finite efficiency).
    pub efficiency: Option<f64>,
    /// Mean FLIP error against the converged picture (NVIDIA's FLIP, 67 pixels per degree).
    pub flip: Option<f64>,
}

/// An outside tracer's run sampled with Linux perf (`rtprof record`'s recording), where
/// the suite's `[[tracers]]` entry asks (`record = true`): on the suite's profile scene
/// at its profile size. Paths are relative to results.json.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct OutsideProfile {
    /// The tracer, `tracer:NAME`.
    pub variant: crate::VariantName,
    /// The scene recorded (the suite's profile scene) and the frame asked of it.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// The command as it ran (placeholders expanded).
    pub command: Vec<String>,
    /// Samples taken, and the program's CPU and wall seconds.
    pub samples: u64,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
    /// Samples per CPU second asked of perf.
    pub frequency: u32,
    /// How callers were found ("frame pointers", "DWARF unwinding").
    pub call_graph: String,
    /// The directory of its files (`record.json`, `report.html`, `perf.data`, …).
    pub directory: String,
    /// The profile by native symbols: flat rows (self time first), the gprof-layout
    /// flat profile and call graph, and the flamegraph.
    pub profile: crate::ProfileViewFiles,
    /// Its folded stacks (one line per stack, samples last).
    pub folded: String,
    /// Every file written, `directory` included in each path.
    pub files: Vec<String>,
}

/// A program as found on disk when it ran.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct Program {
    pub path: String,
    pub bytes: u64,
    /// Its GNU build id in hex (`None`: not an ELF file with one).
    #[serde(default)]
    pub build_id: Option<String>,
}
