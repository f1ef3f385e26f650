//! One run of an outside tracer: its command expanded for the scene file, size,
//! threads and samples, run without a shell in a directory of its own under its time
//! limit, its image read back and checked, its time taken where its definition says.
//! Whatever goes wrong is a [`Failure`] with the reason and the last lines of its
//! standard error; only the caller's stop flag (Ctrl-C) is not a failure of the program.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use analysis::RgbImage;
use launch::{End, Launch, LaunchError, Stream};
use rtprof_probe::format::{ENV_FILE, ProbeFile};
use tracer::{MAX_DEPTH, RenderOptions, ShadingMode};

use super::definition::{ImageOutput, SceneFormat, TimeSource, TracerDef, expand};
use super::failure::{Failure, FailureKind};

/// Lines of standard error a failure keeps.
pub const STDERR_LINES: usize = 8;

/// What one run is asked.
#[derive(Clone, Copy, Debug)]
pub struct RunPlan<'a> {
    pub def: &'a TracerDef,
    /// The scene file written for it (`None` for a tracer that draws its own).
    pub scene_file: Option<&'a Path>,
    pub width: u32,
    pub height: u32,
    pub threads: usize,
    pub spp: u32,
    /// The shading rtprof's variants render with (`{shading}`, `{depth}`).
    pub shading: Shading,
}

/// How rtprof's variants shade the picture, for a program that can shade the same way:
/// `{shading}` is the mode's name, `{depth}` the ray-tree depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shading {
    pub mode: ShadingMode,
    /// Ray-tree depth, the eye ray being 1.
    pub depth: u32,
}

impl Shading {
    /// The shading of `options`.
    pub fn of(options: &RenderOptions) -> Self {
        Self {
            mode: options.mode,
            depth: options.max_depth,
        }
    }

    /// `{shading}`: `color`, `gray` or `diffuse-only` (rtprof's `--gray` and
    /// `--diffuse-only`).
    pub fn name(self) -> &'static str {
        match self.mode {
            ShadingMode::Color => "color",
            ShadingMode::Gray => "gray",
            ShadingMode::DiffuseOnly => "diffuse-only",
        }
    }
}

impl Default for Shading {
    /// Full Whitted colour to the SPD's depth, what `compare` and the suite render.
    fn default() -> Self {
        Self {
            mode: ShadingMode::Color,
            depth: MAX_DEPTH,
        }
    }
}

/// A run that worked.
#[derive(Clone, Debug)]
pub struct OutsideRun {
    /// The time its definition's source gives, seconds.
    pub seconds: f64,
    /// The whole process's wall time, seconds.
    pub wall: f64,
    /// User + system CPU seconds of the process and its children.
    pub cpu: f64,
    pub image: RgbImage,
    /// Its probe file, when it has the probe.
    pub probe: Option<ProbeFile>,
}

/// How a run ended when it did not give an [`OutsideRun`].
#[derive(Debug)]
pub enum RunEnd {
    /// The caller's stop flag was set.
    Stopped,
    Failed(Failure),
}

impl From<Failure> for RunEnd {
    fn from(f: Failure) -> Self {
        RunEnd::Failed(f)
    }
}

/// The command line of `plan` in `workdir`: program and arguments expanded.
pub fn command_line(plan: &RunPlan<'_>, workdir: &Path) -> Result<Vec<String>, Failure> {
    let values = values(plan, workdir);
    plan.def
        .command
        .iter()
        .map(|a| expand(a, &values).map_err(|m| Failure::new(FailureKind::Setup, m)))
        .collect()
}

/// The variables of `plan`'s definition, expanded for a run in `workdir`.
pub fn environment(
    plan: &RunPlan<'_>,
    workdir: &Path,
) -> Result<Vec<(std::ffi::OsString, std::ffi::OsString)>, Failure> {
    let values = values(plan, workdir);
    plan.def
        .env
        .iter()
        .map(|(key, value)| {
            let value = expand(value, &values).map_err(|m| Failure::new(FailureKind::Setup, m))?;
            Ok((key.into(), value.into()))
        })
        .collect()
}

/// The image file `{output}` names.
pub fn output_path(plan: &RunPlan<'_>, workdir: &Path) -> PathBuf {
    workdir.join(format!("image.{}", plan.def.image.extension()))
}

fn values<'a>(plan: &'a RunPlan<'a>, workdir: &'a Path) -> impl Fn(&str) -> Option<String> + 'a {
    move |name: &str| {
        Some(match name {
            "scene" => plan
                .scene_file
                .map(|p| p.display().to_string())
                .unwrap_or_default(),
            "width" => plan.width.to_string(),
            "height" => plan.height.to_string(),
            "output" => output_path(plan, workdir).display().to_string(),
            "threads" => plan.threads.to_string(),
            "spp" => plan.spp.to_string(),
            "shading" => plan.shading.name().to_string(),
            "depth" => plan.shading.depth.to_string(),
            "workdir" => workdir.display().to_string(),
            // The program running this: rtprof's own binary, or a test's harness.
            "rtprof" => std::env::current_exe().ok()?.display().to_string(),
            _ => return None,
        })
    }
}

/// Runs `plan` once in `workdir` (emptied first, and the program's working directory).
pub fn run_once(
    plan: &RunPlan<'_>,
    workdir: &Path,
    stop: &AtomicBool,
) -> Result<OutsideRun, RunEnd> {
    let setup = |what: &str, e: &std::io::Error| {
        Failure::new(
            FailureKind::Setup,
            format!("cannot {what} {}: {e}", workdir.display()),
        )
    };
    if workdir.exists() {
        std::fs::remove_dir_all(workdir).map_err(|e| setup("empty", &e))?;
    }
    std::fs::create_dir_all(workdir).map_err(|e| setup("create", &e))?;
    let workdir = std::path::absolute(workdir).map_err(|e| setup("resolve", &e))?;
    if plan.def.scene != SceneFormat::Own && plan.scene_file.is_none() {
        return Err(Failure::new(FailureKind::Setup, "no scene file was written for it").into());
    }
    let line = command_line(plan, &workdir)?;
    let mut env = environment(plan, &workdir)?;
    let probe_path = workdir.join(crate::record_probe::PROBE_FILE);
    env.push((ENV_FILE.into(), probe_path.clone().into_os_string()));
    let (stdout, stderr) = (workdir.join("stdout.txt"), workdir.join("stderr.txt"));
    let mut args = line.into_iter();
    let program = args.next().unwrap_or_default();
    let launch = Launch {
        program: program.clone().into(),
        args: args.map(Into::into).collect(),
        env,
        stdin: Stream::Null,
        stdout: Stream::File(stdout.clone()),
        stderr: Stream::File(stderr.clone()),
        time_limit: Some(Duration::from_secs_f64(plan.def.time_limit)),
        own_process_group: true,
        dir: Some(workdir.clone()),
    };
    let finished = launch
        .start()
        .and_then(|running| running.wait(stop))
        .map_err(|e| match e {
            LaunchError::NotFound { .. } | LaunchError::NotExecutable { .. } => {
                Failure::new(FailureKind::NotFound, e.to_string())
            }
            e => Failure::new(FailureKind::Setup, e.to_string()),
        })?;
    let tail = || stderr_tail(&stderr);
    let failed = |kind, reason: String| {
        RunEnd::Failed(Failure {
            kind,
            reason,
            stderr_tail: tail(),
        })
    };
    match finished.end {
        End::Exited(0) => {}
        End::Stopped => return Err(RunEnd::Stopped),
        End::Exited(code) => {
            return Err(failed(
                FailureKind::Exited,
                format!("{program} exited with code {code}"),
            ));
        }
        End::Signalled(_) => {
            return Err(failed(
                FailureKind::Killed,
                format!("{program} {}", finished.end),
            ));
        }
        End::TimedOut => {
            return Err(failed(
                FailureKind::TimedOut,
                format!(
                    "{program} ran past its time limit of {} s and was stopped",
                    plan.def.time_limit
                ),
            ));
        }
    }
    let image_file = match plan.def.output {
        ImageOutput::File => output_path(plan, &workdir),
        ImageOutput::Stdout => stdout.clone(),
    };
    let image = read_image(plan, &image_file).map_err(|f| {
        RunEnd::Failed(Failure {
            stderr_tail: tail(),
            ..f
        })
    })?;
    let probe = probe_path
        .exists()
        .then(|| rtprof_probe::format::read_file(&probe_path))
        .transpose()
        .map_err(|e| {
            failed(
                FailureKind::NoTime,
                format!("its probe file cannot be read: {e}"),
            )
        })?;
    let wall = finished.wall.as_secs_f64();
    let seconds = match &plan.def.time {
        TimeSource::Process => wall,
        TimeSource::Printout { pattern, scale } => {
            let printed = [&stdout, &stderr]
                .iter()
                .filter(|p| plan.def.output == ImageOutput::File || **p != &stdout)
                .find_map(|p| printed_seconds(p, pattern));
            match printed {
                Some(s) => s * scale,
                None => {
                    return Err(failed(
                        FailureKind::NoTime,
                        format!("{program} printed no time matching `{pattern}`"),
                    ));
                }
            }
        }
        TimeSource::Probe { phases } => match probe.as_ref().and_then(|p| probe_seconds(p, phases))
        {
            Some(s) => s,
            None => {
                return Err(failed(
                    FailureKind::NoTime,
                    format!(
                        "{program} wrote no probe file with phases {} sampled",
                        phases.join(", ")
                    ),
                ));
            }
        },
    };
    Ok(OutsideRun {
        seconds,
        wall,
        cpu: finished.cpu.as_secs_f64(),
        image,
        probe,
    })
}

/// The image the program wrote, checked against the size asked (unless it draws a
/// scene of its own).
fn read_image(plan: &RunPlan<'_>, path: &Path) -> Result<RgbImage, Failure> {
    match std::fs::metadata(path) {
        Ok(m) if m.len() > 0 => {}
        _ => {
            return Err(Failure::new(
                FailureKind::NoImage,
                format!("it wrote no image ({} is missing or empty)", path.display()),
            ));
        }
    }
    let image = RgbImage::load(path).map_err(|e| {
        Failure::new(
            FailureKind::BadImage,
            format!(
                "its image cannot be read as {} (truncated?): {e}",
                plan.def.image.extension().to_uppercase()
            ),
        )
    })?;
    if plan.def.scene != SceneFormat::Own
        && (image.width, image.height) != (plan.width, plan.height)
    {
        return Err(Failure::new(
            FailureKind::WrongSize,
            format!(
                "its image is {}x{}, not the {}x{} asked",
                image.width, image.height, plan.width, plan.height
            ),
        ));
    }
    Ok(image)
}

/// The seconds the first capture group of `pattern` finds in the file at `path`.
fn printed_seconds(path: &Path, pattern: &str) -> Option<f64> {
    let text = String::from_utf8_lossy(&std::fs::read(path).ok()?).into_owned();
    let re = regex::Regex::new(pattern).ok()?;
    let seconds: f64 = re.captures(&text)?.get(1)?.as_str().trim().parse().ok()?;
    (seconds.is_finite() && seconds >= 0.0).then_some(seconds)
}

/// The CPU seconds the probe's samples give for `phases` (each phase's samples
/// anywhere on the stack, summed): `None` without samples or without any of them.
fn probe_seconds(probe: &ProbeFile, phases: &[String]) -> Option<f64> {
    let per_sample = probe.seconds_per_sample()?;
    let found: Vec<u64> = phases
        .iter()
        .filter_map(|name| probe.phase(name).map(|p| p.total_samples))
        .collect();
    (!found.is_empty()).then(|| found.iter().sum::<u64>() as f64 * per_sample)
}

/// The last [`STDERR_LINES`] non-empty lines of the file (progress lines ending in
/// carriage returns count as their last state).
pub fn stderr_tail(path: &Path) -> Vec<String> {
    let Ok(bytes) = std::fs::read(path) else {
        return Vec::new();
    };
    let text = String::from_utf8_lossy(&bytes);
    let lines: Vec<String> = text
        .lines()
        .filter_map(|l| l.rsplit('\r').find(|s| !s.trim().is_empty()))
        .map(|l| {
            let l = l.trim_end();
            match l.char_indices().nth(200) {
                Some((at, _)) => format!("{}…", &l[..at]),
                None => l.to_string(),
            }
        })
        .collect();
    lines[lines.len().saturating_sub(STDERR_LINES)..].to_vec()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outside::definition::TracerDef;

    /// A definition running `sh -c SCRIPT` (the script sees the size as $1 $2 and the
    /// output file as $3), a PPM image and the time given.
    fn sh_tracer(script: &str, time: &str, limit: f64) -> TracerDef {
        let text = format!(
            "name = \"sh-tracer\"\ncommand = [\"sh\", \"-c\", '''{script}''', \"sh\", \"{{width}}\", \"{{height}}\", \"{{output}}\"]\nscene = \"own\"\nimage = \"ppm\"\ntime = {time}\ntime_limit = {limit}\n"
        );
        TracerDef::parse(&text, "test.toml").unwrap()
    }

    /// A shell line writing a W x H binary PPM of grey 128 to $3.
    const GREY: &str = "printf 'P6\\n%s %s\\n255\\n' $1 $2 > $3; head -c $(($1 * $2 * 3)) /dev/zero | tr '\\0' '\\200' >> $3";

    fn run(def: &TracerDef, name: &str) -> Result<OutsideRun, RunEnd> {
        let dir =
            std::env::temp_dir().join(format!("rtprof-outside-{}-{name}", std::process::id()));
        let plan = RunPlan {
            def,
            scene_file: None,
            width: 4,
            height: 3,
            threads: 1,
            spp: 1,
            shading: Shading::default(),
        };
        let out = run_once(&plan, &dir, &AtomicBool::new(false));
        let _ = std::fs::remove_dir_all(&dir);
        out
    }

    fn failure(out: Result<OutsideRun, RunEnd>) -> Failure {
        match out {
            Err(RunEnd::Failed(f)) => f,
            Err(RunEnd::Stopped) => panic!("stopped"),
            Ok(_) => panic!("the run worked"),
        }
    }

    #[test]
    fn a_run_gives_its_image_and_its_printed_time() {
        let def = sh_tracer(
            &format!("{GREY}; echo 'Ray Tracing Time: 0.250 seconds' >&2"),
            "{ pattern = 'Ray Tracing Time:\\s+([0-9.]+)', scale = 1000.0 }",
            30.0,
        );
        let out = run(&def, "works").unwrap();
        assert_eq!((out.image.width, out.image.height), (4, 3));
        assert!(out.image.data.iter().all(|&b| b == 128));
        // 0.250 printed, times the definition's scale.
        assert_eq!(out.seconds, 250.0);
        assert!(out.wall > 0.0 && out.wall < 30.0);
    }

    #[test]
    fn each_way_of_failing_is_named_with_the_end_of_stderr() {
        let process = "\"process\"";
        let f = failure(run(
            &sh_tracer("echo 'cannot open scene' >&2; exit 1", process, 30.0),
            "exit",
        ));
        assert_eq!(f.kind, FailureKind::Exited);
        assert!(f.reason.contains("exited with code 1"), "{}", f.reason);
        assert_eq!(f.stderr_tail, ["cannot open scene"]);

        let started = std::time::Instant::now();
        let f = failure(run(&sh_tracer("sleep 30", process, 0.3), "hang"));
        assert_eq!(f.kind, FailureKind::TimedOut);
        assert!(f.reason.contains("0.3 s"), "{}", f.reason);
        assert!(started.elapsed().as_secs_f64() < 10.0);

        let f = failure(run(&sh_tracer("true", process, 30.0), "none"));
        assert_eq!(f.kind, FailureKind::NoImage);

        // The header promises 4 x 3 pixels; half the bytes follow.
        let truncated = format!("{GREY}; head -c 25 $3 > $3.cut; mv $3.cut $3");
        let f = failure(run(&sh_tracer(&truncated, process, 30.0), "cut"));
        assert_eq!(f.kind, FailureKind::BadImage, "{}", f.reason);

        let f = failure(run(
            &sh_tracer(
                &format!("{GREY}; echo done"),
                "{ pattern = 'Time: ([0-9.]+)' }",
                30.0,
            ),
            "notime",
        ));
        assert_eq!(f.kind, FailureKind::NoTime);

        let mut missing = sh_tracer(GREY, process, 30.0);
        missing.command[0] = "no-such-tracer-rtprof".into();
        let f = failure(run(&missing, "missing"));
        assert_eq!(f.kind, FailureKind::NotFound);
        assert!(f.reason.contains("no-such-tracer-rtprof"), "{}", f.reason);
    }

    #[test]
    fn shading_and_depth_expand_to_the_variants_own() {
        let def = TracerDef::parse(
            "name = \"t\"\ncommand = [\"t\", \"--shading\", \"{shading}\", \"--depth\", \"{depth}\", \"{output}\"]\nscene = \"own\"\nimage = \"ppm\"\ntime = \"process\"\n",
            "t.toml",
        )
        .unwrap();
        let plan = |mode, depth| RunPlan {
            def: &def,
            scene_file: None,
            width: 4,
            height: 3,
            threads: 1,
            spp: 1,
            shading: Shading { mode, depth },
        };
        let line =
            |plan: RunPlan<'_>| command_line(&plan, Path::new("/w")).unwrap()[1..5].join(" ");
        assert_eq!(
            line(plan(ShadingMode::DiffuseOnly, 3)),
            "--shading diffuse-only --depth 3"
        );
        assert_eq!(line(plan(ShadingMode::Gray, 5)), "--shading gray --depth 5");
        let mut options =
            RenderOptions::new(8, 8, tracer::Sampling::PixelCenters, ShadingMode::Color);
        options.max_depth = 7;
        assert_eq!(
            line(plan(
                Shading::of(&options).mode,
                Shading::of(&options).depth
            )),
            "--shading color --depth 7"
        );
        assert_eq!(
            Shading::default(),
            Shading {
                mode: ShadingMode::Color,
                depth: MAX_DEPTH
            }
        );
    }

    #[test]
    fn an_image_of_another_size_is_refused_when_the_scene_is_rtprofs() {
        let mut def = sh_tracer(GREY, "\"process\"", 30.0);
        def.scene = SceneFormat::Nff;
        let dir = std::env::temp_dir().join(format!("rtprof-outside-{}-size", std::process::id()));
        let scene = dir.with_extension("nff");
        std::fs::write(&scene, "").unwrap();
        let plan = RunPlan {
            def: &def,
            scene_file: Some(&scene),
            width: 5,
            height: 3,
            threads: 1,
            spp: 1,
            shading: Shading::default(),
        };
        // The script draws $1 x $2, but the command gives it "{width}" = 5... so make
        // it draw 4 by hand: replace the size arguments.
        let mut fixed = def.clone();
        fixed.command[4] = "4".into();
        let plan = RunPlan {
            def: &fixed,
            ..plan
        };
        let f = failure(run_once(&plan, &dir, &AtomicBool::new(false)));
        let _ = std::fs::remove_dir_all(&dir);
        let _ = std::fs::remove_file(&scene);
        assert_eq!(f.kind, FailureKind::WrongSize);
        assert!(f.reason.contains("4x3, not the 5x3"), "{}", f.reason);
    }

    #[test]
    fn the_tail_keeps_the_last_lines_and_the_last_state_of_progress_lines() {
        let path = std::env::temp_dir().join(format!("rtprof-tail-{}", std::process::id()));
        let mut text = String::new();
        for i in 0..20 {
            text += &format!("line {i}\n");
        }
        text += "10%\r50%\r100%\r\n";
        std::fs::write(&path, text).unwrap();
        let tail = stderr_tail(&path);
        std::fs::remove_file(&path).unwrap();
        assert_eq!(tail.len(), STDERR_LINES);
        assert_eq!(tail.last().unwrap(), "100%");
        assert_eq!(tail[0], "line 13");
    }
}
