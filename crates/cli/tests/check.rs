//! `mason check`: artefacts from Mason's own commands pass (exit 0), one broken artefact of
//! each kind is refused naming its rule and what it concerns (exit 1), malformed files are
//! refused naming the file and the line (exit 2), `--all` lists every violation, and the
//! plain formats (order list, schedule CSV, result file) are read.

use serde_json::Value;
use std::path::PathBuf;
use std::process::Output;

mod common;
use common::{assert_input_error, data, mason, stderr, stdout};

/// A scratch file holding `text`.
fn file(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("mason-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path: PathBuf = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Runs a Mason command that must succeed and returns its stdout.
fn output_of(args: &[&str]) -> String {
    let o = mason(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stdout(&o)
}

fn assert_valid(o: &Output, needles: &[&str]) {
    let out = stdout(o);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(o));
    for n in needles {
        assert!(out.contains(n), "`{n}` missing in: {out}");
    }
}

/// Exit 1, one line on stderr naming the rule and every needle.
fn assert_broken(o: &Output, rule: &str, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(
        o.status.code(),
        Some(1),
        "stderr: {err} stdout: {}",
        stdout(o)
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(
        err.contains(&format!("breaks {rule}: ")),
        "rule {rule} in: {err}"
    );
    for n in needles {
        assert!(err.contains(n), "`{n}` missing in: {err}");
    }
}

#[test]
fn orders_from_every_planner_and_a_plain_list_pass() {
    for planner in ["exact", "greedy", "brute", "improved:1,4"] {
        let plan = output_of(&["plan", &data("wall-ok.txt"), "--planner", planner, "--json"]);
        let v: Value = serde_json::from_str(&plan).unwrap();
        let cost = v["total_cost"].as_f64().unwrap();
        let path = file(&format!("plan-{planner}.json"), &plan);
        let o = mason(&["check", "order", &data("wall-ok.txt"), &path]);
        assert_valid(
            &o,
            &[
                "valid build order (plan --json)",
                &format!("{cost:.3} (file: {cost:.3})"),
            ],
        );
    }
    let list = file(
        "order.txt",
        "# bottom first\n101, 102 103\n104 105\n201,202,203,204,205\n",
    );
    let o = mason(&["check", "order", "builtin:thesis-2x5", &list]);
    assert_valid(&o, &["valid build order (list) of the 10 bricks"]);
}

#[test]
fn a_broken_order_names_the_rule_and_the_brick() {
    let list = file("order-bad.txt", "101 102 103 104 205 105 201 202 203 204\n");
    let o = mason(&["check", "order", "builtin:thesis-2x5", &list]);
    assert_broken(&o, "Unsupported", &["brick 205", "support 105", "step 4"]);
    // A stated cost that is not the order's.
    let plan = output_of(&["plan", "builtin:thesis-2x5", "--json"]);
    let mut v: Value = serde_json::from_str(&plan).unwrap();
    v["total_cost"] = Value::from(1.0);
    let path = file("plan-cost.json", &v.to_string());
    let o = mason(&["check", "order", "builtin:thesis-2x5", &path]);
    assert_broken(&o, "CostMismatch", &["claimed total cost 1"]);
}

#[test]
fn all_lists_every_violation_of_an_order() {
    let list = file(
        "order-all.txt",
        "201 101 102 103 104 105 202 203 204 205 205\n",
    );
    let o = mason(&["check", "--all", "order", "builtin:thesis-2x5", &list]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    let rules: Vec<&str> = out.lines().map(|l| l.split(':').next().unwrap()).collect();
    assert_eq!(rules, ["WrongLength", "Unsupported", "Repeated"], "{out}");
    assert!(stderr(&o).contains("3 violation(s)"), "{}", stderr(&o));
    // Without --all, only the first.
    let o = mason(&["check", "order", "builtin:thesis-2x5", &list]);
    assert_broken(&o, "WrongLength", &["11 entries"]);
    assert!(stdout(&o).is_empty());
}

#[test]
fn malformed_orders_name_the_file_and_line() {
    let bad = file("order-token.txt", "101 102\n103 x3\n");
    assert_input_error(
        &mason(&["check", "order", "builtin:thesis-2x5", &bad]),
        &["order-token.txt:2:", "`x3` is not a brick id"],
    );
    let unknown = file("order-unknown.txt", "101\n\n\n999\n");
    assert_input_error(
        &mason(&["check", "order", "builtin:thesis-2x5", &unknown]),
        &["order-unknown.txt:4:", "brick 999 is not in the wall"],
    );
    let json = file("order-cut.json", "{\"order\": [101,\n102,");
    assert_input_error(
        &mason(&["check", "order", "builtin:thesis-2x5", &json]),
        &["order-cut.json:2:", "EOF"],
    );
    assert_input_error(
        &mason(&[
            "check",
            "order",
            "builtin:thesis-2x5",
            "/nonexistent/order.txt",
        ]),
        &["/nonexistent/order.txt"],
    );
}

#[test]
fn schedules_from_every_objective_pass_with_their_figures() {
    let runs: [&[&str]; 3] = [
        &["--objective", "makespan", "--model", "cmcp"],
        &["--objective", "reward", "--budget", "300"],
        &[
            "--objective",
            "expected",
            "--budget",
            "300",
            "--uav-hazard",
            "2",
        ],
    ];
    for extra in runs {
        let mut args = vec!["plan", "builtin:mbzirc", "--uavs", "3", "--json"];
        args.extend_from_slice(extra);
        let json = output_of(&args);
        let v: Value = serde_json::from_str(&json).unwrap();
        let path = file(&format!("schedule-{}.json", extra[1]), &json);
        let o = mason(&["check", "schedule", "builtin:mbzirc", &path]);
        let reward = format!("reward {} (file: {})", v["reward"], v["reward"]);
        let makespan = format!(
            "makespan {} s (file: {} s)",
            v["makespan_s"], v["makespan_s"]
        );
        assert_valid(
            &o,
            &["valid team schedule (plan --json)", &reward, &makespan],
        );
    }
}

#[test]
fn a_schedule_csv_is_checked_with_the_model_given() {
    let csv = data("schedule-thesis-2x5-cmcp.csv");
    let o = mason(&[
        "check",
        "schedule",
        "builtin:thesis-2x5",
        &csv,
        "--model",
        "cmcp",
    ]);
    assert_valid(
        &o,
        &[
            "valid team schedule (csv)",
            "10 of 10 bricks",
            "reward 20",
            "makespan 190 s",
            "3 UAVs",
        ],
    );
    // The same rows under the thesis model (other placing times): the stated ends are wrong.
    let o = mason(&["check", "schedule", "builtin:thesis-2x5", &csv]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // Too small a budget: the first brick placed after it is named.
    let o = mason(&[
        "check",
        "schedule",
        "builtin:thesis-2x5",
        &csv,
        "--model",
        "cmcp",
        "--budget",
        "150",
    ]);
    assert_broken(&o, "Budget", &["brick 204", "180 s", "budget of 150 s"]);
}

#[test]
fn a_broken_schedule_csv_names_the_rule_the_uav_and_the_bricks() {
    // UAV 0 starts brick 103 at 45 s, 5 s before its first cycle ends, and says it ends at 90 s.
    let text = std::fs::read_to_string(data("schedule-thesis-2x5-cmcp.csv"))
        .unwrap()
        .replace("0,103,50,90", "0,103,45,90");
    let path = file("schedule-cycle.csv", &text);
    let o = mason(&[
        "check",
        "schedule",
        "builtin:thesis-2x5",
        &path,
        "--model",
        "cmcp",
    ]);
    assert_broken(
        &o,
        "Cycle",
        &["UAV 0", "brick 103", "brick 102", "45 s", "50 s"],
    );
    let o = mason(&[
        "check",
        "--all",
        "schedule",
        "builtin:thesis-2x5",
        &path,
        "--model",
        "cmcp",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let out = stdout(&o);
    assert!(out.lines().any(|l| l.starts_with("Cycle: UAV 0")), "{out}");
    assert!(
        out.lines().any(|l| l.starts_with("End: UAV 0: brick 103")),
        "{out}"
    );
    assert_eq!(out.lines().count(), 2, "{out}");
}

#[test]
fn malformed_schedules_name_the_file_and_line() {
    let path = file("schedule-bad.csv", "uav,brick,start\n0,101,0\n1,102\n");
    assert_input_error(
        &mason(&["check", "schedule", "builtin:thesis-2x5", &path]),
        &["schedule-bad.csv:3:", "expected uav,brick,start[,end]"],
    );
    let path = file(
        "schedule-bad.json",
        "{\"schedule\": [\n{\"uav\": 0, \"brick\": 101, \"start_s\": \"soon\"}]}",
    );
    assert_input_error(
        &mason(&["check", "schedule", "builtin:thesis-2x5", &path]),
        &["schedule-bad.json:2:", "invalid type"],
    );
}

#[test]
fn traces_from_simulate_and_their_event_lists_pass() {
    let json = output_of(&[
        "simulate",
        "builtin:thesis-2x5",
        "--uavs",
        "3",
        "--coord",
        "comm",
        "--json",
    ]);
    let path = file("sim.json", &json);
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_valid(
        &o,
        &[
            "valid mission trace (simulate --json)",
            "10 of 10 bricks placed",
        ],
    );
    let v: Value = serde_json::from_str(&json).unwrap();
    let events = serde_json::to_string_pretty(&v["events"]).unwrap();
    let path = file("events.json", &events);
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_valid(&o, &["valid mission trace (events)", "3 UAVs"]);
    let faulty = output_of(&[
        "simulate",
        "builtin:mbzirc",
        "--uavs",
        "3",
        "--coord",
        "windows",
        "--grasp-fail",
        "0.3",
        "--uav-fail",
        "1@300",
        "--seed",
        "4",
        "--json",
    ]);
    let path = file("sim-faults.json", &faulty);
    let o = mason(&["check", "trace", "builtin:mbzirc", &path]);
    assert_valid(&o, &["valid mission trace (simulate --json)"]);
}

/// The simulated thesis-2x5 trace with its first placement removed: a brick grasped and never
/// placed, and bricks placed on a missing support.
fn trace_without_first_place() -> String {
    let json = output_of(&[
        "simulate",
        "builtin:thesis-2x5",
        "--uavs",
        "3",
        "--coord",
        "comm",
        "--json",
    ]);
    let mut v: Value = serde_json::from_str(&json).unwrap();
    let events = v["events"].as_array_mut().unwrap();
    let i = events.iter().position(|e| e["kind"] == "place").unwrap();
    events.remove(i);
    serde_json::to_string_pretty(&v).unwrap()
}

#[test]
fn a_broken_trace_names_the_rule_the_uav_and_the_time() {
    let path = file("trace-broken.json", &trace_without_first_place());
    // UAV 0 still holds its first brick (102) when it grasps the next (105).
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_broken(
        &o,
        "Unaccounted",
        &["UAV 0", "brick 105", "grasped while holding another"],
    );
    let o = mason(&["check", "--all", "trace", "builtin:thesis-2x5", &path]);
    let out = stdout(&o);
    assert!(
        out.lines().any(|l| l.starts_with("Precedence: t = ")),
        "{out}"
    );
    // A UAV that enters the zone twice.
    let trace = r#"[{"t": 0, "uav": 0, "kind": "grasp", "brick": 101},
{"t": 5, "uav": 0, "kind": "zone_enter"},
{"t": 6, "uav": 0, "kind": "zone_enter"}]"#;
    let path = file("trace-twice.json", trace);
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_broken(&o, "Zone", &["t = 6", "UAV 0", "enters the zone twice"]);
}

#[test]
fn an_agent_trace_file_is_read_with_dense_ids() {
    // One event per line, as agents write them: bricks by dense index (0 is brick 101).
    let lines = "{\"t\":1.0,\"uav\":0,\"kind\":\"grasp\",\"brick\":0}\n{\"t\":2.0,\"uav\":0,\"kind\":\"zone_enter\"}\n{\"t\":3.0,\"uav\":0,\"kind\":\"place\",\"brick\":0}\n{\"t\":3.0,\"uav\":0,\"kind\":\"zone_leave\"}\n";
    let path = file("uav-0.jsonl", lines);
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_valid(
        &o,
        &[
            "valid mission trace (agent trace file)",
            "1 of 10 bricks placed",
        ],
    );
    let bad = lines.replace("\"brick\":0}\n{\"t\":2.0", "\"brick\":5}\n{\"t\":2.0");
    let path = file("uav-0-bad.jsonl", &bad);
    let o = mason(&["check", "trace", "builtin:thesis-2x5", &path]);
    assert_broken(
        &o,
        "Placement",
        &["t = 3", "UAV 0", "brick 101", "does not hold it"],
    );
    let cut = lines.replace("\"kind\":\"zone_enter\"", "\"kind\":\"hover\"");
    let path = file("uav-0-cut.jsonl", &cut);
    assert_input_error(
        &mason(&["check", "trace", "builtin:thesis-2x5", &path]),
        &["uav-0-cut.jsonl", "line 2", "hover"],
    );
}

#[test]
fn malformed_traces_name_the_file_and_line() {
    let path = file("trace-bad.json", "{\"uavs\": 3, \"events\": [\n{\"t\": 0, \"uav\": 0, \"kind\": \"grasp\", \"brick\": 101},\n{\"t\": 1, \"uav\": 7, \"kind\": \"fail\"}]}");
    assert_input_error(
        &mason(&["check", "trace", "builtin:thesis-2x5", &path]),
        &["trace-bad.json:3:", "UAV 7"],
    );
    let path = file(
        "trace-label.json",
        "[\n{\"t\": 0, \"uav\": 0, \"kind\": \"place\", \"brick\": 404}]",
    );
    assert_input_error(
        &mason(&["check", "trace", "builtin:thesis-2x5", &path]),
        &["trace-label.json:2:", "brick 404 is not in the wall"],
    );
}

#[test]
fn crew_plans_from_every_resolution_pass() {
    let (map, scen) = (data("crew-room.map"), data("crew-room.scen"));
    for extra in [
        &["--resolve", "paper"][..],
        &["--resolve", "st"],
        &["--resolve", "lacam", "--time-limit", "1"],
        &["--assign", "hungarian"],
    ] {
        let mut args = vec!["crew", map.as_str(), "--scen", scen.as_str(), "--json"];
        args.extend_from_slice(extra);
        let json = output_of(&args);
        let v: Value = serde_json::from_str(&json).unwrap();
        let path = file(&format!("crew-{}.json", extra[1]), &json);
        let o = mason(&["check", "crew", &map, "--scen", &scen, &path]);
        let soc = format!(
            "sum of costs {} (file: {})",
            v["sum_of_costs"], v["sum_of_costs"]
        );
        assert_valid(&o, &["valid crew plan (crew --json)", "4 robots", &soc]);
    }
}

#[test]
fn a_result_file_is_checked_against_its_scenario() {
    let (map, scen) = (data("crew-room.map"), data("crew-room.scen"));
    let result = data("crew-room-result.txt");
    let o = mason(&[
        "check",
        "crew",
        &map,
        "--scen",
        &scen,
        &result,
        "--connectivity",
        "4",
    ]);
    assert_valid(
        &o,
        &[
            "valid crew plan (result)",
            "4 robots",
            "sum of costs 56 (file: 56)",
            "makespan 14 (file: 14)",
        ],
    );
    let o = mason(&["check", "crew", &map, &result]);
    assert_valid(&o, &["valid crew plan (result)"]);
}

#[test]
fn a_broken_result_file_names_the_rule_the_robots_and_the_step() {
    let (map, scen) = (data("crew-room.map"), data("crew-room.scen"));
    let text = std::fs::read_to_string(data("crew-room-result.txt")).unwrap();
    // Robot 2 stays on (1,0) from step 6 to 7, then jumps two cells to (3,0).
    let jump = text.replace("7:(7,0),(4,2),(2,0),", "7:(7,0),(4,2),(1,0),");
    let path = file("result-jump.txt", &jump);
    let o = mason(&["check", "crew", &map, "--scen", &scen, &path]);
    assert_broken(&o, "IllegalMove", &["robot 2", "(1, 0) → (3, 0)", "step 7"]);
    // Robot 1 waits on (5,0), where robot 0 arrives at step 1.
    let path = file(
        "result-vertex.txt",
        "solution=\n0:(4,0),(5,0),\n1:(5,0),(5,0),\n",
    );
    let o = mason(&["check", "crew", &map, &path]);
    assert_broken(&o, "Vertex", &["robots 0 and 1", "(5, 0)", "step 1"]);
    // Robots 0 and 1 exchange cells.
    let swap = "solution=\n0:(4,0),(5,0),\n1:(5,0),(4,0),\n";
    let path = file("result-swap.txt", swap);
    let o = mason(&["check", "crew", &map, &path]);
    assert_broken(&o, "Swap", &["robots 0 and 1", "steps 0 and 1"]);
    // A plan whose starts are not the scenario's.
    let moved = text
        .replacen("starts=(0,0),", "starts=(0,1),", 1)
        .replacen("0:(0,0),", "0:(0,1),", 1);
    let path = file("result-start.txt", &moved);
    let o = mason(&["check", "crew", &map, "--scen", &scen, &path]);
    assert_broken(&o, "WrongStart", &["robot 0", "(0, 1)", "(0, 0)"]);
    // A stated sum of costs that is not the plan's.
    let soc = text.replace("soc=56", "soc=50");
    let path = file("result-soc.txt", &soc);
    let o = mason(&["check", "crew", &map, &path]);
    assert_broken(&o, "Claim", &["sum of costs 50", "gives 56"]);
    // --all: every rule broken.
    let o = mason(&[
        "check",
        "--all",
        "crew",
        &map,
        "--scen",
        &scen,
        &file("result-start-all.txt", &moved),
    ]);
    let out = stdout(&o);
    assert!(
        out.lines().filter(|l| l.starts_with("WrongStart")).count() >= 2,
        "{out}"
    );
}

#[test]
fn malformed_result_files_name_the_file_and_line() {
    let map = data("crew-room.map");
    let cases = [
        (
            "solution=\n0:(0,0),(9,0),\n1:(1,0),\n",
            "result-count.txt:3:",
            "1 agents at step 1, but 2",
        ),
        (
            "soc=1\nsolution=\n0:(0,0),(99,0),\n",
            "result-off.txt:3:",
            "cell (99, 0) is off the 10×6 map",
        ),
        (
            "solution=\n0:(0,0)\n2:(1,0)\n",
            "result-step.txt:3:",
            "time step 2, expected 1",
        ),
        ("agents=1\n", "result-none.txt", "no solution= line"),
    ];
    for (text, name, reason) in cases {
        let name_only = name.split(':').next().unwrap();
        let path = file(name_only, text);
        assert_input_error(&mason(&["check", "crew", &map, &path]), &[name, reason]);
    }
}

#[test]
fn garbage_and_extreme_values_are_refused_in_one_line() {
    let wall = "builtin:thesis-2x5";
    let cases: [(&str, &str, &[u8], &[&str]); 7] = [
        ("schedule", "binary.csv", b"\x00\xff\xfe", &["binary.csv", "not UTF-8"]),
        ("schedule", "empty.csv", b"uav,brick,start\n", &["empty.csv", "no rows"]),
        ("order", "empty.txt", b"", &["empty.txt:1:", "no brick ids"]),
        ("trace", "empty.json", b"", &["empty.json:1:", "EOF"]),
        ("trace", "huge-t.json", b"[{\"t\": 1e400, \"uav\": 0, \"kind\": \"fail\"}]", &["huge-t.json:1:", "out of range"]),
        (
            "trace",
            "huge-uav.json",
            b"[{\"t\": 1, \"uav\": 4294967295, \"kind\": \"fail\"}]",
            &["huge-uav.json:1:", "UAV 4294967295", "at most 1024"],
        ),
        (
            "trace",
            "huge-uav.jsonl",
            b"{\"t\": 1, \"uav\": 0, \"kind\": \"fail\"}\n{\"t\": 1, \"uav\": 4294967295, \"kind\": \"fail\"}\n",
            &["huge-uav.jsonl:2:", "UAV 4294967295", "at most 1024"],
        ),
    ];
    for (what, name, contents, needles) in cases {
        let dir = std::env::temp_dir().join(format!("mason-check-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, contents).unwrap();
        let o = mason(&["check", what, wall, &path.to_string_lossy()]);
        assert_input_error(&o, needles);
    }
    assert_input_error(
        &mason(&["check", "order", wall, "/dev/zero"]),
        &["/dev/zero", "not a regular file"],
    );
    let csv = data("schedule-thesis-2x5-cmcp.csv");
    for (flag, value, needle) in [
        ("--uavs", "0", "--uavs 0"),
        ("--uavs", "5000", "--uavs 5000"),
        ("--budget", "-1", "--budget -1"),
        ("--budget", "NaN", "--budget NaN"),
    ] {
        let o = mason(&[
            "check", "schedule", wall, &csv, "--model", "cmcp", flag, value,
        ]);
        assert_input_error(&o, &[needle]);
    }
    // A start of 10^308 s is a finite time: valid, and shown short.
    let path = file("far.csv", "0,101,1e308\n");
    let o = mason(&["check", "schedule", wall, &path]);
    assert_valid(&o, &["makespan 1e308 s"]);
    let o = mason(&[
        "check",
        "crew",
        &data("crew-room.map"),
        &file("r.txt", "solution=\n0:(0,0),(99999999999999999999,0)\n"),
    ]);
    assert_input_error(&o, &["r.txt:2:", "is not a cell"]);
    let o = mason(&[
        "check",
        "crew",
        &data("crew-room.map"),
        &data("crew-room-result.txt"),
        "--connectivity",
        "6",
    ]);
    assert_input_error(&o, &["--connectivity", "4 or 8"]);
}

/// #31: the distance rule's metric. A schedule that overlaps two bricks 0.796 m apart in the
/// plan and a level apart is valid under `xyz` only; `check schedule` reads the metric the
/// file states, and `--metric` overrides it.
#[test]
fn the_metric_a_schedule_states_is_the_one_it_is_checked_under() {
    let wall = data("cmcp-two-levels.txt");
    let rows = r#""schedule": [
        {"uav": 0, "brick": 3, "start_s": 0},
        {"uav": 1, "brick": 1, "start_s": 40},
        {"uav": 2, "brick": 2, "start_s": 40}
    ]"#;
    let xyz = file(
        "metric-xyz.json",
        &format!(r#"{{"model": "cmcp", "metric": "xyz", "uavs": 3, {rows}}}"#),
    );
    let plain = file(
        "metric-none.json",
        &format!(r#"{{"model": "cmcp", "uavs": 3, {rows}}}"#),
    );
    assert_valid(
        &mason(&["check", "schedule", &wall, &xyz]),
        &["model cmcp (distance xyz)"],
    );
    assert_broken(
        &mason(&["check", "schedule", &wall, &xyz, "--metric", "xy"]),
        "Concurrent",
        &["0.796 m apart (xy)"],
    );
    assert_broken(
        &mason(&["check", "schedule", &wall, &plain]),
        "Concurrent",
        &["0.796 m apart (xy)"],
    );
    assert_input_error(
        &mason(&["check", "schedule", &wall, &plain, "--metric", "3d"]),
        &["--metric 3d", "xy", "xyz"],
    );
    // plan says which metric it used, and plans around the rule it was given.
    for (metric, overlap) in [("xy", false), ("xyz", true)] {
        let json = output_of(&[
            "plan",
            &wall,
            "--objective",
            "makespan",
            "--model",
            "cmcp",
            "--metric",
            metric,
            "--json",
        ]);
        let v: Value = serde_json::from_str(&json).unwrap();
        assert_eq!(v["metric"], metric);
        assert_eq!(v["team_model"]["concurrency"]["metric"], metric);
        // Under xy the three conflict pairwise (120 s); under xyz 1 and 2 place together.
        let makespan = v["makespan_s"].as_f64().unwrap();
        assert_eq!(makespan, if overlap { 80.0 } else { 120.0 }, "{metric}");
        let path = file(&format!("metric-plan-{metric}.json"), &json);
        assert_valid(&mason(&["check", "schedule", &wall, &path]), &[metric]);
    }
}
