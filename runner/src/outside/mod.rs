//! Outside tracers as variants (docs/tracers.md): a user's renderer, or a built-in peer
//! (POV-Ray, Tachyon), run the way its definition says and measured like rtprof's own
//! variants. [`definition`]: the TOML file, checked on load; [`entry`]: a suite's
//! `[[tracers]]`; [`failure`]: why a run failed; [`flags`]: `--tracer`; [`run`]: one run, its
//! image, time and failure; [`identity`]: the program that ran (path, size, build id);
//! [`scene_file`]: the scene written in the format the program reads; [`measure`]: a
//! tracer prepared and timed beside rtprof's variants; [`peers`]: the built-in
//! definitions (POV-Ray, Tachyon).

pub mod definition;
pub mod entry;
pub mod failure;
pub mod flags;
pub mod identity;
pub mod measure;
pub mod peers;
pub mod run;
pub mod scene_file;

pub use definition::{ImageFormat, ImageOutput, SceneFormat, TimeSource, TracerDef};
pub use entry::TracerEntry;
pub use failure::{Failure, FailureKind};
pub use flags::TracerFlags;
pub use identity::ProgramIdentity;
pub use measure::{OutsideJobs, OutsideMeasurement, Prepared};
pub use run::{OutsideRun, RunEnd, RunPlan, Shading, run_once};
