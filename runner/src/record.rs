//! `rtprof record -- CMD`: another program profiled with Linux perf. The program is
//! forked and held before its `exec` ([`launch::Held`]); `perf record -p` attaches to
//! it with its events disabled, enables them through its control pipe and says so;
//! then the program runs as rtprof's own child (its streams the user's, its exit
//! status and CPU time read by rtprof, not by perf), every thread and process it
//! starts inherited by the events. When it ends (or Ctrl-C or the time limit stops
//! it), perf is stopped and its `perf.data` read into the sample model
//! ([`analysis::profile::perf_data`]) and written by the profile writer `rtprof
//! profile` uses ([`crate::record_files`]). docs/record.md says why this design.

use std::ffi::OsString;
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::record_diff::{Baseline, read_baseline};
use crate::report_files::Pdf;
use analysis::profile::perf_data::coverage::ModuleCoverage;
use analysis::profile::perf_data::{PerfProfile, read_perf_data};
use analysis::profile::phase_rules::{PhaseBreakdown, PhaseRules};
pub use launch::End;
use launch::{Finished, Launch, Running, Stream};
use results::ProfileView;

use crate::error::{PARANOID, PERF_VARIABLE, PerfError, RunError};
use crate::profile_job::ViewProfile;
use crate::record_probe::{self, ProbeOutcome};

/// Samples per CPU second asked by default: the in-process sampler's perf rate.
pub const DEFAULT_FREQUENCY: u32 = 4000;
/// Share of the samples in shared libraries from which a frame-pointer recording warns
/// that their callers may be skipped ([`Recording::frame_pointer_caveat`]).
const LIBRARY_SHARE_CAVEAT: f64 = 0.05;
/// Longest perf may take to attach and say its events are on.
const ATTACH_LIMIT: Duration = Duration::from_secs(30);
/// Longest perf may take to write its file once told to stop.
const STOP_LIMIT: Duration = Duration::from_secs(120);

/// How perf finds the callers of each sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum CallGraph {
    /// The kernel walks frame pointers: cheap and small, needs code built with them.
    #[default]
    Fp,
    /// perf copies 32 KiB of stack per sample, unwound here from `.eh_frame`: works
    /// without frame pointers, writes far more.
    Dwarf,
}

impl CallGraph {
    /// How the summary and the report say it.
    pub fn describe(self) -> &'static str {
        match self {
            CallGraph::Fp => "frame pointers",
            CallGraph::Dwarf => "DWARF unwinding",
        }
    }

    fn perf_option(self) -> &'static str {
        match self {
            CallGraph::Fp => "fp",
            // 32 KiB of stack, not perf's 8: rtprof's own render needs about 16.
            CallGraph::Dwarf => "dwarf,32768",
        }
    }
}

// `rtprof record`'s flags: the settings of a recording, declared here (behind the
// `clap` feature) with their defaults and help. (A plain comment: a doc comment here
// would replace the command's help line.)
#[derive(Clone, Debug)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
// A program to run or a recording to import: one of them, named in the usage error;
// the usage shows both forms (the group's own would hide the `--` before CMD).
#[cfg_attr(feature = "clap", command(group(clap::ArgGroup::new("source")
    .required(true).args(["command", "import"])),
    override_usage = "rtprof record [OPTIONS] -- <CMD>...\n       rtprof record --import <FILE> [-o <DIR>]"))]
pub struct RecordSettings {
    // The angle brackets are for `--help` (clap reads this doc), not HTML.
    #[allow(rustdoc::invalid_html_tags)]
    /// Output directory [default: record-<program>]: perf.data, flat-<program>.txt,
    /// callgraph-, flame-, folded-, amdahl-, profile-…pb.gz, speedscope-, modules.txt,
    /// modules.json, phases-, report.html, report.pdf (unless --no-pdf), record.json; with rtprof's
    /// probe in the program, probe.rtprof and counts-.
    #[cfg_attr(feature = "clap", arg(short, long, value_name = "DIR"))]
    pub output: Option<PathBuf>,
    /// Samples per CPU second of each thread (perf's cpu-clock).
    #[cfg_attr(feature = "clap", arg(long, default_value_t = DEFAULT_FREQUENCY, value_name = "HZ",
        value_parser = clap::value_parser!(u32).range(10..=10_000)))]
    pub freq: u32,
    /// How callers are found: fp (frame pointers, walked by the kernel) or dwarf
    /// (32 KiB of stack copied per sample and unwound here; for code without frame
    /// pointers).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value_t = CallGraph::Fp))]
    pub call_graph: CallGraph,
    /// Stop the program after this many seconds (its profile is kept).
    #[cfg_attr(feature = "clap", arg(long, value_name = "SECONDS",
        value_parser = parse_seconds))]
    pub time_limit: Option<Duration>,
    /// Phase rules (TOML: function-name and source-file patterns to phases of ray
    /// tracing) instead of the built-in ones; docs/record.md shows the form.
    #[cfg_attr(feature = "clap", arg(long, value_name = "FILE"))]
    pub phases: Option<PathBuf>,
    /// An earlier record's directory: differential flamegraphs from it to this run
    /// (what grew, what shrank), flame-diff-*.svg.
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub baseline: Option<PathBuf>,
    /// The program and its arguments, after `--` (run without a shell).
    #[cfg_attr(feature = "clap", arg(last = true, value_name = "CMD"))]
    pub command: Vec<OsString>,
    /// Read a recording made elsewhere instead of running a program: a perf.data
    /// (perf record -g) or GNU gprof's text output (gprof PROG gmon.out > prof.txt).
    #[cfg_attr(feature = "clap", arg(long, value_name = "FILE",
        conflicts_with_all = ["command", "freq", "call_graph", "time_limit"]))]
    pub import: Option<PathBuf>,
    #[cfg_attr(feature = "clap", command(flatten))]
    pub pdf: crate::report_files::PdfFlag,
}

/// A positive number of seconds.
pub fn parse_seconds(text: &str) -> Result<Duration, String> {
    text.parse::<f64>()
        .ok()
        .filter(|s| *s > 0.0)
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .ok_or_else(|| format!("'{text}' is not a positive number of seconds"))
}

impl RecordSettings {
    /// The output directory: `--output`, or `record-<program's file name>`.
    pub fn dir(&self) -> PathBuf {
        self.output.clone().unwrap_or_else(|| {
            let program = self.command.first().map(Path::new);
            let name = program
                .and_then(Path::file_name)
                .unwrap_or("command".as_ref());
            PathBuf::from(format!("record-{}", name.to_string_lossy()))
        })
    }

    /// The plan of these settings, writing into `dir`, stopped by `stop`.
    pub fn plan<'a>(&'a self, dir: &'a Path, stop: &'a AtomicBool) -> RecordPlan<'a> {
        RecordPlan {
            command: &self.command,
            frequency: self.freq,
            call_graph: self.call_graph,
            dir,
            stop,
            time_limit: self.time_limit,
            phases: self.phases.as_deref(),
            baseline: self.baseline.as_deref(),
            setup: ProgramSetup::default(),
            pdf: self.pdf.choice(),
        }
    }
}

/// How the recorded program is started beyond its command: `rtprof record`'s default
/// (the caller's directory, streams and environment), or an outside tracer's run in a
/// suite (its own directory, its definition's variables, its output in files).
#[derive(Clone, Debug, Default)]
pub struct ProgramSetup {
    /// Variables set on top of rtprof's environment.
    pub env: Vec<(OsString, OsString)>,
    /// Its working directory (`None`: the caller's).
    pub dir: Option<PathBuf>,
    pub stdin: Stream,
    pub stdout: Stream,
    pub stderr: Stream,
}

/// What to record and how.
pub struct RecordPlan<'a> {
    /// The program and its arguments.
    pub command: &'a [OsString],
    pub frequency: u32,
    pub call_graph: CallGraph,
    /// Where perf.data, perf's log and the profile's files go.
    pub dir: &'a Path,
    /// Set on Ctrl-C: the program is stopped and what was sampled is kept.
    pub stop: &'a AtomicBool,
    /// Longest the program may run.
    pub time_limit: Option<Duration>,
    /// A phase rules file; `None`: the built-in rules.
    pub phases: Option<&'a Path>,
    /// An earlier record to draw the differences from.
    pub baseline: Option<&'a Path>,
    /// Where the program runs and where its streams go.
    pub setup: ProgramSetup,
    /// Whether the recording's report.pdf is written.
    pub pdf: Pdf,
}

/// The phase rules of a plan: its file's, or the built-in ones. Read before the
/// program runs, so a bad file costs nothing (exit 2, `file:line: …`).
pub fn phase_rules(file: Option<&Path>) -> Result<PhaseRules, RunError> {
    match file {
        Some(path) => PhaseRules::load(path),
        None => PhaseRules::builtin(),
    }
    .map_err(|e| RunError::Input(e.to_string()))
}

/// How a recording counts as failed (each its exit code in the binary).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Failure {
    /// Ctrl-C stopped the program (130).
    Interrupted(String),
    /// The program exited non-zero, was killed or timed out (4).
    CommandFailed(String),
    /// The program's probe file could not be read (2, bad input).
    BadProbeFile(String),
}

/// A recorded run: how the program ended and its profile.
pub struct Recording {
    pub command: Vec<String>,
    pub finished: Finished,
    pub frequency: u32,
    pub call_graph: CallGraph,
    /// perf.data as read: stacks, modules, lost samples.
    pub perf: PerfProfile,
    /// The native-symbol view: flat profile, call graph, folded stacks, Amdahl.
    pub view: ViewProfile,
    /// The samples by phase of ray tracing, by the phase rules.
    pub phases: PhaseBreakdown,
    /// The earlier record `--baseline` named.
    pub baseline: Option<Baseline>,
    pub perf_data: PathBuf,
    /// What the program's probe file gave ([`crate::record_probe`]).
    pub probe: ProbeOutcome,
    /// Whether its report.pdf is written.
    pub pdf: Pdf,
}

impl Recording {
    /// Samples taken.
    pub fn samples(&self) -> u64 {
        self.perf.samples.total()
    }

    /// CPU seconds of the program and the processes it waited for.
    pub fn cpu_seconds(&self) -> f64 {
        self.finished.cpu.as_secs_f64()
    }

    /// What the phases may get wrong under frame pointers ([`frame_pointer_caveat`]).
    pub fn frame_pointer_caveat(&self) -> Option<String> {
        frame_pointer_caveat(self.call_graph, &self.perf.modules)
    }

    /// Why the recording counts as failed, if it does. The program's own failure comes
    /// first; a probe file it wrote that cannot be read is bad input (everything else
    /// is written: the profile from perf's samples stands).
    pub fn failure(&self) -> Option<Failure> {
        match &self.finished.end {
            end if end.success() => self.probe.error().map(|e| {
                Failure::BadProbeFile(format!(
                    "{e}; no exact counts or probe phases, the rest of the profile is written"
                ))
            }),
            End::Stopped => Some(Failure::Interrupted(
                "interrupted: the program was stopped; what was sampled is written".into(),
            )),
            end => Some(Failure::CommandFailed(format!(
                "the recorded program {end}; its profile is written"
            ))),
        }
    }

    /// The program's short name (its file name).
    pub fn name(&self) -> &str {
        let first = self.command.first().map_or("command", String::as_str);
        first.rsplit('/').next().unwrap_or(first)
    }
}

/// Under frame pointers, what the phases may get wrong, when shared libraries hold
/// enough samples for it to matter: a leaf function of a library built without frame
/// pointers (Debian's libc and libm) loses its caller in the kernel's walk, so its
/// samples go to the caller's caller.
pub fn frame_pointer_caveat(call_graph: CallGraph, modules: &[ModuleCoverage]) -> Option<String> {
    if call_graph != CallGraph::Fp {
        return None;
    }
    let total: u64 = modules.iter().map(|m| m.samples).sum();
    let in_libraries: u64 = modules
        .iter()
        .filter(|m| m.path.contains(".so"))
        .map(|m| m.samples)
        .sum();
    let share = in_libraries as f64 / total.max(1) as f64;
    (share >= LIBRARY_SHARE_CAVEAT).then(|| {
        format!(
            "shared libraries hold {} of the samples: under frame pointers a library \
             function built without them loses its caller (its time goes to the \
             caller's caller, and so to that one's phase); --call-graph dwarf finds it",
            reports::format::percent(100.0 * share, 1)
        )
    })
}

/// Records `plan.command` under perf. A program that fails still gives its profile
/// (its end is in [`Recording::finished`]); errors are what kept it from running or
/// being sampled.
pub fn record(plan: &RecordPlan) -> Result<Recording, RunError> {
    let Some((program, args)) = plan.command.split_first() else {
        return Err(RunError::Input(
            "no command to record (give it after --)".into(),
        ));
    };
    let rules = phase_rules(plan.phases)?;
    let baseline = plan.baseline.map(read_baseline).transpose()?;
    // Found before perf starts: "not found" names the user's program, not perf's.
    let program_path = launch::resolve(program)?;
    let perf_program = std::env::var_os(PERF_VARIABLE).unwrap_or_else(|| "perf".into());
    launch::resolve(&perf_program).map_err(|_| PerfError::Missing {
        program: perf_program.to_string_lossy().into_owned(),
    })?;
    let io = |action, path: &Path, e: std::io::Error| RunError::io(action, path, &e);
    std::fs::create_dir_all(plan.dir).map_err(|e| io("create", plan.dir, e))?;
    let perf_data = plan.dir.join("perf.data");
    let log = plan.dir.join("perf.log");
    let ctl = plan.dir.join(".perf-ctl");
    let ack = plan.dir.join(".perf-ack");
    for fifo in [&ctl, &ack] {
        // A stale pipe of an interrupted run is replaced.
        let _ = std::fs::remove_file(fifo);
        launch::make_fifo(fifo).map_err(|e| io("create", fifo, e))?;
    }
    let mut child = Launch::new(program_path.clone(), args.iter().cloned());
    child.program = program_path.into_os_string();
    child.time_limit = plan.time_limit;
    child.env.clone_from(&plan.setup.env);
    child.dir.clone_from(&plan.setup.dir);
    child.stdin = plan.setup.stdin.clone();
    child.stdout = plan.setup.stdout.clone();
    child.stderr = plan.setup.stderr.clone();
    // The probe, if the program has one, writes its counts and phases there.
    let probe_file = record_probe::prepare(plan.dir)?;
    child
        .env
        .push((rtprof_probe::ENV_FILE.into(), probe_file.clone().into()));
    let held = child.start_held()?;
    let perf = perf_launch(
        &perf_program,
        plan,
        held.pid(),
        &perf_data,
        &log,
        &ctl,
        &ack,
    );
    let attached = perf
        .start()
        .map_err(RunError::from)
        .and_then(|p| attach(&p, &ctl, &ack, &log).map(|()| p));
    let perf = match attached {
        Ok(p) => p,
        Err(e) => {
            held.abandon();
            remove_fifos(&ctl, &ack);
            return Err(e);
        }
    };
    let finished = held.release().and_then(|running| running.wait(plan.stop));
    // The program is done (or never ran): perf writes what it has and ends.
    let perf_end = stop_perf(perf);
    remove_fifos(&ctl, &ack);
    let finished = finished?;
    let perf_end = perf_end?;
    let profile = read_perf_data(&perf_data).map_err(|e| PerfError::Failed {
        message: format!("{e} (perf {})", perf_end.end),
        log: log.clone(),
    })?;
    let mut recording = recording(plan, &rules, finished, profile, perf_data);
    recording.baseline = baseline;
    recording.probe = record_probe::read(&probe_file, &recording.phases, record_probe::cores());
    Ok(recording)
}

/// The profile's views from what perf.data held.
fn recording(
    plan: &RecordPlan,
    rules: &PhaseRules,
    finished: Finished,
    mut perf: PerfProfile,
    perf_data: PathBuf,
) -> Recording {
    let command: Vec<String> = plan
        .command
        .iter()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    // Seconds per sample: the program's measured CPU time over the samples; perf's
    // periods only when the kernel gave no time (the program was not ours to wait).
    let samples = perf.samples.total();
    let cpu = finished.cpu.as_secs_f64();
    if samples > 0 && cpu > 0.0 {
        perf.samples.seconds_per_sample = cpu / samples as f64;
    }
    let name = command
        .first()
        .and_then(|c| c.rsplit('/').next())
        .unwrap_or("command")
        .to_string();
    // One run of the program: no exact call counts (the probe will bring them).
    let view = ViewProfile::of_run(ProfileView::Native, perf.samples.clone(), &name);
    let phases = rules.classify(&perf.samples, &perf.sources);
    Recording {
        command,
        finished,
        frequency: plan.frequency,
        call_graph: plan.call_graph,
        perf,
        view,
        phases,
        baseline: None,
        perf_data,
        probe: ProbeOutcome::Absent,
        pdf: plan.pdf,
    }
}

fn perf_launch(
    perf: &OsString,
    plan: &RecordPlan,
    pid: u32,
    data: &Path,
    log: &Path,
    ctl: &Path,
    ack: &Path,
) -> Launch {
    let mut control = OsString::from("fifo:");
    control.push(ctl);
    control.push(",");
    control.push(ack);
    let mut args: Vec<OsString> = vec![
        "record".into(),
        "-q".into(),
        // CPU time, on an hrtimer: no hardware counters needed (works in a VM).
        "-e".into(),
        "cpu-clock".into(),
        "-F".into(),
        plan.frequency.to_string().into(),
        "--call-graph".into(),
        plan.call_graph.perf_option().into(),
        "-p".into(),
        pid.to_string().into(),
        // Events off until the control pipe turns them on: the "ack" is the sign
        // that perf is attached, and only then does the program run.
        "-D".into(),
        "-1".into(),
        "--control".into(),
        control,
        "-o".into(),
        data.into(),
        // No copies of every sampled binary in ~/.debug (perf's build-id cache):
        // rtprof names the samples from the files themselves, and the cache grows by
        // a copy of each rebuilt program on every run (gigabytes over a day of tests).
        "--no-buildid-cache".into(),
    ];
    if plan.call_graph == CallGraph::Dwarf {
        // 32 KiB a sample fills perf's default 512 KiB buffers between its reads:
        // 4 MiB loses none at 4,000 Hz on one thread.
        args.extend(["--mmap-pages".into(), "1024".into()]);
    }
    let mut l = Launch::new(perf.clone(), args);
    l.stdin = Stream::Null;
    l.stdout = Stream::Null;
    l.stderr = Stream::File(log.to_path_buf());
    // Out of the terminal's reach: Ctrl-C stops the program, and perf is stopped
    // after it, so that the end of the run is sampled and the file written.
    l.own_process_group = true;
    l
}

/// Turns perf's events on and waits for its acknowledgement, or for it to fail.
fn attach(perf: &Running, ctl: &Path, ack: &Path, log: &Path) -> Result<(), RunError> {
    let io = |action, path: &Path, e: std::io::Error| RunError::io(action, path, &e);
    let mut control = launch::open_fifo(ctl).map_err(|e| io("open", ctl, e))?;
    let acks = launch::open_fifo(ack).map_err(|e| io("open", ack, e))?;
    let mut unblock = acks.try_clone().map_err(|e| io("open", ack, e))?;
    control
        .write_all(b"enable\n")
        .map_err(|e| io("write", ctl, e))?;
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let read = std::io::BufReader::new(acks).read_line(&mut line);
        let _ = tx.send(read.map(|_| line));
    });
    let started = Instant::now();
    loop {
        match rx.recv_timeout(Duration::from_millis(20)) {
            Ok(Ok(line)) if line.trim() == "ack" => return Ok(()),
            Ok(_) | Err(mpsc::RecvTimeoutError::Disconnected) => break,
            Err(mpsc::RecvTimeoutError::Timeout) => {}
        }
        if let Some(done) = perf.poll()? {
            let _ = unblock.write_all(b"\n");
            return Err(perf_failure(log, &done.end));
        }
        if started.elapsed() > ATTACH_LIMIT {
            break;
        }
    }
    let _ = unblock.write_all(b"\n");
    perf.kill();
    Err(PerfError::Failed {
        message: "perf did not attach to the program".into(),
        log: log.to_path_buf(),
    }
    .into())
}

/// Asks perf to stop (SIGINT: it flushes and writes its file) and waits for it.
fn stop_perf(perf: Running) -> Result<Finished, RunError> {
    perf.interrupt();
    let give_up = AtomicBool::new(false);
    let deadline = Instant::now() + STOP_LIMIT;
    loop {
        if let Some(done) = perf.poll()? {
            return Ok(done);
        }
        if Instant::now() > deadline {
            give_up.store(true, std::sync::atomic::Ordering::Relaxed);
            return Ok(perf.wait(&give_up)?);
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// What perf's log says about why it ended early.
fn perf_failure(log: &Path, end: &End) -> RunError {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let lowered = text.to_lowercase();
    if lowered.contains("perf_event_paranoid")
        || lowered.contains("permission denied")
        || lowered.contains("no permission")
        || lowered.contains("operation not permitted")
    {
        let paranoid = std::fs::read_to_string(PARANOID)
            .map(|s| s.trim().to_string())
            .unwrap_or_else(|_| "unreadable".into());
        return PerfError::NotPermitted { paranoid }.into();
    }
    let last = text
        .lines()
        .map(str::trim)
        .rfind(|l| !l.is_empty())
        .unwrap_or("no message");
    PerfError::Failed {
        message: format!("{last} (perf {end})"),
        log: log.to_path_buf(),
    }
    .into()
}

fn remove_fifos(ctl: &Path, ack: &Path) {
    let _ = std::fs::remove_file(ctl);
    let _ = std::fs::remove_file(ack);
}
