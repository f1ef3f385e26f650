//! `rtprof serve` killed (SIGKILL) during a job and started again on the same data
//! directory: the history lists the earlier complete job with its results intact, the
//! interrupted one is marked so with its partial outputs, and no file is corrupt.

mod serve;

use std::time::Duration;

use serde_json::{Value, json};
use serve::{Served, temp_dir};

#[test]
fn a_killed_server_restarts_with_its_history_and_the_interrupted_job_marked() {
    let data = temp_dir("serve-restart");
    let first = Served::start(&data);
    let done = first.submit(json!({"scene": "balls2", "variants": ["bvh"], "size": [32, 24]}));
    let job = first.wait_until(&done, Duration::from_secs(300), |j| {
        j["status"] != "queued" && j["status"] != "running"
    });
    assert_eq!(job["status"], "done", "{job}");
    // A long job (brute force over the SPD balls, one thread), killed once its renders
    // have begun.
    let killed = first.submit(json!({
        "scene": "spd:balls", "variants": ["simd", "fast-sqrt"], "size": [128, 96], "threads": 1
    }));
    first.wait_until(&killed, Duration::from_secs(120), |j| {
        j["progress"]["stage"] == "scenes"
    });
    drop(first); // SIGKILL: no chance to clean up.
    let killed_at = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_secs();
    // The server stays down a while: that time is not the job's.
    std::thread::sleep(Duration::from_secs(3));
    let dir = data.join("jobs").join(&killed);
    let saved: Value =
        serde_json::from_slice(&std::fs::read(dir.join("job.json")).unwrap()).unwrap();
    assert_eq!(
        saved["status"], "running",
        "job.json still says running after the kill"
    );

    // A job directory whose job.json is not readable (written by hand, say): skipped and
    // left alone, never reused.
    std::fs::create_dir_all(data.join("jobs/3")).unwrap();
    std::fs::write(data.join("jobs/3/job.json"), "{not json").unwrap();

    let second = Served::start(&data);
    let jobs = second.get("/api/jobs")["jobs"].as_array().unwrap().clone();
    assert_eq!(jobs.len(), 2, "{jobs:?}");
    let find = |id: &str| jobs.iter().find(|j| j["id"] == id).unwrap().clone();
    assert_eq!(find(&done)["status"], "done");
    let interrupted = find(&killed);
    assert_eq!(interrupted["status"], "interrupted", "{interrupted}");
    assert!(interrupted["finished"].is_string());
    // It ended at its last written file, before the kill, not at the restart.
    let (started, finished) = (
        interrupted["started_unix"].as_u64().unwrap(),
        interrupted["finished_unix"].as_u64().unwrap(),
    );
    assert!(
        started <= finished && finished <= killed_at,
        "{started} {finished} {killed_at}"
    );
    // Its staged outputs are kept under partial/, with no results.json.
    let files = serve::files(&interrupted);
    assert!(files.iter().all(|f| f.starts_with("partial/")), "{files:?}");
    assert!(!files.iter().any(|f| f.ends_with("results.json")));
    assert!(!dir.join("results.json").exists());
    // job.json was rewritten whole; the done job's results read as valid results.
    let saved: Value =
        serde_json::from_slice(&std::fs::read(dir.join("job.json")).unwrap()).unwrap();
    assert_eq!(saved["status"], "interrupted");
    let results = data.join("jobs").join(&done).join("results.json");
    let results = std::fs::read(&results).unwrap();
    let results: Value = serde_json::from_slice(&results).unwrap();
    assert_eq!(
        results["scenes"][0]["variants"].as_array().unwrap().len(),
        2
    );
    // No temporary file is left in either job's directory.
    for id in [&done, &killed] {
        for entry in std::fs::read_dir(data.join("jobs").join(id)).unwrap() {
            let name = entry.unwrap().file_name().to_string_lossy().into_owned();
            assert!(!name.starts_with('.'), "leftover {name} in job {id}");
        }
    }
    // The new server takes new jobs and numbers them after the old ones.
    let next = second.submit(json!({"scene": "balls1", "size": [8, 6]}));
    assert_eq!(next, "4");
    assert_eq!(
        std::fs::read_to_string(data.join("jobs/3/job.json")).unwrap(),
        "{not json"
    );
    let job = second.wait_until(&next, Duration::from_secs(300), |j| {
        j["status"] == "done" || j["status"] == "failed"
    });
    assert_eq!(job["status"], "done", "{job}");
    drop(second);
    std::fs::remove_dir_all(&data).unwrap();
}
