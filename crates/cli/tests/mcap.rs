//! `mason simulate --mcap`: the log read back by a reader Mason did not write, PyPI's `mcap`
//! (tests/python/read_mcap.py), every message validated against its channel's JSON Schema
//! (PyPI `jsonschema`) and the `foxglove.*` schemas compared with Foxglove's published ones
//! (scripts/fetch-foxglove-schemas.sh), and compared with `mason simulate --json` of the same
//! seed. `.ci/run` installs the reader and fetches the schemas (scripts/install-python-mcap.sh, a venv in
//! `${MASON_PYENV:-target/pyenv}`) and sets MASON_REQUIRE_PYTHON=1; elsewhere the Python part is
//! skipped when that venv is missing. Bad output paths are checked without Python.

mod common;

use common::{assert_input_error, mason, python_with, root, stdout};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Foxglove's published JSON schemas (scripts/fetch-foxglove-schemas.sh writes them to
/// `target/foxglove-schemas/json`), if fetched; with MASON_REQUIRE_PYTHON set they must be.
fn foxglove_schemas() -> Option<PathBuf> {
    let dir = root().join("target/foxglove-schemas/json");
    if dir.join("foxglove.Log.json").exists() {
        return Some(dir);
    }
    assert!(
        std::env::var_os("MASON_REQUIRE_PYTHON").is_none(),
        "MASON_REQUIRE_PYTHON is set but {} has no schemas (run scripts/fetch-foxglove-schemas.sh)",
        dir.display()
    );
    eprintln!(
        "not compared with Foxglove's schemas: scripts/fetch-foxglove-schemas.sh fetches them"
    );
    None
}

/// The checker's one-line JSON summary of `file`: every message validated against the schema
/// its channel declares, and the `foxglove.*` schemas compared with Foxglove's published ones
/// when those are there.
fn read_mcap(python: &Path, file: &Path) -> Value {
    let mut command = Command::new(python);
    command
        .arg(root().join("tests/python/read_mcap.py"))
        .arg(file);
    let foxglove = foxglove_schemas();
    if let Some(dir) = &foxglove {
        command.arg("--foxglove").arg(dir);
    }
    let out = command.output().expect("python runs");
    assert!(
        out.status.success(),
        "read_mcap.py {}: {}",
        file.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: Value = serde_json::from_slice(&out.stdout).expect("one line of JSON");
    assert_eq!(summary["validated"], summary["messages"]);
    if foxglove.is_some() {
        assert_eq!(
            summary["compared_with_foxglove"],
            serde_json::json!([
                "foxglove.Log",
                "foxglove.PoseInFrame",
                "foxglove.SceneUpdate"
            ])
        );
    }
    summary
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mason-mcap-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `mason simulate ARGS --json`, and again with `--mcap FILE`; the JSON must not change.
fn simulate_with_log(args: &[&str], file: &Path) -> Value {
    let mut plain = vec!["simulate"];
    plain.extend_from_slice(args);
    plain.push("--json");
    let without = mason(&plain);
    assert_eq!(without.status.code(), Some(0), "{plain:?}");
    plain.extend_from_slice(&["--mcap", file.to_str().unwrap()]);
    let with = mason(&plain);
    assert_eq!(with.status.code(), Some(0), "{plain:?}");
    assert_eq!(stdout(&with), stdout(&without), "--mcap changed the run");
    serde_json::from_str(&stdout(&with)).unwrap()
}

fn count(events: &[Value], kind: &str) -> usize {
    events.iter().filter(|e| e["kind"] == kind).count()
}

/// What the log must show of the run `--json` printed.
fn assert_agrees(summary: &Value, run: &Value, uavs: usize) {
    let events = run["events"].as_array().unwrap();
    assert_eq!(summary["placed"], run["metrics"]["bricks_placed"]);
    let placed: Vec<&Value> = events
        .iter()
        .filter(|e| e["kind"] == "place")
        .map(|e| &e["brick"])
        .collect();
    assert_eq!(
        summary["placed_bricks"]
            .as_array()
            .unwrap()
            .iter()
            .collect::<Vec<_>>(),
        placed
    );
    assert_eq!(summary["states"], count(events, "state"));
    assert_eq!(summary["zone_entries"], count(events, "zone_enter"));
    assert_eq!(summary["topics"]["/events"], events.len());
    assert_eq!(
        summary["topics"]["/bricks"],
        count(events, "grasp") + count(events, "place") + count(events, "lost")
    );
    assert_eq!(summary["topics"]["/wall"], placed.len() + 1);
    for i in 0..uavs {
        let states = events
            .iter()
            .filter(|e| e["kind"] == "state" && e["uav"] == i)
            .count();
        assert_eq!(summary["topics"][format!("/uav/{i}/state")], states);
        assert_eq!(
            summary["schemas"][format!("/uav/{i}/pose")],
            "foxglove.PoseInFrame"
        );
        assert!(
            summary["topics"][format!("/uav/{i}/pose")]
                .as_u64()
                .unwrap()
                > 10
        );
    }
    assert_eq!(summary["schemas"]["/wall"], "foxglove.SceneUpdate");
    assert_eq!(summary["schemas"]["/events"], "foxglove.Log");
    assert!(summary["channels"]
        .as_array()
        .unwrap()
        .contains(&Value::from("/messages")));
    let end_ns = (run["metrics"]["end_s"].as_f64().unwrap() * 1e9).round();
    assert_eq!(summary["end_ns"].as_f64().unwrap(), end_ns);
    assert_eq!(summary["metadata"]["mission"]["uavs"], uavs.to_string());
}

#[test]
fn simulate_mcap_reads_back_with_pypi_mcap_and_matches_the_json() {
    let Some(python) = python_with("mcap.reader, jsonschema", "scripts/install-python-mcap.sh")
    else {
        return;
    };
    let dir = temp_dir("read");
    let file = dir.join("mbzirc.mcap");
    let args = [
        "builtin:mbzirc",
        "--uavs",
        "3",
        "--coord",
        "comm",
        "--seed",
        "4",
    ];
    let run = simulate_with_log(&args, &file);
    let summary = read_mcap(&python, &file);
    assert_eq!(summary["placed"], 42);
    assert_agrees(&summary, &run, 3);
    // A run with faults: a UAV fails (its brick is lost), a blackout, grasp failures.
    let faulty = dir.join("faults.mcap");
    let args = [
        "builtin:thesis-2x5",
        "--uavs",
        "3",
        "--coord",
        "auto",
        "--uav-fail",
        "1@150",
        "--blackout",
        "60-120",
        "--grasp-fail",
        "0.2",
    ];
    let run = simulate_with_log(&args, &faulty);
    let summary = read_mcap(&python, &faulty);
    assert_agrees(&summary, &run, 3);
    // The failure is a warning or an error in the log, not an info line.
    let levels = &summary["log_levels"];
    assert!(levels["3"].as_u64().unwrap_or(0) + levels["4"].as_u64().unwrap_or(0) > 0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn one_seed_writes_the_same_log_twice() {
    let dir = temp_dir("same");
    let (a, b) = (dir.join("a.mcap"), dir.join("b.mcap"));
    for f in [&a, &b] {
        let o = mason(&[
            "simulate",
            "builtin:thesis-2x5",
            "--mcap",
            f.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0));
    }
    let (a, b) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert!(a.starts_with(b"\x89MCAP0\r\n"));
    assert_eq!(a, b);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mcap_to_a_folder_or_a_missing_folder_is_one_line_exit_2() {
    let dir = temp_dir("bad");
    let folder = dir.to_str().unwrap();
    let o = mason(&["simulate", "builtin:thesis-2x5", "--mcap", folder]);
    assert_input_error(&o, &[folder, "is a folder"]);
    let missing = dir.join("no-such-folder/log.mcap");
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--mcap",
        missing.to_str().unwrap(),
    ]);
    assert_input_error(&o, &["no-such-folder/log.mcap", "does not exist"]);
    assert!(!missing.exists());
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--runs",
        "5",
        "--mcap",
        dir.join("many.mcap").to_str().unwrap(),
    ]);
    assert_input_error(&o, &["--mcap", "one mission"]);
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    std::fs::remove_dir_all(&dir).ok();
}
