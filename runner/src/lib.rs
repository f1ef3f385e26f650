//! `runner`: the rtprof suite as a library. It measures (renders with `tracer`,
//! statistics and profiles with `analysis`, the FPGA model with `hwmodel`) and collects
//! everything into the typed results; it writes nothing but the files a run produces
//! (images, profiles, flamegraphs, the reports) and prints nothing (progress goes to a [`Progress`]).
//! The binary and the web app (`serve`) call it; reports are made from its results.
//!
//! Modules:
//! - [`definition`]: the suite definition (scenes/suite.toml) and its `[quick]` form;
//! - [`scene_input`]: a scene as users name it (file, built-in, `spd:rings:3`, generator);
//! - [`scenes`]: suite entries and directories resolved to scene texts;
//! - [`timing`]: the one timing policy (repeats, minimum measured time, bootstrap) and
//!   what a time covers (tracing; preprocessing apart);
//! - [`calibration`]: the fixed kernel timed between renders (the gate's yardstick);
//! - [`render_job`]: one render with its phase times (`rtprof render`, `count`);
//! - [`reference_job`]: one render by the f64 reference renderer (`render --reference`);
//! - [`pixel_maps`]: per-sample records into per-pixel maps (NPY, PNG, JSON);
//! - [`variant_catalogue`]: what each variant does and how accurate it is;
//! - [`render_setup`]: where and how a job renders (scene, options, pools, stop flag);
//! - [`variant_job`]: one variant on one scene: counts, timed renders, picture;
//! - [`estimate`]: how long a brute-force render of a big scene will take;
//! - [`compare`]: variants side by side (`rtprof compare SCENE --variants`);
//! - [`profile_job`]: counted + sampled renders into two views (phases, native symbols):
//!   gprof tables, folded stacks, Amdahl; [`profile_files`]: their files, one naming scheme;
//!   `profile_settings`: `rtprof profile`'s flags (with the `clap` feature);
//! - [`record`]: `rtprof record -- CMD`, another program under perf into the same
//!   profile model; [`record_files`]: its files and summary; [`record_import`]: a
//!   perf.data or gprof output recorded elsewhere, into the same files; [`record_probe`]:
//!   what the program's probe file gives (exact counts, phases, the FPGA question);
//!   [`record_diff`]: differential flamegraphs against an earlier record;
//! - [`outside`]: outside tracers as variants (a definition file, one run, the
//!   program's identity, the scene in the format it reads);
//! - [`hardware_job`]: the FPGA model, emulator and software time on the same job;
//! - [`hardware_prediction`]: `rtprof hw time`: frame time, fit and what-ifs;
//! - [`hardware_tables`]: `rtprof hw table` as text; [`hardware_files`]: `hw render`, `hw mif`;
//! - [`hardware_rtl`]: `hw rtl | sim | synth`: the generated RTL written, simulated and
//!   synthesized against the model;
//! - [`collect`]: measurements into results entries; [`bvh_study`]: the BVH's quality
//!   per build strategy;
//! - [`scaling`]: the growth study (`rtprof scaling`), cost per ray against scene size;
//! - [`suite`]: the whole suite into one results value (what it records about a scene
//!   beside its times in `scene_facts`); [`suite_dir`]: a suite run into
//!   a directory, staged and published (`rtprof suite` and the web app's jobs); [`shard`]: its deterministic
//!   shares (`--shard I/N`); [`merge`]: shards' results joined into one;
//! - [`report_files`]: results files read back, report.html and report.pdf written;
//! - [`benchmarks`]: criterion estimates and instruction counts picked up from disk;
//! - [`machine`]: machine, build and command line of a run; [`machine_peak`]: its
//!   measured compute and bandwidth roofs;
//! - [`ray_rates`]: rays per second by kind, from a clocked pass;
//! - [`staging`]: staged, atomic output; [`pool`]: worker threads;
//! - [`progress`], [`error`]; [`messages`]: errors on one line, as rtprof prints them.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod benchmarks;
pub mod bvh_study;
pub mod calibration;
pub mod collect;
pub mod compare;
pub mod definition;
pub mod error;
pub mod estimate;
pub mod hardware_files;
pub mod hardware_job;
pub mod hardware_prediction;
pub mod hardware_rtl;
pub mod hardware_tables;
pub mod machine;
pub mod machine_peak;
pub mod merge;
pub mod messages;
pub mod outside;
pub mod pixel_maps;
pub mod pool;
pub mod profile_files;
pub mod profile_job;
#[cfg(feature = "clap")]
pub mod profile_settings;
pub mod progress;
pub mod ray_rates;
pub mod record;
pub mod record_diff;
pub mod record_files;
pub mod record_import;
pub mod record_phases;
pub mod record_probe;
pub mod reference_job;
pub mod render_job;
pub mod render_setup;
pub mod report_files;
pub mod scaling;
mod scene_facts;
pub mod scene_input;
pub mod scenes;
pub mod shard;
pub mod staging;
pub mod suite;
pub mod suite_dir;
pub mod text_position;
pub mod timing;
pub mod variant_catalogue;
pub mod variant_job;

pub use error::RunError;
pub use progress::{Progress, Silent};
