//! Issue #15: no input may crash, hang or exhaust the machine. One test per item of the
//! issue's list, each with the exact command; every bad input gets exit 2 and one line.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::{data, mason, stderr, stdout};

/// A fresh scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mason-harden-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, contents: impl AsRef<[u8]>) -> String {
    let p = dir.join(name);
    std::fs::write(&p, contents).unwrap();
    p.to_string_lossy().into_owned()
}

/// Exit 2, one short line on stderr containing every `needle`, and no panic.
fn assert_input_error(o: &Output, needles: &[&str]) {
    common::assert_input_error(o, needles);
    let err = stderr(o);
    assert!(err.len() < 400, "short: {err}");
}

#[test]
fn time_limit_1e300_is_refused_in_plan_demo_bench_and_crew() {
    let dir = scratch("time-limit");
    let out = dir.join("demo-out").to_string_lossy().into_owned();
    for args in [
        vec![
            "plan",
            "builtin:thesis-2x5",
            "--planner",
            "brute",
            "--time-limit",
            "1e300",
        ],
        vec!["plan", "builtin:thesis-2x5", "--time-limit", "1e20"],
        vec!["demo", "--out", &out, "--time-limit", "1e300"],
        vec!["bench", "thesis", "--time-limit", "1e300"],
        vec![
            "crew",
            &data("crew-room.map"),
            "--scen",
            &data("crew-room.scen"),
            "--time-limit",
            "1e300",
        ],
        vec![
            "plan",
            "builtin:thesis-2x5",
            "--objective",
            "makespan",
            "--time-limit",
            "inf",
        ],
    ] {
        let o = mason(&args);
        assert_input_error(&o, &["--time-limit"]);
    }
    assert!(!Path::new(&out).exists());
}

#[test]
fn negative_and_nan_numbers_get_a_correct_message() {
    let o = mason(&["plan", "builtin:thesis-2x5", "--time-limit", "-1"]);
    assert_input_error(&o, &["--time-limit -1", "positive"]);
    let o = mason(&["plan", "builtin:thesis-2x5", "--time-limit=-1"]);
    assert_input_error(&o, &["positive"]);
    let o = mason(&["plan", "builtin:thesis-2x5", "--time-limit", "NaN"]);
    assert_input_error(&o, &["positive"]);
    for args in [
        ["simulate", "builtin:thesis-2x5", "--seed", "-1"],
        ["simulate", "builtin:thesis-2x5", "--runs", "-5"],
        ["simulate", "builtin:thesis-2x5", "--uavs", "-3"],
    ] {
        let o = mason(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(!err.contains("-- -"), "no wrong tip: {err}");
        assert!(err.contains("invalid value '-"), "{err}");
    }
    let o = mason(&["simulate", "builtin:thesis-2x5", "--grasp-fail", "-0.5"]);
    assert_input_error(&o, &["grasp_fail", "probability"]);
}

#[test]
fn runs_0_is_refused_everywhere() {
    for args in [
        vec!["simulate", "builtin:thesis-2x5", "--runs", "0"],
        vec!["bench", "missions", "--runs", "0"],
        vec!["bench", "planning", "--runs", "0"],
        vec!["bench", "thesis-mission", "--runs", "0"],
    ] {
        assert_input_error(&mason(&args), &["--runs must be at least 1"]);
    }
}

#[test]
fn seeds_that_would_run_past_u64_max_are_refused() {
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--seed",
        "18446744073709551615",
        "--runs",
        "2",
    ]);
    assert_input_error(&o, &["--seed", "past"]);
}

#[test]
fn dev_zero_folders_and_fifos_are_refused_without_reading() {
    let dir = scratch("special-files");
    let folder = dir.to_string_lossy().into_owned();
    assert_input_error(
        &mason(&["plan", "/dev/zero"]),
        &["/dev/zero", "not a regular file"],
    );
    assert_input_error(
        &mason(&["plan", "builtin:thesis-2x5", "--model", "/dev/zero"]),
        &["/dev/zero", "not a regular file"],
    );
    assert_input_error(&mason(&["plan", &folder]), &["a folder"]);
    assert_input_error(
        &mason(&["generate", "scen", "--map", "/dev/zero", "--agents", "3"]),
        &["/dev/zero", "not a regular file"],
    );
    let fifo = dir.join("wall.fifo");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let f = fifo.to_string_lossy().into_owned();
        assert_input_error(&mason(&["plan", &f]), &["wall.fifo", "not a regular file"]);
        assert_input_error(
            &mason(&["crew", &f, "--scen", &data("crew-room.scen")]),
            &["wall.fifo", "not a regular file"],
        );
        assert_input_error(
            &mason(&["simulate", "builtin:thesis-2x5", "--faults", &f]),
            &["wall.fifo", "not a regular file"],
        );
        assert_input_error(
            &mason(&["generate", "scen", "--map", &f, "--agents", "3"]),
            &["wall.fifo", "not a regular file"],
        );
    }
}

#[test]
fn a_file_over_the_size_limit_is_refused_before_it_is_read() {
    let dir = scratch("big-file");
    let p = dir.join("huge.txt");
    let f = std::fs::File::create(&p).unwrap();
    f.set_len(65 << 20).unwrap(); // sparse: nothing is written
    let o = mason(&["plan", &p.to_string_lossy()]);
    assert_input_error(&o, &["huge.txt", "larger than 67108864 bytes"]);
    let t = dir.join("huge.toml");
    std::fs::File::create(&t).unwrap().set_len(2 << 20).unwrap();
    let o = mason(&[
        "plan",
        "builtin:thesis-2x5",
        "--model",
        &t.to_string_lossy(),
    ]);
    assert_input_error(&o, &["huge.toml", "larger than 1048576 bytes"]);
}

#[test]
fn a_ten_megabyte_wall_line_is_refused_and_not_echoed() {
    let dir = scratch("long-line");
    let p = write(&dir, "long.txt", "R".repeat(10_000_000));
    let o = mason(&["plan", &p]);
    assert_input_error(&o, &["long.txt:1", "MAX_LINE_CHARS"]);
}

#[test]
fn too_many_layers_and_bricks_are_refused() {
    let dir = scratch("many");
    let p = write(&dir, "tall.txt", "R\n".repeat(1001));
    assert_input_error(
        &mason(&["wall", "show", &p]),
        &["tall.txt:1001", "MAX_LAYERS"],
    );
    let p = write(&dir, "many.txt", "R".repeat(5000) + "\n");
    let o = mason(&["wall", "show", &p, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_long_bad_token_is_cut_in_the_message() {
    let dir = scratch("long-token");
    let p = write(&dir, "tok.txt", format!("R X{}\n", "Z".repeat(5000)));
    let o = mason(&["plan", &p]);
    assert_input_error(&o, &["tok.txt:1", "unknown token", "(5001 characters)"]);
}

#[test]
fn a_byte_order_mark_is_accepted() {
    let dir = scratch("bom");
    let plain = write(&dir, "plain.txt", "R G\nB\n");
    let bom = write(&dir, "bom.txt", "\u{feff}R G\nB\n");
    let a = mason(&["plan", &plain, "--json"]);
    let b = mason(&["plan", &bom, "--json"]);
    assert!(b.status.success(), "{}", stderr(&b));
    let cost = |o: &Output| {
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["total_cost"].as_f64().unwrap()
    };
    assert_eq!(cost(&a), cost(&b));
    let cmcp = write(
        &dir,
        "bom-cmcp.txt",
        "\u{feff}1 2 0 0 0.1 0\n2 1 0 0 0.3 0\n",
    );
    assert!(mason(&["wall", "show", &cmcp]).status.success());
    let model = write(&dir, "bom-model.toml", "\u{feff}alpha = 0.2\n");
    let o = mason(&["plan", &plain, "--model", &model]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A BOM inside a line is still an error, and it is shown escaped.
    let mid = write(&dir, "mid.txt", "R \u{feff}G\n");
    assert_input_error(&mason(&["plan", &mid]), &["mid.txt:1", "\\u{feff}"]);
}

#[test]
fn cmcp_coordinates_of_1e308_are_refused() {
    let dir = scratch("cmcp-far");
    for (x, y) in [
        ("1e308", "0"),
        ("-1e308", "0"),
        ("0", "1e308"),
        ("0", "1e6"),
    ] {
        let p = write(&dir, "far.txt", format!("1 1 {x} {y} 0.1 0\n"));
        let svg = dir.join("far.svg");
        let o = mason(&[
            "wall",
            "show",
            &p,
            "--format",
            "cmcp",
            "--svg",
            &svg.to_string_lossy(),
        ]);
        assert_input_error(&o, &["far.txt:1", "MAX_COORD_M"]);
        assert!(!svg.exists());
    }
}

#[test]
fn map_and_image_limits_are_checked_from_the_header() {
    let dir = scratch("map-limits");
    let map = write(
        &dir,
        "big.map",
        "type octile\nheight 32768\nwidth 32768\nmap\n",
    );
    let scen = write(&dir, "big.scen", "version 1\n");
    let o = mason(&["crew", &map, "--scen", &scen]);
    assert_input_error(&o, &["big.map", "MAX_CELLS"]);
    // A PNG header claiming 10 000 × 10 000 pixels, with no pixel data behind it: more than a
    // one-pixel-per-cell map may have (MAX_CELLS) and than a photograph (aerial::MAX_PIXELS).
    let png = write(&dir, "big.png", png_header_only(10_000, 10_000));
    let o = mason(&["crew", "--image", &png]);
    assert_input_error(&o, &["big.png", "aerial::MAX_PIXELS"]);
    let o = mason(&["crew", "--image", &png, "--grid", "10x10"]);
    assert_input_error(&o, &["big.png", "aerial::MAX_PIXELS"]);
}

#[test]
fn a_birdseye_image_with_too_many_robots_is_refused() {
    let dir = scratch("noise");
    let (w, h) = (300u32, 150u32);
    let img = image::RgbImage::from_fn(w, h, |x, y| {
        if x % 2 == 0 && y % 2 == 0 {
            image::Rgb([255, 0, 0])
        } else {
            image::Rgb([255, 255, 255])
        }
    });
    let p = dir.join("dots.png");
    img.save(&p).unwrap();
    let o = mason(&["crew", "--image", &p.to_string_lossy()]);
    assert_input_error(&o, &["dots.png", "11250 robots", "MAX_AGENTS"]);
}

#[test]
fn model_values_negative_nan_or_huge_name_the_file_and_key() {
    let dir = scratch("model");
    for (text, key, shown) in [
        ("[red]\ngrasp = -1\n", "red.grasp", "-1"),
        ("[green]\nfly = nan\n", "green.fly", "NaN"),
        ("[blue]\ndrop = 1e308\n", "blue.drop", "1e308"),
        ("kappa = [1.0, -2.0, 1.5]\n", "kappa[1]", "-2"),
    ] {
        let p = write(&dir, "model.toml", text);
        let o = mason(&["plan", "builtin:thesis-2x5", "--model", &p]);
        assert_input_error(&o, &["model.toml", key, shown]);
    }
}

#[test]
fn a_partial_model_table_keeps_the_other_defaults() {
    let dir = scratch("partial-model");
    let p = write(&dir, "model.toml", "[red]\ngrasp = 10\n");
    let o = mason(&["plan", "builtin:thesis-2x5", "--model", &p, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let full = write(
        &dir,
        "full.toml",
        "[red]\ngrasp = 10\nfly = 22.5\ndrop = 8.0\n",
    );
    let f = mason(&["plan", "builtin:thesis-2x5", "--model", &full, "--json"]);
    let cost = |o: &Output| {
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["total_cost"].as_f64().unwrap()
    };
    assert_eq!(cost(&o), cost(&f));
    let d = mason(&["plan", "builtin:thesis-2x5", "--json"]);
    assert!(cost(&o) < cost(&d));
    let bad = write(&dir, "bad.toml", "[red]\ngrap = 10\n");
    let o = mason(&["plan", "builtin:thesis-2x5", "--model", &bad]);
    assert_input_error(&o, &["bad.toml:2", "grap"]);
}

#[test]
fn fault_and_mission_file_errors_name_the_file_and_key() {
    let dir = scratch("faults");
    for (text, needles) in [
        (
            "grasp_fail = 2\n",
            vec!["faults.toml", "grasp_fail", "probability"],
        ),
        (
            "uav_fail = [\"9@3\"]\n",
            vec!["faults.toml", "uav_fail", "9@3"],
        ),
        (
            "uav_fail = [\"x\"]\n",
            vec!["faults.toml", "uav_fail", "U@T"],
        ),
        ("blackout = [\"5-1\"]\n", vec!["faults.toml", "blackout"]),
        ("latency = -1\n", vec!["faults.toml", "latency"]),
    ] {
        let p = write(&dir, "faults.toml", text);
        let o = mason(&["simulate", "builtin:thesis-2x5", "--faults", &p]);
        assert_input_error(&o, &needles);
    }
    for (text, needles) in [
        (
            "max_time_s = 1e300\n",
            vec!["mission.toml", "max_time_s", "1e300"],
        ),
        ("[uav]\nspeed = -2\n", vec!["mission.toml", "uav.speed"]),
        (
            "[faults]\nmsg_loss = 7\n",
            vec!["mission.toml", "faults.msg_loss"],
        ),
        // A heartbeat of 1e-300 s made `--coord auto` spin forever.
        (
            "[coord]\nheartbeat_s = 1e-300\n",
            vec!["mission.toml", "coord.heartbeat_s"],
        ),
    ] {
        let p = write(&dir, "mission.toml", text);
        let o = mason(&["simulate", "builtin:thesis-2x5", "--mission", &p]);
        assert_input_error(&o, &needles);
    }
}

#[test]
fn a_mission_time_of_1e300_is_refused_so_the_mission_ends() {
    let dir = scratch("max-time");
    let p = write(
        &dir,
        "m.toml",
        "max_time_s = 1e300\n[faults]\ngrasp_fail = 0.99\n",
    );
    let o = mason(&["simulate", "builtin:thesis-2x5", "--mission", &p]);
    assert_input_error(&o, &["max_time_s", "1e6"]);
    let p = write(&dir, "m.toml", "max_time_s = 1000000\n");
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--mission",
        &p,
        "--uav-fail",
        "0@0",
        "--uav-fail",
        "1@0",
        "--uav-fail",
        "2@0",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

/// Issue #32: zero durations make events without progress. The mission stops at its event
/// cap (exit 2, one line), once or in a batch, instead of allocating gigabytes or never ending.
#[test]
fn a_mission_with_zero_durations_stops_at_its_event_cap() {
    let dir = scratch("zero-times");
    let p = write(
        &dir,
        "zero.toml",
        "max_time_s = 1000000.0\n[uav]\nspeed = 1e9\ncheck_s = 0.0\ntakeoff_s = 0.0\n\
         land_s = 0.0\ndetect_s = 0.0\nabove_s = 0.0\nzone_transit_s = 0.0\n\
         [faults]\ngrasp_fail = 0.999\ndetect_fail = 0.999\n",
    );
    for extra in [&[][..], &["--json"][..], &["--runs", "4"][..]] {
        let mut args = vec!["simulate", "builtin:thesis-2x5", "--mission", &p];
        args.extend_from_slice(extra);
        let o = mason(&args);
        assert_input_error(&o, &["event", "cap", "too short"]);
        assert!(o.stdout.is_empty(), "{extra:?}: nothing printed");
    }
}

#[test]
fn when_html_cannot_be_written_the_svg_is_not_left_behind() {
    let dir = scratch("outputs");
    let svg = dir.join("gantt.svg");
    let html = dir.join("no-such-folder").join("replay.html");
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--svg",
        &svg.to_string_lossy(),
        "--html",
        &html.to_string_lossy(),
    ]);
    assert_input_error(&o, &["no-such-folder", "does not exist"]);
    assert!(!svg.exists());
    assert!(!dir.join("no-such-folder").exists(), "no folder is created");
    // An output that is a folder is refused too, before any work.
    let o = mason(&[
        "plan",
        "builtin:thesis-2x5",
        "--svg",
        &svg.to_string_lossy(),
        "--html",
        &dir.to_string_lossy(),
    ]);
    assert_input_error(&o, &["is a folder"]);
    assert!(!svg.exists());
    // Success leaves exactly the outputs, no temporary files.
    let html = dir.join("replay.html");
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--svg",
        &svg.to_string_lossy(),
        "--html",
        &html.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["gantt.svg", "replay.html"]);
}

#[test]
fn readme_matches_the_binary_on_the_prm_default() {
    let help = String::from_utf8(mason(&["crew", "--help"]).stdout).unwrap();
    assert!(help.contains("[default: 2000]"), "{help}");
    let readme =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    assert!(readme.contains("--samples 2000"));
    assert!(!readme.contains("--samples 4000"));
    let o = mason(&[
        "crew",
        &data("crew-room.map"),
        "--scen",
        &data("crew-room.scen"),
        "--samples",
        "2000000",
    ]);
    assert_input_error(&o, &["--samples"]);
}

#[test]
fn monte_carlo_summaries_are_deterministic() {
    let run = || {
        mason(&[
            "simulate",
            "builtin:thesis-2x5",
            "--runs",
            "300",
            "--seed",
            "7",
            "--grasp-fail",
            "0.3",
            "--json",
        ])
        .stdout
    };
    assert_eq!(run(), run());
}

/// A PNG for a w×h RGB image whose IDAT chunk is empty: a valid header, no pixels.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    for chunk in [ihdr, b"IDAT".to_vec(), b"IEND".to_vec()] {
        out.extend_from_slice(&(chunk.len() as u32 - 4).to_be_bytes());
        out.extend_from_slice(&chunk);
        out.extend_from_slice(&crc32(&chunk).to_be_bytes());
    }
    out
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn a_noisy_birdseye_image_over_robots_times_cells_is_refused() {
    let dir = scratch("agent-cells");
    let img = image::RgbImage::from_fn(1200, 1200, |x, y| match (x % 50, y % 50) {
        (0, 0) if x < 600 => image::Rgb([255, 0, 0]),
        (0, 0) => image::Rgb([0, 255, 0]),
        _ => image::Rgb([255, 255, 255]),
    });
    let p = dir.join("sparse.png");
    img.save(&p).unwrap();
    let o = mason(&["crew", "--image", &p.to_string_lossy()]);
    assert_input_error(&o, &["sparse.png", "288 robots", "MAX_AGENT_CELLS"]);
}

#[test]
fn brute_on_a_deep_wall_stops_at_its_budget_without_a_crash() {
    // 1000 layers of 100 bricks: 100 000 bricks, as deep as the recursive search that
    // overflowed the stack. Brute force cannot finish it: the search stops at its budget and
    // says so (a timeout with its best order, or no complete order), with no crash.
    let dir = scratch("deep-brute");
    let p = write(
        &dir,
        "deep.txt",
        format!("{}\n", "R".repeat(100)).repeat(1000),
    );
    let o = mason(&["plan", &p, "--planner", "brute", "--time-limit", "1"]);
    let err = stderr(&o);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{err}");
    assert!(
        !err.contains("panicked") && !err.contains("overflow"),
        "{err}"
    );
    if o.status.code() == Some(0) {
        assert!(stdout(&o).contains("timeout"), "{}", stdout(&o));
    } else {
        assert!(err.contains("within the budget"), "{err}");
    }
}

#[test]
fn a_huge_scenario_or_map_line_is_refused_without_being_split_or_echoed() {
    let dir = scratch("scen-line");
    let scen = write(
        &dir,
        "long.scen",
        format!("version 1\n{}\n", "7 ".repeat(3_000_000)),
    );
    let o = mason(&["crew", &data("crew-room.map"), "--scen", &scen]);
    assert_input_error(&o, &["long.scen:2", "found more"]);
    let map = write(
        &dir,
        "long.map",
        format!(
            "type octile\nheight 1\nwidth 2\nmap\n{}\n",
            ".".repeat(5_000_000)
        ),
    );
    let o = mason(&["crew", &map, "--scen", &scen]);
    assert_input_error(&o, &["long.map:5", "5000000 cells"]);
    let map = write(
        &dir,
        "bad.map",
        format!("type octile\nheight {}\n", "9".repeat(500)),
    );
    let o = mason(&["crew", &map, "--scen", &scen]);
    assert_input_error(&o, &["bad.map:2", "(500 characters)"]);
}

/// Runs `args` and asserts that, when the whole command took over 10 % more than `limit`
/// seconds, it said so on stderr. Starting a process is not the command's time: it is
/// measured on `mason --version` under the same load, and allowed for three times over.
fn assert_overrun_reported(args: &[&str], limit: f64) {
    let started = std::time::Instant::now();
    let _ = mason(&["--version"]);
    let spawn = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let o = mason(args);
    let took = started.elapsed().as_secs_f64();
    let err = stderr(&o);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{err}");
    if took > 1.1 * limit + 3.0 * spawn + 0.05 {
        assert!(
            err.contains("overrun") && err.contains(&format!("--time-limit {limit} s")),
            "took {took:.2} s under --time-limit {limit}, no overrun reported: {err}"
        );
    }
}

#[test]
fn crew_and_team_schedules_keep_their_time_limit_or_report_the_overrun() {
    // A debug build reads, solves, checks and prints these well past 10 ms.
    assert_overrun_reported(
        &[
            "crew",
            &data("crew-room.map"),
            "--scen",
            &data("crew-room.scen"),
            "--resolve",
            "lacam",
            "--time-limit",
            "0.01",
        ],
        0.01,
    );
    assert_overrun_reported(
        &[
            "plan",
            "builtin:mbzirc",
            "--objective",
            "makespan",
            "--time-limit",
            "0.01",
        ],
        0.01,
    );
}

#[test]
fn a_damaged_png_palette_is_refused_by_both_image_readers() {
    // A palette of 5 bytes (not whole colours), every CRC right: the png crate panicked on it
    // when expanding the palette (found by fuzzing the wall reader; the crew's reader, then on
    // the image crate, panicked too).
    let p = data("palette-5-bytes.png");
    for args in [vec!["wall", "show", &p], vec!["crew", "--image", &p]] {
        let o = mason(&args);
        assert_input_error(&o, &["palette-5-bytes.png", "PLTE) is 5 bytes"]);
    }
}

/// #32: an output that is a device is written in place, a FIFO is refused, and neither is ever
/// replaced by a regular file (atomic writes rename, which would replace them).
#[cfg(unix)]
#[test]
fn outputs_never_replace_a_device_or_a_fifo() {
    use std::os::unix::fs::FileTypeExt;
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--mcap",
        "/dev/null",
        "--svg",
        "/dev/null",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let t = std::fs::metadata("/dev/null").unwrap().file_type();
    assert!(t.is_char_device(), "/dev/null is still a device");
    let dir = scratch("fifo-out");
    let fifo = dir.join("out.svg");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let path = fifo.to_string_lossy().into_owned();
        assert_input_error(
            &mason(&["plan", "builtin:thesis-2x5", "--svg", &path]),
            &["is a FIFO", "never replaced"],
        );
        assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    }
    #[cfg(target_os = "linux")]
    assert_input_error(
        &mason(&["simulate", "builtin:thesis-2x5", "--mcap", "/proc/version"]),
        &["/proc/version", "cannot be written"],
    );
}

/// #32: a slot too short for any brick says so in words, and a kilobytes-long team-model base
/// is cut in the message.
#[test]
fn a_tiny_slot_and_a_huge_base_get_short_clear_messages() {
    assert_input_error(
        &mason(&[
            "simulate",
            "builtin:thesis-2x5",
            "--coord",
            "windows",
            "--slot",
            "5e-324",
        ]),
        &["slot", "too small"],
    );
    let dir = scratch("huge-base");
    let model = write(
        &dir,
        "team.toml",
        format!("base = \"{}\"\n", "x".repeat(5000)),
    );
    let o = mason(&[
        "plan",
        "builtin:thesis-2x5",
        "--objective",
        "makespan",
        "--model",
        &model,
    ]);
    assert_input_error(&o, &["team.toml", "(5000 characters)"]);
    assert!(stderr(&o).len() < 400, "{}", stderr(&o));
}

/// #32: a tiny hazard keeps the expected reward under its bound, and a placing phase shorter
/// than a millisecond (which the validator's tolerance could not tell from none) is refused.
#[test]
fn bounds_hold_at_a_tiny_hazard_and_near_zero_durations_are_refused() {
    let o = mason(&[
        "plan",
        "builtin:thesis-2x5",
        "--objective",
        "expected",
        "--uav-hazard",
        "1e-18",
        "--budget",
        "300",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let (e, b) = (
        v["expected_reward"].as_f64().unwrap(),
        v["bound"].as_f64().unwrap(),
    );
    assert!(e <= b + 1e-9, "expected {e} over its bound {b}");
    let dir = scratch("tiny-place");
    let model = write(
        &dir,
        "team.toml",
        "base = \"cmcp\"\n[red]\nplace_s = 1e-10\n",
    );
    assert_input_error(
        &mason(&[
            "plan",
            "builtin:thesis-2x5",
            "--objective",
            "makespan",
            "--model",
            &model,
        ]),
        &["team.toml", "red.place_s", "0.001"],
    );
}

/// #32: a CMCP file of 3 000 bricks in one spot (4.5 million overlapping pairs) is refused at
/// once by `plan` and `wall show`, naming the limit, instead of planning or listing them all.
#[test]
fn thousands_of_piled_bricks_are_refused_by_name() {
    let dir = scratch("piled");
    let text: String = (1..=3000).map(|i| format!("{i} 1 0 0 0.1 0\n")).collect();
    let wall = write(&dir, "piled.txt", text);
    for args in [vec!["plan", &wall], vec!["wall", "show", &wall]] {
        assert_input_error(&mason(&args), &["piled.txt", "MAX_PAIRS"]);
    }
}

/// #32: a model value that makes the team model of `simulate --objective` invalid names the
/// `--model` file it came from, and arenas of thousands of points are refused.
#[test]
fn a_bad_team_model_from_a_cost_model_names_the_file() {
    let dir = scratch("slow-model");
    // κ₂ · drop = 10⁸ s of placing: a valid cost model, an invalid team model.
    let model = write(
        &dir,
        "slow.toml",
        "kappa = [1.0, 1000.0, 1000.0]\n[red]\ndrop = 100000.0\n",
    );
    let o = mason(&[
        "simulate",
        "builtin:thesis-2x5",
        "--objective",
        "makespan",
        "--model",
        &model,
    ]);
    assert_input_error(&o, &["slow.toml", "red.place_s"]);
    let starts: String = (0..20_000)
        .map(|_| "[[arena.uav_starts]]\nx = 1.0\ny = 1.0\n")
        .collect();
    let mission = write(&dir, "arena.toml", starts);
    assert_input_error(
        &mason(&["simulate", "builtin:thesis-2x5", "--mission", &mission]),
        &["arena.toml", "MAX_ARENA_POINTS"],
    );
}

#[test]
fn a_closed_pipe_on_stdout_ends_quietly_with_141() {
    // About 200 kB of wall text, more than a pipe holds; the reader stops after 10 bytes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_mason"))
        .args(["generate", "wall", "--bricks", "100000", "--levels", "50"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = child.stdout.take().unwrap();
    let mut first = [0u8; 10];
    std::io::Read::read_exact(&mut out, &mut first).unwrap();
    drop(out);
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(141), "{}", stderr(&o));
    assert!(stderr(&o).is_empty(), "quiet: {}", stderr(&o));
}
