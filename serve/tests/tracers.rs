//! Outside tracers in the web app (docs/serve.md, docs/tracers.md): only definitions
//! given when the server starts run, each named by a job; a request naming a path, a
//! command or an unknown name is refused with a 400 and nothing is queued; a loaded
//! tracer runs beside the variants and its row (and a failed one's reason) is in the
//! job's results and in the figures the page shows; a bad definition stops the start
//! naming its file, line and column.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use runner::outside::TracerFlags;
use serde_json::{Value, json};
use serve::{Config, ServeError, Server};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "rtprof-serve-tracers-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A definition `name` run by `sh -c SCRIPT` with `$0` … the arguments given.
fn definition(dir: &Path, name: &str, script: &str, args: &[&str]) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    let args: Vec<String> = args.iter().map(|a| format!("{a:?}")).collect();
    let text = format!(
        "name = \"{name}\"\ndescription = \"a test tracer\"\ncommand = [\"sh\", \"-c\", {script:?}, {}]\nscene = \"nff\"\nimage = \"ppm\"\ntime = \"process\"\ntime_limit = 30\n",
        args.join(", ")
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// A tracer that draws a black picture of the size asked (binary PPM).
fn black(dir: &Path) -> PathBuf {
    definition(
        dir,
        "black",
        r#"printf 'P6\n%s %s\n255\n' "$0" "$1" > "$2"; head -c $(($0 * $1 * 3)) /dev/zero >> "$2""#,
        &["{width}", "{height}", "{output}", "{scene}"],
    )
}

/// A tracer that cannot open its scene: a message on standard error, exit 1.
fn broken(dir: &Path) -> PathBuf {
    definition(
        dir,
        "broken",
        r#"echo "cannot open $0" >&2; exit 1"#,
        &["{scene}", "{output}"],
    )
}

struct Fixture {
    server: Server,
    dir: PathBuf,
    agent: ureq::Agent,
}

impl Fixture {
    fn new(name: &str) -> Fixture {
        let dir = scratch(name);
        let config = Config {
            port: 0,
            data: dir.join("data"),
            tracers: TracerFlags {
                tracers: vec![black(&dir), broken(&dir)],
                ..TracerFlags::default()
            },
            ..Config::default()
        };
        let server = Server::start(&config).unwrap();
        let agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .build()
            .into();
        Fixture { server, dir, agent }
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

    fn wait(&self, id: &str, limit: Duration) -> Value {
        let start = Instant::now();
        loop {
            let (_, job) = self.get(&format!("/api/jobs/{id}"));
            let status = job["status"].as_str().unwrap_or_default().to_string();
            if !matches!(status.as_str(), "queued" | "running") {
                return job;
            }
            assert!(start.elapsed() < limit, "job {id} still {status}: {job}");
            std::thread::sleep(Duration::from_millis(200));
        }
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

#[test]
fn a_request_names_only_tracers_loaded_at_start_never_a_command_or_a_path() {
    let f = Fixture::new("refused");
    // The page is offered the two loaded tracers, by name, with their commands to read.
    let (_, listing) = f.get("/api/scenes");
    let offered: Vec<&str> = listing["tracers"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|t| t["name"].as_str())
        .collect();
    assert_eq!(offered, ["black", "broken"], "{listing}");
    assert_eq!(listing["tracers"][0]["variant"], "tracer:black");
    assert!(
        listing["tracers"][0]["command"]
            .as_str()
            .unwrap()
            .starts_with("sh -c ")
    );
    let black_file = f.dir.join("black.toml").display().to_string();
    let marker = f.dir.join("ran");
    let command = format!("sh -c 'touch {}'", marker.display());
    for (tracer, says) in [
        // The very definition file a loaded tracer came from, named by path.
        (black_file.as_str(), "never runs a command or a path"),
        ("/bin/sh", "never runs a command or a path"),
        (command.as_str(), "never runs a command or a path"),
        ("touch", "not one of the outside tracers this server loaded"),
        (
            "povray",
            "not one of the outside tracers this server loaded",
        ),
        (
            "tracer:nope",
            "not one of the outside tracers this server loaded",
        ),
        ("", "not one of the outside tracers this server loaded"),
    ] {
        let (status, body) = f.post_job(json!({"scene": "balls3", "tracers": [tracer]}));
        assert_eq!(status, 400, "{tracer}: {body}");
        let error = body["error"].as_str().unwrap_or_default();
        assert!(error.contains(says), "{tracer}: {error}");
        assert!(error.contains("it runs: black, broken"), "{error}");
    }
    // A command or a path as a whole-suite job's tracer too.
    let (status, _) = f.post_job(json!({"run": ["suite"], "tracers": ["/usr/bin/tachyon"]}));
    assert_eq!(status, 400);
    // Nothing was queued and nothing ran.
    let (_, jobs) = f.get("/api/jobs");
    assert_eq!(jobs["jobs"].as_array().map(Vec::len), Some(0), "{jobs}");
    assert!(!marker.exists());
    // Not a tracer list: the JSON reader refuses it (422, like any malformed field).
    let (status, _) = f.post_job(json!({"scene": "balls3", "tracers": "black"}));
    assert_eq!(status, 422);
}

#[test]
fn a_loaded_tracer_runs_beside_the_variants_and_a_failed_one_says_why() {
    let f = Fixture::new("runs");
    let (status, job) = f.post_job(json!({
        "scene": "balls3",
        "variants": ["bvh"],
        "size": [24, 16],
        "tracers": ["tracer:broken", "black", "black"],
    }));
    assert_eq!(status, 202, "{job}");
    // Each once, in the server's order, by its own name.
    assert_eq!(
        job["request"]["tracers"],
        json!(["black", "broken"]),
        "{job}"
    );
    assert_eq!(
        job["text"]["variants"],
        "baseline, bvh, tracer:black, tracer:broken"
    );
    let id = job["id"].as_str().unwrap().to_string();
    let job = f.wait(&id, Duration::from_secs(600));
    assert_eq!(job["status"], "done", "{job}");
    let (_, results) = f.get(&format!("/api/jobs/{id}/files/results.json"));
    let names: Vec<&str> = results["suite"]["variants"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert_eq!(names, ["baseline", "bvh", "tracer:black", "tracer:broken"]);
    let scene = &results["scenes"][0];
    let rows: Vec<&Value> = scene["variants"].as_array().unwrap().iter().collect();
    let black = rows
        .iter()
        .find(|v| v["variant"] == "tracer:black")
        .unwrap_or_else(|| panic!("no tracer:black row: {scene}"));
    // It ran the loaded definition: its command, sh found on disk, and its picture
    // is the black frame the script writes, at the size asked.
    assert_eq!(black["outside"]["command"][0], "sh");
    assert!(
        black["outside"]["definition"]
            .as_str()
            .unwrap()
            .ends_with("black.toml")
    );
    let image = black["image"].as_str().unwrap();
    let path = f.dir.join("data/jobs").join(&id).join(image);
    let picture = analysis::RgbImage::load(&path).unwrap();
    assert_eq!((picture.width, picture.height), (24, 16));
    assert!(picture.data.iter().all(|b| *b == 0));
    let baseline = rows.iter().find(|v| v["variant"] == "baseline").unwrap();
    let ours = analysis::RgbImage::load(
        &f.dir
            .join("data/jobs")
            .join(&id)
            .join(baseline["image"].as_str().unwrap()),
    )
    .unwrap();
    assert!(ours.data.iter().any(|b| *b != 0), "balls3 is not black");
    // The failed one: no row, a failure with its reason and its standard error.
    assert!(!rows.iter().any(|v| v["variant"] == "tracer:broken"));
    let failure = results["failures"]
        .as_array()
        .unwrap()
        .iter()
        .find(|x| x["part"]["variant"] == "tracer:broken")
        .unwrap_or_else(|| panic!("{}", results["failures"]));
    let message = failure["message"].as_str().unwrap();
    assert!(message.contains("exited with code 1"), "{message}");
    assert!(message.contains("cannot open"), "{message}");
    // What the page shows: the tracer's row among the variants, like the others, and
    // the failure placed and explained.
    let (status, values) = f.get(&format!("/api/jobs/{id}/values"));
    assert_eq!(status, 200, "{values}");
    let shown: Vec<&str> = values["scenes"][0]["variants"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|v| v["variant"].as_str())
        .collect();
    assert_eq!(shown, ["baseline", "bvh", "tracer:black"]);
    let row = &values["scenes"][0]["variants"][2];
    assert_eq!(row["image"], black["image"]);
    assert!(
        row["median"].as_str().is_some_and(|m| !m.is_empty()),
        "{row}"
    );
    let failed = &values["failures"][0];
    assert_eq!(failed["place"], "balls3 / tracer:broken", "{values}");
    assert!(failed["message"].as_str().unwrap().contains("cannot open"));
    // The report shows both.
    let (_, report) = f.get(&format!("/api/jobs/{id}/files/report.html"));
    let report = report.as_str().unwrap_or_default();
    assert!(report.contains("tracer:black"));
    assert!(report.contains("tracer:broken"));
}

#[test]
fn a_bad_definition_stops_the_start_naming_its_file_line_and_column() {
    let dir = scratch("bad");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"bad\"\ncommand = [\"t\", \"{scene}\", \"{wide}\", \"{output}\"]\nscene = \"nff\"\nimage = \"ppm\"\ntime = \"process\"\n",
    )
    .unwrap();
    let config = Config {
        port: 0,
        data: dir.join("data"),
        tracers: TracerFlags {
            tracers: vec![bad.clone()],
            ..TracerFlags::default()
        },
        ..Config::default()
    };
    let error = match Server::start(&config) {
        Ok(_) => panic!("a server started with a bad definition"),
        Err(e) => e,
    };
    assert!(matches!(error, ServeError::Tracer(_)), "{error:?}");
    let message = error.to_string();
    assert!(
        message.starts_with(&format!("{}:2:", bad.display())),
        "{message}"
    );
    assert!(message.contains("{wide}"), "{message}");
    // Nothing was made of the data directory.
    assert!(!dir.join("data").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
