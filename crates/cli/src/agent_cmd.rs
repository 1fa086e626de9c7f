//! `mason agent`: one UAV as its own process. The decision core is
//! [`mason_mission::agent::Agent`]; this module gives it a real clock ([`MissionClock`]), a
//! transport (Zenoh, `zenoh_link.rs`, behind the `zenoh` feature), the fault layer, a
//! vehicle simulated in-process, and a trace file, and drives it ([`drive`]).
//!
//! The team options ([`TeamArgs`]: design, order, coordination, speed, faults) are shared with
//! `mason launch`, which checks them once and passes them on to every agent it starts.

use crate::fail::{check_output, input_error, CliResult};
use crate::input::{load_model, read_toml};
use crate::transport::{Clock, LinkFaults, Transport};
use crate::DesignArgs;
use mason_mission::agent::{Agent, AgentSetup, Message, DEFAULT_DEAD_AFTER_S, DEFAULT_LEASE_S};
use mason_mission::{Coord, Event, MissionConfig, Window};
use mason_order::{BuildProblem, CostModel, PlannerSpec, Status};
use mason_wall::{BrickId, Wall};
use serde::Deserialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The fastest clock accepted (`--speed`): a heartbeat every millisecond of wall time.
pub const MAX_SPEED: f64 = 1000.0;

/// The options every agent of a team shares (`mason agent` and `mason launch`).
#[derive(clap::Args, Clone)]
pub struct TeamArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// Team size
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Coordination: comm (zone requests acknowledged by every teammate), windows (time
    /// slots) or auto (comm, windows while heartbeats are lost)
    #[arg(long, default_value = "auto")]
    pub coord: String,
    /// Planner of the shared build order (every agent plans it; it must be deterministic)
    #[arg(long, default_value = "exact")]
    pub planner: String,
    /// Cost model (grasp and placement times, κ)
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Arena, UAV model, coordination timings and max_time_s from a TOML file (as
    /// `simulate --mission`)
    #[arg(long)]
    pub mission_config: Option<PathBuf>,
    /// Windows slot length in seconds (default 20, raised to the longest zone time)
    #[arg(long, allow_negative_numbers = true)]
    pub slot: Option<f64>,
    /// Mission clock speed: K mission seconds per wall second
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub speed: f64,
    /// Seed of the simulated vehicle and of the transport faults (mixed with the UAV number
    /// and incarnation)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// Probability that one grasp attempt fails
    #[arg(long, allow_negative_numbers = true)]
    pub grasp_fail: Option<f64>,
    /// Probability that one detection attempt fails
    #[arg(long, allow_negative_numbers = true)]
    pub detect_fail: Option<f64>,
    /// A teammate unheard this long (mission s) is declared out by a majority
    #[arg(long, allow_negative_numbers = true)]
    pub dead_after: Option<f64>,
    /// Transport fault: probability that a received message is dropped
    #[arg(long, allow_negative_numbers = true)]
    pub drop: Option<f64>,
    /// Transport fault: probability that a received message is delivered twice
    #[arg(long, allow_negative_numbers = true)]
    pub duplicate: Option<f64>,
    /// Transport fault: each received message is held back up to S mission seconds (reorders)
    #[arg(long, allow_negative_numbers = true)]
    pub delay_jitter: Option<f64>,
    /// Transport fault: nothing is sent or received from A to B mission seconds, as A-B;
    /// repeatable
    #[arg(long)]
    pub cut: Vec<String>,
}

/// A team's setting, checked: what every agent needs besides its own number and network.
pub struct Team {
    /// The wall.
    pub wall: Wall,
    /// The cost model.
    pub model: CostModel,
    /// The shared build order.
    pub order: Vec<BrickId>,
    /// Team, arena, UAV model, coordination timings (vehicle faults only).
    pub config: MissionConfig,
    /// The policy.
    pub coord: Coord,
    /// The windows slot (s).
    pub slot: f64,
    /// Clock speed.
    pub speed: f64,
    /// Seed.
    pub seed: u64,
    /// Declared out after (mission s).
    pub dead_after: f64,
    /// Transport faults.
    pub link: LinkFaults,
}

fn probability(flag: &str, p: Option<f64>) -> CliResult<f64> {
    match p {
        None => Ok(0.0),
        Some(p) if (0.0..=1.0).contains(&p) => Ok(p),
        Some(p) => Err(input_error(format!(
            "{flag} {p}: a probability must lie in [0, 1]"
        ))),
    }
}

/// Parses `A-B` (mission seconds, 0 ≤ A < B).
pub fn parse_window(flag: &str, s: &str) -> CliResult<Window> {
    let bad = |why: &str| input_error(format!("{flag} `{s}`: {why}"));
    let (a, b) = s
        .split_once('-')
        .ok_or_else(|| bad("expected A-B in mission seconds, e.g. 100-125"))?;
    let num = |x: &str| {
        x.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| bad(&format!("`{x}` is not a time in seconds")))
    };
    let (from, to) = (num(a)?, num(b)?);
    if from >= to {
        return Err(bad("the window ends before it starts"));
    }
    Ok(Window { from, to })
}

/// Parses `U@T` for a team of `uavs`.
pub fn parse_at(flag: &str, s: &str, uavs: usize) -> CliResult<(usize, f64)> {
    let bad = |why: String| input_error(format!("{flag} `{s}`: {why}"));
    let (u, t) = s
        .split_once('@')
        .ok_or_else(|| bad("expected U@T, e.g. 1@300".into()))?;
    let uav = u
        .trim()
        .parse::<usize>()
        .map_err(|_| bad(format!("`{u}` is not a UAV number")))?;
    if uav >= uavs {
        return Err(bad(format!(
            "UAV {uav} is not in a team of {uavs} (0..{})",
            uavs - 1
        )));
    }
    let at = t
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
        .ok_or_else(|| bad(format!("`{t}` is not a time in seconds")))?;
    Ok((uav, at))
}

impl TeamArgs {
    /// The transport faults of the flags.
    pub fn link_faults(&self) -> CliResult<LinkFaults> {
        let jitter = match self.delay_jitter {
            None => 0.0,
            Some(s) if s.is_finite() && s >= 0.0 => s,
            Some(s) => {
                return Err(input_error(format!(
                    "--delay-jitter {s}: expected seconds ≥ 0"
                )))
            }
        };
        Ok(LinkFaults {
            drop: probability("--drop", self.drop)?,
            duplicate: probability("--duplicate", self.duplicate)?,
            delay_jitter: jitter,
            cuts: self
                .cut
                .iter()
                .map(|s| parse_window("--cut", s))
                .collect::<CliResult<_>>()?,
        })
    }

    /// Checks every option and plans the shared order (exit 2 on bad input).
    pub fn resolve(&self) -> CliResult<Team> {
        let coord: Coord = self
            .coord
            .parse()
            .map_err(|e| input_error(format!("--coord: {e}")))?;
        let spec: PlannerSpec = self
            .planner
            .parse()
            .map_err(|e| input_error(format!("--planner: {e}")))?;
        if !(self.speed.is_finite() && self.speed > 0.0 && self.speed <= MAX_SPEED) {
            return Err(input_error(format!(
                "--speed {}: expected a factor in (0, {MAX_SPEED}]",
                self.speed
            )));
        }
        let dead_after = self.dead_after.unwrap_or(DEFAULT_DEAD_AFTER_S);
        if !(dead_after.is_finite() && dead_after > 0.0) {
            return Err(input_error(format!(
                "--dead-after {dead_after}: expected seconds > 0"
            )));
        }
        let link = self.link_faults()?;
        let mut config = match &self.mission_config {
            Some(p) => crate::sim_cmd::read_mission(p, self.uavs)?,
            None => MissionConfig::default(),
        };
        if let Some(p) = &self.mission_config {
            let f = &config.faults;
            if !f.uav_fail.is_empty()
                || f.uav_hazard > 0.0
                || !f.blackout.is_empty()
                || f.msg_loss > 0.0
                || f.latency > 0.0
            {
                return Err(input_error(format!(
                    "{}: [faults] uav_fail, uav_hazard, blackout, msg_loss and latency are the simulator's; agents take --drop, --duplicate, --delay-jitter, --cut (and launch --kill)",
                    p.display()
                )));
            }
        }
        config.uavs = self.uavs;
        if let Some(p) = self.grasp_fail {
            config.faults.grasp_fail = p;
        }
        if let Some(p) = self.detect_fail {
            config.faults.detect_fail = p;
        }
        if self.slot.is_some() {
            config.coord.slot_s = self.slot;
        }
        let wall = self.design.load()?;
        let model = load_model(self.model.as_deref())?;
        let slot = crate::sim_cmd::prepare(&wall, &model, &config)?;
        let problem =
            BuildProblem::new(&wall, model.clone()).map_err(|e| input_error(e.to_string()))?;
        let checked = crate::plan::solve(&problem, spec, Some(60.0))?;
        crate::plan::exit_for(&checked)?;
        if checked.outcome.status == Status::Timeout {
            return Err(input_error(format!(
                "--planner {spec} stopped at its time limit: the agents could disagree on the order (use a faster planner, e.g. greedy)"
            )));
        }
        let order = checked.outcome.order.clone().expect("checked order");
        Ok(Team {
            wall,
            model,
            order,
            config,
            coord,
            slot,
            speed: self.speed,
            seed: self.seed,
            dead_after,
            link,
        })
    }

    /// The same options as command-line arguments, for an agent process.
    pub fn to_args(&self) -> Vec<String> {
        let d = &self.design;
        let mut a: Vec<String> = vec![d.design.clone()];
        let mut opt = |k: &str, v: String| {
            a.push(k.to_string());
            a.push(v);
        };
        opt("--format", value_name(&d.format));
        opt("--cmcp-sizes", value_name(&d.cmcp_sizes));
        opt("--uavs", self.uavs.to_string());
        opt("--coord", self.coord.clone());
        opt("--planner", self.planner.clone());
        opt("--speed", self.speed.to_string());
        opt("--seed", self.seed.to_string());
        let path = |p: &Path| p.to_string_lossy().into_owned();
        if let Some(p) = &self.model {
            opt("--model", path(p));
        }
        if let Some(p) = &self.mission_config {
            opt("--mission-config", path(p));
        }
        for (k, v) in [
            ("--slot", self.slot),
            ("--grasp-fail", self.grasp_fail),
            ("--detect-fail", self.detect_fail),
            ("--dead-after", self.dead_after),
            ("--drop", self.drop),
            ("--duplicate", self.duplicate),
            ("--delay-jitter", self.delay_jitter),
        ] {
            if let Some(v) = v {
                opt(k, v.to_string());
            }
        }
        for c in &self.cut {
            opt("--cut", c.clone());
        }
        if d.strict {
            a.push("--strict".into());
        }
        a
    }
}

/// The command-line name of a value.
fn value_name<T: clap::ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// `mason agent`'s own options.
#[derive(clap::Args)]
pub struct AgentArgs {
    #[command(flatten)]
    pub team: TeamArgs,
    /// This UAV (0-based)
    #[arg(long, allow_negative_numbers = true)]
    pub uav: usize,
    /// The mission id: every message carries it, and its key starts with it
    #[arg(long)]
    pub mission: Option<String>,
    /// Mission time 0 as Unix seconds (default: now); before it the agent waits
    #[arg(long, allow_negative_numbers = true)]
    pub start_at: Option<f64>,
    /// Zenoh endpoint to listen on, e.g. tcp/127.0.0.1:7447; repeatable
    #[arg(long)]
    pub listen: Vec<String>,
    /// Zenoh endpoint of a teammate to connect to; repeatable
    #[arg(long)]
    pub connect: Vec<String>,
    /// Key prefix: messages go to PREFIX/MISSION/UAV/KIND (default mason)
    #[arg(long)]
    pub prefix: Option<String>,
    /// Network options from a TOML file: mission, prefix, listen, connect (flags add to the
    /// lists and override the rest)
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Write the trace here: one JSON event per line, flushed per line
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Write an MCAP log here for Foxglove: this UAV's poses (2 Hz), states, zone, bricks,
    /// and every message it sent or heard (finished when the agent stops; an agent killed
    /// with SIGKILL leaves a log without its summary)
    #[arg(long)]
    pub mcap: Option<PathBuf>,
    /// This run's incarnation (a restarted agent takes a higher one than before)
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub incarnation: u64,
    /// A trace of this UAV's earlier run: the bricks it placed are remembered; repeatable
    #[arg(long)]
    pub remember: Vec<PathBuf>,
    /// The simulated camera at the wall sees what the team's trace files (*.jsonl) in this
    /// folder say is on the wall or fell (launch passes its --out); without it, no camera
    #[arg(long)]
    pub world: Option<PathBuf>,
}

/// The network options of `--config FILE.toml`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetworkFile {
    /// The mission id.
    pub mission: Option<String>,
    /// The key prefix.
    pub prefix: Option<String>,
    /// Endpoints to listen on.
    #[serde(default)]
    pub listen: Vec<String>,
    /// Endpoints to connect to.
    #[serde(default)]
    pub connect: Vec<String>,
}

pub use crate::transport::Network;

/// The default key prefix.
pub const DEFAULT_PREFIX: &str = "mason";

/// Checks a Zenoh endpoint `proto/host:port` (tcp or udp; port 0 only to listen).
pub fn check_endpoint(flag: &str, e: &str, listen: bool) -> CliResult<()> {
    let bad = |why: &str| input_error(format!("{flag} `{e}`: {why}"));
    let (proto, addr) = e
        .split_once('/')
        .ok_or_else(|| bad("expected PROTO/HOST:PORT, e.g. tcp/127.0.0.1:7447"))?;
    if proto != "tcp" && proto != "udp" {
        return Err(bad(&format!(
            "unknown protocol `{proto}` (this build speaks tcp and udp)"
        )));
    }
    let addr = addr.split(['?', '#']).next().unwrap_or_default();
    let (host, port) = addr.rsplit_once(':').ok_or_else(|| bad("missing :PORT"))?;
    let host = host.trim_start_matches('[').trim_end_matches(']');
    if host.is_empty() || host.chars().any(|c| c.is_whitespace() || c == '/') {
        return Err(bad("missing or bad host"));
    }
    match port.parse::<u16>() {
        Ok(0) if !listen => Err(bad("port 0 can only be listened on")),
        Ok(_) => Ok(()),
        Err(_) => Err(bad(&format!("`{port}` is not a port (0..65535)"))),
    }
}

fn check_chunks(flag: &str, s: &str, one: bool) -> CliResult<()> {
    let chunk_ok = |c: &str| {
        !c.is_empty()
            && c.chars()
                .all(|ch| ch.is_ascii_alphanumeric() || "-_.~+=".contains(ch))
    };
    let ok = if one {
        chunk_ok(s)
    } else {
        s.split('/').all(chunk_ok)
    };
    if ok {
        Ok(())
    } else {
        let what = if one {
            "one key chunk of letters, digits and - _ . ~ + ="
        } else {
            "key chunks of letters, digits and - _ . ~ + =, joined by /"
        };
        Err(input_error(format!("{flag} `{s}`: expected {what}")))
    }
}

impl AgentArgs {
    /// The network options: the file's, with the flags on top; every one checked.
    pub fn network(&self) -> CliResult<Network> {
        let file: NetworkFile = match &self.config {
            Some(p) => read_toml(p)?,
            None => NetworkFile::default(),
        };
        let shown = |flag: &str| match &self.config {
            Some(p) => format!("{} ({}: {flag})", flag, p.display()),
            None => flag.to_string(),
        };
        let mission = self.mission.clone().or(file.mission).ok_or_else(|| {
            input_error("--mission: every agent needs the mission id (or `mission` in --config)")
        })?;
        check_chunks(&shown("--mission"), &mission, true)?;
        let prefix = self
            .prefix
            .clone()
            .or(file.prefix)
            .unwrap_or_else(|| DEFAULT_PREFIX.into());
        check_chunks(&shown("--prefix"), &prefix, false)?;
        let mut listen = file.listen;
        listen.extend(self.listen.iter().cloned());
        let mut connect = file.connect;
        connect.extend(self.connect.iter().cloned());
        for e in &listen {
            check_endpoint(&shown("--listen"), e, true)?;
        }
        for e in &connect {
            check_endpoint(&shown("--connect"), e, false)?;
        }
        Ok(Network {
            mission,
            prefix,
            listen,
            connect,
        })
    }

    /// Checks this agent's own options against the team.
    pub fn check(&self, team: &Team) -> CliResult<()> {
        if self.uav >= team.config.uavs {
            return Err(input_error(format!(
                "--uav {}: not in a team of {} (0..{})",
                self.uav,
                team.config.uavs,
                team.config.uavs - 1
            )));
        }
        if self.incarnation == 0 {
            return Err(input_error("--incarnation: starts at 1"));
        }
        if let Some(s) = self.start_at {
            if !(s.is_finite() && s >= 0.0) {
                return Err(input_error(format!(
                    "--start-at {s}: expected Unix seconds"
                )));
            }
        }
        if let Some(p) = &self.trace {
            check_output(p)?;
        }
        if let Some(d) = self.world.as_ref().filter(|d| !d.is_dir()) {
            return Err(input_error(format!(
                "--world {}: not a folder",
                d.display()
            )));
        }
        Ok(())
    }
}

/// Where an agent writes what it does.
///
/// Where an agent's events, messages and poses go: its trace file ([`JsonLines`]) and its
/// MCAP log ([`McapAgentLog`]).
pub trait AgentLog {
    /// One trace event.
    fn event(&mut self, e: &Event) -> std::io::Result<()>;
    /// A message sent (`sent`) or heard.
    fn message(&mut self, _t: f64, _m: &Message, _sent: bool) -> std::io::Result<()> {
        Ok(())
    }
    /// The UAV's pose at mission time `t` (m), after every tick.
    fn pose(&mut self, _t: f64, _pose: (f64, f64, f64)) -> std::io::Result<()> {
        Ok(())
    }
    /// The agent stopped: complete the log.
    fn finish(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The agent's MCAP log (the topics of `simulate --mcap`): poses at most every
/// [`mason_report::POSE_RATE_HZ`]⁻¹ s of mission time and at every event, heading along
/// the last move; every event; every message sent or heard on `/messages` (`kind` is
/// `sent/KIND` or `heard/KIND`, `body` the whole message).
pub struct McapAgentLog<'a> {
    log: Option<mason_report::McapLog<'a, std::io::BufWriter<std::fs::File>>>,
    uav: u32,
    last: Option<(f64, (f64, f64, f64))>,
    yaw: f64,
    pose_due: bool,
}

impl<'a> McapAgentLog<'a> {
    /// A log into `file` for UAV `uav` of the mission `meta` describes.
    pub fn new(
        file: std::fs::File,
        meta: &mason_report::LogMeta<'a>,
        uav: usize,
    ) -> std::io::Result<Self> {
        let log = mason_report::McapLog::new(std::io::BufWriter::new(file), meta)
            .map_err(std::io::Error::other)?;
        Ok(McapAgentLog {
            log: Some(log),
            uav: uav as u32,
            last: None,
            yaw: 0.0,
            pose_due: true,
        })
    }

    fn log(
        &mut self,
    ) -> std::io::Result<&mut mason_report::McapLog<'a, std::io::BufWriter<std::fs::File>>> {
        self.log
            .as_mut()
            .ok_or_else(|| std::io::Error::other("the MCAP log is finished"))
    }
}

impl AgentLog for McapAgentLog<'_> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.pose_due = true;
        self.log()?.event(e).map_err(std::io::Error::other)
    }

    fn message(&mut self, t: f64, m: &Message, sent: bool) -> std::io::Result<()> {
        let body = serde_json::to_value(m).map_err(std::io::Error::other)?;
        let kind = format!("{}/{}", if sent { "sent" } else { "heard" }, m.kind.key());
        self.log()?
            .message(t, m.uav, &kind, &body)
            .map_err(std::io::Error::other)
    }

    fn pose(&mut self, t: f64, (x, y, z): (f64, f64, f64)) -> std::io::Result<()> {
        let period = 1.0 / mason_report::POSE_RATE_HZ;
        let due = self.pose_due || self.last.is_none_or(|(t0, _)| t - t0 >= period);
        if !due {
            return Ok(());
        }
        if let Some((_, (x0, y0, _))) = self.last {
            if (x - x0).hypot(y - y0) > 1e-6 {
                self.yaw = (y - y0).atan2(x - x0);
            }
        }
        self.last = Some((t, (x, y, z)));
        self.pose_due = false;
        let (uav, yaw) = (self.uav, self.yaw);
        self.log()?
            .pose(t, uav, mason_report::UavPose { x, y, z, yaw })
            .map_err(std::io::Error::other)
    }

    fn finish(&mut self) -> std::io::Result<()> {
        match self.log.take() {
            Some(log) => {
                let mut out = log.finish().map_err(std::io::Error::other)?;
                std::io::Write::flush(&mut out)
            }
            None => Ok(()),
        }
    }
}

impl AgentLog for Vec<Event> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.push(*e);
        Ok(())
    }
}

/// The trace file: one [`Event`] as JSON per line, written and flushed line by line so that
/// an agent killed mid-mission leaves every event but at most a truncated last line.
pub struct JsonLines(pub std::fs::File);

impl AgentLog for JsonLines {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        let mut line = serde_json::to_vec(e).map_err(std::io::Error::other)?;
        line.push(b'\n');
        self.0.write_all(&line)?;
        self.0.flush()
    }
}

/// Logs to none, one or several logs.
impl AgentLog for Vec<Box<dyn AgentLog + '_>> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.event(e))
    }
    fn message(&mut self, t: f64, m: &Message, sent: bool) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.message(t, m, sent))
    }
    fn pose(&mut self, t: f64, p: (f64, f64, f64)) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.pose(t, p))
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.finish())
    }
}

/// How a drive ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// The UAV is on the ground for good (landed, or down).
    Finished,
    /// Mission time ran past `max_time_s`.
    Timeout,
    /// Asked to stop (Ctrl-C, SIGTERM).
    Interrupted,
}

/// After it has finished, an agent repeats its last message this many heartbeats, so that a
/// teammate on a lossy link still hears that it landed.
pub const LAST_WORD_REPEATS: u32 = 3;

/// The longest a driver sleeps at once (wall), to notice a stop request.
const POLL: Duration = Duration::from_millis(100);

/// Runs `agent` on `clock` and `transport` until it finishes, mission time passes `max_time`,
/// or `stop` is set. Messages heard before mission time 0 are dropped; the agent's events go
/// to `log` as they happen.
pub fn drive(
    agent: &mut Agent<'_>,
    transport: &mut dyn Transport,
    clock: &dyn Clock,
    log: &mut dyn AgentLog,
    max_time: f64,
    heartbeat_s: f64,
    stop: &AtomicBool,
) -> std::io::Result<Ending> {
    // Before the start: wait, and drop what is heard.
    while clock.now() < 0.0 {
        if stop.load(Ordering::Relaxed) {
            return Ok(Ending::Interrupted);
        }
        let deadline = clock.instant_at(0.0).min(Instant::now() + POLL);
        transport.recv(deadline);
    }
    let mut last: Option<Message> = None;
    loop {
        if stop.load(Ordering::Relaxed) {
            return Ok(Ending::Interrupted);
        }
        let now = clock.now();
        if now > max_time {
            return Ok(Ending::Timeout);
        }
        let tick = agent.tick(now);
        for e in &tick.events {
            log.event(e)?;
        }
        for m in &tick.messages {
            transport.send(m);
            log.message(now, m, true)?;
        }
        log.pose(now, agent.pose(now))?;
        if let Some(m) = tick.messages.last() {
            last = Some(m.clone());
        }
        if agent.finished() {
            last_words(transport, clock, last.as_ref(), heartbeat_s, stop);
            return Ok(Ending::Finished);
        }
        let idle = tick.messages.is_empty() && tick.events.is_empty() && tick.wake <= now;
        let mut deadline = clock
            .instant_at(tick.wake.min(max_time + heartbeat_s))
            .min(Instant::now() + POLL);
        if idle {
            // Nothing happened and it asks to be woken now: do not spin.
            deadline = deadline.max(Instant::now() + Duration::from_millis(1));
        }
        let heard = transport.recv(deadline);
        if !heard.is_empty() {
            let now = clock.now();
            for m in heard {
                log.message(now, &m, false)?;
                agent.receive(now, m);
            }
        }
    }
}

/// Repeats the last message [`LAST_WORD_REPEATS`] times, a heartbeat apart (duplicates are
/// ignored by whoever heard it already).
fn last_words(
    transport: &mut dyn Transport,
    clock: &dyn Clock,
    last: Option<&Message>,
    heartbeat_s: f64,
    stop: &AtomicBool,
) {
    let Some(m) = last else { return };
    let mut at = clock.now();
    for _ in 0..LAST_WORD_REPEATS {
        at += heartbeat_s;
        while Instant::now() < clock.instant_at(at) && !stop.load(Ordering::Relaxed) {
            let deadline = clock.instant_at(at).min(Instant::now() + POLL);
            transport.recv(deadline);
        }
        transport.send(m);
    }
}

/// The agent setup of `team` for UAV `uav`.
pub fn setup<'a>(team: &'a Team, uav: usize, mission: &'a str, incarnation: u64) -> AgentSetup<'a> {
    AgentSetup {
        wall: &team.wall,
        order: &team.order,
        assignment: None,
        model: &team.model,
        config: &team.config,
        coord: team.coord,
        slot_s: team.slot,
        uav,
        mission,
        incarnation,
        dead_after_s: team.dead_after,
        lease_s: DEFAULT_LEASE_S,
    }
}

/// The seed of UAV `uav`'s vehicle and fault layer in incarnation `incarnation`.
pub fn agent_seed(seed: u64, uav: usize, incarnation: u64) -> u64 {
    seed ^ (uav as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ incarnation.wrapping_mul(0x2545_f491_4f6c_dd1d)
}

/// Exit code of an agent interrupted by a signal (as shells report SIGINT).
pub const INTERRUPTED: u8 = 130;

/// `mason agent`: checks everything, joins the team over Zenoh, flies, and reports.
#[cfg(feature = "zenoh")]
pub fn run(a: AgentArgs, quiet: bool) -> CliResult<()> {
    use crate::fail::{no_solution, Failure};
    use crate::transport::{unix_now, FaultLayer, MissionClock};
    use mason_mission::agent::SimulatedVehicle;
    use std::sync::Arc;

    let net = a.network()?;
    let team = a.team.resolve()?;
    a.check(&team)?;
    let trace_file = match &a.trace {
        Some(p) => Some(
            std::fs::File::create(p).map_err(|e| input_error(format!("{}: {e}", p.display())))?,
        ),
        None => None,
    };
    let mcap_file = match &a.mcap {
        Some(p) => Some(
            std::fs::File::create(p).map_err(|e| input_error(format!("{}: {e}", p.display())))?,
        ),
        None => None,
    };
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        // A second handler cannot be set in one process; only `run` sets one.
        ctrlc::set_handler(move || stop.store(true, Ordering::Relaxed))
            .map_err(|e| input_error(format!("cannot handle Ctrl-C: {e}")))?;
    }
    let link = crate::zenoh_link::ZenohLink::open(&net, a.uav)?;
    let start_at = a.start_at.unwrap_or_else(unix_now);
    let clock = MissionClock::new(start_at, team.speed);
    let seed = agent_seed(team.seed, a.uav, a.incarnation);
    let mut transport = FaultLayer::new(link, clock, team.link.clone(), seed);
    let mut vehicle = SimulatedVehicle::new(&team.config, seed);
    if let Some(dir) = &a.world {
        let world = crate::world::TraceWorld::new(dir.clone(), team.wall.len());
        vehicle = vehicle.with_world(Arc::new(world));
    }
    let mut agent = Agent::new(
        setup(&team, a.uav, &net.mission, a.incarnation),
        Box::new(vehicle),
    );
    agent.remember(&crate::world::placed_by(a.uav, &a.remember)?);
    let mut logs: Vec<Box<dyn AgentLog + '_>> = Vec::new();
    if let Some(f) = trace_file {
        logs.push(Box::new(JsonLines(f)));
    }
    let meta = mason_report::LogMeta {
        mission_id: &net.mission,
        uavs: team.config.uavs,
        arena: &team.config.arena,
        wall: &team.wall,
    };
    if let Some(f) = mcap_file {
        let log = McapAgentLog::new(f, &meta, a.uav).map_err(|e| {
            input_error(format!(
                "{}: {e}",
                a.mcap.as_ref().expect("given").display()
            ))
        })?;
        logs.push(Box::new(log));
    }
    let started = Instant::now();
    let ending = drive(
        &mut agent,
        &mut transport,
        &clock,
        &mut logs,
        team.config.max_time_s,
        team.config.coord.heartbeat_s,
        &stop,
    )
    .and_then(|ending| logs.finish().map(|()| ending))
    .map_err(|e| input_error(format!("trace: {e}")))?;
    let stats = transport.stats;
    transport.into_inner().close();
    if !quiet {
        eprintln!(
            "mason agent: UAV {} ({}), {:?} at mission time {:.1} s after {:.1} s wall; sent {}, heard {}, cut {}, dropped {}, duplicated {}; {} bricks known placed",
            a.uav,
            net.mission,
            ending,
            clock.now(),
            started.elapsed().as_secs_f64(),
            stats.sent,
            stats.received,
            stats.cut,
            stats.dropped,
            stats.duplicated,
            agent.placed_known()
        );
    }
    match ending {
        Ending::Finished => Ok(()),
        Ending::Timeout => Err(no_solution(format!(
            "UAV {}: mission time passed max_time_s {} before it landed",
            a.uav, team.config.max_time_s
        ))),
        Ending::Interrupted => Err(Failure {
            code: INTERRUPTED,
            message: format!("UAV {}: interrupted", a.uav),
        }),
    }
}

/// Without the `zenoh` feature there is no transport: exit 2 with a hint.
#[cfg(not(feature = "zenoh"))]
pub fn run(_: AgentArgs, _: bool) -> CliResult<()> {
    Err(crate::fail::input_error(
        "mason agent needs the zenoh feature: cargo build --release --features zenoh",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::{FaultLayer, Hub, MissionClock};
    use mason_mission::agent::SimulatedVehicle;
    use mason_mission::check_trace;

    fn team(name: &str, coord: &str, speed: f64) -> Team {
        let args = TeamArgs {
            design: DesignArgs {
                design: format!("builtin:{name}"),
                format: crate::input::Format::Auto,
                cmcp_sizes: crate::input::Sizes::Yaml,
                strict: false,
            },
            uavs: 3,
            coord: coord.into(),
            planner: "exact".into(),
            model: None,
            mission_config: None,
            slot: None,
            speed,
            seed: 1,
            grasp_fail: None,
            detect_fail: None,
            dead_after: None,
            drop: None,
            duplicate: None,
            delay_jitter: None,
            cut: vec![],
        };
        args.resolve().expect("a good team")
    }

    /// Three agents on threads, an in-memory bus, the real clock at `speed`.
    fn fly_threads(team: &Team, faults: LinkFaults) -> Vec<Event> {
        let start = crate::transport::unix_now() + 0.05;
        let stop = AtomicBool::new(false);
        let links = Hub::new(3).links();
        let traces: Vec<Vec<Event>> = std::thread::scope(|s| {
            let handles: Vec<_> = links
                .into_iter()
                .enumerate()
                .map(|(u, link)| {
                    let (stop, faults) = (&stop, faults.clone());
                    s.spawn(move || {
                        let clock = MissionClock::new(start, team.speed);
                        let seed = agent_seed(team.seed, u, 1);
                        let mut t = FaultLayer::new(link, clock, faults, seed);
                        let v = SimulatedVehicle::new(&team.config, seed);
                        let mut agent = Agent::new(setup(team, u, "test", 1), Box::new(v));
                        let mut log: Vec<Event> = Vec::new();
                        let end =
                            drive(&mut agent, &mut t, &clock, &mut log, 7200.0, 1.0, stop).unwrap();
                        assert_eq!(end, Ending::Finished, "UAV {u}");
                        log
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let mut all: Vec<Event> = traces.into_iter().flatten().collect();
        all.sort_by(|a, b| a.t.total_cmp(&b.t));
        all
    }

    fn placed(events: &[Event]) -> usize {
        events
            .iter()
            .filter(|e| matches!(e.kind, mason_mission::EventKind::Place { .. }))
            .count()
    }

    #[test]
    fn three_threads_on_a_real_clock_build_the_wall() {
        let team = team("thesis-2x5", "auto", 200.0);
        let events = fly_threads(&team, LinkFaults::default());
        check_trace(&team.wall, 3, &events).expect("a safe trace");
        assert_eq!(placed(&events), team.wall.len());
    }

    #[test]
    fn the_fault_layer_does_no_harm_to_the_driver() {
        let team = team("thesis-2x5", "comm", 200.0);
        let faults = LinkFaults {
            drop: 0.3,
            duplicate: 0.2,
            delay_jitter: 0.5,
            cuts: vec![],
        };
        let events = fly_threads(&team, faults);
        check_trace(&team.wall, 3, &events).expect("a safe trace");
        assert_eq!(placed(&events), team.wall.len());
    }

    #[test]
    fn endpoints_are_checked() {
        assert!(check_endpoint("--listen", "tcp/127.0.0.1:0", true).is_ok());
        assert!(check_endpoint("--connect", "tcp/[::1]:7447", false).is_ok());
        for bad in [
            "127.0.0.1:7447",
            "quic/1.2.3.4:5",
            "tcp/127.0.0.1",
            "tcp/:7447",
            "tcp/h:99999",
            "tcp/h:0",
        ] {
            let e = check_endpoint("--connect", bad, false).unwrap_err();
            assert_eq!(e.code, 2);
            assert!(e.message.contains(bad), "{}", e.message);
        }
    }

    #[test]
    fn windows_and_times_are_checked() {
        assert_eq!(
            parse_window("--cut", "100-125").unwrap(),
            Window {
                from: 100.0,
                to: 125.0
            }
        );
        for bad in ["100", "125-100", "a-b", "-5-10", "10-inf"] {
            assert!(parse_window("--cut", bad).is_err(), "{bad}");
        }
        assert_eq!(parse_at("--kill", "1@300", 3).unwrap(), (1, 300.0));
        assert!(parse_at("--kill", "3@300", 3).is_err());
        assert!(parse_at("--kill", "1@-3", 3).is_err());
    }
}
