//! The runner's error type: what failed, with the scene, file or stage it concerns.
//! Messages carry their cause inline (no `#[source]` chain), so the binary's one-line
//! error printer shows each cause once.

use std::path::PathBuf;

/// Something the runner could not do.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A suite definition that cannot be used.
    #[error("{file}: {message}")]
    Definition { file: String, message: String },
    /// Bad input whose message already says where (an NFF error names file and line).
    #[error("{0}")]
    Input(String),
    /// A scene entry that cannot be resolved or parsed.
    #[error("scene '{scene}': {message}")]
    Scene { scene: String, message: String },
    /// A file or directory that cannot be read or written.
    #[error("cannot {action} {}: {message}", path.display())]
    Io {
        action: &'static str,
        path: PathBuf,
        message: String,
    },
    /// A render that failed.
    #[error("{context}: {message}")]
    Render { context: String, message: String },
    /// An input over one of the tracer's limits; `message` names the limit with
    /// [`tracer::Limit::hint`], which a front end may replace with how to raise it.
    #[error("{message}")]
    OverLimit {
        message: String,
        limit: tracer::Limit,
    },
    #[error("{0}")]
    Variant(#[from] tracer::VariantError),
    /// The generated RTL or its tools (Verilator, Yosys) failed.
    #[error(transparent)]
    Rtl(#[from] rtl::RtlError),
    #[error("{0}")]
    Metrics(#[from] analysis::MetricsError),
    #[error("{0}")]
    Stats(#[from] analysis::StatsError),
    /// The sampling profiler or the flamegraph writer failed.
    #[error("profile: {0}")]
    Profile(String),
    /// Benchmark figures that cannot be imported.
    #[error("{0}")]
    Benchmarks(#[from] crate::benchmarks::BenchImportError),
    /// A report that cannot be built.
    #[error("{0}")]
    Report(String),
    /// A program to run that could not be found or started (`rtprof record`).
    #[error(transparent)]
    Launch(#[from] launch::LaunchError),
    /// perf, which `rtprof record` drives, missing, not permitted or failing.
    #[error(transparent)]
    Perf(#[from] PerfError),
    /// An outside tracer's run that failed (docs/tracers.md): recorded with its reason,
    /// the other entries go on.
    #[error("tracer {tracer}: {}", failure.describe())]
    Outside {
        tracer: String,
        failure: crate::outside::failure::Failure,
    },
    /// The caller asked the run to stop (Ctrl-C).
    #[error("stopped on request")]
    Stopped,
    /// A run that panicked (a bug), caught where its partial outputs are kept.
    #[error("internal error (panic) while running this job; please report it")]
    Panicked,
    /// A suite stopped on request after `done` of its `total` scenes.
    #[error("stopped on request after {done} of {total} scenes")]
    StoppedAfter { done: usize, total: usize },
}

/// The environment variable naming the perf binary (default: `perf` on PATH).
pub const PERF_VARIABLE: &str = "RTPROF_PERF";
/// Where the kernel says who may sample.
pub const PARANOID: &str = "/proc/sys/kernel/perf_event_paranoid";

/// perf missing, not permitted, or failing.
#[derive(Debug, thiserror::Error)]
pub enum PerfError {
    #[error(
        "perf is not installed ({program}): install the linux-perf package (Debian; linux-tools on Ubuntu), or set {PERF_VARIABLE} to perf's path (rtprof's own tracer needs no perf: `rtprof profile` samples it in-process)"
    )]
    Missing { program: String },
    #[error(
        "perf may not sample this program: {PARANOID} is {paranoid}; lower it (sysctl kernel.perf_event_paranoid=1) or run as root or with CAP_PERFMON (in a container, the container must allow perf_event_open); rtprof's own tracer can still be sampled in-process: `rtprof profile`"
    )]
    NotPermitted { paranoid: String },
    #[error("perf failed: {message} (its log: {})", log.display())]
    Failed { message: String, log: PathBuf },
}

impl RunError {
    /// For a suite of `total` scenes stopped on request: the scenes done and the total.
    pub fn stopped_scenes(&self, total: usize) -> Option<(usize, usize)> {
        match self {
            RunError::StoppedAfter { done, total } => Some((*done, *total)),
            RunError::Stopped => Some((total, total)),
            _ => None,
        }
    }

    /// The limit the input exceeded, when that is the error.
    pub fn limit(&self) -> Option<tracer::Limit> {
        match self {
            RunError::OverLimit { limit, .. } => Some(*limit),
            _ => None,
        }
    }

    /// `message` said of an input, typed by the limit it exceeded (if any): bad input
    /// ([`RunError::Input`]) otherwise.
    fn input_over(message: String, limit: Option<tracer::Limit>) -> Self {
        match limit {
            Some(limit) => RunError::OverLimit { message, limit },
            None => RunError::Input(message),
        }
    }

    /// A scene that could not be loaded (its message names file and line).
    pub fn load(err: &tracer::LoadError) -> Self {
        Self::input_over(err.to_string(), err.limit())
    }

    /// A scene that could not be parsed (its message names file and line).
    pub fn parse(err: &tracer::NffError) -> Self {
        Self::input_over(err.to_string(), err.limit)
    }

    /// A size or depth of `context` (a file or scene name) the limits refuse.
    pub fn refused(context: impl std::fmt::Display, err: &tracer::LimitError) -> Self {
        match err.limit {
            Some(limit) => RunError::OverLimit {
                message: format!("{context}: {err}"),
                limit,
            },
            None => RunError::Render {
                context: context.to_string(),
                message: err.to_string(),
            },
        }
    }

    /// An I/O error on `path`.
    pub fn io(action: &'static str, path: impl Into<PathBuf>, err: &std::io::Error) -> Self {
        RunError::Io {
            action,
            path: path.into(),
            message: err.to_string(),
        }
    }

    /// A render error, said of `context` (a file or scene name); a render stopped by its
    /// flag is [`RunError::Stopped`], as the other stops are.
    pub fn render(context: impl std::fmt::Display, err: &tracer::RenderError) -> Self {
        match err {
            tracer::RenderError::Cancelled => return RunError::Stopped,
            tracer::RenderError::Size(e) | tracer::RenderError::Depth(e) => {
                return Self::refused(context, e);
            }
            _ => {}
        }
        RunError::Render {
            context: context.to_string(),
            message: err.to_string(),
        }
    }
}
