//! The data directory: one directory per job (`jobs/ID/`, its `job.json` written
//! atomically, its outputs published there only when complete, an unfinished job's
//! under `partial/`), the uploaded scenes (`scenes/`) and `server.json` (the running
//! server's address and token, for scripts). The history is rebuilt from it on start.

use std::path::{Component, Path, PathBuf};

use tracer::image_io::write_atomically;

use crate::error::{ApiError, ServeError};
use crate::job::{Job, JobStatus};

/// A job's record in its directory.
pub const JOB_FILE: &str = "job.json";

/// The data directory's record of the highest job id given ([`Store::next_id`]).
pub const LAST_ID_FILE: &str = "last-job-id";

/// Where an unfinished job's outputs are kept.
pub const PARTIAL_DIR: &str = "partial";

/// The data directory.
#[derive(Clone, Debug)]
pub struct Store {
    root: PathBuf,
}

/// The data directory held by one server: a second server on it would mark the
/// first one's running job interrupted and number its jobs over the first's.
pub struct DataLock {
    _file: std::fs::File,
}

/// What the data directory held on start.
pub struct History {
    pub jobs: Vec<Job>,
    /// Directories under `jobs/` that are not readable jobs (skipped, said once).
    pub skipped: Vec<String>,
}

impl Store {
    /// Opens (creating) the data directory.
    pub fn open(root: &Path) -> Result<Self, ServeError> {
        for dir in [root.to_path_buf(), root.join("jobs"), root.join("scenes")] {
            std::fs::create_dir_all(&dir).map_err(|e| ServeError::io("create", &dir, &e))?;
        }
        Ok(Store {
            root: root.to_path_buf(),
        })
    }

    /// Takes the data directory for this process (an advisory lock on `.lock`, released
    /// when the process ends, however it ends).
    pub fn lock(&self) -> Result<DataLock, ServeError> {
        let path = self.root.join(".lock");
        let file = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(|e| ServeError::io("open", &path, &e))?;
        match file.try_lock() {
            Ok(()) => Ok(DataLock { _file: file }),
            Err(std::fs::TryLockError::WouldBlock) => Err(ServeError::Other(format!(
                "another rtprof serve is using {} (its address is in server.json there): stop it, \
                 or give this one another --data directory",
                self.root.display()
            ))),
            Err(std::fs::TryLockError::Error(e)) => Err(ServeError::io("lock", &path, &e)),
        }
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    pub fn scenes_dir(&self) -> PathBuf {
        self.root.join("scenes")
    }

    /// The directory of job `id`.
    pub fn job_dir(&self, id: u64) -> PathBuf {
        self.root.join("jobs").join(id.to_string())
    }

    /// A new job's id, never one given before in this data directory: above the
    /// highest id recorded in [`LAST_ID_FILE`] (written before the id is used, so a
    /// deleted newest job's id is not given again, across restarts too), at least
    /// `at_least` (above the jobs the history holds), and never a directory that
    /// exists (an unreadable one the history skipped).
    pub fn next_id(&self, at_least: u64) -> Result<u64, ServeError> {
        let path = self.root.join(LAST_ID_FILE);
        let recorded = std::fs::read_to_string(&path)
            .ok()
            .and_then(|text| text.trim().parse::<u64>().ok())
            .unwrap_or(0);
        let mut id = at_least.max(recorded.saturating_add(1)).max(1);
        while self.job_dir(id).exists() {
            id = id.saturating_add(1);
        }
        write_atomically(&path, format!("{id}\n").as_bytes())
            .map_err(|e| ServeError::io("write", &path, &e))?;
        Ok(id)
    }

    /// Writes `job.json` atomically (temporary file, then rename).
    pub fn save(&self, job: &Job) -> Result<(), ServeError> {
        let id: u64 = job
            .id
            .parse()
            .map_err(|_| ServeError::Other(format!("job id '{}' is not a number", job.id)))?;
        let dir = self.job_dir(id);
        std::fs::create_dir_all(&dir).map_err(|e| ServeError::io("create", &dir, &e))?;
        let path = dir.join(JOB_FILE);
        let json = serde_json::to_vec_pretty(job)
            .map_err(|e| ServeError::Other(format!("cannot serialize {}: {e}", path.display())))?;
        write_atomically(&path, &json).map_err(|e| ServeError::io("write", &path, &e))
    }

    /// The jobs of earlier runs of the server, oldest first. A job that was queued or
    /// running when the server stopped is marked interrupted (saved so), its staged
    /// outputs kept under `partial/`.
    pub fn history(&self) -> Result<History, ServeError> {
        let jobs_dir = self.root.join("jobs");
        let entries =
            std::fs::read_dir(&jobs_dir).map_err(|e| ServeError::io("read", &jobs_dir, &e))?;
        let mut found: Vec<(u64, PathBuf)> = Vec::new();
        let mut skipped = Vec::new();
        for entry in entries.filter_map(Result::ok) {
            let name = entry.file_name().to_string_lossy().into_owned();
            match name.parse::<u64>() {
                Ok(id) if entry.path().is_dir() => found.push((id, entry.path())),
                _ => skipped.push(name),
            }
        }
        found.sort();
        let mut jobs = Vec::new();
        for (id, dir) in found {
            let text = std::fs::read(dir.join(JOB_FILE));
            let job = text
                .ok()
                .and_then(|t| serde_json::from_slice::<Job>(&t).ok())
                .filter(|j| j.id == id.to_string());
            let Some(mut job) = job else {
                skipped.push(id.to_string());
                continue;
            };
            if !job.status.is_final() {
                // It ended when its last file was written, not now: the time the server
                // was down is not the job's.
                let last = newest_change(&dir);
                keep_staged(&dir);
                job.status = JobStatus::Interrupted;
                job.finished_unix = last.or(job.started_unix);
                job.finished.get_or_insert_with(|| match job.finished_unix {
                    Some(at) => results::rfc3339_utc(at),
                    None => runner::machine::now_rfc3339(),
                });
                job.error = Some(
                    "the server stopped while this job was queued or running; run it again".into(),
                );
                self.save(&job)?;
            }
            job.files = list_files(&dir);
            jobs.push(job);
        }
        Ok(History { jobs, skipped })
    }

    /// Writes `server.json`: the address and token of the running server.
    pub fn announce(&self, url: &str, token: &str) -> Result<(), ServeError> {
        let path = self.root.join("server.json");
        let json = serde_json::json!({
            "url": url,
            "token": token,
            "pid": std::process::id(),
        });
        let text = serde_json::to_vec_pretty(&json)
            .map_err(|e| ServeError::Other(format!("cannot serialize server.json: {e}")))?;
        write_atomically(&path, &text).map_err(|e| ServeError::io("write", &path, &e))
    }
}

/// When anything under `dir` last changed (seconds since the Unix epoch), staging
/// directories included.
fn newest_change(dir: &Path) -> Option<u64> {
    let mut newest = None;
    let mut pending = vec![dir.to_path_buf()];
    while let Some(current) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&current) else {
            continue;
        };
        for entry in entries.filter_map(Result::ok) {
            let Ok(meta) = entry.metadata() else { continue };
            if meta.is_dir() {
                pending.push(entry.path());
            }
            let at = meta
                .modified()
                .ok()
                .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                .map(|d| d.as_secs());
            newest = newest.max(at);
        }
    }
    newest
}

/// Renames a dead server's staging directories (`.rtprof-suite-PID.partial`) in a job
/// directory to `partial/` (the first; any further one is removed).
fn keep_staged(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.filter_map(Result::ok) {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with(".rtprof-suite-") && name.ends_with(".partial") {
            let target = dir.join(PARTIAL_DIR);
            if target.exists() {
                let _ = std::fs::remove_dir_all(entry.path());
            } else {
                let _ = std::fs::rename(entry.path(), target);
            }
        }
    }
}

/// Every file under `dir` (relative, `/`-separated, sorted), but hidden ones (staging,
/// temporary files) and `job.json`.
pub fn list_files(dir: &Path) -> Vec<String> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(current) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&current) else {
            continue;
        };
        for entry in entries.filter_map(Result::ok) {
            let path = entry.path();
            if entry.file_name().to_string_lossy().starts_with('.') {
                continue;
            }
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                pending.push(path);
            } else if kind.is_file()
                && let Ok(rel) = path.strip_prefix(dir)
            {
                let rel: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                let rel = rel.join("/");
                if rel != JOB_FILE {
                    files.push(rel);
                }
            }
        }
    }
    files.sort();
    files
}

/// `dir/rel` when `rel` names a file inside `dir`: relative, no `..`, `.`, hidden
/// component, backslash or NUL, and (after symbolic links) still inside `dir`.
/// Anything else is a 400: no request names a file outside the data directory.
pub fn safe_join(dir: &Path, rel: &str) -> Result<PathBuf, ApiError> {
    let refuse = || {
        ApiError::bad_request(format!(
            "'{rel}' is not a file of this job: name one of its files (GET /api/jobs/ID lists them)"
        ))
    };
    if rel.is_empty() || rel.contains(['\\', '\0']) {
        return Err(refuse());
    }
    let path = Path::new(rel);
    let plain = path.components().all(|c| match c {
        Component::Normal(part) => !part.to_string_lossy().starts_with('.'),
        _ => false,
    });
    if !plain {
        return Err(refuse());
    }
    let joined = dir.join(path);
    let (Ok(real_dir), Ok(real)) = (dir.canonicalize(), joined.canonicalize()) else {
        return Err(ApiError::not_found(format!("this job has no file '{rel}'")));
    };
    if !real.starts_with(&real_dir) {
        return Err(refuse());
    }
    if !real.is_file() {
        return Err(ApiError::not_found(format!("this job has no file '{rel}'")));
    }
    Ok(real)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_relative_names_inside_the_directory_are_joined() {
        let dir = std::env::temp_dir().join(format!("rtprof-serve-store-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("images")).unwrap();
        std::fs::write(dir.join("images/a.png"), b"png").unwrap();
        std::fs::write(dir.join("results.json"), b"{}").unwrap();
        assert!(safe_join(&dir, "images/a.png").is_ok());
        assert!(safe_join(&dir, "results.json").is_ok());
        for bad in [
            "../x",
            "images/../../x",
            "/etc/passwd",
            "./results.json",
            ".hidden",
            "images\\a.png",
            "",
        ] {
            let e = safe_join(&dir, bad).unwrap_err();
            assert_eq!(e.status, axum::http::StatusCode::BAD_REQUEST, "{bad}");
        }
        assert_eq!(
            safe_join(&dir, "missing.png").unwrap_err().status,
            axum::http::StatusCode::NOT_FOUND
        );
        // A symbolic link out of the directory is refused too.
        std::os::unix::fs::symlink("/etc", dir.join("out")).unwrap();
        assert_eq!(
            safe_join(&dir, "out/hostname").unwrap_err().status,
            axum::http::StatusCode::BAD_REQUEST
        );
        assert_eq!(
            list_files(&dir),
            vec!["images/a.png".to_string(), "results.json".to_string()]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn job_ids_are_never_given_twice_even_after_the_newest_is_deleted() {
        let root = std::env::temp_dir().join(format!("rtprof-serve-ids-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let store = Store::open(&root).unwrap();
        assert_eq!(store.next_id(1).unwrap(), 1);
        std::fs::create_dir_all(store.job_dir(1)).unwrap();
        assert_eq!(store.next_id(2).unwrap(), 2);
        std::fs::create_dir_all(store.job_dir(2)).unwrap();
        // Job 2, the newest, deleted: the history's highest is 1 again, yet 3 comes next.
        std::fs::remove_dir_all(store.job_dir(2)).unwrap();
        assert_eq!(store.next_id(2).unwrap(), 3);
        // Across a restart (the record is on disk), and with every job deleted.
        std::fs::remove_dir_all(store.job_dir(1)).unwrap();
        let reopened = Store::open(&root).unwrap();
        assert_eq!(reopened.next_id(1).unwrap(), 4);
        // A directory nobody recorded (left by hand) is stepped over.
        std::fs::create_dir_all(reopened.job_dir(5)).unwrap();
        assert_eq!(reopened.next_id(1).unwrap(), 6);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
