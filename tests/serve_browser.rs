//! The web app end to end in a real headless Chromium, driven over the DevTools
//! protocol: open the page, pick balls3, select baseline and bvh, run, follow the job
//! through its live progress (server-sent events) to the end, see both images and the
//! difference map, open the report. Needs Debian's `chromium` (`.ci/run` installs it);
//! `RTPROF_SCREENSHOTS=DIR` keeps a screenshot of each view there.

mod serve;

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::{Value, json};
use serve::{Served, temp_dir};
use tungstenite::WebSocket;
use tungstenite::stream::MaybeTlsStream;

/// A headless Chromium and a DevTools connection to its page.
struct Browser {
    child: Child,
    socket: WebSocket<MaybeTlsStream<TcpStream>>,
    next_id: u64,
}

impl Browser {
    fn launch(profile: &Path) -> Browser {
        let mut child = Command::new("chromium")
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--remote-debugging-port=0",
                "--window-size=1280,1000",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("chromium (Debian package chromium) is needed for this test");
        // "DevTools listening on ws://127.0.0.1:PORT/devtools/browser/ID"
        let stderr = child.stderr.take().unwrap();
        let mut lines = BufReader::new(stderr).lines();
        let browser_ws = loop {
            let line = lines
                .next()
                .expect("chromium exited before DevTools listened")
                .unwrap();
            if let Some(at) = line.find("ws://") {
                break line[at..].trim().to_string();
            }
        };
        // Keep draining stderr so that Chromium never blocks on it.
        std::thread::spawn(move || for _ in lines {});
        let port = browser_ws["ws://127.0.0.1:".len()..]
            .split('/')
            .next()
            .unwrap()
            .to_string();
        let targets: Value = ureq::get(&format!("http://127.0.0.1:{port}/json/list"))
            .call()
            .unwrap()
            .body_mut()
            .read_json()
            .unwrap();
        let page = targets
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["type"] == "page")
            .expect("a page target");
        let url = page["webSocketDebuggerUrl"].as_str().unwrap();
        let (socket, _) = tungstenite::connect(url).unwrap();
        Browser {
            child,
            socket,
            next_id: 1,
        }
    }

    /// One DevTools command; its result.
    fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let message = json!({"id": id, "method": method, "params": params}).to_string();
        self.socket
            .send(tungstenite::Message::text(message))
            .unwrap();
        loop {
            let message = self.socket.read().unwrap();
            let Ok(text) = message.to_text() else {
                continue;
            };
            let Ok(reply) = serde_json::from_str::<Value>(text) else {
                continue;
            };
            if reply["id"] == id {
                assert!(reply["error"].is_null(), "{method}: {reply}");
                return reply["result"].clone();
            }
        }
    }

    /// Evaluates `expression` in the page (awaiting a promise) and returns its value.
    fn eval(&mut self, expression: &str) -> Value {
        let result = self.call(
            "Runtime.evaluate",
            json!({"expression": expression, "awaitPromise": true, "returnByValue": true}),
        );
        assert!(
            result["exceptionDetails"].is_null(),
            "{expression}: {result}"
        );
        result["result"]["value"].clone()
    }

    /// Polls `expression` until it is truthy; returns its value.
    fn wait_for(&mut self, expression: &str, limit: Duration) -> Value {
        let start = Instant::now();
        loop {
            let value = self.eval(expression);
            if !(value.is_null() || value == false || value == 0 || value == "") {
                return value;
            }
            assert!(start.elapsed() < limit, "never true: {expression}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn navigate(&mut self, url: &str) {
        self.call("Page.navigate", json!({"url": url}));
        self.wait_for(
            "document.readyState === 'complete'",
            Duration::from_secs(30),
        );
    }

    /// A screenshot of the whole page, into `dir/name.png` when `dir` is given.
    fn screenshot(&mut self, dir: Option<&Path>, name: &str) {
        let Some(dir) = dir else { return };
        let size = self
            .eval("[document.documentElement.scrollWidth, document.documentElement.scrollHeight]");
        let (w, h) = (
            size[0].as_f64().unwrap(),
            size[1].as_f64().unwrap().min(6000.0),
        );
        let shot = self.call(
            "Page.captureScreenshot",
            json!({"format": "png", "captureBeyondViewport": true,
                   "clip": {"x": 0, "y": 0, "width": w, "height": h, "scale": 1}}),
        );
        let png = base64::engine::general_purpose::STANDARD
            .decode(shot["data"].as_str().unwrap())
            .unwrap();
        std::fs::write(dir.join(format!("{name}.png")), png).unwrap();
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
#[ignore = "needs chromium (Debian package chromium; .ci/run installs it)"]
fn pick_run_view_open_in_a_real_browser() {
    let data = temp_dir("serve-browser");
    let shots: Option<PathBuf> = std::env::var_os("RTPROF_SCREENSHOTS").map(PathBuf::from);
    if let Some(dir) = &shots {
        std::fs::create_dir_all(dir).unwrap();
    }
    let shots = shots.as_deref();
    let server = Served::start(&data);
    let mut browser = Browser::launch(&data.join("chromium"));
    browser.navigate(&server.url);
    browser.wait_for(
        "document.querySelectorAll('#scene option[value=\"balls3\"]').length",
        Duration::from_secs(30),
    );

    // Pick: balls3.
    browser.eval("(() => { const s = document.getElementById('scene'); s.value = 'balls3'; s.dispatchEvent(new Event('change', {bubbles: true})); })()");
    assert_eq!(
        browser.eval("document.getElementById('chosen-scene').textContent"),
        "balls3"
    );
    browser.screenshot(shots, "1-pick");

    // Run: baseline (always) and bvh, with the hardware model and a profile; a small frame.
    browser.eval("document.getElementById('tab-run').click()");
    browser.eval("document.querySelector('input[name=variant][value=bvh]').click()");
    browser.eval("['profile', 'hardware'].forEach(p => document.querySelector(`input[name=part][value=${p}]`).click())");
    browser.eval("(() => { for (const [id, v] of [['width', '96'], ['height', '72']]) { const e = document.getElementById(id); e.value = v; e.dispatchEvent(new Event('input', {bubbles: true})); } })()");
    let checked = browser
        .eval("[...document.querySelectorAll('input[name=variant]:checked')].map(b => b.value)");
    assert_eq!(checked, json!(["baseline", "bvh"]));
    browser.screenshot(shots, "2-run");
    // Count the live events the page receives, and the progress it shows.
    browser.eval(
        "(() => { const Real = window.EventSource; window.__events = []; \
           window.EventSource = function (url) { const s = new Real(url); \
             s.addEventListener('job', e => window.__events.push(JSON.parse(e.data).progress.fraction)); return s; }; \
           window.EventSource.prototype = Real.prototype; window.EventSource.CLOSED = Real.CLOSED; \
           window.__shown = []; setInterval(() => window.__shown.push(document.getElementById('job-progress').value), 20); })()",
    );
    browser.eval("document.getElementById('run-button').click()");
    browser.wait_for(
        "/done/.test(document.getElementById('job-status').textContent)",
        Duration::from_secs(600),
    );
    let events = browser.eval("window.__events");
    let fractions: Vec<f64> = events
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    assert!(
        fractions.len() >= 3,
        "the page got {} live events",
        fractions.len()
    );
    assert!(
        fractions.iter().any(|f| *f > 0.0 && *f < 1.0),
        "no progress between start and end: {fractions:?}"
    );
    assert_eq!(fractions.last(), Some(&1.0));
    assert!(
        fractions.windows(2).all(|w| w[0] <= w[1]),
        "the progress went back: {fractions:?}"
    );
    let shown = browser.eval("window.__shown.filter(v => v > 0 && v < 1).length");
    assert!(
        shown.as_u64().unwrap() > 0,
        "the progress bar never showed a partial value"
    );
    eprintln!(
        "live progress: {} events, fractions {fractions:?}; the bar showed a partial value {shown} times",
        fractions.len()
    );

    // View: both images and the difference map, loaded (decoded, not broken).
    let loaded = "(sel) => [...document.querySelectorAll(sel)].filter(i => i.complete && i.naturalWidth > 0).length";
    browser.wait_for(
        &format!("({loaded})('figure.variant-image img') === 2"),
        Duration::from_secs(30),
    );
    browser.wait_for(
        &format!("({loaded})('img.heat-map') >= 1"),
        Duration::from_secs(30),
    );
    let captions = browser.eval("[...document.querySelectorAll('figure.variant-image')].map(f => f.textContent).join(' | ')");
    let captions = captions.as_str().unwrap();
    assert!(
        captions.contains("baseline") && captions.contains("bvh"),
        "{captions}"
    );
    let sizes = browser.eval("[...document.querySelectorAll('figure.variant-image img')].map(i => [i.naturalWidth, i.naturalHeight])");
    assert_eq!(sizes, json!([[96, 72], [96, 72]]));
    // The counts table has the eye rays of a 96 x 72 frame for both variants.
    let rays = browser.eval("[...document.querySelectorAll('#counts-table tr')].find(r => r.textContent.includes('rays.primary'))?.textContent");
    assert!(
        rays.as_str().unwrap_or_default().matches("6,912").count() == 2,
        "{rays}"
    );
    browser.screenshot(shots, "3-view");

    // Open: the report in the browser.
    browser.eval("document.getElementById('tab-open').click()");
    browser.screenshot(shots, "4-open");
    let href = browser.eval("document.getElementById('open-report').href");
    let href = href.as_str().unwrap().to_string();
    assert!(href.ends_with("/files/report.html"), "{href}");
    // The gate of the run against itself, as the page shows it.
    browser.eval("document.getElementById('tab-gate').click()");
    browser.eval("(() => { for (const id of ['gate-old', 'gate-new']) { const s = document.getElementById(id); s.value = s.options[s.options.length - 1].value; s.dispatchEvent(new Event('change', {bubbles: true})); } document.getElementById('gate-button').click(); })()");
    browser.wait_for(
        "/passed/i.test(document.getElementById('gate-output').textContent)",
        Duration::from_secs(30),
    );
    browser.screenshot(shots, "5-gate");
    browser.navigate(&href);
    let text = browser.wait_for(
        "document.body && document.body.innerText.includes('balls3') && document.body.innerText",
        Duration::from_secs(30),
    );
    assert!(text.as_str().unwrap().contains("bvh"));
    browser.screenshot(shots, "6-report");
    drop(browser);
    drop(server);
    std::fs::remove_dir_all(&data).unwrap();
}
