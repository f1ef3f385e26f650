//! The job queue: jobs run one at a time on a worker thread (the renders use every
//! core), each watched through a channel the event streams follow, each cancellable
//! at the runner's next safe point. Status changes are saved to the job's `job.json`.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, mpsc};

use runner::RunError;
use runner::definition::SuiteDef;
use runner::report_files::Pdf;
use runner::suite::Suite;
use runner::suite_dir::{DirRun, run_into_dir};
use tokio::sync::watch;

use crate::catalogue::{Catalogue, Part};
use crate::error::ApiError;
use crate::job::{Job, JobProgress, JobRequest, JobStatus};
use crate::store::{PARTIAL_DIR, Store, list_files};

struct Entry {
    job: Job,
    stop: Arc<AtomicBool>,
    watch: watch::Sender<Job>,
}

/// Every job this server knows (the history and the new ones).
pub struct Jobs {
    entries: Mutex<BTreeMap<u64, Entry>>,
    store: Store,
    catalogue: Catalogue,
    queue: Mutex<Option<mpsc::Sender<u64>>>,
    /// Set when the server stops: the running job ends as interrupted, not cancelled.
    shutting_down: AtomicBool,
}

impl Jobs {
    /// The registry with the history of the data directory, and its worker started.
    pub fn start(store: Store, catalogue: Catalogue, history: Vec<Job>) -> Arc<Self> {
        let entries = history
            .into_iter()
            .filter_map(|job| {
                let id = job.id.parse().ok()?;
                let (watch, _) = watch::channel(job.clone());
                let stop = Arc::new(AtomicBool::new(false));
                Some((id, Entry { job, stop, watch }))
            })
            .collect();
        let (sender, receiver) = mpsc::channel();
        let jobs = Arc::new(Jobs {
            entries: Mutex::new(entries),
            store,
            catalogue,
            queue: Mutex::new(Some(sender)),
            shutting_down: AtomicBool::new(false),
        });
        let worker = Arc::clone(&jobs);
        std::thread::Builder::new()
            .name("rtprof-jobs".into())
            .spawn(move || {
                while let Ok(id) = receiver.recv() {
                    worker.run(id);
                }
            })
            .map_or_else(
                |e| eprintln!("rtprof: error: cannot start the job worker: {e}"),
                |_| (),
            );
        jobs
    }

    fn lock(&self) -> MutexGuard<'_, BTreeMap<u64, Entry>> {
        // A panic while holding the lock leaves plain data; keep serving it.
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn catalogue(&self) -> &Catalogue {
        &self.catalogue
    }

    pub fn store(&self) -> &Store {
        &self.store
    }

    /// Checks `request` and queues it.
    pub fn submit(&self, request: JobRequest) -> Result<Job, ApiError> {
        let request = request.checked(&self.catalogue)?;
        let job = {
            let mut entries = self.lock();
            // Never an id given before (a deleted job's), nor a directory the history
            // skipped (unreadable, left alone).
            let id = self
                .store
                .next_id(entries.keys().next_back().map_or(1, |last| last + 1))
                .map_err(|e| ApiError::internal(e.to_string()))?;
            let job = Job {
                id: id.to_string(),
                request,
                status: JobStatus::Queued,
                created: runner::machine::now_rfc3339(),
                started: None,
                finished: None,
                progress: JobProgress {
                    stage: "queued".into(),
                    ..JobProgress::default()
                },
                error: None,
                files: Vec::new(),
                started_unix: None,
                finished_unix: None,
                text: Default::default(),
            };
            self.store
                .save(&job)
                .map_err(|e| ApiError::internal(e.to_string()))?;
            let (watch, _) = watch::channel(job.clone());
            let stop = Arc::new(AtomicBool::new(false));
            entries.insert(
                id,
                Entry {
                    job: job.clone(),
                    stop,
                    watch,
                },
            );
            job
        };
        let queued = self
            .queue
            .lock()
            .ok()
            .and_then(|q| q.as_ref().map(|s| s.send(job_id(&job)).is_ok()));
        if queued != Some(true) {
            return Err(ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                "the server is stopping; it takes no new jobs",
            ));
        }
        Ok(job)
    }

    /// Every job, newest first.
    pub fn list(&self) -> Vec<Job> {
        self.lock().values().rev().map(|e| e.job.clone()).collect()
    }

    pub fn get(&self, id: u64) -> Result<Job, ApiError> {
        self.lock()
            .get(&id)
            .map(|e| e.job.clone())
            .ok_or_else(|| unknown(id))
    }

    /// A receiver of the job's every change (its current state first).
    pub fn subscribe(&self, id: u64) -> Result<watch::Receiver<Job>, ApiError> {
        self.lock()
            .get(&id)
            .map(|e| e.watch.subscribe())
            .ok_or_else(|| unknown(id))
    }

    /// Cancels a queued job at once, a running one within a sample row's time (the
    /// renders read its stop flag before each row).
    pub fn cancel(&self, id: u64) -> Result<Job, ApiError> {
        let status = self.get(id)?.status;
        match status {
            JobStatus::Queued => {
                self.update(id, true, |job| {
                    job.status = JobStatus::Cancelled;
                    job.finished = Some(runner::machine::now_rfc3339());
                    job.finished_unix = Some(crate::job::unix_now());
                    job.error = Some("cancelled before it started".into());
                });
            }
            JobStatus::Running => {
                if let Some(entry) = self.lock().get(&id) {
                    entry.stop.store(true, Ordering::SeqCst);
                }
                self.update(id, false, |job| {
                    job.progress.message = CANCELLING.into();
                });
            }
            done => {
                return Err(ApiError::conflict(format!(
                    "job {id} is already {}: there is nothing to cancel",
                    serde_json::to_value(done)
                        .ok()
                        .and_then(|v| v.as_str().map(str::to_string))
                        .unwrap_or_default()
                )));
            }
        }
        self.get(id)
    }

    /// Deletes finished job `id`: its directory and its entry. A queued or running job
    /// is cancelled instead ([`Jobs::cancel`]); that is a 409 here.
    pub fn delete(&self, id: u64) -> Result<(), ApiError> {
        let mut entries = self.lock();
        let entry = entries.get(&id).ok_or_else(|| unknown(id))?;
        if !entry.job.status.is_final() {
            return Err(ApiError::conflict(format!(
                "job {id} is {}: cancel it first (DELETE /api/jobs/{id}), then delete it",
                match entry.job.status {
                    JobStatus::Queued => "queued",
                    _ => "running",
                }
            )));
        }
        let dir = self.store.job_dir(id);
        match std::fs::remove_dir_all(&dir) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => {
                return Err(ApiError::internal(format!(
                    "cannot delete {}: {e}",
                    dir.display()
                )));
            }
        }
        entries.remove(&id);
        Ok(())
    }

    /// Stops taking jobs: the queued ones end as interrupted at once, the running one
    /// at the runner's next safe point (also as interrupted).
    pub fn shut_down(&self) {
        self.shutting_down.store(true, Ordering::SeqCst);
        if let Ok(mut queue) = self.queue.lock() {
            queue.take();
        }
        let queued: Vec<u64> = {
            let entries = self.lock();
            for entry in entries.values() {
                if entry.job.status == JobStatus::Running {
                    entry.stop.store(true, Ordering::SeqCst);
                }
            }
            entries
                .iter()
                .filter(|(_, e)| e.job.status == JobStatus::Queued)
                .map(|(&id, _)| id)
                .collect()
        };
        for id in queued {
            self.update(id, true, |job| {
                // The worker may have started it meanwhile; then it stops as running.
                if job.status != JobStatus::Queued {
                    return;
                }
                job.status = JobStatus::Interrupted;
                job.finished = Some(runner::machine::now_rfc3339());
                job.finished_unix = Some(crate::job::unix_now());
                job.error = Some("the server stopped before this job started; run it again".into());
            });
        }
    }

    /// Whether a job is running.
    pub fn busy(&self) -> bool {
        self.lock()
            .values()
            .any(|e| e.job.status == JobStatus::Running)
    }

    /// Changes job `id`, tells its watchers, and saves `job.json` when `save`.
    fn update(&self, id: u64, save: bool, change: impl FnOnce(&mut Job)) {
        let mut entries = self.lock();
        let Some(entry) = entries.get_mut(&id) else {
            return;
        };
        change(&mut entry.job);
        entry.watch.send_replace(entry.job.clone());
        if save && let Err(e) = self.store.save(&entry.job) {
            eprintln!("rtprof: warning: {e}");
        }
    }

    /// Runs job `id` (on the worker thread), unless it was cancelled while queued.
    fn run(&self, id: u64) {
        let Some((request, stop)) = self.lock().get(&id).and_then(|e| {
            (e.job.status == JobStatus::Queued).then(|| (e.job.request.clone(), e.stop.clone()))
        }) else {
            return;
        };
        self.update(id, true, |job| {
            job.status = JobStatus::Running;
            job.started = Some(runner::machine::now_rfc3339());
            job.started_unix = Some(crate::job::unix_now());
            job.progress.stage = "starting".into();
        });
        // A stop that came while it was being started.
        if self.shutting_down.load(Ordering::SeqCst) {
            stop.store(true, Ordering::SeqCst);
        }
        let dir = self.store.job_dir(id);
        let progress = ProgressSink {
            jobs: self,
            id,
            stop: &stop,
        };
        let outcome = execute(&request, &self.catalogue, &dir, &progress, &stop);
        let interrupted = self.shutting_down.load(Ordering::SeqCst);
        let files = list_files(&dir);
        let partial = match files.iter().any(|f| f.starts_with("partial/")) {
            true => "; its partial outputs are under partial/",
            false => "; it had written no output yet",
        };
        self.update(id, true, |job| {
            job.finished = Some(runner::machine::now_rfc3339());
            job.finished_unix = Some(crate::job::unix_now());
            job.files = files;
            match outcome {
                Ok(()) => {
                    job.status = JobStatus::Done;
                    job.progress.fraction = 1.0;
                    job.progress.stage = "done".into();
                    job.progress.message.clear();
                }
                Err(Ended::Stopped) if interrupted => {
                    job.status = JobStatus::Interrupted;
                    job.error = Some(format!("the server stopped during this job{partial}"));
                }
                Err(Ended::Stopped) => {
                    job.status = JobStatus::Cancelled;
                    job.error = Some(format!("cancelled{partial}"));
                }
                Err(Ended::Failed(message)) => {
                    job.status = JobStatus::Failed;
                    job.error = Some(format!("{message}{partial}"));
                }
            }
        });
    }
}

/// What a job being cancelled says: renders read the stop flag before each sample row,
/// so the job ends within a row's time (well under a second on the suite's scenes).
const CANCELLING: &str = "cancelling";

fn job_id(job: &Job) -> u64 {
    job.id.parse().unwrap_or(0)
}

fn unknown(id: u64) -> ApiError {
    ApiError::not_found(format!("no job {id}: GET /api/jobs lists them"))
}

/// How a job ended without finishing.
enum Ended {
    Stopped,
    Failed(String),
}

/// The suite definition of a job: its one scene and variants at its size, with the
/// parts it asked for; or the embedded suite's quick run.
fn definition(request: &JobRequest, catalogue: &Catalogue) -> Result<(SuiteDef, bool), Ended> {
    let failed = |e: &dyn std::fmt::Display| Ended::Failed(e.to_string());
    if request.runs(Part::Suite) {
        return Ok((SuiteDef::load(None).map_err(|e| failed(&e))?, true));
    }
    let entry = catalogue
        .resolve(&request.scene)
        .map_err(|e| Ended::Failed(e.message))?;
    let def = SuiteDef {
        name: "serve".into(),
        size: request.size,
        repeats: 3,
        min_seconds: 0.1,
        // Timed on one thread, as the suite is (`SuiteDef::timing_threads`).
        timing_threads: 1,
        variants: request.variants.clone(),
        scenes: vec![entry],
        extra_size: request.size,
        profile_size: request.size,
        // The sampler's timer picks the rate (4,000 Hz under perf cpu-clock).
        profile_frequency: None,
        profile_samples: 300,
        hardware_repeats: 1,
        hardware: request.runs(Part::Hardware),
        profile: request.runs(Part::Profile),
        f64_reference: true,
        // The job's one scene is the heaviest.
        profile_scene: None,
        pixel_stats: Vec::new(),
        spd: None,
        // The job's outside tracers are added as loaded definitions, not entries.
        tracers: Vec::new(),
        quick: None,
    };
    Ok((def.checked("the job").map_err(|e| failed(&e))?, false))
}

/// Runs a job into its directory: staged, published whole when it succeeds, kept as
/// `partial/` when it is stopped, fails or panics.
fn execute(
    request: &JobRequest,
    catalogue: &Catalogue,
    dir: &Path,
    progress: &ProgressSink<'_>,
    stop: &AtomicBool,
) -> Result<(), Ended> {
    let failed = |e: &dyn std::fmt::Display| Ended::Failed(e.to_string());
    let (def, quick) = definition(request, catalogue)?;
    // The outside tracers: the definitions loaded at start that the request named
    // (checked when it was queued; a name only ever selects one of them).
    let tracers = catalogue
        .tracers_named(&request.tracers)
        .map_err(|e| Ended::Failed(e.message))?;
    let mut suite = Suite::prepare(def, quick, Path::new(""), None)
        .and_then(|s| s.with_tracers(tracers))
        .map_err(|e| failed(&e))?;
    if request.runs(Part::PixelMaps) {
        suite.def.pixel_stats = suite.scenes.iter().map(|s| s.name.clone()).collect();
    }
    let threads = request
        .thread_count()
        .map_err(|e| Ended::Failed(e.message))?;
    let run = DirRun {
        threads,
        progress,
        stop,
        pdf: Pdf::Write,
        keep_partial: Some(&dir.join(PARTIAL_DIR)),
    };
    match run_into_dir(&suite, dir, &run, &mut |_| Ok(())) {
        Ok(_) => Ok(()),
        Err(RunError::Stopped | RunError::StoppedAfter { .. }) => Err(Ended::Stopped),
        Err(e) => Err(Ended::Failed(e.to_string())),
    }
}

/// The runner's progress, as the job's progress.
struct ProgressSink<'a> {
    jobs: &'a Jobs,
    id: u64,
    /// The job's stop flag: once set, every message says the job is being cancelled.
    stop: &'a AtomicBool,
}

/// The share of a whole job done at the start and end of each stage.
fn stage_span(stage: &str) -> (f64, f64) {
    match stage {
        "machine" => (0.0, 0.05),
        "scenes" => (0.05, 0.85),
        "profile" => (0.85, 0.93),
        "reports" => (0.93, 1.0),
        _ => (0.0, 0.0),
    }
}

impl ProgressSink<'_> {
    fn change(&self, change: impl FnOnce(&mut JobProgress)) {
        self.jobs.update(self.id, false, |job| {
            change(&mut job.progress);
            let p = &mut job.progress;
            let (start, end) = stage_span(&p.stage);
            let fraction = start + (end - start) * stage_share(p);
            // Never back within a stage (a finished count gives way to the next work
            // before the stage's step is counted); a new stage starts at its start.
            p.fraction = match p.fraction >= start && p.fraction <= end {
                true => p.fraction.max(fraction),
                false => fraction,
            };
        });
    }
}

/// The share of its stage a job has done: its steps, and the counted work under way
/// as the next step's share (a stage without steps: that work's share).
fn stage_share(p: &JobProgress) -> f64 {
    let within = p.within.as_ref().and_then(crate::job::Within::fraction);
    match (p.total, within) {
        (0, within) => within.unwrap_or(0.0),
        (total, within) => {
            let done = p.done.min(total) as f64;
            ((done + within.unwrap_or(0.0)) / total as f64).min(1.0)
        }
    }
}

impl runner::Progress for ProgressSink<'_> {
    fn begin(&self, stage: &str, total: u64) {
        self.change(|p| {
            p.stage = stage.to_string();
            p.total = total;
            p.done = 0;
            p.message.clear();
            p.within = None;
            p.fraction = 0.0;
        });
    }

    fn within(&self, what: &str, done: u64, total: u64) {
        self.change(|p| {
            p.within = Some(crate::job::Within {
                what: what.to_string(),
                done,
                total,
            })
        });
    }

    fn message(&self, text: &str) {
        let text = match self.stop.load(Ordering::SeqCst) {
            true => format!("{CANCELLING}; {text}"),
            false => text.to_string(),
        };
        self.change(|p| {
            p.message = text;
            p.within = None;
        });
    }

    fn advance(&self, steps: u64) {
        self.change(|p| p.done += steps);
    }

    fn note(&self, text: &str) {
        // The runner's asides (a render repeated to gather samples, partial outputs
        // that could not be kept) belong in the server's log.
        eprintln!("rtprof: {text}");
    }
}

#[cfg(test)]
mod tests {
    use super::stage_span;

    #[test]
    fn the_stages_cover_the_job_in_order_without_gaps() {
        // The runner's stages in the order it runs them, then the reports: the
        // fraction never goes back and ends at 1.
        let order = ["machine", "scenes", "profile", "reports"];
        let mut end = 0.0;
        for stage in order {
            let (start, stop) = stage_span(stage);
            assert_eq!(start, end, "{stage} starts where the stage before ended");
            assert!(stop > start, "{stage}");
            end = stop;
        }
        assert_eq!(end, 1.0);
        // A stage the table does not know shows no progress rather than a wrong one.
        assert_eq!(stage_span("starting"), (0.0, 0.0));
    }
}
