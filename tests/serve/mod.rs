//! Helpers of the `rtprof serve` tests that run the binary: start it on a free port
//! with a data directory, read its address and token from `server.json`, talk to it.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

/// A running `rtprof serve`.
pub struct Served {
    pub child: Child,
    pub url: String,
    pub token: String,
    pub agent: ureq::Agent,
}

/// The files a job lists.
pub fn files(job: &Value) -> Vec<&str> {
    job["files"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect()
}

/// A fresh directory under the system's temporary directory.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

impl Served {
    /// Starts the server on `data` and waits for its `server.json`.
    pub fn start(data: &Path) -> Served {
        let _ = std::fs::remove_file(data.join("server.json"));
        let child = Command::new(env!("CARGO_BIN_EXE_rtprof"))
            .args(["serve", "--port", "0", "--data"])
            .arg(data)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let info: Value = loop {
            if let Ok(text) = std::fs::read(data.join("server.json"))
                && let Ok(info) = serde_json::from_slice::<Value>(&text)
            {
                break info;
            }
            assert!(
                start.elapsed() < Duration::from_secs(30),
                "the server never started"
            );
            std::thread::sleep(Duration::from_millis(50));
        };
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .build()
            .into();
        Served {
            child,
            url: info["url"].as_str().unwrap().to_string(),
            token: info["token"].as_str().unwrap().to_string(),
            agent,
        }
    }

    pub fn get(&self, path: &str) -> Value {
        let url = format!("{}{}", self.url, path.trim_start_matches('/'));
        let mut r = self.agent.get(&url).call().unwrap();
        assert_eq!(r.status().as_u16(), 200, "{url}");
        r.body_mut().read_json().unwrap()
    }

    pub fn submit(&self, job: Value) -> String {
        let url = format!("{}api/jobs", self.url);
        let mut r = self
            .agent
            .post(&url)
            .header("X-Rtprof-Token", &self.token)
            .send_json(job)
            .unwrap();
        assert_eq!(r.status().as_u16(), 202);
        let job: Value = r.body_mut().read_json().unwrap();
        job["id"].as_str().unwrap().to_string()
    }

    /// Polls job `id` until `done(job)` holds.
    pub fn wait_until(&self, id: &str, limit: Duration, done: impl Fn(&Value) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let job = self.get(&format!("/api/jobs/{id}"));
            if done(&job) {
                return job;
            }
            assert!(start.elapsed() < limit, "job {id}: {job}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
