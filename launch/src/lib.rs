//! `launch`: running other programs is this crate's one job. A program is found on
//! `PATH` without a shell ([`resolve`]), started with its arguments, environment and
//! standard streams as the caller says ([`Launch`]), or held just before its `exec`
//! so that a profiler can attach to it first ([`Launch::start_held`]), then waited
//! for under a time limit and a stop flag ([`Running::wait`]). How it ended is data
//! ([`End`]: an exit code, the signal that killed it, timed out, stopped), and so is
//! a failure to start it ([`LaunchError`]: not found, not executable, each naming
//! the program). `runner` uses it; `tracer` and `analysis` stay free of processes.

// What user input can reach returns an error: no unwrap, expect or panic outside tests.
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

mod end;
mod error;
mod fifo;
mod held;
mod resolve;
mod running;

pub use end::{End, Finished, signal_name};
pub use error::LaunchError;
pub use fifo::{make_fifo, open_fifo};
pub use held::Held;
pub use resolve::resolve;
pub use running::Running;

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

/// Where a standard stream of the program goes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Stream {
    /// The caller's own (a recorded program talks to the user's terminal).
    #[default]
    Inherit,
    /// Nowhere (`/dev/null`).
    Null,
    /// Into this file, created or truncated.
    File(PathBuf),
}

/// A program to run, and how.
#[derive(Clone, Debug, Default)]
pub struct Launch {
    /// The program: a path, or a name looked up on `PATH` ([`resolve`]).
    pub program: OsString,
    pub args: Vec<OsString>,
    /// Variables set on top of the caller's environment.
    pub env: Vec<(OsString, OsString)>,
    pub stdin: Stream,
    pub stdout: Stream,
    pub stderr: Stream,
    /// Longest the program may run; past it, it is stopped ([`End::TimedOut`]).
    pub time_limit: Option<Duration>,
    /// In a process group of its own: the terminal's Ctrl-C does not reach it, the
    /// caller stops it (a profiler that must outlive the program it records).
    pub own_process_group: bool,
    /// Its working directory (`None`: the caller's).
    pub dir: Option<PathBuf>,
}

impl Launch {
    /// `program` with `args`, streams inherited, no time limit.
    pub fn new(
        program: impl Into<OsString>,
        args: impl IntoIterator<Item = impl Into<OsString>>,
    ) -> Self {
        Launch {
            program: program.into(),
            args: args.into_iter().map(Into::into).collect(),
            ..Launch::default()
        }
    }

    /// The program's name as messages give it.
    pub fn name(&self) -> String {
        self.program.to_string_lossy().into_owned()
    }

    /// The std command for the resolved program (no shell: arguments go as they are).
    fn command(&self) -> Result<(Command, PathBuf), LaunchError> {
        let path = resolve(&self.program)?;
        let mut command = Command::new(&path);
        command.args(&self.args);
        command.envs(self.env.iter().map(|(k, v)| (k, v)));
        command.stdin(stdio(&self.stdin, &self.name())?);
        command.stdout(stdio(&self.stdout, &self.name())?);
        command.stderr(stdio(&self.stderr, &self.name())?);
        if let Some(dir) = &self.dir {
            command.current_dir(dir);
        }
        if self.own_process_group {
            std::os::unix::process::CommandExt::process_group(&mut command, 0);
        }
        Ok((command, path))
    }

    /// Starts the program.
    pub fn start(&self) -> Result<Running, LaunchError> {
        let (mut command, _) = self.command()?;
        let child = command
            .spawn()
            .map_err(|e| LaunchError::from_spawn(&self.name(), &e))?;
        Ok(Running::new(child.id(), self.name(), self.time_limit))
    }
}

fn stdio(stream: &Stream, program: &str) -> Result<Stdio, LaunchError> {
    Ok(match stream {
        Stream::Inherit => Stdio::inherit(),
        Stream::Null => Stdio::null(),
        Stream::File(path) => std::fs::File::create(path)
            .map_err(|e| LaunchError::Output {
                program: program.to_string(),
                path: path.clone(),
                message: e.to_string(),
            })?
            .into(),
    })
}
