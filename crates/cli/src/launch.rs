//! `mason launch`: one `mason agent` process per UAV on this machine, over Zenoh on
//! 127.0.0.1. It kills (`SIGKILL`) and restarts agents at given mission times, waits for all
//! of them, merges their trace files into one trace (with the events of the agents it killed),
//! checks it with [`mason_mission::check_trace`], and prints a summary.
//!
//! Exit codes: 0 the wall is finished and the merged trace passes `check_trace`; 1 it passes
//! but the wall is unfinished; 2 bad input; 3 the merged trace fails `check_trace` (or a trace
//! file cannot be read); 130 interrupted.

use crate::agent_cmd::{parse_at, TeamArgs, DEFAULT_PREFIX};
use crate::fail::{input_error, CliResult, Failure};
use crate::transport::unix_now;
use mason_mission::state::EventRecord;
use mason_mission::team::killed_events;
use mason_mission::{check_trace, CommMode, Event, EventKind};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// `mason launch`'s options.
#[derive(clap::Args)]
pub struct LaunchArgs {
    #[command(flatten)]
    pub team: TeamArgs,
    /// Kill UAV U's agent (SIGKILL) at mission time T, as U@T; repeatable
    #[arg(long)]
    pub kill: Vec<String>,
    /// Start UAV U's agent again at mission time T (after a --kill), as U@T; repeatable
    #[arg(long)]
    pub restart: Vec<String>,
    /// Output folder: the agents' traces and logs, and the merged trace (trace.json)
    #[arg(long, default_value = "mason-out/launch")]
    pub out: PathBuf,
    /// Agent U listens on tcp/127.0.0.1:P+U (default: free ports)
    #[arg(long, allow_negative_numbers = true)]
    pub base_port: Option<u32>,
    /// The mission id (default: a fresh one)
    #[arg(long)]
    pub mission: Option<String>,
    /// Key prefix (default mason)
    #[arg(long)]
    pub prefix: Option<String>,
    /// Wall seconds between the launch and mission time 0 (the agents open their sessions)
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub lead: f64,
}

/// Exit code when the merged trace fails `check_trace`.
pub const UNSAFE: u8 = 3;

/// One agent process.
struct Run {
    uav: usize,
    incarnation: u64,
    child: Option<Child>,
    trace: PathBuf,
    log: PathBuf,
    exit: Option<String>,
    killed_at: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Action {
    Kill,
    Restart,
}

fn free_port() -> CliResult<u16> {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .map_err(|e| input_error(format!("cannot find a free port on 127.0.0.1: {e}")))
}

/// The kills and restarts, by time; each restart follows a kill of its UAV.
fn schedule(a: &LaunchArgs) -> CliResult<Vec<(f64, usize, Action)>> {
    let n = a.team.uavs;
    let mut plan = Vec::new();
    for s in &a.kill {
        let (u, t) = parse_at("--kill", s, n)?;
        plan.push((t, u, Action::Kill));
    }
    for s in &a.restart {
        let (u, t) = parse_at("--restart", s, n)?;
        plan.push((t, u, Action::Restart));
    }
    plan.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut down = vec![false; n];
    for (t, u, what) in &plan {
        match what {
            Action::Kill if down[*u] => {
                return Err(input_error(format!(
                    "--kill {u}@{t}: UAV {u} is already killed then (add a --restart before)"
                )))
            }
            Action::Restart if !down[*u] => {
                return Err(input_error(format!(
                "--restart {u}@{t}: UAV {u} is not killed before (add a --kill {u}@T with T < {t})"
            )))
            }
            Action::Kill => down[*u] = true,
            Action::Restart => down[*u] = false,
        }
    }
    Ok(plan)
}

/// `mason launch`.
pub fn run(a: LaunchArgs, quiet: bool) -> CliResult<()> {
    if !cfg!(feature = "zenoh") {
        return Err(input_error(
            "mason launch needs the zenoh feature: cargo build --release --features zenoh",
        ));
    }
    let wall_started = Instant::now();
    let team = a.team.resolve()?;
    let plan = schedule(&a)?;
    let n = team.config.uavs;
    if !(a.lead.is_finite() && (0.0..=60.0).contains(&a.lead)) {
        return Err(input_error(format!(
            "--lead {}: expected wall seconds in [0, 60]",
            a.lead
        )));
    }
    let ports: Vec<u16> = match a.base_port {
        Some(p) if p >= 1 && p as usize + n - 1 <= 65535 => {
            (0..n).map(|u| (p as usize + u) as u16).collect()
        }
        Some(p) => {
            return Err(input_error(format!(
                "--base-port {p}: ports {p}..{} must lie in 1..65535",
                p as usize + n - 1
            )))
        }
        None => (0..n).map(|_| free_port()).collect::<CliResult<_>>()?,
    };
    let mission = a
        .mission
        .clone()
        .unwrap_or_else(|| format!("launch-{}-{}", unix_now() as u64, std::process::id()));
    std::fs::create_dir_all(&a.out)
        .map_err(|e| input_error(format!("--out {}: {e}", a.out.display())))?;
    // The agents' cameras read every trace in --out: an earlier launch's must go.
    if let Ok(entries) = std::fs::read_dir(&a.out) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with("uav-") && (name.ends_with(".jsonl") || name.ends_with(".log")) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    let exe = std::env::current_exe()
        .map_err(|e| input_error(format!("cannot find the mason binary: {e}")))?;
    let start_at = unix_now() + a.lead;
    let endpoint = |u: usize| format!("tcp/127.0.0.1:{}", ports[u]);
    let team_args = a.team.to_args();
    let spawn = |uav: usize, incarnation: u64, earlier: &[PathBuf]| -> CliResult<Run> {
        let trace = a.out.join(format!("uav-{uav}-{incarnation}.jsonl"));
        let log_path = a.out.join(format!("uav-{uav}-{incarnation}.log"));
        let log = std::fs::File::create(&log_path)
            .map_err(|e| input_error(format!("{}: {e}", log_path.display())))?;
        let err = log
            .try_clone()
            .map_err(|e| input_error(format!("{}: {e}", log_path.display())))?;
        let mut cmd = Command::new(&exe);
        cmd.arg("agent").args(&team_args);
        cmd.args(["--uav", &uav.to_string(), "--mission", &mission]);
        cmd.args(["--start-at", &format!("{start_at:.6}")]);
        cmd.args(["--incarnation", &incarnation.to_string()]);
        cmd.args(["--listen", &endpoint(uav)]);
        for v in (0..n).filter(|&v| v != uav) {
            cmd.args(["--connect", &endpoint(v)]);
        }
        if let Some(p) = &a.prefix {
            cmd.args(["--prefix", p]);
        }
        cmd.arg("--trace").arg(&trace);
        let mcap = a.out.join(format!("uav-{uav}-{incarnation}.mcap"));
        cmd.arg("--mcap").arg(&mcap);
        cmd.arg("--world").arg(&a.out);
        for p in earlier {
            cmd.arg("--remember").arg(p);
        }
        cmd.stdin(Stdio::null()).stdout(log).stderr(err);
        let child = cmd
            .spawn()
            .map_err(|e| input_error(format!("cannot start {}: {e}", exe.display())))?;
        Ok(Run {
            uav,
            incarnation,
            child: Some(child),
            trace,
            log: log_path,
            exit: None,
            killed_at: None,
        })
    };
    let mut runs: Vec<Run> = (0..n).map(|u| spawn(u, 1, &[])).collect::<CliResult<_>>()?;
    if !quiet {
        let eps: Vec<String> = (0..n).map(endpoint).collect();
        eprintln!(
            "mason launch: mission {mission}, {n} agents on {}, key {}/{mission}/UAV/KIND, speed {}",
            eps.join(" "),
            a.prefix.as_deref().unwrap_or(DEFAULT_PREFIX),
            team.speed
        );
    }
    let interrupted = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    #[cfg(feature = "zenoh")]
    {
        let flag = interrupted.clone();
        let _ = ctrlc::set_handler(move || flag.store(true, std::sync::atomic::Ordering::Relaxed));
    }
    let mission_now = || (unix_now() - start_at) * team.speed;
    // Past max_time_s every agent stops by itself; give it a few wall seconds more.
    let give_up = start_at + team.config.max_time_s / team.speed + 10.0;
    let mut next = 0;
    let mut timed_out = false;
    loop {
        let now = mission_now();
        while next < plan.len() && plan[next].0 <= now {
            let (_, u, what) = plan[next];
            next += 1;
            match what {
                Action::Kill => {
                    if let Some(r) = runs
                        .iter_mut()
                        .rev()
                        .find(|r| r.uav == u && r.child.is_some())
                    {
                        let mut child = r.child.take().expect("running");
                        let _ = child.kill();
                        let status = child.wait();
                        let at = mission_now();
                        r.killed_at = Some(append_death(&r.trace, u, at)?);
                        r.exit = Some(match status {
                            Ok(s) if s.code().is_some() => {
                                format!("exited {} before the kill", s.code().unwrap_or(-1))
                            }
                            _ => "killed".into(),
                        });
                    }
                }
                Action::Restart => {
                    let earlier: Vec<PathBuf> = runs
                        .iter()
                        .filter(|r| r.uav == u)
                        .map(|r| r.trace.clone())
                        .collect();
                    let inc = 1 + earlier.len() as u64;
                    runs.push(spawn(u, inc, &earlier)?);
                }
            }
        }
        for r in runs.iter_mut() {
            if let Some(c) = r.child.as_mut() {
                if let Ok(Some(status)) = c.try_wait() {
                    r.exit = Some(match status.code() {
                        Some(code) => code.to_string(),
                        None => format!("{status}"),
                    });
                    r.child = None;
                }
            }
        }
        let running = runs.iter().any(|r| r.child.is_some());
        if !running && next >= plan.len() {
            break;
        }
        let stop = interrupted.load(std::sync::atomic::Ordering::Relaxed);
        if stop || unix_now() > give_up {
            timed_out = !stop;
            for r in runs.iter_mut() {
                if let Some(mut c) = r.child.take() {
                    let _ = c.kill();
                    let _ = c.wait();
                    r.exit = Some(if stop { "interrupted" } else { "timed out" }.into());
                }
            }
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    // An agent that refused its input (which launch checked already) is a bad launch.
    if let Some(r) = runs.iter().find(|r| r.exit.as_deref() == Some("2")) {
        let text = std::fs::read_to_string(&r.log).unwrap_or_default();
        let why = text
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("");
        return Err(input_error(format!(
            "agent of UAV {} refused its input ({}): {why}",
            r.uav,
            r.log.display()
        )));
    }
    let merged = merge(&runs)?;
    let verdict = check_trace(&team.wall, n, &merged);
    let placed = merged
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Place { .. }))
        .count();
    let total = team.wall.len();
    let finished = placed == total;
    let makespan = finished.then(|| {
        merged
            .iter()
            .filter(|e| matches!(e.kind, EventKind::Place { .. }))
            .map(|e| e.t)
            .fold(0.0, f64::max)
    });
    let end = merged.iter().map(|e| e.t).fold(0.0, f64::max);
    let switches = |mode| {
        merged
            .iter()
            .filter(|e| e.kind == EventKind::Comm { mode })
            .count()
    };
    let wall_s = wall_started.elapsed().as_secs_f64();
    let violation = verdict.as_ref().err().map(|e| e.to_string());
    let agents: Vec<serde_json::Value> = runs
        .iter()
        .map(|r| {
            serde_json::json!({
                "uav": r.uav, "incarnation": r.incarnation,
                "exit": r.exit, "killed_at": r.killed_at,
                "trace": r.trace.file_name().map(|f| f.to_string_lossy().into_owned()),
            })
        })
        .collect();
    let summary = serde_json::json!({
        "bricks_placed": placed, "bricks_total": total, "finished": finished,
        "makespan_s": makespan, "end_s": end,
        "check_trace": violation.clone().unwrap_or_else(|| "passed".into()),
        "to_windows": switches(CommMode::Windows), "to_comm": switches(CommMode::Comm),
        "wall_time_s": wall_s, "timed_out": timed_out,
    });
    let doc = serde_json::json!({
        "wall": team.wall.name(), "uavs": n, "coord": team.coord, "mission": mission,
        "speed": team.speed, "seed": team.seed, "start_at": start_at,
        "endpoints": (0..n).map(endpoint).collect::<Vec<_>>(),
        "order": team.order.iter().map(|b| team.wall.brick(*b).label).collect::<Vec<_>>(),
        "agents": agents, "summary": summary,
        "events": merged.iter().map(|e| crate::sim_cmd::event_json(&team.wall, e)).collect::<Vec<_>>(),
    });
    let out_file = a.out.join("trace.json");
    crate::fail::write_file(
        &out_file,
        serde_json::to_string_pretty(&doc).expect("json").as_bytes(),
    )?;
    println!(
        "{}: {n} agents, coord {}, speed {}, mission {mission}",
        team.wall.name(),
        a.team.coord,
        team.speed
    );
    println!("bricks placed: {placed}/{total}");
    println!(
        "makespan: {}; mission end {}",
        makespan.map_or("-".into(), crate::sim_cmd::clock),
        crate::sim_cmd::clock(end)
    );
    let (w, c) = (switches(CommMode::Windows), switches(CommMode::Comm));
    if w + c > 0 {
        println!("coordination switches: {w} to windows, {c} to comm");
    }
    for r in &runs {
        println!(
            "  UAV {} incarnation {}: {}{}",
            r.uav,
            r.incarnation,
            r.exit.as_deref().unwrap_or("-"),
            r.killed_at
                .map_or(String::new(), |t| format!(" at mission time {t:.1} s"))
        );
    }
    println!(
        "check_trace: {}",
        violation
            .as_deref()
            .unwrap_or("passed (zone, precedence, every brick accounted for)")
    );
    println!(
        "wall time: {wall_s:.1} s; merged trace: {}",
        out_file.display()
    );
    if let Some(v) = violation {
        return Err(Failure {
            code: UNSAFE,
            message: format!("the merged trace fails check_trace: {v}"),
        });
    }
    if interrupted.load(std::sync::atomic::Ordering::Relaxed) {
        return Err(Failure {
            code: crate::agent_cmd::INTERRUPTED,
            message: "interrupted".into(),
        });
    }
    if !finished {
        return Err(crate::fail::no_solution(format!(
            "the wall is unfinished: {placed}/{total} bricks placed"
        )));
    }
    Ok(())
}

/// Reads one agent's trace file. A killed agent may have left a truncated last line: it is
/// dropped. Any other bad line is an error.
fn read_trace(path: &Path, killed: bool) -> CliResult<Vec<Event>> {
    let unreadable = |why: String| Failure {
        code: UNSAFE,
        message: format!("{}: {why}", path.display()),
    };
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        // An agent killed before it opened its trace wrote nothing.
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(unreadable(e.to_string())),
    };
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let mut events = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let last = i + 1 == lines.len();
        let parsed = serde_json::from_str::<EventRecord>(line.trim_end())
            .map_err(|e| e.to_string())
            .and_then(EventRecord::into_event);
        match parsed {
            Ok(e) => events.push(e),
            Err(_) if last && killed && !line.ends_with('\n') => {}
            Err(e) => return Err(unreadable(format!("line {}: {e}", i + 1))),
        }
    }
    Ok(events)
}

/// Every agent's events (a killed agent's file ends with the events of its death), sorted
/// stably by time.
fn merge(runs: &[Run]) -> CliResult<Vec<Event>> {
    let mut all = Vec::new();
    for r in runs {
        all.extend(read_trace(&r.trace, r.killed_at.is_some())?);
    }
    all.sort_by(|a, b| a.t.total_cmp(&b.t));
    Ok(all)
}

/// Completes the trace of an agent killed at mission time `t`: a truncated last line is cut
/// off, and the events of its death (`mission::team::killed_events`: it fails, leaves the
/// zone, loses what it held, is down) are appended at `t`, or at its last event if that is
/// later. The teammates' cameras (`--world`) see the lost brick from then on. Returns the
/// time used.
fn append_death(path: &Path, uav: usize, t: f64) -> CliResult<f64> {
    let fail = |e: std::io::Error| Failure {
        code: UNSAFE,
        message: format!("{}: {e}", path.display()),
    };
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(e) => return Err(fail(e)),
    };
    let complete = text.rfind('\n').map_or(0, |i| i + 1);
    let events = read_trace(path, true)?;
    let t = events.iter().map(|e| e.t).fold(t, f64::max);
    let mut out = text[..complete].to_string();
    for e in killed_events(&events, uav as u32, t) {
        out.push_str(&serde_json::to_string(&e).expect("an event serialises"));
        out.push('\n');
    }
    std::fs::write(path, out).map_err(fail)?;
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_truncated_last_line_of_a_killed_agent_is_dropped() {
        let dir = std::env::temp_dir().join(format!("mason-launch-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.jsonl");
        let good =
            r#"{"t":0.0,"uav":1,"kind":"state","state":"Check","outcome":"start","x":1.0,"y":2.0}"#;
        std::fs::write(&path, format!("{good}\n{{\"t\":1.0,\"uav\"")).unwrap();
        assert_eq!(read_trace(&path, true).unwrap().len(), 1);
        let e = read_trace(&path, false).unwrap_err();
        assert_eq!(e.code, UNSAFE);
        assert!(e.message.contains("line 2"), "{}", e.message);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
