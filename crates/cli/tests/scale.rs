//! `mason generate structure`: generated CMCP walls, Ls and towers of a few storeys read
//! strictly, plan whole with a team, and pass `mason check schedule`; bad options are refused.

use serde_json::Value;

mod common;
use common::{assert_input_error, mason, stderr, stdout};

fn scratch(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("mason-scale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn generated_structures_plan_whole_near_their_bound_and_pass_the_check() {
    for shape in ["wall", "l", "tower"] {
        let args = [
            "generate",
            "structure",
            "--shape",
            shape,
            "--bricks",
            "1200",
            "--levels",
            "6",
            "--storeys",
            "2",
            "--seed",
            "3",
        ];
        let g = mason(&args);
        assert!(g.status.success(), "{}", stderr(&g));
        assert_eq!(stdout(&g), stdout(&mason(&args)), "same seed, same text");
        let wall = scratch(&format!("{shape}.txt"), &stdout(&g));
        let o = mason(&[
            "plan",
            &wall,
            "--strict",
            "--objective",
            "makespan",
            "--uavs",
            "12",
            "--model",
            "cmcp",
            "--time-limit",
            "2",
            "--json",
        ]);
        assert!(o.status.success(), "{shape}: {}", stderr(&o));
        let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
        let total = v["bricks_total"].as_u64().unwrap();
        assert!((900..=1600).contains(&total), "{shape}: {total} bricks");
        assert_eq!(v["bricks_placed"], v["bricks_total"]);
        let (makespan, bound) = (
            v["makespan_s"].as_f64().unwrap(),
            v["bound"].as_f64().unwrap(),
        );
        assert!(
            makespan <= bound * 1.03,
            "{shape}: {makespan} s against a bound of {bound} s"
        );
        let plan = scratch(&format!("{shape}.json"), &stdout(&o));
        let c = mason(&["check", "schedule", &wall, &plan]);
        assert!(c.status.success(), "{shape}: {}", stderr(&c));
    }
}

#[test]
fn bad_structure_options_are_refused() {
    let run = |extra: &[&str]| {
        let mut args = vec!["generate", "structure", "--bricks", "100", "--levels", "4"];
        args.extend_from_slice(extra);
        mason(&args)
    };
    assert_input_error(
        &run(&["--shape", "dome"]),
        &["--shape dome", "wall, l or tower"],
    );
    assert_input_error(&run(&["--storeys", "5"]), &["--storeys 5", "1..=4"]);
    assert_input_error(&run(&["--storeys", "0"]), &["--storeys 0"]);
}
