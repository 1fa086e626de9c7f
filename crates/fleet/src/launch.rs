//! Launching a team on one machine: one agent process per UAV over Zenoh on 127.0.0.1 (mutual
//! TLS over QUIC or TCP with a mission authority made in the output folder, or plain TCP with
//! `insecure`), kills (`SIGKILL`) and restarts at given mission times, then the agents' trace
//! files merged into one trace (with the events of the agents it killed, and of any that died
//! by a signal or a panic: a crashed agent is a failed UAV) and checked by
//! [`mason_mission::check_trace`].

use crate::clock::unix_now;
use crate::error::{FleetError, FleetResult};
use crate::network::{SecureLink, DEFAULT_PREFIX};
use crate::setting::FleetSetting;
use crate::trace::{append_death, merge};
use mason_mission::{check_trace, CommMode, Event, EventKind, TraceError, TraceSummary};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// What happens to an agent at a mission time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Killed (SIGKILL: no last word).
    Kill,
    /// Started again as a new incarnation.
    Restart,
}

/// How to launch a team.
#[derive(Clone, Debug)]
pub struct LaunchOptions {
    /// The `mason` program: each agent runs `EXE agent AGENT_ARGS --uav U …`.
    pub exe: PathBuf,
    /// The team's options as `mason agent` arguments (the same for every agent).
    pub agent_args: Vec<String>,
    /// Output folder: the agents' traces, MCAP logs and stderr.
    pub out: PathBuf,
    /// Agent U listens on 127.0.0.1:P+U (default: free ports, TCP and UDP).
    pub base_port: Option<u32>,
    /// The mission id (default: a fresh one).
    pub mission: Option<String>,
    /// Key prefix (default [`DEFAULT_PREFIX`]).
    pub prefix: Option<String>,
    /// Wall seconds between the launch and mission time 0, in [0, 60].
    pub lead: f64,
    /// `(uav, t)`: kill the agent at mission time t.
    pub kills: Vec<(usize, f64)>,
    /// `(uav, t)`: start the killed agent again at mission time t.
    pub restarts: Vec<(usize, f64)>,
    /// Plain TCP without authentication instead of mutual TLS.
    pub insecure: bool,
    /// The link of mutual TLS (QUIC by default).
    pub link: SecureLink,
    /// Ground stations to make keys for (TLS only), in `out/station-<s>`.
    pub stations: usize,
}

/// One agent process and how it ended.
#[derive(Debug)]
pub struct AgentRun {
    /// The UAV.
    pub uav: usize,
    /// Its incarnation.
    pub incarnation: u64,
    /// Its trace file.
    pub trace: PathBuf,
    /// Its stdout and stderr.
    pub log: PathBuf,
    /// How it ended: an exit code, `killed`, `crashed: …`, `timed out`, `interrupted`.
    pub exit: Option<String>,
    /// The mission time its death's events were written at, if it was killed or crashed.
    pub killed_at: Option<f64>,
    child: Option<Child>,
}

/// A finished launch.
#[derive(Debug)]
pub struct Launch {
    /// The mission id.
    pub mission: String,
    /// Mission time 0 (Unix s).
    pub start_at: f64,
    /// Each agent's endpoint.
    pub endpoints: Vec<String>,
    /// `mutual-tls` or `insecure` ([`crate::Security::name`]).
    pub security: &'static str,
    /// The mission authority's folder, with TLS.
    pub authority: Option<PathBuf>,
    /// Every agent process, in start order.
    pub runs: Vec<AgentRun>,
    /// The merged trace.
    pub events: Vec<Event>,
    /// [`check_trace`] on the merged trace.
    pub verdict: Result<TraceSummary, TraceError>,
    /// Wall time (s).
    pub wall_s: f64,
    /// Agents were still running past the mission's time limit and were killed.
    pub timed_out: bool,
    /// Stopped by `interrupted`.
    pub interrupted: bool,
}

impl Launch {
    /// Bricks placed.
    pub fn placed(&self) -> usize {
        self.events
            .iter()
            .filter(|e| matches!(e.kind, EventKind::Place { .. }))
            .count()
    }

    /// The time of the last placement, when all `total` bricks were placed.
    pub fn makespan(&self, total: usize) -> Option<f64> {
        (self.placed() == total).then(|| {
            self.events
                .iter()
                .filter(|e| matches!(e.kind, EventKind::Place { .. }))
                .map(|e| e.t)
                .fold(0.0, f64::max)
        })
    }

    /// The time of the last event.
    pub fn end(&self) -> f64 {
        self.events.iter().map(|e| e.t).fold(0.0, f64::max)
    }

    /// How many times an agent switched to `mode`.
    pub fn switches(&self, mode: CommMode) -> usize {
        self.events
            .iter()
            .filter(|e| e.kind == EventKind::Comm { mode })
            .count()
    }

    /// The merged trace with the launch's facts, as JSON (`trace.json`).
    pub fn to_json(&self, s: &FleetSetting) -> serde_json::Value {
        let total = s.wall.len();
        let placed = self.placed();
        let violation = self.verdict.as_ref().err().map(|e| e.to_string());
        let mut dropped = std::collections::BTreeMap::<String, u64>::new();
        let agents: Vec<serde_json::Value> = self
            .runs
            .iter()
            .map(|r| {
                let drops = drops_in_log(&r.log);
                for (cause, k) in &drops {
                    *dropped.entry(cause.clone()).or_default() += k;
                }
                serde_json::json!({
                    "uav": r.uav, "incarnation": r.incarnation,
                    "exit": r.exit, "killed_at": r.killed_at,
                    "trace": r.trace.file_name().map(|f| f.to_string_lossy().into_owned()),
                    "dropped": drops,
                })
            })
            .collect();
        let summary = serde_json::json!({
            "bricks_placed": placed, "bricks_total": total, "finished": placed == total,
            "makespan_s": self.makespan(total), "end_s": self.end(),
            "check_trace": violation.unwrap_or_else(|| "passed".into()),
            "to_windows": self.switches(CommMode::Windows), "to_comm": self.switches(CommMode::Comm),
            "wall_time_s": self.wall_s, "timed_out": self.timed_out, "dropped": dropped,
            "security": self.security,
        });
        serde_json::json!({
            "wall": s.wall.name(), "uavs": s.config.uavs, "coord": s.coord,
            "mission": self.mission, "speed": s.speed, "seed": s.seed, "start_at": self.start_at,
            "endpoints": self.endpoints, "security": self.security,
            "authority": self.authority.as_ref().map(|p| p.to_string_lossy().into_owned()),
            "order": s.order.iter().map(|b| s.wall.brick(*b).label).collect::<Vec<_>>(),
            "agents": agents, "summary": summary,
            "events": self.events.iter().map(|e| mason_report::event_json(&s.wall, e)).collect::<Vec<_>>(),
        })
    }
}

/// How an agent reports, as its last line on stderr, the samples it dropped on arrival: this
/// prefix, then the counts by cause as a JSON object (`{"replay":3}`).
pub const DROPPED_LINE: &str = "mason agent: samples dropped on arrival ";

/// The counts of an agent's [`DROPPED_LINE`] in its stderr log (none if it has none, or the
/// log is unreadable or over 16 MiB).
pub fn drops_in_log(log: &Path) -> std::collections::BTreeMap<String, u64> {
    const MAX_LOG: u64 = 16 << 20;
    let small = std::fs::metadata(log).is_ok_and(|m| m.len() <= MAX_LOG);
    let text = if small {
        std::fs::read_to_string(log).unwrap_or_default()
    } else {
        String::new()
    };
    text.lines()
        .filter_map(|l| l.strip_prefix(DROPPED_LINE))
        .next_back()
        .and_then(|j| serde_json::from_str(j).ok())
        .unwrap_or_default()
}

/// The kills and restarts, by time; each restart must follow a kill of its UAV and each kill a
/// running agent (errors name the flag).
pub fn schedule(
    kills: &[(usize, f64)],
    restarts: &[(usize, f64)],
    uavs: usize,
) -> FleetResult<Vec<(f64, usize, Action)>> {
    let mut plan: Vec<(f64, usize, Action)> = kills
        .iter()
        .map(|&(u, t)| (t, u, Action::Kill))
        .chain(restarts.iter().map(|&(u, t)| (t, u, Action::Restart)))
        .collect();
    plan.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut down = vec![false; uavs];
    for &(t, u, what) in &plan {
        let Some(d) = down.get_mut(u) else {
            return Err(FleetError::bad(format!(
                "UAV {u} is not in a team of {uavs} (0..{})",
                uavs.saturating_sub(1)
            )));
        };
        match what {
            Action::Kill if *d => {
                return Err(FleetError::bad(format!(
                    "--kill {u}@{t}: UAV {u} is already killed then (add a --restart before)"
                )))
            }
            Action::Restart if !*d => {
                return Err(FleetError::bad(format!(
                "--restart {u}@{t}: UAV {u} is not killed before (add a --kill {u}@T with T < {t})"
            )))
            }
            Action::Kill => *d = true,
            Action::Restart => *d = false,
        }
    }
    Ok(plan)
}

/// A port free on 127.0.0.1 for both TCP and UDP (QUIC links are UDP), with the sockets that
/// hold it: while they are open no later call gets the same port.
fn free_port() -> FleetResult<(u16, std::net::TcpListener, std::net::UdpSocket)> {
    let err = |e: std::io::Error| {
        FleetError::Network(format!("cannot find a free port on 127.0.0.1: {e}"))
    };
    for _ in 0..64 {
        let tcp = std::net::TcpListener::bind("127.0.0.1:0").map_err(err)?;
        let port = tcp.local_addr().map_err(err)?.port();
        if let Ok(udp) = std::net::UdpSocket::bind(("127.0.0.1", port)) {
            return Ok((port, tcp, udp));
        }
    }
    Err(FleetError::Network(
        "cannot find a port free for both TCP and UDP on 127.0.0.1".into(),
    ))
}

fn ports(base: Option<u32>, n: usize) -> FleetResult<Vec<u16>> {
    match base {
        Some(p) if p >= 1 && p as usize + n - 1 <= 65535 => {
            Ok((0..n).map(|u| (p as usize + u) as u16).collect())
        }
        Some(p) => Err(FleetError::bad(format!(
            "--base-port {p}: ports {p}..{} must lie in 1..65535",
            p as usize + n - 1
        ))),
        // Every socket stays open until all n ports are found, so that the ports differ.
        None => {
            let held: Vec<_> = (0..n).map(|_| free_port()).collect::<FleetResult<_>>()?;
            Ok(held.into_iter().map(|(port, _, _)| port).collect())
        }
    }
}

/// Removes an earlier launch's agent files from `out` (the cameras read every trace there).
fn clear(out: &Path) -> FleetResult<()> {
    std::fs::create_dir_all(out).map_err(|source| FleetError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    if let Ok(entries) = std::fs::read_dir(out) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with("uav-") && (name.ends_with(".jsonl") || name.ends_with(".log")) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    Ok(())
}

/// What every agent process of one launch shares.
struct Spawner<'a> {
    opts: &'a LaunchOptions,
    mission: String,
    start_at: f64,
    endpoints: Vec<String>,
}

impl Spawner<'_> {
    fn spawn(&self, uav: usize, incarnation: u64, earlier: &[PathBuf]) -> FleetResult<AgentRun> {
        let out = &self.opts.out;
        let trace = out.join(format!("uav-{uav}-{incarnation}.jsonl"));
        let log_path = out.join(format!("uav-{uav}-{incarnation}.log"));
        let io = |source| FleetError::Io {
            path: log_path.clone(),
            source,
        };
        let log = std::fs::File::create(&log_path).map_err(io)?;
        let err = log.try_clone().map_err(io)?;
        let mut cmd = Command::new(&self.opts.exe);
        cmd.arg("agent").args(&self.opts.agent_args);
        cmd.args(["--uav", &uav.to_string(), "--mission", &self.mission]);
        cmd.args(["--start-at", &format!("{:.6}", self.start_at)]);
        cmd.args(["--incarnation", &incarnation.to_string()]);
        if self.opts.insecure {
            cmd.arg("--insecure");
        } else {
            cmd.arg("--tls-dir").arg(out.join(format!("uav-{uav}")));
        }
        cmd.args(["--listen", &self.endpoints[uav]]);
        for (v, e) in self.endpoints.iter().enumerate() {
            if v != uav {
                cmd.args(["--connect", e]);
            }
        }
        if let Some(p) = &self.opts.prefix {
            cmd.args(["--prefix", p]);
        }
        cmd.arg("--trace").arg(&trace);
        cmd.arg("--mcap")
            .arg(out.join(format!("uav-{uav}-{incarnation}.mcap")));
        cmd.arg("--world").arg(out);
        for p in earlier {
            cmd.arg("--remember").arg(p);
        }
        cmd.stdin(Stdio::null()).stdout(log).stderr(err);
        let child = cmd.spawn().map_err(|source| FleetError::Io {
            path: self.opts.exe.clone(),
            source,
        })?;
        Ok(AgentRun {
            uav,
            incarnation,
            trace,
            log: log_path,
            exit: None,
            killed_at: None,
            child: Some(child),
        })
    }
}

/// Launches the team of `setting`, carries out the kills and restarts, waits for every agent
/// (or `interrupted`, or the mission's time limit plus 10 wall seconds), then merges and
/// checks the traces. `started` hears one line once the agents are running.
pub fn launch(
    setting: &FleetSetting,
    opts: &LaunchOptions,
    interrupted: &AtomicBool,
    started: &mut dyn FnMut(String),
) -> FleetResult<Launch> {
    let wall_started = Instant::now();
    let n = setting.config.uavs;
    let plan = schedule(&opts.kills, &opts.restarts, n)?;
    if !(opts.lead.is_finite() && (0.0..=60.0).contains(&opts.lead)) {
        return Err(FleetError::bad(format!(
            "--lead {}: expected wall seconds in [0, 60]",
            opts.lead
        )));
    }
    let ports = ports(opts.base_port, n)?;
    let mission = opts
        .mission
        .clone()
        .unwrap_or_else(|| format!("launch-{}-{}", unix_now() as u64, std::process::id()));
    crate::network::check_chunks("--mission", &mission, true)?;
    clear(&opts.out)?;
    let authority = if opts.insecure {
        None
    } else {
        Some(make_authority(&opts.out, &mission, n, opts.stations)?)
    };
    let scheme = if opts.insecure {
        "tcp"
    } else {
        opts.link.scheme()
    };
    let start_at = unix_now() + opts.lead;
    let spawner = Spawner {
        opts,
        mission,
        start_at,
        endpoints: ports
            .iter()
            .map(|p| format!("{scheme}/127.0.0.1:{p}"))
            .collect(),
    };
    let mut runs: Vec<AgentRun> = (0..n)
        .map(|u| spawner.spawn(u, 1, &[]))
        .collect::<FleetResult<_>>()?;
    let security = match &authority {
        Some(dir) => format!(
            "mutual TLS {}, mission authority in {}",
            opts.link.carrier(),
            dir.display()
        ),
        None => "INSECURE: plain TCP, no authentication".into(),
    };
    started(format!(
        "mission {}, {n} agents on {} ({security}), key {}/{}/UAV/KIND, speed {}",
        spawner.mission,
        spawner.endpoints.join(" "),
        opts.prefix.as_deref().unwrap_or(DEFAULT_PREFIX),
        spawner.mission,
        setting.speed
    ));
    let mission_now = || (unix_now() - start_at) * setting.speed;
    // Past max_time_s every agent stops by itself; give it a few wall seconds more.
    let give_up = start_at + setting.config.max_time_s / setting.speed + 10.0;
    let mut next = 0;
    let mut timed_out = false;
    loop {
        while next < plan.len() && plan[next].0 <= mission_now() {
            let (_, u, what) = plan[next];
            next += 1;
            match what {
                Action::Kill => kill(&mut runs, u, mission_now())?,
                Action::Restart => {
                    let earlier: Vec<PathBuf> = runs
                        .iter()
                        .filter(|r| r.uav == u)
                        .map(|r| r.trace.clone())
                        .collect();
                    let inc = 1 + earlier.len() as u64;
                    runs.push(spawner.spawn(u, inc, &earlier)?);
                }
            }
        }
        reap(&mut runs, mission_now())?;
        if runs.iter().all(|r| r.child.is_none()) && next >= plan.len() {
            break;
        }
        let stop = interrupted.load(Ordering::Relaxed);
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
    // An agent that refused its input (which the launch checked already) is a bad launch.
    if let Some(r) = runs.iter().find(|r| r.exit.as_deref() == Some("2")) {
        let text = std::fs::read_to_string(&r.log).unwrap_or_default();
        let why = text
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or("");
        return Err(FleetError::bad(format!(
            "agent of UAV {} refused its input ({}): {why}",
            r.uav,
            r.log.display()
        )));
    }
    let files: Vec<(PathBuf, bool)> = runs
        .iter()
        .map(|r| (r.trace.clone(), r.killed_at.is_some()))
        .collect();
    let events = merge(&files)?;
    let verdict = check_trace(&setting.wall, n, &events);
    Ok(Launch {
        mission: spawner.mission,
        start_at,
        endpoints: spawner.endpoints,
        security: if opts.insecure {
            "insecure"
        } else {
            "mutual-tls"
        },
        authority,
        runs,
        events,
        verdict,
        wall_s: wall_started.elapsed().as_secs_f64(),
        timed_out,
        interrupted: interrupted.load(Ordering::Relaxed),
    })
}

/// Makes the mission authority and every member's files in `out` (see [`crate::authority`]);
/// returns the authority's folder.
#[cfg(feature = "zenoh")]
fn make_authority(out: &Path, mission: &str, uavs: usize, stations: usize) -> FleetResult<PathBuf> {
    let keys = crate::authority::make_keys(out, mission, uavs, stations)?;
    Ok(keys.dir.join(crate::authority::AUTHORITY_DIR))
}

/// Without the `zenoh` feature there is no TLS.
#[cfg(not(feature = "zenoh"))]
fn make_authority(_: &Path, _: &str, _: usize, _: usize) -> FleetResult<PathBuf> {
    Err(FleetError::bad(
        "a launch over TLS needs the zenoh feature (or --insecure)",
    ))
}

/// Kills UAV `u`'s running agent and writes the events of its death into its trace.
fn kill(runs: &mut [AgentRun], u: usize, now: f64) -> FleetResult<()> {
    let Some(r) = runs
        .iter_mut()
        .rev()
        .find(|r| r.uav == u && r.child.is_some())
    else {
        return Ok(());
    };
    let Some(mut child) = r.child.take() else {
        return Ok(());
    };
    let _ = child.kill();
    let status = child.wait();
    r.killed_at = Some(append_death(&r.trace, u, now)?);
    r.exit = Some(match status.ok().and_then(|s| s.code()) {
        Some(code) => format!("exited {code} before the kill"),
        None => "killed".into(),
    });
    Ok(())
}

/// The exit code of a Rust program that panicked.
const PANIC_EXIT: i32 = 101;

/// How an agent that did not end by itself ended (`None` if it did): killed by a signal
/// nobody sent it here, or a panic.
pub fn crash(status: std::process::ExitStatus) -> Option<String> {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = status.signal() {
            let name = match sig {
                4 => " (SIGILL)",
                6 => " (SIGABRT)",
                7 => " (SIGBUS)",
                8 => " (SIGFPE)",
                9 => " (SIGKILL)",
                11 => " (SIGSEGV)",
                15 => " (SIGTERM)",
                _ => "",
            };
            return Some(format!("crashed: signal {sig}{name}"));
        }
    }
    match status.code() {
        Some(PANIC_EXIT) => Some(format!("crashed: exit {PANIC_EXIT} (panic)")),
        Some(_) => None,
        None => Some(format!("crashed: {status}")),
    }
}

/// Notes the agents that have exited. One that crashed (see [`crash`]) is a failed UAV from
/// mission time `now` on, as if it had been killed: its death's events go into its trace,
/// so that the merged trace does not keep it in the zone or holding a brick.
fn reap(runs: &mut [AgentRun], now: f64) -> FleetResult<()> {
    for r in runs.iter_mut() {
        if let Some(c) = r.child.as_mut() {
            if let Ok(Some(status)) = c.try_wait() {
                r.child = None;
                r.exit = Some(match crash(status) {
                    Some(why) => {
                        r.killed_at = Some(append_death(&r.trace, r.uav, now)?);
                        why
                    }
                    None => status.code().map_or(format!("{status}"), |c| c.to_string()),
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_agents_drop_counts_are_read_back_from_its_log() {
        let dir = std::env::temp_dir().join(format!("mason-drops-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let log = dir.join("uav-1-1.log");
        let mut counts = mason_mission::agent::DropCounts::default();
        counts.record(mason_mission::agent::DropCause::Replay);
        counts.record(mason_mission::agent::DropCause::UnknownUav);
        let line = format!("{DROPPED_LINE}{}", serde_json::to_string(&counts).unwrap());
        std::fs::write(
            &log,
            format!("something else\n{line}\nmason agent: UAV 1 …\n"),
        )
        .unwrap();
        let got = drops_in_log(&log);
        assert_eq!(got.get("replay"), Some(&1));
        assert_eq!(got.get("unknown_uav"), Some(&1));
        assert_eq!(got.len(), 2);
        // No line, a bad line, or no file: nothing.
        std::fs::write(&log, format!("{DROPPED_LINE}{{oops\n")).unwrap();
        assert!(drops_in_log(&log).is_empty());
        assert!(drops_in_log(&dir.join("none.log")).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn kills_and_restarts_must_alternate() {
        let plan = schedule(&[(1, 10.0)], &[(1, 20.0)], 3).unwrap();
        assert_eq!(
            plan,
            vec![(10.0, 1, Action::Kill), (20.0, 1, Action::Restart)]
        );
        let e = schedule(&[(1, 10.0), (1, 12.0)], &[], 3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("already killed"), "{e}");
        let e = schedule(&[], &[(0, 5.0)], 3).unwrap_err().to_string();
        assert!(e.contains("not killed before"), "{e}");
        assert!(schedule(&[(3, 1.0)], &[], 3).is_err());
    }

    #[cfg(unix)]
    #[test]
    fn a_signal_or_a_panic_is_a_crash_and_an_exit_code_is_not() {
        let status = |script: &str| {
            Command::new("sh")
                .args(["-c", script])
                .status()
                .expect("sh runs")
        };
        assert_eq!(
            crash(status("kill -ILL $$")).as_deref(),
            Some("crashed: signal 4 (SIGILL)")
        );
        assert_eq!(
            crash(status("kill -USR1 $$")).as_deref(),
            Some("crashed: signal 10")
        );
        assert_eq!(
            crash(status("exit 101")).as_deref(),
            Some("crashed: exit 101 (panic)")
        );
        for code in [0, 1, 2, 3] {
            assert_eq!(crash(status(&format!("exit {code}"))), None, "{code}");
        }
    }

    #[test]
    fn ports_stay_in_range() {
        assert_eq!(ports(Some(7000), 3).unwrap(), vec![7000, 7001, 7002]);
        assert!(ports(Some(65535), 2).is_err());
        assert!(ports(Some(0), 1).is_err());
        let free = ports(None, 8).unwrap();
        let distinct: std::collections::BTreeSet<u16> = free.iter().copied().collect();
        assert_eq!(distinct.len(), 8, "{free:?}");
    }
}
