//! The JSON API against a real server on a free port: refusals (path traversal, an
//! oversized upload, a malformed NFF, an absurd size, an unknown variant, requests
//! without the token or from another site) each with its status code, a job run to
//! the end with every file it lists, a cancelled job's partial outputs, and 50
//! concurrent status requests while a job runs.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use serve::{Config, Server};

struct Fixture {
    server: Server,
    data: PathBuf,
    agent: ureq::Agent,
}

impl Fixture {
    fn new(name: &str, max_upload_bytes: u64) -> Fixture {
        let data = std::env::temp_dir().join(format!("rtprof-serve-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&data);
        let config = Config {
            port: 0,
            data: data.clone(),
            max_upload_bytes,
            ..Config::default()
        };
        let server = Server::start(&config).unwrap();
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .build()
            .into();
        Fixture {
            server,
            data,
            agent,
        }
    }

    fn url(&self, path: &str) -> String {
        format!("{}{}", self.server.url, path.trim_start_matches('/'))
    }

    fn get(&self, path: &str) -> (u16, Value) {
        let mut r = self.agent.get(&self.url(path)).call().unwrap();
        let status = r.status().as_u16();
        let text = r.body_mut().read_to_string().unwrap_or_default();
        (
            status,
            serde_json::from_str(&text).unwrap_or(Value::String(text)),
        )
    }

    fn post_job(&self, body: Value) -> (u16, Value) {
        let mut r = self
            .agent
            .post(&self.url("/api/jobs"))
            .header("X-Rtprof-Token", &self.server.token)
            .send_json(body)
            .unwrap();
        let status = r.status().as_u16();
        (status, r.body_mut().read_json().unwrap_or(Value::Null))
    }

    fn upload(&self, name: &str, body: &[u8]) -> (u16, Value) {
        let mut r = self
            .agent
            .post(&self.url(&format!("/api/scenes?name={name}")))
            .header("X-Rtprof-Token", &self.server.token)
            .send(body)
            .unwrap();
        let status = r.status().as_u16();
        (status, r.body_mut().read_json().unwrap_or(Value::Null))
    }

    /// DELETE /api/jobs/ID with the token: the status code.
    fn cancel(&self, id: &str) -> u16 {
        let url = self.url(&format!("/api/jobs/{id}"));
        let r = self
            .agent
            .delete(&url)
            .header("X-Rtprof-Token", &self.server.token);
        r.call().unwrap().status().as_u16()
    }

    /// Waits until job `id` has a final status (at most `limit`).
    fn wait(&self, id: &str, limit: Duration) -> Value {
        let start = Instant::now();
        loop {
            let (_, job) = self.get(&format!("/api/jobs/{id}"));
            let status = job["status"].as_str().unwrap_or_default().to_string();
            if !matches!(status.as_str(), "queued" | "running") {
                return job;
            }
            assert!(start.elapsed() < limit, "job {id} still {status}: {job}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.data);
    }
}

/// The files a job lists.
fn files(job: &Value) -> Vec<&str> {
    job["files"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect()
}

#[test]
fn bad_requests_are_refused_with_the_right_status() {
    let f = Fixture::new("refusals", 4096);
    // Oversized upload: 413, before anything is parsed or kept.
    let big = vec![b'#'; 8192];
    let (status, body) = f.upload("big", &big);
    assert_eq!(status, 413, "{body}");
    assert!(body["error"].as_str().unwrap().contains("4096"), "{body}");
    // Malformed NFF: 422 with the line.
    let bad =
        b"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\ns 0 0 0 oops\n";
    let (status, body) = f.upload("broken", bad);
    assert_eq!(status, 422, "{body}");
    assert_eq!(body["line"], 8, "{body}");
    assert!(
        body["error"].as_str().unwrap().starts_with("broken.nff:8:"),
        "{body}"
    );
    // A name that is a path: 422; nothing was kept.
    let (status, _) = f.upload("..%2Fevil", b"v\n");
    assert_eq!(status, 422);
    assert_eq!(std::fs::read_dir(f.data.join("scenes")).unwrap().count(), 0);
    // The limits `GET /api/scenes` lists are the ones the checks apply.
    let limits = f.get("/api/scenes").1["limits"].clone();
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max_threads = 4 * cpus;
    assert_eq!(limits["max_threads"], max_threads, "{limits}");
    assert_eq!(limits["max_side"], 16384, "{limits}");
    assert_eq!(limits["max_pixels"], 67_108_864, "{limits}");
    assert_eq!(limits["max_upload_bytes"], 4096, "{limits}");
    // An upload name of 65 characters: 422.
    let (status, body) = f.upload(&"n".repeat(65), b"v\n");
    assert_eq!(status, 422, "{body}");
    assert!(
        body["error"].as_str().unwrap().contains("1 to 64"),
        "{body}"
    );
    // Absurd sizes, unknown variants and scenes, a scene named by path: 422.
    for (body, says) in [
        (
            json!({"scene": "balls3", "size": [100000, 100000]}),
            "size 100000x100000",
        ),
        (json!({"scene": "balls3", "size": [0, 10]}), "size 0x10"),
        (
            json!({"scene": "balls3", "variants": ["warp-drive"]}),
            "warp-drive",
        ),
        (json!({"scene": "/etc/passwd"}), "unknown scene"),
        (
            json!({"scene": "../../shared/spd/balls.nff"}),
            "unknown scene",
        ),
        (json!({"scene": "balls3", "threads": 0}), "threads 0"),
        // The one thread rule of the CLI and the API: 1 to 4 × the logical CPUs.
        (
            json!({"scene": "balls3", "threads": 999}),
            &*format!("threads 999: choose 1 to {max_threads} "),
        ),
        (
            json!({"scene": "balls3", "threads": 70000}),
            &*format!("threads 70000: choose 1 to {max_threads} "),
        ),
        // Each side and the pixel count within the tracer's limits.
        (
            json!({"scene": "balls3", "size": [16385, 1]}),
            "size 16385x1",
        ),
        (
            json!({"scene": "balls3", "size": [16384, 16384]}),
            "size 16384x16384",
        ),
        // Generators within their documented ranges.
        (json!({"scene": "spd:balls:7"}), "out of range"),
        (json!({"scene": "sphereflake:7"}), "the maximum is 6"),
        (json!({"scene": "lattice:41"}), "out of range"),
        (json!({"scene": "upload:bad/name"}), "not a scene name"),
        (
            json!({"scene": "balls3", "run": ["warp"]}),
            "unknown variant",
        ),
    ] {
        let (status, answer) = f.post_job(body.clone());
        assert_eq!(status, 422, "{body} -> {answer}");
        assert!(answer["error"].as_str().unwrap().contains(says), "{answer}");
    }
    // Not JSON at all: 400; unknown fields: 422.
    let r = f
        .agent
        .post(&f.url("/api/jobs"))
        .header("X-Rtprof-Token", &f.server.token)
        .header("Content-Type", "application/json")
        .send("{not json")
        .unwrap();
    assert_eq!(r.status().as_u16(), 400);
    let (status, _) = f.post_job(json!({"scene": "balls3", "colour": "red"}));
    assert_eq!(status, 422);
    // No token, a wrong token, another origin, another host name: 403.
    let job = json!({"scene": "balls1"});
    let r = f.agent.post(&f.url("/api/jobs")).send_json(&job).unwrap();
    assert_eq!(r.status().as_u16(), 403);
    let r = f
        .agent
        .post(&f.url("/api/jobs"))
        .header("X-Rtprof-Token", "0123456789abcdef0123456789abcdef")
        .send_json(&job)
        .unwrap();
    assert_eq!(r.status().as_u16(), 403);
    let r = f
        .agent
        .post(&f.url("/api/jobs"))
        .header("X-Rtprof-Token", &f.server.token)
        .header("Origin", "http://evil.example")
        .send_json(&job)
        .unwrap();
    assert_eq!(r.status().as_u16(), 403);
    let r = f.agent.delete(&f.url("/api/jobs/1")).call().unwrap();
    assert_eq!(r.status().as_u16(), 403);
    let r = f
        .agent
        .get(&f.url("/api/jobs"))
        .header("Host", "evil.example")
        .call()
        .unwrap();
    assert_eq!(r.status().as_u16(), 403);
    // None of the refused requests made a job.
    assert_eq!(f.get("/api/jobs").1["jobs"].as_array().unwrap().len(), 0);
    // A second server on the same data directory is refused (it would mark the first
    // one's running job interrupted).
    let second = Config {
        port: 0,
        data: f.data.clone(),
        ..Config::default()
    };
    let refused = Server::start(&second).err().map(|e| e.to_string());
    assert!(
        refused
            .as_deref()
            .unwrap_or_default()
            .contains("another rtprof serve"),
        "{refused:?}"
    );
    // Unknown job: 404; not a number: 400.
    assert_eq!(f.get("/api/jobs/99").0, 404);
    assert_eq!(f.get("/api/jobs/abc").0, 400);
}

#[test]
fn a_job_runs_to_the_end_and_its_files_are_served_but_nothing_outside() {
    let f = Fixture::new("job", serve::DEFAULT_MAX_UPLOAD_BYTES);
    // An uploaded scene, run with two variants and the hardware model.
    let scene = tracer::builtin_scenes::find("balls2").unwrap().text;
    let (status, entry) = f.upload("mine", scene.as_bytes());
    assert_eq!(status, 201, "{entry}");
    assert_eq!(entry["id"], "upload:mine");
    assert_eq!(entry["primitives"], 2);
    let (status, _) = f.upload("mine", scene.as_bytes());
    assert_eq!(status, 409, "an upload never replaces another");
    let listing = f.get("/api/scenes").1;
    assert!(
        listing["scenes"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s["id"] == "upload:mine")
    );
    let (status, job) = f.post_job(json!({
        "scene": "upload:mine", "variants": ["bvh"], "size": [24, 18], "threads": 1,
        "run": ["render", "hardware"]
    }));
    assert_eq!(status, 202, "{job}");
    let id = job["id"].as_str().unwrap().to_string();
    assert_eq!(job["request"]["variants"], json!(["baseline", "bvh"]));
    let job = f.wait(&id, Duration::from_secs(300));
    assert_eq!(job["status"], "done", "{job}");
    assert_eq!(job["progress"]["fraction"], 1.0);
    let files = files(&job);
    for expected in [
        "results.json",
        "report.html",
        "report.pdf",
        "images/mine-baseline.png",
        "images/mine-bvh.png",
        "images/mine-bvh-diff.png",
        "images/mine-hw.png",
    ] {
        assert!(files.contains(&expected), "{expected} not in {files:?}");
    }
    // Every listed file is served, with its type.
    for file in &files {
        let r = f
            .agent
            .get(&f.url(&format!("/api/jobs/{id}/files/{file}")))
            .call()
            .unwrap();
        assert_eq!(r.status().as_u16(), 200, "{file}");
    }
    // results.json is a valid results file `rtprof report` reads: one scene, both
    // variants, their counts exact (the same rays for both).
    let results =
        results::Results::read_file(&f.data.join("jobs").join(&id).join("results.json")).unwrap();
    let s = &results.scenes[0];
    assert_eq!((s.width, s.height, s.variants.len()), (24, 18, 2));
    assert_eq!(s.variants[0].counts["rays.primary"], 24 * 18);
    assert_eq!(
        s.variants[0].counts["rays.primary"],
        s.variants[1].counts["rays.primary"]
    );
    assert!(s.hardware.is_some() && results.profile.is_none());
    // Traversal, encoded every way a client might: 400 (and never the file).
    std::fs::write(f.data.join("secret.txt"), "secret").unwrap();
    for path in [
        "..%2F..%2Fsecret.txt",
        "%2e%2e/%2e%2e/secret.txt",
        "images%2F..%2F..%2F..%2Fsecret.txt",
        "%2Fetc%2Fpasswd",
        ".rtprof-x",
        "job.json%00",
    ] {
        let (status, body) = f.get(&format!("/api/jobs/{id}/files/{path}"));
        assert!(status == 400, "{path}: {status} {body}");
    }
    // The gate of the run against itself passes; against another frame it cannot compare.
    let gate = f.get(&format!("/api/gate?old={id}&new={id}")).1;
    assert_eq!(gate["passed"], true, "{gate}");
    assert!(gate["text"].as_str().unwrap().contains("passed"), "{gate}");
    // A job of another scene has nothing in common with it: the gate refuses (422)
    // rather than passing on nothing compared.
    let (status, other) = f.post_job(json!({"scene": "balls1", "size": [8, 6], "threads": 1}));
    assert_eq!(status, 202, "{other}");
    let other = other["id"].as_str().unwrap().to_string();
    let other_job = f.wait(&other, Duration::from_secs(300));
    assert_eq!(other_job["status"], "done", "{other_job}");
    let (status, gate) = f.get(&format!("/api/gate?old={id}&new={other}"));
    assert_eq!(status, 422, "{gate}");
    let error = gate["error"].as_str().unwrap();
    assert!(error.contains("nothing in common"), "{error}");
    assert!(
        error.contains("mine 24x18") && error.contains("balls1 8x6"),
        "{error}"
    );

    // The page's figures are the report's: bvh's speed-up as the report's matrix
    // writes it (its 95 % interval decides the digits), baseline's median as its
    // time cell does; and both strings are in report.html.
    let (status, values) = f.get(&format!("/api/jobs/{id}/values"));
    assert_eq!(status, 200, "{values}");
    let bvh = &s.variants[1];
    let [low, high] = bvh.speedup_interval.unwrap();
    let speedup = reports::format::ratio_estimate(bvh.speedup.unwrap(), low, high).median;
    let shown = &values["scenes"][0]["variants"][1];
    assert_eq!(shown["variant"], "bvh");
    assert_eq!(shown["speedup"], speedup.as_str(), "{shown}");
    let base = &s.variants[0].time;
    let median = reports::format::estimate(base.median, base.low, base.high).median;
    assert_eq!(
        values["scenes"][0]["variants"][0]["median"],
        median.as_str()
    );
    let report =
        std::fs::read_to_string(f.data.join("jobs").join(&id).join("report.html")).unwrap();
    assert!(
        report.contains(&speedup) && report.contains(&median),
        "{speedup} {median}"
    );
    // Two primitives, said in the plural; one would be in the singular.
    assert!(
        values["scenes"][0]["summary"]
            .as_str()
            .unwrap()
            .contains("2 primitives")
    );

    // report.pdf opens in the browser rather than downloading.
    let r = f
        .agent
        .get(&f.url(&format!("/api/jobs/{id}/files/report.pdf")))
        .call()
        .unwrap();
    assert_eq!(r.headers()["content-type"], "application/pdf");
    assert_eq!(r.headers()["content-disposition"], "inline");

    // A finished job is deleted with its directory; then it is gone from the list,
    // and a second DELETE finds nothing.
    let dir = f.data.join("jobs").join(&other);
    assert!(dir.is_dir());
    let r = f
        .agent
        .delete(&f.url(&format!("/api/jobs/{other}")))
        .call()
        .unwrap();
    assert_eq!(r.status().as_u16(), 403, "DELETE needs the token");
    assert!(dir.is_dir());
    assert_eq!(f.cancel(&other), 200);
    assert!(!dir.exists(), "{} still there", dir.display());
    let listed = f.get("/api/jobs").1;
    assert!(
        !listed["jobs"]
            .as_array()
            .unwrap()
            .iter()
            .any(|j| j["id"] == other.as_str()),
        "{listed}"
    );
    assert_eq!(f.get(&format!("/api/jobs/{other}")).0, 404);
    assert_eq!(f.cancel(&other), 404);
    // The other job is untouched.
    assert!(f.data.join("jobs").join(&id).join("results.json").is_file());
}

#[test]
fn every_answer_refuses_framing_by_other_sites() {
    let f = Fixture::new("framing", 4096);
    for path in [
        "/",
        "/assets/app.js",
        "/api/jobs",
        "/api/scenes",
        "/api/jobs/99",
        "/nothing",
    ] {
        let r = f.agent.get(&f.url(path)).call().unwrap();
        assert_eq!(r.headers()["x-frame-options"], "DENY", "{path}");
        assert_eq!(
            r.headers()["content-security-policy"],
            "frame-ancestors 'none'",
            "{path}"
        );
    }
    // Refusals too (the guard answers before the route).
    let r = f
        .agent
        .post(&f.url("/api/jobs"))
        .send_json(json!({}))
        .unwrap();
    assert_eq!(r.status().as_u16(), 403);
    assert_eq!(r.headers()["x-frame-options"], "DENY");
}

#[test]
fn the_estimate_counts_primitives_and_times_a_slow_brute_force_render() {
    let f = Fixture::new("estimate", 4096);
    // balls2: 1 + 9 + 81 spheres and a polygon (tracer's built-in table).
    let primitives = tracer::builtin_scenes::find("balls2").unwrap().primitives as u64;
    let (status, e) = f.get("/api/estimate?scene=balls2&width=64&height=48");
    assert_eq!(status, 200, "{e}");
    assert_eq!(e["primitives"], primitives);
    assert_eq!(
        e["primitives_text"],
        format!("{primitives} primitives").as_str()
    );
    // Under runner::estimate::MANY_PRIMITIVES: no timing, said so.
    assert!(e["brute_force"].is_null(), "{e}");
    assert!(
        e["text"].as_str().unwrap().contains("brute force is quick"),
        "{e}"
    );
    // SPD balls at size factor 4: 7,382 primitives (Haines's table), a brute-force
    // render at a large size that the probe times past the note's threshold.
    let (status, e) = f.get("/api/estimate?scene=spd:balls:4&width=1920&height=1080&threads=1");
    assert_eq!(status, 200, "{e}");
    assert_eq!(e["primitives"], 7_382, "{e}");
    assert!(
        e["brute_force"].as_str().unwrap().starts_with("about "),
        "{e}"
    );
    assert!(
        e["text"].as_str().unwrap().contains("7,382 primitives"),
        "{e}"
    );
    // Refusals say what to change.
    for (query, said) in [
        ("scene=balls99&width=8&height=8", "unknown scene"),
        ("scene=balls2&width=8", "width=W&height=H"),
        ("scene=balls2&width=1048576&height=2", "size 1048576x2"),
        ("scene=balls2&width=8&height=8&threads=0", "threads 0"),
    ] {
        let (status, e) = f.get(&format!("/api/estimate?{query}"));
        assert_eq!(status, 422, "{query}: {e}");
        assert!(e["error"].as_str().unwrap().contains(said), "{query}: {e}");
    }
}

#[test]
fn a_running_job_answers_50_concurrent_requests_and_cancels_to_partial_outputs() {
    let f = Fixture::new("cancel", serve::DEFAULT_MAX_UPLOAD_BYTES);
    // Brute force over the SPD balls' 7,382 primitives, one thread: seconds a render.
    let (status, job) = f.post_job(json!({
        "scene": "spd:balls", "variants": ["simd", "fast-sqrt"], "size": [128, 96],
        "threads": 1, "run": ["render", "profile"]
    }));
    assert_eq!(status, 202, "{job}");
    let id = job["id"].as_str().unwrap().to_string();
    // A second job waits its turn.
    let (_, second) = f.post_job(json!({"scene": "balls1", "size": [8, 6]}));
    let second = second["id"].as_str().unwrap().to_string();
    let start = Instant::now();
    while f.get(&format!("/api/jobs/{id}")).1["progress"]["stage"] != "scenes" {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "the job never reached its renders"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    assert_eq!(f.get(&format!("/api/jobs/{second}")).1["status"], "queued");
    let asked = Instant::now();
    let answered: Vec<(u16, String)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..50)
            .map(|_| {
                scope.spawn(|| {
                    let (status, job) = f.get(&format!("/api/jobs/{id}"));
                    (
                        status,
                        job["status"].as_str().unwrap_or_default().to_string(),
                    )
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(answered.len(), 50);
    assert!(
        answered.iter().all(|(s, st)| *s == 200 && st == "running"),
        "{answered:?}"
    );
    eprintln!(
        "50 concurrent status requests during the job: all 200, answered in {:.0} ms",
        asked.elapsed().as_secs_f64() * 1e3
    );
    // Cancel the second while queued, then the running one.
    assert_eq!(f.cancel(&second), 202);
    let cancelled = Instant::now();
    assert_eq!(f.cancel(&id), 202);
    let job = f.wait(&id, Duration::from_secs(300));
    eprintln!(
        "cancelled mid-render: stopped {:.2} s later (renders stop within a row)",
        cancelled.elapsed().as_secs_f64()
    );
    assert_eq!(job["status"], "cancelled", "{job}");
    assert_eq!(
        f.get(&format!("/api/jobs/{second}")).1["status"],
        "cancelled"
    );
    // Cancelling again: 409 (POST .../cancel never deletes, whenever it arrives).
    let r = f
        .agent
        .post(&f.url(&format!("/api/jobs/{id}/cancel")))
        .header("X-Rtprof-Token", &f.server.token)
        .send_empty()
        .unwrap();
    assert_eq!(r.status().as_u16(), 409);
    // Its outputs are marked partial; no results.json anywhere in it.
    let files = files(&job);
    assert!(files.iter().all(|f| f.starts_with("partial/")), "{files:?}");
    assert!(
        !files.iter().any(|f| f.ends_with("results.json")),
        "{files:?}"
    );
    let dir = f.data.join("jobs").join(&id);
    assert!(dir.join("partial").is_dir());
    assert!(!dir.join("results.json").exists());
    // job.json on disk says so too.
    let saved: Value =
        serde_json::from_slice(&std::fs::read(dir.join("job.json")).unwrap()).unwrap();
    assert_eq!(saved["status"], "cancelled");
}
