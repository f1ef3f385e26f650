//! `rtprof serve`: the thesis's GUI (Pick, Run, View Image, Open report) as a local
//! web app over the same runner and reports as the command line. A page (askama
//! template, embedded script, no network reference) drives a JSON API
//! (docs/serve.md); jobs run one at a time in the background with live progress
//! (server-sent events), each into its own directory of the data directory, where
//! `rtprof report` can read its results.json too.
//!
//! The server binds to 127.0.0.1 unless told otherwise, answers only requests
//! addressed to it by that name, and refuses state-changing requests without its
//! per-server token ([`guard`]).

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod api;
pub mod catalogue;
pub mod config;
pub mod error;
pub mod estimate;
pub mod guard;
pub mod job;
pub mod jobs;
pub mod page;
pub mod pixel;
pub mod store;
pub mod uploads;

use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

pub use config::Config;
pub use error::{ApiError, ServeError};

/// Default largest upload, bytes (64 MiB).
pub const DEFAULT_MAX_UPLOAD_BYTES: u64 = 64 << 20;

/// How long connections still open at a stop may take to finish.
const SHUTDOWN_GRACE: std::time::Duration = std::time::Duration::from_secs(2);

/// A server running on its own threads.
pub struct Server {
    pub address: SocketAddr,
    pub url: String,
    pub token: String,
    /// Directories under `jobs/` that were not readable jobs, skipped on start.
    pub skipped: Vec<String>,
    /// The outside tracers jobs may run (`--tracer`, `--peers`), by name.
    pub tracers: Vec<String>,
    /// Built-in peers `--peers` asked for that are not installed (not offered).
    pub missing_peers: Vec<String>,
    /// The data directory, for [`Server::notes`].
    data: std::path::PathBuf,
    jobs: Arc<jobs::Jobs>,
    _lock: store::DataLock,
    shutdown: Option<tokio::sync::watch::Sender<bool>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Server {
    /// Opens the data directory (rebuilding the history), binds and starts serving.
    /// The outside tracers' definitions are read and checked first: a bad one stops
    /// the start ([`ServeError::Tracer`], naming its file, line and column).
    pub fn start(config: &Config) -> Result<Server, ServeError> {
        let (tracers, missing_peers) = config
            .tracers
            .load_with_peers()
            .map_err(ServeError::Tracer)?;
        let tracer_names = tracers.iter().map(|t| t.name.clone()).collect();
        let store = store::Store::open(&config.data)?;
        let lock = store.lock()?;
        let history = store.history()?;
        let catalogue = catalogue::Catalogue::new(store.scenes_dir(), config.max_upload_bytes)
            .with_tracers(tracers);
        let token = guard::new_token().map_err(ServeError::Other)?;
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .map_err(|e| ServeError::Other(format!("cannot start the async runtime: {e}")))?;
        let wanted = SocketAddr::new(config.bind, config.port);
        let listener = runtime
            .block_on(tokio::net::TcpListener::bind(wanted))
            .map_err(|e| ServeError::Bind {
                address: wanted.to_string(),
                message: e.to_string(),
            })?;
        let address = listener.local_addr().map_err(|e| ServeError::Bind {
            address: wanted.to_string(),
            message: e.to_string(),
        })?;
        let url = match address.ip() {
            IpAddr::V6(ip) => format!("http://[{ip}]:{}/", address.port()),
            IpAddr::V4(ip) => format!("http://{ip}:{}/", address.port()),
        };
        let hosts = if config.bind.is_loopback() {
            vec![
                "127.0.0.1".to_string(),
                "localhost".to_string(),
                "::1".to_string(),
            ]
        } else {
            // An explicit non-local --bind: the user chose to be reachable by any name.
            Vec::new()
        };
        let jobs = jobs::Jobs::start(store.clone(), catalogue, history.jobs);
        let state = api::AppState {
            jobs: Arc::clone(&jobs),
            token: token.clone(),
        };
        let guard = guard::Guard {
            token: token.clone(),
            hosts,
        };
        let app = api::router(state, guard, config.max_upload_bytes);
        store.announce(&url, &token)?;
        let (shutdown, stopped) = tokio::sync::watch::channel(false);
        let thread = std::thread::Builder::new()
            .name("rtprof-serve".into())
            .spawn(move || {
                runtime.block_on(async move {
                    let mut graceful = stopped.clone();
                    let served = axum::serve(listener, app).with_graceful_shutdown(async move {
                        let _ = graceful.wait_for(|stop| *stop).await;
                    });
                    // Open connections get a moment to finish; a client that holds one
                    // (an event stream of a page left open) does not hold the stop.
                    let mut deadline = stopped;
                    let deadline = async move {
                        let _ = deadline.wait_for(|stop| *stop).await;
                        tokio::time::sleep(SHUTDOWN_GRACE).await;
                    };
                    tokio::select! {
                        served = served => if let Err(e) = served {
                            eprintln!("rtprof: error: the server stopped: {e}");
                        },
                        () = deadline => {}
                    }
                });
                // Event streams never end by themselves: do not wait for them.
                runtime.shutdown_background();
            })
            .map_err(|e| ServeError::Other(format!("cannot start the server thread: {e}")))?;
        Ok(Server {
            address,
            url,
            token,
            skipped: history.skipped,
            tracers: tracer_names,
            missing_peers,
            data: config.data.clone(),
            jobs,
            _lock: lock,
            shutdown: Some(shutdown),
            thread: Some(thread),
        })
    }

    /// Stops serving and stops the running job (it ends as interrupted, its partial
    /// outputs kept); waits for both.
    pub fn stop(mut self) {
        self.stop_now();
    }

    fn stop_now(&mut self) {
        if let Some(shutdown) = self.shutdown.take() {
            let _ = shutdown.send(true);
        }
        self.jobs.shut_down();
        while self.jobs.busy() {
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }

    /// What is worth saying at start besides the address, one line each: the job
    /// directories skipped, the outside tracers offered and the peers not installed.
    pub fn notes(&self) -> Vec<String> {
        let mut notes: Vec<String> = self
            .skipped
            .iter()
            .map(|name| {
                format!(
                    "warning: {}/jobs/{name} is not a readable job; left alone",
                    self.data.display()
                )
            })
            .collect();
        if !self.tracers.is_empty() {
            notes.push(format!(
                "outside tracers jobs may run: {}",
                self.tracers.join(", ")
            ));
        }
        for name in &self.missing_peers {
            notes.push(format!(
                "--peers: {name} is not installed, so it is not offered"
            ));
        }
        notes
    }

    /// Whether a job is running now.
    pub fn busy(&self) -> bool {
        self.jobs.busy()
    }

    /// Serves until `stop` is raised (Ctrl-C), then stops as [`Server::stop`] does.
    /// `note` hears the one line worth saying before a running job is stopped.
    pub fn serve_until(self, stop: &AtomicBool, note: impl Fn(&str)) {
        while !stop.load(Ordering::SeqCst) {
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
        if self.busy() {
            note(
                "rtprof serve: stopping the job under way (within a sample row); it is kept as interrupted",
            );
        }
        self.stop();
    }

    /// Opens the page in the user's browser (xdg-open); the error says what to do.
    pub fn open_in_browser(&self) -> Result<(), String> {
        std::process::Command::new("xdg-open")
            .arg(&self.url)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .map(drop)
            .map_err(|_| {
                format!(
                    "could not start a browser (xdg-open); open {} yourself",
                    self.url
                )
            })
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop_now();
    }
}
