//! Exports of sampled stacks to the formats other profile viewers read: pprof's
//! gzipped protobuf (`profile.pb.gz`: `go tool pprof`, speedscope, many IDEs) and
//! speedscope's own JSON file format (several views of one run in one file).
//!
//! Both carry the samples as they are: one pprof sample or speedscope sample per
//! distinct stack, weighted by its count (pprof: the count and its CPU nanoseconds;
//! speedscope: its CPU seconds). Frame names are the function (or phase) names the
//! stacks carry; there are no addresses, files or lines.

use super::StackSamples;
use flate2::Compression;
use flate2::write::GzEncoder;
use pprof::protos::{Function, Line, Location, Message, Profile, Sample, ValueType};
use serde_json::{Value, json};
use std::collections::HashMap;
use std::io::Write;
use std::time::Duration;

/// The speedscope file-format schema every speedscope file names.
pub const SPEEDSCOPE_SCHEMA: &str = "https://www.speedscope.app/file-format-schema.json";

/// Who wrote the files (speedscope's `exporter`).
const EXPORTER: &str = concat!("rtprof ", env!("CARGO_PKG_VERSION"));

/// Why an export could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("cannot gzip the pprof profile: {0}")]
    Gzip(std::io::Error),
    #[error("a sample count ({0}) does not fit pprof's 64-bit signed values")]
    TooLarge(u64),
}

/// What a pprof profile says about the run besides its samples.
#[derive(Clone, Debug, Default)]
pub struct PprofRun {
    /// Wall time the samples were taken over (pprof's `duration_nanos`).
    pub duration: Duration,
    /// Free-text comments (`go tool pprof -comments`), e.g. which view this is.
    pub comments: Vec<String>,
}

/// The samples as a gzipped pprof protobuf (profile.proto): sample types
/// `samples/count` and `cpu/nanoseconds`, one function and one location per distinct
/// frame name, each sample's locations leaf first, its values the stack's count and
/// count x seconds per sample in nanoseconds (rounded). The period is the CPU time
/// one sample stands for.
pub fn pprof_profile_gz(samples: &StackSamples, run: &PprofRun) -> Result<Vec<u8>, ExportError> {
    let profile = pprof_profile(samples, run)?;
    let mut gz = GzEncoder::new(Vec::new(), Compression::default());
    gz.write_all(&profile.encode_to_vec())
        .map_err(ExportError::Gzip)?;
    gz.finish().map_err(ExportError::Gzip)
}

/// CPU nanoseconds of `count` samples.
pub fn sample_nanoseconds(count: u64, seconds_per_sample: f64) -> i64 {
    (count as f64 * seconds_per_sample * 1e9).round() as i64
}

/// The profile before encoding.
fn pprof_profile(samples: &StackSamples, run: &PprofRun) -> Result<Profile, ExportError> {
    let mut strings = StringTable::default();
    let mut function_ids: HashMap<&str, u64> = HashMap::new();
    let mut functions = Vec::new();
    let mut profile_samples = Vec::with_capacity(samples.stacks.len());
    for stack in &samples.stacks {
        let mut location_id = Vec::with_capacity(stack.frames.len());
        // profile.proto: "The leaf is at location_id[0]".
        for frame in stack.frames.iter().rev() {
            let next_id = function_ids.len() as u64 + 1;
            let id = *function_ids.entry(frame.as_str()).or_insert_with(|| {
                let name = strings.index(frame);
                functions.push(Function {
                    id: next_id,
                    name,
                    system_name: name,
                    filename: 0,
                    start_line: 0,
                });
                next_id
            });
            location_id.push(id);
        }
        let count = i64::try_from(stack.count).map_err(|_| ExportError::TooLarge(stack.count))?;
        profile_samples.push(Sample {
            location_id,
            value: vec![
                count,
                sample_nanoseconds(stack.count, samples.seconds_per_sample),
            ],
            label: Vec::new(),
        });
    }
    // Location i and function i are one-to-one (one line each, no addresses).
    let location = functions
        .iter()
        .map(|f| Location {
            id: f.id,
            mapping_id: 0,
            address: 0,
            line: vec![Line {
                function_id: f.id,
                line: 0,
            }],
            is_folded: false,
        })
        .collect();
    let sample_type = vec![
        ValueType {
            ty: strings.index("samples"),
            unit: strings.index("count"),
        },
        ValueType {
            ty: strings.index("cpu"),
            unit: strings.index("nanoseconds"),
        },
    ];
    let period_type = Some(ValueType {
        ty: strings.index("cpu"),
        unit: strings.index("nanoseconds"),
    });
    let comment = run.comments.iter().map(|c| strings.index(c)).collect();
    Ok(Profile {
        sample_type,
        sample: profile_samples,
        mapping: Vec::new(),
        location,
        function: functions,
        drop_frames: 0,
        keep_frames: 0,
        time_nanos: 0,
        duration_nanos: i64::try_from(run.duration.as_nanos()).unwrap_or(i64::MAX),
        period_type,
        period: (samples.seconds_per_sample * 1e9).round() as i64,
        comment,
        // The CPU time, not the count, is what `go tool pprof` shows first.
        default_sample_type: 1,
        string_table: strings.strings,
    })
}

/// profile.proto's string table: every string once, `""` at index 0.
struct StringTable {
    strings: Vec<String>,
    index: HashMap<String, i64>,
}

impl Default for StringTable {
    fn default() -> Self {
        StringTable {
            strings: vec![String::new()],
            index: HashMap::from([(String::new(), 0)]),
        }
    }
}

impl StringTable {
    fn index(&mut self, s: &str) -> i64 {
        if let Some(&i) = self.index.get(s) {
            return i;
        }
        let i = self.strings.len() as i64;
        self.strings.push(s.to_string());
        self.index.insert(s.to_string(), i);
        i
    }
}

/// A speedscope file (its published schema, [`SPEEDSCOPE_SCHEMA`]) named `name`, with
/// one sampled profile per `(profile name, samples)`: e.g. the phase view and the
/// native view of one run. Frames are shared between the profiles; each distinct
/// stack is one sample (frame indices root first) weighted by its CPU seconds, so a
/// profile's `endValue` is its total CPU time. The first profile opens first.
pub fn speedscope_json(name: &str, profiles: &[(&str, &StackSamples)]) -> String {
    let mut frame_index: HashMap<&str, usize> = HashMap::new();
    let mut frames: Vec<Value> = Vec::new();
    let mut out_profiles = Vec::with_capacity(profiles.len());
    for &(profile_name, samples) in profiles {
        let mut stacks = Vec::with_capacity(samples.stacks.len());
        let mut weights = Vec::with_capacity(samples.stacks.len());
        let mut end = 0.0;
        for stack in &samples.stacks {
            let indices: Vec<usize> = stack
                .frames
                .iter()
                .map(|frame| {
                    *frame_index.entry(frame.as_str()).or_insert_with(|| {
                        frames.push(json!({ "name": frame }));
                        frames.len() - 1
                    })
                })
                .collect();
            let weight = stack.count as f64 * samples.seconds_per_sample;
            end += weight;
            stacks.push(indices);
            weights.push(weight);
        }
        out_profiles.push(json!({
            "type": "sampled",
            "name": profile_name,
            "unit": "seconds",
            "startValue": 0.0,
            "endValue": end,
            "samples": stacks,
            "weights": weights,
        }));
    }
    json!({
        "$schema": SPEEDSCOPE_SCHEMA,
        "shared": { "frames": frames },
        "profiles": out_profiles,
        "name": name,
        "activeProfileIndex": 0,
        "exporter": EXPORTER,
    })
    .to_string()
}
