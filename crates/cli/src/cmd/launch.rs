//! `mason launch`: one `mason agent` process per UAV on this machine ([`mason_fleet::launch`]),
//! kills and restarts, then the merged trace checked, summarised and written.
//!
//! Exit codes: 0 the wall is finished and the merged trace passes `check_trace`; 1 it passes
//! but the wall is unfinished; 2 bad input; 3 the merged trace fails `check_trace` (or a trace
//! file cannot be read); 130 interrupted.

use crate::cmd::agent::FleetArgs;
use crate::cmd::plan::pretty;
use crate::fail::{input_error, no_solution, CliResult, Failure, INTERRUPTED, UNSAFE};
use mason_fleet::LaunchOptions;
use mason_mission::CommMode;
use mason_report::text::clock;
use std::path::PathBuf;

/// `mason launch`'s options.
#[derive(clap::Args)]
pub struct LaunchArgs {
    #[command(flatten)]
    pub fleet: FleetArgs,
    /// Kill UAV U's agent (SIGKILL) at mission time T, as U@T; repeatable
    #[arg(long)]
    pub kill: Vec<String>,
    /// Start UAV U's agent again at mission time T (after a --kill), as U@T; repeatable
    #[arg(long)]
    pub restart: Vec<String>,
    /// Output folder: the agents' traces and logs, and the merged trace (trace.json)
    #[arg(long, default_value = "mason-out/launch")]
    pub out: PathBuf,
    /// Agent U listens on 127.0.0.1:P+U (quic/, tls/ or, with --insecure, tcp/; default: free
    /// ports)
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
    /// Also write the merged trace as a ROS 2 bag in this folder (made if missing; see
    /// `simulate --rosbag`)
    #[arg(long)]
    pub rosbag: Option<PathBuf>,
    /// Plain TCP without authentication, for a trusted bench (by default the launch makes a
    /// mission authority in OUT/authority and one TLS set per UAV in OUT/uav-<i>, and the
    /// agents talk over mutual TLS, in QUIC, with access control)
    #[arg(long)]
    pub insecure: bool,
    /// The link that carries mutual TLS: quic (TLS 1.3 in QUIC over UDP, the default) or tls
    /// (TLS over TCP; Zenoh 1.10.2's TLS link has a data race that now and then crashes an
    /// agent with SIGILL, see the README's "Why QUIC")
    #[arg(long, value_enum, default_value_t = Link::Quic, conflicts_with = "insecure")]
    pub link: Link,
    /// Ground stations to make TLS files for, in OUT/station-<s>
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub stations: usize,
}

/// `--link`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Link {
    /// TLS 1.3 inside QUIC (UDP)
    Quic,
    /// TLS over TCP
    Tls,
}

/// Parses `U@T` values of `flag` for a team of `uavs`.
fn at_times(flag: &str, values: &[String], uavs: usize) -> CliResult<Vec<(usize, f64)>> {
    values
        .iter()
        .map(|s| {
            let (u, t) = mason_io::parse_at(flag, s)?;
            mason_io::check_uav(flag, s, u, uavs)?;
            Ok((u, t))
        })
        .collect()
}

/// `mason launch`.
pub fn run(a: LaunchArgs, quiet: bool) -> CliResult<()> {
    if !cfg!(feature = "zenoh") {
        return Err(input_error(
            "mason launch needs the zenoh feature: cargo build --release --features zenoh",
        ));
    }
    let setting = a.fleet.resolve()?;
    crate::cmd::rosbag::check(&a.rosbag)?;
    let n = setting.config.uavs;
    let opts = LaunchOptions {
        exe: std::env::current_exe()
            .map_err(|e| input_error(format!("cannot find the mason binary: {e}")))?,
        agent_args: a.fleet.to_args(),
        out: a.out.clone(),
        base_port: a.base_port,
        mission: a.mission.clone(),
        prefix: a.prefix.clone(),
        lead: a.lead,
        kills: at_times("--kill", &a.kill, n)?,
        restarts: at_times("--restart", &a.restart, n)?,
        insecure: a.insecure,
        link: match a.link {
            Link::Quic => mason_fleet::SecureLink::Quic,
            Link::Tls => mason_fleet::SecureLink::Tls,
        },
        stations: a.stations,
    };
    let interrupted = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    #[cfg(feature = "zenoh")]
    {
        let flag = interrupted.clone();
        let _ = ctrlc::set_handler(move || flag.store(true, std::sync::atomic::Ordering::Relaxed));
    }
    let mut started = |line: String| {
        if !quiet {
            eprintln!("mason launch: {line}");
        }
    };
    let done = mason_fleet::launch(&setting, &opts, &interrupted, &mut started)?;
    let out_file = a.out.join("trace.json");
    let doc = done.to_json(&setting);
    crate::fail::write_file(&out_file, pretty(&doc).as_bytes())?;
    if let Some(dir) = &a.rosbag {
        let rejected: std::collections::BTreeMap<String, u64> =
            serde_json::from_value(doc["summary"]["dropped"].clone()).unwrap_or_default();
        let src = mason_report::BagMeta {
            uavs: n,
            arena: &setting.config.arena,
            wall: &setting.wall,
            mode: crate::cmd::rosbag::start_mode(setting.coord),
            rejected: &rejected,
        };
        crate::fail::write_all(&crate::cmd::rosbag::files(
            dir,
            &src,
            &done.events,
            done.end(),
        )?)?;
    }
    let total = setting.wall.len();
    let placed = done.placed();
    let makespan = done.makespan(total);
    println!(
        "{}: {n} agents, coord {}, speed {}, mission {}",
        setting.wall.name(),
        crate::cmd::simulate::coord_name(setting.coord),
        setting.speed,
        done.mission
    );
    println!("bricks placed: {placed}/{total}");
    println!(
        "makespan: {}; mission end {}",
        makespan.map_or("-".into(), clock),
        clock(done.end())
    );
    let (w, c) = (
        done.switches(CommMode::Windows),
        done.switches(CommMode::Comm),
    );
    if w + c > 0 {
        println!("coordination switches: {w} to windows, {c} to comm");
    }
    for r in &done.runs {
        println!(
            "  UAV {} incarnation {}: {}{}",
            r.uav,
            r.incarnation,
            r.exit.as_deref().unwrap_or("-"),
            r.killed_at
                .map_or(String::new(), |t| format!(" at mission time {t:.1} s"))
        );
    }
    let violation = done.verdict.as_ref().err().map(|e| e.to_string());
    println!(
        "check_trace: {}",
        violation
            .as_deref()
            .unwrap_or("passed (zone, precedence, every brick accounted for)")
    );
    match &done.authority {
        Some(dir) => println!(
            "security: mutual TLS {}, mission authority {}",
            opts.link.carrier(),
            dir.display()
        ),
        None => println!("security: INSECURE (plain TCP, no authentication)"),
    }
    println!(
        "wall time: {:.1} s; merged trace: {}",
        done.wall_s,
        out_file.display()
    );
    if let Some(v) = violation {
        return Err(Failure {
            code: UNSAFE,
            message: format!("the merged trace fails check_trace: {v}"),
        });
    }
    if done.interrupted {
        return Err(Failure {
            code: INTERRUPTED,
            message: "interrupted".into(),
        });
    }
    if placed != total {
        return Err(no_solution(format!(
            "the wall is unfinished: {placed}/{total} bricks placed"
        )));
    }
    Ok(())
}
