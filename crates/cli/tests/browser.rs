//! The replay pages in a real browser: headless Chromium loads each page, and the test checks
//! that no error was caught and that the animation advanced (the page exposes its clock and
//! frame count on <body>). `.ci/run` installs Debian's chromium (scripts/install-chromium.sh)
//! and sets MASON_REQUIRE_BROWSER=1; elsewhere the test is skipped when no browser is found.

use std::path::{Path, PathBuf};
use std::process::Command;

fn chromium() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|name| {
            let out = Command::new("sh")
                .arg("-c")
                .arg(format!("command -v {name}"))
                .output()
                .ok()?;
            let path = String::from_utf8_lossy(&out.stdout).trim().to_string();
            (out.status.success() && !path.is_empty()).then(|| PathBuf::from(path))
        })
}

fn mason(args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_mason"))
        .args(args)
        .output()
        .expect("mason runs");
    assert!(
        o.status.code() == Some(0),
        "mason {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Loads `page` headless for a few seconds of virtual time; returns the <body> attributes
/// and Chromium's console log.
fn load(browser: &Path, page: &Path, profile: &Path) -> (String, String) {
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=4000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout).into_owned();
    let body = dom
        .split("<body")
        .nth(1)
        .and_then(|rest| rest.split('>').next())
        .unwrap_or_default()
        .to_string();
    (body, String::from_utf8_lossy(&out.stderr).into_owned())
}

fn attr(body: &str, name: &str) -> Option<f64> {
    let key = format!("{name}=\"");
    let start = body.find(&key)? + key.len();
    body[start..].split('"').next()?.parse().ok()
}

#[test]
fn replay_pages_play_without_errors_in_a_real_browser() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("MASON_REQUIRE_BROWSER").is_none(),
            "MASON_REQUIRE_BROWSER is set but no chromium was found (run scripts/install-chromium.sh)"
        );
        eprintln!("skipped: no chromium on PATH (scripts/install-chromium.sh installs it)");
        return;
    };
    let dir = std::env::temp_dir().join(format!("mason-browser-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mission = dir.join("mission.html");
    let crew = dir.join("crew.html");
    mason(&[
        "simulate",
        "builtin:mbzirc",
        "--coord",
        "auto",
        "--blackout",
        "100-200",
        "--grasp-fail",
        "0.1",
        "--html",
        mission.to_str().unwrap(),
    ]);
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data");
    mason(&[
        "crew",
        data.join("crew-room.map").to_str().unwrap(),
        "--scen",
        data.join("crew-room.scen").to_str().unwrap(),
        "--html",
        crew.to_str().unwrap(),
    ]);
    for page in [&mission, &crew] {
        let (body, log) = load(&browser, page, &dir.join("profile"));
        assert_eq!(
            attr(&body, "data-errors"),
            Some(0.0),
            "{}: body {body:?}\n{log}",
            page.display()
        );
        assert!(!log.contains("Uncaught"), "{}: {log}", page.display());
        let frames = attr(&body, "data-frames").unwrap_or(0.0);
        let t = attr(&body, "data-t").unwrap_or(0.0);
        assert!(
            frames >= 2.0,
            "{}: only {frames} frames drawn ({body:?})",
            page.display()
        );
        assert!(
            t > 0.0,
            "{}: the animation did not advance ({body:?})",
            page.display()
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}
