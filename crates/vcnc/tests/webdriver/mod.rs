//! A minimal W3C WebDriver client for headless Chromium: JSON over HTTP
//! to a chromedriver this process starts on the loopback interface (ureq,
//! blocking). Shared by the browser test and the page benchmark
//! (`benches/plot_page.rs`).
//!
//! WebDriver rather than the DevTools protocol: it is request/response
//! over HTTP, so a small blocking client is all it takes — no WebSocket,
//! no event stream, no async runtime — and Debian ships the matching
//! driver beside the browser (`chromium-driver`).

#![allow(clippy::unwrap_used, clippy::expect_used, dead_code)] // test support: a panic is a failure report

use serde_json::{Value, json};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Chromium and chromedriver, from `VCNC_CHROMIUM` / `VCNC_CHROMEDRIVER`
/// or Debian's places; a clear message when they are missing.
pub fn tools() -> Result<(PathBuf, PathBuf), String> {
    let chromium = find(
        "VCNC_CHROMIUM",
        &["/usr/bin/chromium", "/usr/bin/chromium-browser"],
    );
    let chromedriver = find("VCNC_CHROMEDRIVER", &["/usr/bin/chromedriver"]);
    match (chromium, chromedriver) {
        (Some(a), Some(b)) => Ok((a, b)),
        _ => Err("headless Chromium and its WebDriver are needed: \
                  `apt-get install -y chromium chromium-driver` (Debian), or point \
                  VCNC_CHROMIUM and VCNC_CHROMEDRIVER at them"
            .to_string()),
    }
}

/// The file named by `var` in the environment, else the first of `paths`,
/// that exists.
fn find(var: &str, paths: &[&str]) -> Option<PathBuf> {
    std::env::var_os(var)
        .map(PathBuf::from)
        .into_iter()
        .chain(paths.iter().map(PathBuf::from))
        .find(|p| p.is_file())
}

/// A WebDriver session on a chromedriver this process started; both end
/// when it drops, pass or fail.
pub struct Browser {
    driver: Child,
    base: String,
    session: Option<String>,
    agent: ureq::Agent,
    profile: PathBuf,
}

impl Browser {
    pub fn start(chromium: &Path, chromedriver: &Path) -> Browser {
        // A free port on the loopback interface.
        let port = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let driver = Command::new(chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {}: {e}", chromedriver.display()));
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .timeout_global(Some(Duration::from_secs(60)))
            .http_status_as_error(false)
            .proxy(None)
            .build()
            .into();
        let profile = std::env::temp_dir().join(format!("vcnc-browser-{}", std::process::id()));
        let mut b = Browser {
            driver,
            base: format!("http://127.0.0.1:{port}"),
            session: None,
            agent,
            profile,
        };
        let t0 = Instant::now();
        loop {
            let ready = b
                .agent
                .get(format!("{}/status", b.base))
                .call()
                .ok()
                .and_then(|r| r.into_body().read_to_string().ok())
                .and_then(|s| serde_json::from_str::<Value>(&s).ok())
                .is_some_and(|v| v["value"]["ready"] == json!(true));
            if ready {
                break;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(20),
                "chromedriver did not become ready"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            // The page's console, for `console_errors`.
            "goog:loggingPrefs": {"browser": "ALL"},
            "goog:chromeOptions": {
                "binary": chromium.to_str().unwrap(),
                "args": [
                    "--headless=new", "--no-sandbox", "--disable-gpu",
                    "--disable-background-networking", "--disable-component-update",
                    "--disable-sync", "--disable-quic", "--no-first-run",
                    "--disable-default-apps", "--window-size=1400,900",
                    format!("--user-data-dir={}", b.profile.display()),
                ]
            }
        }}});
        let v = b.post("/session", &caps);
        let id = v["value"]["sessionId"]
            .as_str()
            .unwrap_or_else(|| panic!("no session: {v}"))
            .to_string();
        b.session = Some(id);
        b
    }

    fn url(&self, path: &str) -> String {
        match &self.session {
            Some(id) => format!("{}/session/{id}{path}", self.base),
            None => format!("{}{path}", self.base),
        }
    }

    pub fn post(&self, path: &str, body: &Value) -> Value {
        let r = self
            .agent
            .post(self.url(path))
            .header("Content-Type", "application/json")
            .send(body.to_string())
            .unwrap_or_else(|e| panic!("POST {path}: {e}"));
        let status = r.status();
        let v: Value = serde_json::from_str(&r.into_body().read_to_string().unwrap()).unwrap();
        assert!(status.is_success(), "POST {path}: {status} {v}");
        v
    }

    pub fn get(&self, path: &str) -> Value {
        let r = self.agent.get(self.url(path)).call().unwrap();
        serde_json::from_str(&r.into_body().read_to_string().unwrap()).unwrap()
    }

    /// Runs `script` (a function body) in the page; its return value.
    pub fn js(&self, script: &str) -> Value {
        self.post("/execute/sync", &json!({"script": script, "args": []}))["value"].clone()
    }

    /// The browser console's errors since the last call (chromedriver's
    /// log endpoint; warnings such as the software-WebGL notice are left
    /// out).
    pub fn console_errors(&self) -> Vec<String> {
        let v = self.post("/se/log", &json!({"type": "browser"}));
        v["value"]
            .as_array()
            .map(|entries| {
                entries
                    .iter()
                    .filter(|e| e["level"] == "SEVERE")
                    .map(|e| e["message"].as_str().unwrap_or("").to_string())
                    .collect()
            })
            .unwrap_or_default()
    }

    /// Opens `page` and waits until the viewer has drawn its first frame.
    pub fn open(&self, page: &Path) {
        self.post(
            "/url",
            &json!({"url": format!("file://{}", page.display())}),
        );
        let t0 = Instant::now();
        while self.js("return !!(window.vcnc && window.vcnc.stats.frames > 0);") != json!(true) {
            assert!(
                t0.elapsed() < Duration::from_secs(30),
                "the page never drew a frame: {:?}",
                self.console_errors()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// W3C pointer actions with the mouse, as a list of action objects.
    pub fn mouse(&self, actions: Value) {
        self.post(
            "/actions",
            &json!({"actions": [{"type": "pointer", "id": "mouse",
                "parameters": {"pointerType": "mouse"}, "actions": actions}]}),
        );
    }

    /// Saves a screenshot of the window as a PNG at `path`.
    pub fn screenshot(&self, path: &Path) {
        use base64::Engine;
        let shot = self.get("/screenshot")["value"]
            .as_str()
            .unwrap()
            .to_string();
        let png = base64::engine::general_purpose::STANDARD
            .decode(shot)
            .unwrap();
        assert_eq!(&png[1..4], b"PNG");
        std::fs::write(path, png).unwrap();
    }

    pub fn element(&self, css: &str) -> String {
        let v = self.post("/element", &json!({"using": "css selector", "value": css}));
        v["value"]
            .as_object()
            .and_then(|o| o.values().next())
            .and_then(Value::as_str)
            .unwrap_or_else(|| panic!("no element {css}: {v}"))
            .to_string()
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if self.session.is_some() {
            let _ = self.agent.delete(self.url("")).call();
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}
