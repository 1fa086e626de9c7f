//! The `mason` binary: outputs, JSON and exit codes.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn data(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn mason(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mason"))
        .args(args)
        .output()
        .expect("mason runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exit 2, one line on stderr that contains every `needle`, and no panic.
fn assert_input_error(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` missing in: {err}");
    }
}

#[test]
fn plan_json_has_the_documented_fields_and_a_consistent_total() {
    let o = mason(&["plan", "builtin:thesis-2x5", "--planner", "exact", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["planner"], "exact");
    assert_eq!(v["status"], "optimal");
    let order = v["order"].as_array().unwrap();
    assert_eq!(order.len(), 10);
    let steps = v["steps"].as_array().unwrap();
    let sum: f64 = steps.iter().map(|s| s["cost"].as_f64().unwrap()).sum();
    assert!((sum - v["total_cost"].as_f64().unwrap()).abs() < 1e-9);
    assert!(v["stats"]["elapsed_ms"].as_f64().is_some());
    // Every level-2 brick comes after all level-1 bricks' supports: check via the wall JSON.
    let bricks = v["wall"]["bricks"].as_array().unwrap();
    let pos = |id: &Value| order.iter().position(|x| x == id).unwrap();
    for b in bricks {
        for s in b["supports"].as_array().unwrap() {
            assert!(pos(s) < pos(&b["id"]));
        }
    }
}

#[test]
fn exact_and_brute_agree_through_the_cli() {
    let cost = |planner: &str| {
        let o = mason(&["plan", &data("wall-ok.txt"), "--planner", planner, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
        v["total_cost"].as_f64().unwrap()
    };
    assert!((cost("exact") - cost("brute")).abs() < 1e-9);
    assert!(cost("greedy") >= cost("exact") - 1e-9);
}

#[test]
fn plan_table_lists_steps_and_total() {
    let o = mason(&["plan", &data("wall-ok.txt"), "--planner", "improved:1,4"]);
    assert!(o.status.success());
    let out = stdout(&o);
    assert!(out.contains("planner improved:1,4"), "{out}");
    assert!(out.contains("total cost"), "{out}");
    assert_eq!(
        out.lines()
            .filter(|l| l.trim_start().starts_with(char::is_numeric))
            .count(),
        6
    );
}

#[test]
fn brute_out_of_time_reports_timeout_with_an_order() {
    let o = mason(&[
        "plan",
        "builtin:levels5-width10",
        "--planner",
        "brute",
        "--time-limit",
        "0.05",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["status"], "timeout");
    assert_eq!(v["order"].as_array().unwrap().len(), 43);
}

#[test]
fn a_cost_model_file_changes_the_cost() {
    let run = |extra: &[&str]| {
        let mut args = vec!["plan", "builtin:thesis-2x5", "--json"];
        args.extend_from_slice(extra);
        let o = mason(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str::<Value>(&stdout(&o)).unwrap()["total_cost"]
            .as_f64()
            .unwrap()
    };
    let model = data("model-ok.toml");
    assert!((run(&[]) - run(&["--model", &model])).abs() > 1.0);
}

#[test]
fn demo_prints_the_comparison_and_writes_figures() {
    let out = std::env::temp_dir().join(format!("mason-demo-test-{}", std::process::id()));
    let o = mason(&[
        "demo",
        "--out",
        &out.to_string_lossy(),
        "--time-limit",
        "0.2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for wall in ["thesis-2x5", "levels5-width5", "levels5-width10", "mbzirc"] {
        assert!(text.contains(wall), "{text}");
        assert!(out.join(format!("wall-{wall}.svg")).exists());
    }
    assert_eq!(text.matches("  exact ").count(), 4);
    let plans: Value =
        serde_json::from_slice(&std::fs::read(out.join("plans.json")).unwrap()).unwrap();
    assert_eq!(plans.as_array().unwrap().len(), 20);
    let _ = std::fs::remove_dir_all(out);
}

#[test]
fn wall_show_prints_supports_and_draws_svg() {
    let svg = std::env::temp_dir().join(format!("mason-wall-{}.svg", std::process::id()));
    let o = mason(&[
        "wall",
        "show",
        &data("wall-ok.txt"),
        "--svg",
        &svg.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("6 bricks, 2 levels"), "{out}");
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let _ = std::fs::remove_file(svg);
}

#[test]
fn malformed_inputs_exit_2_with_one_clear_line() {
    assert_input_error(
        &mason(&["plan", &data("wall-bad-token.txt")]),
        &["wall-bad-token.txt:2:", "`X`"],
    );
    assert_input_error(
        &mason(&["wall", "show", &data("wall-floating.txt")]),
        &["wall-floating.txt:1:", "floating brick"],
    );
    assert_input_error(
        &mason(&["wall", "show", "no/such/wall.txt"]),
        &["no/such/wall.txt"],
    );
    assert_input_error(
        &mason(&["wall", "show", &data("cmcp-bad-type.txt")]),
        &["cmcp-bad-type.txt:3:", "unknown brick type 9"],
    );
    assert_input_error(
        &mason(&[
            "wall",
            "show",
            &data("cmcp-bad-fields.txt"),
            "--format",
            "cmcp",
        ]),
        &["cmcp-bad-fields.txt:1:", "6 fields"],
    );
    assert_input_error(
        &mason(&["wall", "show", &data("not-a-png.png")]),
        &["not-a-png.png", "cannot decode"],
    );
    assert_input_error(
        &mason(&[
            "wall",
            "show",
            &data("mbzirc-short.txt"),
            "--format",
            "mbzirc",
        ]),
        &["mbzirc-short.txt:2:", "21 tokens"],
    );
    assert_input_error(
        &mason(&["plan", "builtin:nope"]),
        &["builtin:nope", "thesis-2x5"],
    );
    assert_input_error(
        &mason(&["plan", "builtin:thesis-2x5", "--planner", "astar"]),
        &["unknown planner `astar`"],
    );
    assert_input_error(
        &mason(&[
            "plan",
            "builtin:thesis-2x5",
            "--model",
            &data("model-bad.toml"),
        ]),
        &["model-bad.toml:4:"],
    );
    assert_input_error(
        &mason(&[
            "plan",
            "builtin:thesis-2x5",
            "--model",
            &data("model-negative.toml"),
        ]),
        &["model-negative.toml", "alpha"],
    );
    assert_input_error(
        &mason(&["plan", "builtin:thesis-2x5", "--time-limit", "-1"]),
        &["--time-limit"],
    );
    assert_input_error(&mason(&["bench", "nothing"]), &["unknown bench suite"]);
}

#[test]
fn usage_errors_exit_2() {
    let o = mason(&["plan"]);
    assert_eq!(o.status.code(), Some(2));
    let o = mason(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(mason(&["--help"]).status.success());
}

#[test]
fn cmcp_benchmark_walls_load_when_present() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/benchmarks/walls-cmcp/config");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("skipping: {} not present", dir.display());
        return;
    };
    let mut checked = 0;
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if !name.ends_with(".txt") || name == "wall.obj.txt" {
            continue;
        }
        let sizes = if name.contains("_multi") {
            "swapped"
        } else {
            "yaml"
        };
        let path = e.path().to_string_lossy().into_owned();
        let o = mason(&[
            "plan",
            &path,
            "--format",
            "cmcp",
            "--cmcp-sizes",
            sizes,
            "--json",
        ]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} CMCP walls found");
}
