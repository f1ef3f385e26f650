//! The web app end to end in a real headless Chromium, driven over the DevTools
//! protocol: open the page, pick balls3, select baseline and bvh, run, follow the job
//! through its live progress (server-sent events) to the end, see both images and the
//! difference map, read a figure the page shows against the report's cell for it,
//! zoom, re-run and show two jobs side by side, open the report; the layout at 420 px
//! (no sideways scroll), the Tab order, and a killed server noticed within 5 s. Needs
//! Debian's `chromium` (`.ci/run` installs it); `RTPROF_SCREENSHOTS=DIR` keeps a
//! screenshot of each view there, at 1280 and at 420 px.

mod serve;

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::os::unix::process::CommandExt;
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
            // Its own process group, so that dropping the browser ends its helpers too:
            // they write into the profile, and the test removes it afterwards.
            .process_group(0)
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

    /// The viewport's width (CSS pixels), as a window of that size would have it.
    fn set_width(&mut self, width: u32) {
        self.call(
            "Emulation.setDeviceMetricsOverride",
            json!({"width": width, "height": 1000, "deviceScaleFactor": 1, "mobile": false}),
        );
    }

    /// Presses Tab once, as a keyboard does.
    fn tab(&mut self) {
        for kind in ["keyDown", "keyUp"] {
            self.call(
                "Input.dispatchKeyEvent",
                json!({"type": kind, "key": "Tab", "code": "Tab", "windowsVirtualKeyCode": 9}),
            );
        }
    }

    /// The document scrolls sideways: its width past the viewport's, in CSS pixels.
    fn overflow(&mut self) -> i64 {
        self.eval("document.scrollingElement.scrollWidth - window.innerWidth")
            .as_i64()
            .unwrap()
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
    /// Ends Chromium and every helper process it started (renderer, GPU, crash
    /// handler), and waits until none is left, so that the profile can be removed.
    fn drop(&mut self) {
        let group = self.child.id() as libc::pid_t;
        // SAFETY: kill(2) with a negative pid signals the process group the browser
        // leads (process_group(0) made it one); it touches no memory.
        unsafe { libc::kill(-group, libc::SIGKILL) };
        let _ = self.child.wait();
        let start = Instant::now();
        // kill(-group, 0) fails with ESRCH once the group has no process left.
        // SAFETY: as above; signal 0 only checks.
        while unsafe { libc::kill(-group, 0) } == 0 && start.elapsed() < Duration::from_secs(10) {
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// The screenshot directory of `RTPROF_SCREENSHOTS`, created.
fn screenshots() -> Option<PathBuf> {
    let dir = std::env::var_os("RTPROF_SCREENSHOTS").map(PathBuf::from)?;
    std::fs::create_dir_all(&dir).unwrap();
    Some(dir)
}

/// Shows tab `name` (by a click, as a user would).
fn show(browser: &mut Browser, name: &str) {
    browser.eval(&format!("document.getElementById('tab-{name}').click()"));
}

const TABS: [&str; 5] = ["pick", "run", "view", "open", "gate"];

/// At 420 px every tab fits the screen: no sideways scroll (one screenshot each).
fn check_narrow(browser: &mut Browser, shots: Option<&Path>, prefix: &str) {
    browser.set_width(420);
    for name in TABS {
        show(browser, name);
        std::thread::sleep(Duration::from_millis(150));
        let overflow = browser.overflow();
        let wide = if overflow > 0 {
            browser.eval("[...document.querySelectorAll('body *')].filter(e => e.getBoundingClientRect().right > window.innerWidth + 1 && e.offsetParent).slice(0, 8).map(e => e.tagName + '.' + e.className + '#' + e.id + ' ' + Math.round(e.getBoundingClientRect().right)).join(', ')")
        } else {
            Value::Null
        };
        assert!(
            overflow <= 0,
            "{name} at 420 px scrolls sideways by {overflow} px: {wide}"
        );
        browser.screenshot(shots, &format!("{prefix}-{name}-420"));
    }
    browser.set_width(1280);
}

#[test]
#[ignore = "needs chromium (Debian package chromium; .ci/run installs it)"]
fn pick_run_view_open_in_a_real_browser() {
    let started = Instant::now();
    let data = temp_dir("serve-browser");
    let shots = screenshots();
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

    // Run: baseline (always) and bvh, with a profile, the hardware model and the
    // per-pixel maps; a small frame. The estimate says what it costs before Run.
    show(&mut browser, "run");
    browser.eval("document.querySelector('input[name=variant][value=bvh]').click()");
    browser.eval("['profile', 'hardware', 'pixel_maps'].forEach(p => document.querySelector(`input[name=part][value=${p}]`).click())");
    browser.eval("(() => { for (const [id, v] of [['width', '64'], ['height', '48']]) { const e = document.getElementById(id); e.value = v; e.dispatchEvent(new Event('input', {bubbles: true})); } })()");
    let checked = browser
        .eval("[...document.querySelectorAll('input[name=variant]:checked')].map(b => b.value)");
    assert_eq!(checked, json!(["baseline", "bvh"]));
    let estimate = browser.wait_for(
        "/primitives/.test(document.getElementById('estimate').textContent) && document.getElementById('estimate').textContent",
        Duration::from_secs(30),
    );
    let primitives = tracer::builtin_scenes::find("balls3").unwrap().primitives as u64;
    assert!(
        estimate
            .as_str()
            .unwrap()
            .contains(&reports::format::kind_count(primitives, "primitives")),
        "{estimate}"
    );
    browser.screenshot(shots, "2-run");
    // The form survives a reload (localStorage).
    browser.navigate(&server.url);
    browser.wait_for(
        "document.querySelector('input[name=variant][value=bvh]')?.checked && document.getElementById('width').value === '64'",
        Duration::from_secs(30),
    );
    assert_eq!(
        browser.eval("document.getElementById('chosen-scene').textContent"),
        "balls3"
    );
    // Count the live events the page receives.
    browser.eval(
        "(() => { const Real = window.EventSource; window.__events = []; \
           window.EventSource = function (url) { const s = new Real(url); \
             s.addEventListener('job', e => window.__events.push(JSON.parse(e.data).text.progress)); return s; }; \
           window.EventSource.prototype = Real.prototype; window.EventSource.CLOSED = Real.CLOSED; })()",
    );
    show(&mut browser, "run");
    browser.eval("document.getElementById('run-button').focus(); document.getElementById('run-button').click()");
    // Focus goes to the View tab, not to the page's body.
    let focused = browser.wait_for(
        "document.activeElement && document.activeElement.id === 'tab-view' && document.activeElement.id",
        Duration::from_secs(30),
    );
    assert_eq!(focused, "tab-view");
    browser.wait_for(
        "document.querySelector('#view-badge .badge')?.textContent === 'done'",
        Duration::from_secs(600),
    );
    let events = browser.eval("window.__events");
    let lines: Vec<&str> = events
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert!(lines.len() >= 3, "the page got {} live events", lines.len());
    // Each stage said by name, in order.
    let first = |what: &str| lines.iter().position(|l| l.contains(what));
    let (scenes, profiling) = (
        first("step 2 of 4: rendering"),
        first("step 3 of 4: profiling"),
    );
    assert!(
        scenes.is_some() && profiling.is_some() && scenes < profiling,
        "{lines:?}"
    );
    eprintln!(
        "live progress: {} events, e.g. {:?}",
        lines.len(),
        lines.get(lines.len() / 2)
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
    let sizes = browser.eval("[...document.querySelectorAll('figure.variant-image img')].map(i => [i.naturalWidth, i.naturalHeight])");
    assert_eq!(sizes, json!([[64, 48], [64, 48]]));
    // The counts table has the eye rays of a 64 x 48 frame for both variants.
    let rays = browser.eval("[...document.querySelectorAll('.counts-table tr')].find(r => r.textContent.includes('rays.primary'))?.textContent");
    assert_eq!(
        rays.as_str().unwrap_or_default().matches("3,072").count(),
        2,
        "{rays}"
    );
    // bvh's node visits are its own work: not coloured as a cost.
    let visits = browser.eval("[...document.querySelectorAll('.counts-table tr')].filter(r => /bvh|node/.test(r.cells[0].textContent)).map(r => r.cells[2].className)");
    assert!(
        visits
            .as_array()
            .unwrap()
            .iter()
            .all(|c| !c.as_str().unwrap().contains("tone-more")),
        "{visits}"
    );
    // Hovering a pixel reads the per-pixel maps there.
    browser.eval("(() => { const img = document.querySelector('figure.variant-image img'); const r = img.getBoundingClientRect(); img.dispatchEvent(new MouseEvent('mousemove', {clientX: r.left + r.width / 2, clientY: r.top + r.height / 2, bubbles: true})); })()");
    let readout = browser.wait_for(
        "document.querySelector('.pixel-readout')?.textContent",
        Duration::from_secs(30),
    );
    // The middle of the 64 x 48 picture (its border may shift it by one).
    let readout = readout.as_str().unwrap();
    assert!(
        ["pixel (31, 23)", "pixel (32, 24)"]
            .iter()
            .any(|p| readout.contains(p)),
        "{readout}"
    );
    // Both variants' maps, with bvh's node visits, read from the NumPy arrays.
    assert!(readout.contains("accel.nodes_visited"), "{readout}");
    // The page formats no number: what it shows of bvh and baseline is the report's cell.
    let page_speedup = browser.eval("document.querySelectorAll('figure.variant-image')[1].querySelector('.speedup').textContent.replace(' vs baseline', '')");
    let page_median = browser.eval("document.querySelectorAll('figure.variant-image')[0].querySelector('.median').textContent.replace('median ', '')");
    browser.screenshot(shots, "3-view");
    // The zoom viewer.
    browser.eval("document.querySelector('figure.variant-image .image-button').click()");
    browser.wait_for(
        "document.getElementById('viewer').open",
        Duration::from_secs(10),
    );
    browser.eval("document.getElementById('viewer-in').click(); document.getElementById('viewer-in').click()");
    let zoomed = browser.eval("document.getElementById('viewer-image').style.transform");
    assert!(
        zoomed.as_str().unwrap().contains("scale(1.5625)"),
        "{zoomed}"
    );
    browser.screenshot(shots, "3-view-zoom");
    browser.eval("document.getElementById('viewer-close').click()");

    // Run again: a second job of the same request, then both side by side.
    browser.eval("document.getElementById('rerun-button').click()");
    browser.wait_for(
        "document.getElementById('view-title').textContent === 'Job #2' && document.querySelector('#view-badge .badge')?.textContent === 'done'",
        Duration::from_secs(600),
    );
    browser.eval("(() => { const s = document.getElementById('beside-select'); s.value = '1'; s.dispatchEvent(new Event('change', {bubbles: true})); })()");
    let sides = browser.wait_for(
        "document.querySelectorAll('.side-by-side .side').length === 2 && [...document.querySelectorAll('.side-title')].map(h => h.textContent)",
        Duration::from_secs(30),
    );
    assert_eq!(sides, json!(["Job #2", "Job #1"]));
    browser.screenshot(shots, "3-view-side-by-side");
    check_narrow(&mut browser, shots, "3-view-side-by-side");
    browser.eval("(() => { const s = document.getElementById('beside-select'); s.value = ''; s.dispatchEvent(new Event('change', {bubbles: true})); })()");

    // Open: the report in the browser.
    browser.eval("document.querySelector('#history-list .job-row[data-id=\"1\"]').click()");
    show(&mut browser, "open");
    browser.screenshot(shots, "4-open");
    let href = browser.eval("document.getElementById('open-report').href");
    let href = href.as_str().unwrap().to_string();
    assert!(href.ends_with("/jobs/1/files/report.html"), "{href}");
    // The gate of the two runs, as the page shows it.
    show(&mut browser, "gate");
    browser.eval("document.getElementById('gate-button').click()");
    browser.wait_for(
        "/passed|failed/i.test(document.getElementById('gate-output').textContent)",
        Duration::from_secs(30),
    );
    browser.screenshot(shots, "5-gate");
    check_narrow(&mut browser, shots, "6");

    browser.navigate(&href);
    // The report's cells for bvh and baseline on balls3: the speed-up matrix.
    let cell = |column: &str| {
        format!(
            "(() => {{ for (const t of document.querySelectorAll('table')) {{ \
               const heads = [...t.querySelectorAll('thead th')].map(th => th.childNodes[0]?.textContent.trim()); \
               const col = heads.indexOf('{column}'); if (col < 0 || heads[0] !== 'scene') continue; \
               for (const tr of t.querySelectorAll('tbody tr')) {{ const c = [...tr.children]; \
                 if (c.length === heads.length && c[0].childNodes[0]?.textContent.trim() === 'balls3') \
                   return c[col].childNodes[0].textContent.trim(); }} }} return null; }})()"
        )
    };
    let report_speedup = browser.wait_for(&cell("bvh"), Duration::from_secs(30));
    let report_median = browser.eval(&cell("baseline"));
    eprintln!(
        "page: bvh {page_speedup}, baseline {page_median}; report: bvh {report_speedup}, baseline {report_median}"
    );
    assert_eq!(page_speedup, report_speedup);
    assert_eq!(page_median, report_median);
    let title = browser.eval("document.title");
    assert_eq!(
        title, "rtprof report: balls3",
        "titled by its scene, not the host"
    );
    browser.screenshot(shots, "7-report");
    drop(browser);
    drop(server);
    std::fs::remove_dir_all(&data).unwrap();
    eprintln!(
        "the browser test took {:.0} s",
        started.elapsed().as_secs_f64()
    );
}

#[test]
#[ignore = "needs chromium (Debian package chromium; .ci/run installs it)"]
fn the_keyboard_reaches_pick_before_history_and_gate_by_tab() {
    let data = temp_dir("serve-browser-keys");
    let server = Served::start(&data);
    // One finished job, so that History has a row to reach.
    let id = server.submit(json!({"scene": "balls1", "size": [8, 6], "threads": 1}));
    server.wait_until(&id, Duration::from_secs(300), |j| j["status"] == "done");
    let mut browser = Browser::launch(&data.join("chromium"));
    browser.navigate(&server.url);
    browser.wait_for(
        "document.querySelector('#history-list .job-row')",
        Duration::from_secs(30),
    );
    let mut order = Vec::new();
    for _ in 0..60 {
        browser.tab();
        let at = browser.eval(
            "(e => e.id || (e.classList.contains('job-row') ? 'job-row' : e.tagName))(document.activeElement)",
        );
        order.push(at.as_str().unwrap_or_default().to_string());
    }
    let position = |what: &str| order.iter().position(|x| x == what);
    let (pick, gate, history) = (
        position("tab-pick"),
        position("tab-gate"),
        position("job-row"),
    );
    eprintln!("Tab order: {order:?}");
    assert!(pick.is_some() && history.is_some(), "{order:?}");
    assert!(pick < history, "Pick after History: {order:?}");
    assert!(gate.is_some(), "Gate is not on the Tab path: {order:?}");
    drop(browser);
    drop(server);
    std::fs::remove_dir_all(&data).unwrap();
}

#[test]
#[ignore = "needs chromium (Debian package chromium; .ci/run installs it)"]
fn a_killed_server_shows_a_banner_within_5_s() {
    let data = temp_dir("serve-browser-killed");
    let shots = screenshots();
    let mut server = Served::start(&data);
    let mut browser = Browser::launch(&data.join("chromium"));
    browser.navigate(&server.url);
    browser.wait_for(
        "document.querySelectorAll('#scene option').length > 1",
        Duration::from_secs(30),
    );
    check_narrow(&mut browser, shots.as_deref(), "0-empty");
    assert_eq!(
        browser.eval("document.getElementById('lost-banner').hidden"),
        true
    );
    server.child.kill().unwrap();
    server.child.wait().unwrap();
    let killed = Instant::now();
    browser.wait_for(
        "!document.getElementById('lost-banner').hidden",
        Duration::from_secs(5),
    );
    let noticed = killed.elapsed();
    eprintln!(
        "a killed server: the banner after {:.1} s",
        noticed.as_secs_f64()
    );
    assert!(noticed < Duration::from_secs(5));
    browser.screenshot(shots.as_deref(), "8-server-lost");
    drop(browser);
    drop(server);
    std::fs::remove_dir_all(&data).unwrap();
}
