//! `mason agent`: one UAV as its own process, on the agent runtime ([`mason_fleet`]): the team
//! options ([`FleetArgs`], shared with `mason launch`, which passes them on to every agent it
//! starts) and this agent's own ([`AgentArgs`]).

use crate::cmd::mission::MissionArgs;
use crate::fail::{input_error, CliResult};
use mason_fleet::{AgentOptions, FleetSetting, Network, NetworkFlags};
use mason_mission::{Coord, LinkFaults};
use mason_order::Status;
use std::path::{Path, PathBuf};

/// The options every agent of a team shares (`mason agent` and `mason launch`).
#[derive(clap::Args, Clone)]
pub struct FleetArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// Arena, UAV model, coordination timings and max_time_s from a TOML file (as
    /// `simulate --mission`)
    #[arg(long)]
    pub mission_config: Option<PathBuf>,
    /// Mission clock speed: K mission seconds per wall second
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub speed: f64,
    /// Seed of the simulated vehicle and of the transport faults (mixed with the UAV number
    /// and incarnation)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// A teammate unheard this long (mission s) is declared out by a majority (default 30 s,
    /// or the wall's longest zone time plus five heartbeats if that is longer; a shorter one
    /// is refused, since no agent could then enter the zone for the longest brick)
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

impl FleetArgs {
    /// Checks every option and plans the shared order (exit 2 on bad input).
    pub fn resolve(&self) -> CliResult<FleetSetting> {
        let link = LinkFaults {
            loss: self.drop.unwrap_or(0.0),
            duplicate: self.duplicate.unwrap_or(0.0),
            latency: 0.0,
            jitter: self.delay_jitter.unwrap_or(0.0),
            cuts: self
                .cut
                .iter()
                .map(|s| mason_io::parse_window("--cut", s))
                .collect::<Result<_, _>>()?,
        };
        let file = self.mission_config.as_deref();
        let m = self.mission.resolve(file, None, Coord::Auto)?;
        if let Some(p) = file {
            let f = &m.config.faults;
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
        if m.plan.outcome.status == Status::Timeout {
            return Err(input_error(format!(
                "--planner {} stopped at its time limit: the agents could disagree on the order (use a faster planner, e.g. greedy)",
                m.spec
            )));
        }
        let setting = FleetSetting {
            wall: m.wall,
            model: m.model,
            order: m.order,
            config: m.config,
            coord: m.coord,
            slot: m.slot,
            speed: self.speed,
            seed: self.seed,
            dead_after: 0.0,
            link,
        };
        let dead_after = self.dead_after.unwrap_or_else(|| {
            mason_fleet::default_dead_after(&setting.wall, &setting.model, &setting.config)
        });
        let setting = FleetSetting {
            dead_after,
            ..setting
        };
        setting.check()?;
        Ok(setting)
    }

    /// The same options as command-line arguments, for an agent process.
    pub fn to_args(&self) -> Vec<String> {
        let m = &self.mission;
        let d = &m.design;
        let mut a: Vec<String> = vec![d.design.clone()];
        let mut opt = |k: &str, v: String| {
            a.push(k.to_string());
            a.push(v);
        };
        opt("--format", value_name(&d.format));
        opt("--cmcp-sizes", value_name(&d.cmcp_sizes));
        opt("--uavs", m.uavs.to_string());
        if let Some(c) = &m.coord {
            opt("--coord", c.clone());
        }
        opt("--planner", m.planner.clone());
        opt("--speed", self.speed.to_string());
        opt("--seed", self.seed.to_string());
        let path = |p: &Path| p.to_string_lossy().into_owned();
        if let Some(p) = &m.model {
            opt("--model", path(p));
        }
        if let Some(p) = &self.mission_config {
            opt("--mission-config", path(p));
        }
        for (k, v) in [
            ("--slot", m.slot),
            ("--grasp-fail", m.grasp_fail),
            ("--detect-fail", m.detect_fail),
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
    pub fleet: FleetArgs,
    /// This UAV (0-based)
    #[arg(long, allow_negative_numbers = true)]
    pub uav: usize,
    /// The mission id: every message carries it, and its key starts with it
    #[arg(long)]
    pub mission: Option<String>,
    /// Mission time 0 as Unix seconds (default: now; at most a day ahead); before it the
    /// agent waits
    #[arg(long, allow_negative_numbers = true)]
    pub start_at: Option<f64>,
    /// Zenoh endpoint to listen on, e.g. quic/127.0.0.1:7447 (tls/ also carries mutual TLS;
    /// tcp/ and udp/ need --insecure); repeatable
    #[arg(long)]
    pub listen: Vec<String>,
    /// Zenoh endpoint of a teammate to connect to; repeatable
    #[arg(long)]
    pub connect: Vec<String>,
    /// Key prefix: messages go to PREFIX/MISSION/UAV/KIND (default mason)
    #[arg(long)]
    pub prefix: Option<String>,
    /// Network options from a TOML file: mission, prefix, listen, connect, tls_dir (relative
    /// to the file), insecure (flags add to the lists and override the rest)
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// This UAV's folder of TLS files from its mission authority: ca.pem, cert.pem, key.pem
    /// (made by `mason keys`, or `mason launch` in OUT/uav-<i>); endpoints are quic/HOST:PORT
    /// (TLS 1.3 in QUIC, as `mason launch` uses) or tls/HOST:PORT (TLS over TCP)
    #[arg(long)]
    pub tls_dir: Option<PathBuf>,
    /// Plain links (tcp/, udp/) without authentication, for a trusted bench: any peer on the
    /// network can then speak for any UAV
    #[arg(long)]
    pub insecure: bool,
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

#[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
impl AgentArgs {
    /// The network options: the file's, with the flags on top; every one checked.
    pub fn network(&self) -> CliResult<Network> {
        let flags = NetworkFlags {
            mission: self.mission.clone(),
            prefix: self.prefix.clone(),
            listen: self.listen.clone(),
            connect: self.connect.clone(),
            tls_dir: self.tls_dir.clone(),
            insecure: self.insecure,
        };
        Ok(Network::resolve(self.config.as_deref(), &flags)?)
    }

    /// This agent's own options.
    pub fn options(&self) -> AgentOptions {
        AgentOptions {
            uav: self.uav,
            incarnation: self.incarnation,
            start_at: self.start_at,
            trace: self.trace.clone(),
            mcap: self.mcap.clone(),
            remember: self.remember.clone(),
            world: self.world.clone(),
        }
    }
}

/// `mason agent`: checks everything, joins the team over Zenoh, flies, and reports.
#[cfg(feature = "zenoh")]
pub fn run(a: AgentArgs, quiet: bool) -> CliResult<()> {
    use crate::fail::{no_solution, Failure, INTERRUPTED};
    use mason_fleet::{fly_agent, Ending, ZenohLink};
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;

    let net = a.network()?;
    let setting = a.fleet.resolve()?;
    let opts = a.options();
    opts.check(&setting)?;
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        // A second handler cannot be set in one process; only `run` sets one.
        ctrlc::set_handler(move || stop.store(true, Ordering::Relaxed))
            .map_err(|e| input_error(format!("cannot handle Ctrl-C: {e}")))?;
    }
    let uavs = setting.config.uavs;
    let max_sample = mason_mission::agent::max_message_bytes(setting.wall.len(), uavs);
    let mut link = ZenohLink::open(&net, a.uav, uavs, max_sample)?;
    if !quiet {
        match &net.security {
            mason_fleet::Security::Tls(d) => eprintln!(
                "mason agent: UAV {} ({}): mutual TLS with the keys of {}",
                a.uav,
                net.mission,
                d.display()
            ),
            mason_fleet::Security::Insecure => {}
        }
    }
    if net.security == mason_fleet::Security::Insecure {
        eprintln!(
            "mason agent: warning: UAV {} ({}) is insecure (--insecure): plain links, no authentication; any peer on the network can speak for any UAV",
            a.uav, net.mission
        );
    }
    // The wall, for clients that are not teammates (the ROS 2 bridge).
    link.serve_scene(&mason_report::wall_scene_json(
        &setting.config.arena,
        &setting.wall,
    ))?;
    let report = fly_agent(&setting, &net, &opts, &mut link, &stop);
    link.close();
    let report = report?;
    if let Some(p) = &report.world_problem {
        eprintln!("mason agent: warning: the simulated camera skipped a trace: {p}");
    }
    if report.drops.total() > 0 {
        // One line launch reads back into its summary.
        eprintln!(
            "{}{}",
            mason_fleet::DROPPED_LINE,
            serde_json::to_string(&report.drops).unwrap_or_default()
        );
    }
    if !quiet {
        let s = report.stats;
        eprintln!(
            "mason agent: UAV {} ({}), {:?} at mission time {:.1} s after {:.1} s wall; sent {}, heard {}, cut {}, dropped {}, duplicated {}; {} bricks known placed",
            a.uav,
            net.mission,
            report.ending,
            report.mission_time,
            report.wall_s,
            s.sent,
            s.received,
            s.cut,
            s.dropped,
            s.duplicated,
            report.placed_known
        );
    }
    match report.ending {
        Ending::Finished => Ok(()),
        Ending::Timeout => Err(no_solution(format!(
            "UAV {}: mission time passed max_time_s {} before it landed",
            a.uav, setting.config.max_time_s
        ))),
        Ending::Flooded => Err(input_error(format!(
            "UAV {}: stopped at mission time {:.1} s past its event cap ({} events; 100 000 + 100 \
             per second of mission time): a duration in the mission or the model is too short \
             to make progress",
            a.uav,
            report.mission_time,
            mason_mission::event_cap(1, report.mission_time)
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
    Err(input_error(
        "mason agent needs the zenoh feature: cargo build --release --features zenoh",
    ))
}
