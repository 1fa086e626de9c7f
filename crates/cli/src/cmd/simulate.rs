//! `mason simulate`: fly a build order with a UAV team, once or as a Monte Carlo batch.

use crate::cmd::mission::MissionArgs;
use crate::cmd::plan::pretty;
use crate::cmd::schedule::{flight_plan, ScheduleRequest};
use crate::fail::{check_outputs, input_error, no_solution, write_all, CliResult, Failure};
use mason_io::FaultSpec;
use mason_mission::{
    for_each_run, run_many, Coord, Event, MissionInput, MissionResult, MissionStatus, Summariser,
    TraceError,
};
use mason_report::text::{policy_table, result_table, summary_table, PolicyRow};
use std::path::PathBuf;

/// `mason simulate`'s options.
#[derive(clap::Args)]
pub struct SimArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// Fly a team schedule instead of a shared order: makespan, reward or expected (see
    /// `mason plan --objective`; the team model is the thesis model of --model's times; expected
    /// takes its failure rate from --uav-hazard). Each UAV takes its own bricks in its own order
    #[arg(long)]
    pub objective: Option<String>,
    /// Budget T in seconds for --objective reward|expected
    #[arg(long, allow_negative_numbers = true)]
    pub budget: Option<f64>,
    /// With --objective: when a UAV fails, the survivors re-plan the rest of the wall (within
    /// 100 ms). With --runs N, flies the static and the re-planned schedule on the same seeds
    /// and compares them
    #[arg(long)]
    pub replan: bool,
    /// UAV U (0-based) fails at T seconds, as U@T; repeatable
    #[arg(long)]
    pub uav_fail: Vec<String>,
    /// UAV failures per hour (each UAV)
    #[arg(long, allow_negative_numbers = true)]
    pub uav_hazard: Option<f64>,
    /// No message gets through from A to B seconds, as A-B; repeatable
    #[arg(long)]
    pub blackout: Vec<String>,
    /// Probability that one message is lost
    #[arg(long, allow_negative_numbers = true)]
    pub msg_loss: Option<f64>,
    /// Message latency in seconds
    #[arg(long, allow_negative_numbers = true)]
    pub latency: Option<f64>,
    /// Faults from a TOML file (keys as the flags, with underscores); flags add to it
    #[arg(long)]
    pub faults: Option<PathBuf>,
    /// Arena, UAV model and coordination settings from a TOML file (see README); its
    /// [faults] are used unless --faults or a fault flag is given
    #[arg(long = "mission")]
    pub mission_file: Option<PathBuf>,
    /// Monte Carlo runs (seeds S, S+1, …), spread over the cores
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub runs: usize,
    /// Seed of the first run
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Draw the mission Gantt chart as SVG (single run)
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Write the self-contained HTML replay (single run)
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Write the run as an MCAP log that Foxglove opens as it is (single run): UAV poses
    /// (foxglove.PoseInFrame, 2 Hz along each leg), states, the wall zone, bricks grasped, placed
    /// and lost, the wall as a 3-D scene (foxglove.SceneUpdate), every event as a log line
    /// (foxglove.Log); JSON messages, mission time in ns (see README)
    #[arg(long)]
    pub mcap: Option<PathBuf>,
    /// Write the run as a ROS 2 bag in this folder (single run; made if missing): rosbag2
    /// metadata.yaml and one MCAP file, CDR messages with ROS 2 message definitions; the
    /// topics of the ROS 2 bridge (see README)
    #[arg(long)]
    pub rosbag: Option<PathBuf>,
}

/// The name of a policy, as on the command line.
pub fn coord_name(c: Coord) -> String {
    format!("{c:?}").to_lowercase()
}

/// `mason simulate`.
pub fn run(a: SimArgs, quiet: bool) -> CliResult<()> {
    check_outputs(&[&a.svg, &a.html, &a.mcap])?;
    crate::cmd::rosbag::check(&a.rosbag)?;
    if a.runs == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    if a.seed.checked_add(a.runs as u64 - 1).is_none() {
        return Err(input_error(format!(
            "--seed {} --runs {}: the seeds would run past {}",
            a.seed,
            a.runs,
            u64::MAX
        )));
    }
    let m = &a.mission;
    let cli_faults = FaultSpec {
        grasp_fail: m.grasp_fail,
        detect_fail: m.detect_fail,
        uav_fail: a.uav_fail.clone(),
        uav_hazard: a.uav_hazard,
        blackout: a.blackout.clone(),
        msg_loss: a.msg_loss,
        latency: a.latency,
    };
    let file_faults = match &a.faults {
        Some(p) => FaultSpec::read_checked(p, m.uavs)?,
        None => FaultSpec::default(),
    };
    let any_fault_option = a.faults.is_some() || !cli_faults.is_empty();
    let faults = file_faults.merged(cli_faults).resolve()?;
    if a.replan && a.objective.is_none() {
        return Err(input_error(
            "--replan re-plans a team schedule: add --objective",
        ));
    }
    if a.objective.is_none() && a.budget.is_some() {
        return Err(input_error(
            "--budget belongs to --objective reward|expected",
        ));
    }
    let replaces_faults = any_fault_option || a.mission_file.is_none();
    let mission = m.resolve(
        a.mission_file.as_deref(),
        replaces_faults.then_some(faults),
        Coord::Comm,
    )?;
    let (wall, model, config, coord, slot) = (
        &mission.wall,
        &mission.model,
        &mission.config,
        mission.coord,
        mission.slot,
    );
    let mut order = mission.order.clone();
    let mut assignment: Option<Vec<Vec<mason_wall::BrickId>>> = None;
    let mut replanner: Option<mason_mission::ScheduleReplanner> = None;
    if let Some(objective) = &a.objective {
        let hazard = if objective == "expected" {
            a.uav_hazard
        } else {
            None
        };
        let req = ScheduleRequest::resolve(objective, m.uavs, a.budget, hazard, a.seed, None)?;
        // The team model comes from --model's times: a bad value names that file.
        let flight = flight_plan(wall, model, &req, &order).map_err(|e| match &m.model {
            Some(p) if e.code == 2 && !e.message.starts_with("internal") => {
                input_error(format!("{} (as a team model): {}", p.display(), e.message))
            }
            _ => e,
        })?;
        if a.replan {
            replanner = Some(mason_mission::ScheduleReplanner::new(
                flight.team,
                req.objective,
                req.budget_s,
                a.seed,
            ));
        }
        order = flight.order;
        assignment = Some(flight.lists);
    }
    let one_mission = [&a.svg, &a.html, &a.mcap, &a.rosbag];
    if a.runs > 1 && one_mission.iter().any(|o| o.is_some()) {
        return Err(input_error(
            "--svg, --html, --mcap and --rosbag show one mission; drop --runs (or use --runs 1 --seed S)",
        ));
    }
    let input = MissionInput {
        wall,
        order: &order,
        model,
        assignment: assignment.as_deref(),
        replanner: replanner
            .as_ref()
            .map(|r| r as &dyn mason_mission::Replanner),
        config,
    };
    let spec = mission.spec;
    let coord_text = coord_name(coord);
    let planner = spec.to_string();
    let setting = mason_report::RunSetting {
        wall,
        uavs: m.uavs,
        coord,
        planner: &planner,
        order: &order,
        seed: a.seed,
        slot_s: slot,
        faults: &config.faults,
    };
    if a.runs == 1 {
        let (r, trace) = fly_once(input, coord, slot, a.seed)?;
        check_replans(replanner.as_ref())?;
        let title = format!(
            "{} — {} UAVs, {}, seed {}",
            wall.name(),
            m.uavs,
            coord_text,
            a.seed
        );
        let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
        if let Some(path) = &a.svg {
            let svg = mason_report::gantt_svg(&title, wall, m.uavs, &trace, r.metrics.end_s);
            files.push((path.clone(), svg.into_bytes()));
        }
        if let Some(path) = &a.html {
            let page = mason_report::mission_replay_html(
                &title,
                wall,
                &config.arena,
                m.uavs,
                &trace,
                r.metrics.end_s,
            );
            files.push((path.clone(), page.into_bytes()));
        }
        if let Some(path) = &a.mcap {
            let mission_id = format!("simulate/{}/seed-{}", wall.name(), a.seed);
            let meta = mason_report::LogMeta {
                mission_id: &mission_id,
                uavs: m.uavs,
                arena: &config.arena,
                wall,
            };
            let bytes = mason_report::mission_mcap(&meta, &trace, r.metrics.end_s)
                .map_err(|e| input_error(format!("internal error: {}: {e}", path.display())))?;
            files.push((path.clone(), bytes));
        }
        if let Some(dir) = &a.rosbag {
            let none = Default::default();
            let src = mason_report::BagMeta {
                uavs: m.uavs,
                arena: &config.arena,
                wall,
                mode: crate::cmd::rosbag::start_mode(coord),
                rejected: &none,
            };
            files.extend(crate::cmd::rosbag::files(
                dir,
                &src,
                &trace,
                r.metrics.end_s,
            )?);
        }
        write_all(&files)?;
        if a.json {
            let v = mason_report::simulate_json(&setting, &r, &trace);
            println!("{}", pretty(&v));
        } else {
            println!(
                "{}: {} UAVs, coord {}, order from {} (seed {})",
                wall.name(),
                m.uavs,
                coord_text,
                spec,
                a.seed
            );
            print!("{}", result_table(&r, &trace));
        }
        return exit_for(&r);
    }
    if input.replanner.is_some() {
        compare_replanning(&a, input, coord, slot, quiet)?;
        return check_replans(replanner.as_ref());
    }
    let pb = crate::progress::bar(a.runs as u64, "simulating", !quiet && !a.json);
    let mut lines = crate::progress::Lines::new("simulating", a.runs as u64, !quiet);
    let summary = fly_summary(
        input,
        coord,
        slot,
        a.seed,
        a.runs,
        None,
        &|| pb.inc(1),
        &mut lines,
    )?
    .summary();
    pb.finish_and_clear();
    if a.json {
        println!("{}", pretty(&mason_report::runs_json(&setting, &summary)));
    } else {
        println!(
            "{}: {} UAVs, coord {}, order from {}, seeds {}..{}",
            wall.name(),
            m.uavs,
            coord_text,
            spec,
            a.seed,
            a.seed + a.runs as u64 - 1
        );
        print!("{}", summary_table(&summary));
    }
    Ok(())
}

/// `simulate --objective … --replan --runs N`: the static and the re-planned schedule on the
/// same seeds.
fn compare_replanning(
    a: &SimArgs,
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    quiet: bool,
) -> CliResult<()> {
    let pb = crate::progress::bar(2 * a.runs as u64, "simulating", !quiet && !a.json);
    let fixed = MissionInput {
        replanner: None,
        ..input
    };
    let mut lines = crate::progress::Lines::new("simulating", 2 * a.runs as u64, !quiet);
    let mut rows = Vec::new();
    for (name, flown) in [("static", fixed), ("replanned", input)] {
        let s = fly_summary(
            flown,
            coord,
            slot,
            a.seed,
            a.runs,
            a.budget,
            &|| pb.inc(1),
            &mut lines,
        )?;
        rows.push(PolicyRow::of_summary(name, &s));
    }
    pb.finish_and_clear();
    if a.json {
        let v = serde_json::json!({
            "wall": input.wall.name(), "uavs": a.mission.uavs, "coord": coord,
            "objective": a.objective, "budget_s": a.budget, "first_seed": a.seed,
            "faults": input.config.faults, "compare": rows,
        });
        println!("{}", pretty(&v));
    } else {
        println!(
            "{}: {} UAVs, coord {}, {} schedule, static vs re-planned on seeds {}..{}",
            input.wall.name(),
            a.mission.uavs,
            coord_name(coord),
            a.objective.as_deref().unwrap_or("-"),
            a.seed,
            a.seed + a.runs as u64 - 1
        );
        print!("{}", policy_table(&rows, a.budget));
    }
    Ok(())
}

/// One checked mission and its trace.
pub fn fly_once(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
) -> CliResult<(MissionResult, Vec<Event>)> {
    mason_mission::fly_checked(input, coord, slot, seed).map_err(|e| trace_failure(None, e))
}

/// A flown mission's failure: a flood ([`TraceError::Flooded`]) is the input's fault (durations
/// too short to make progress, exit 2); any other is a simulator bug that `check_trace` caught.
pub fn trace_failure(seed: Option<u64>, e: TraceError) -> Failure {
    let run = seed.map_or("mission".to_string(), |s| format!("mission seed {s}"));
    match e {
        TraceError::Flooded(f) => {
            input_error(format!("{run}: {f} (the times of --mission and --model)"))
        }
        e => input_error(format!("internal error: {run} failed check_trace: {e}")),
    }
}

/// A Monte Carlo batch, every trace checked.
pub fn fly_many(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
    runs: usize,
) -> CliResult<Vec<MissionResult>> {
    run_many(input, coord, slot, seed, runs, &|| {}).map_err(|(s, e)| trace_failure(Some(s), e))
}

/// A Monte Carlo batch streamed into a [`Summariser`] (memory flat in `runs`), every trace
/// checked; `reward_by_t` also summarises the reward placed by that time. Off a terminal,
/// `lines` reports progress on stderr.
#[allow(clippy::too_many_arguments)]
pub fn fly_summary(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
    runs: usize,
    reward_by_t: Option<f64>,
    progress: &(dyn Fn() + Sync),
    lines: &mut crate::progress::Lines,
) -> CliResult<Summariser> {
    let mut summary = Summariser::new(reward_by_t);
    let mut done = 0u64;
    for_each_run(input, coord, slot, seed, runs, progress, &mut |r| {
        summary.push(r);
        done += 1;
        lines.at(done);
    })
    .map_err(|(s, e)| trace_failure(Some(s), e))?;
    Ok(summary)
}

/// A replan that failed `order::schedule::validate_continuation` is a bug: reported, exit 2.
pub fn check_replans(r: Option<&mason_mission::ScheduleReplanner>) -> CliResult<()> {
    match r.map(|r| r.rejected.load(std::sync::atomic::Ordering::Relaxed)) {
        Some(n) if n > 0 => Err(input_error(format!(
            "internal error: {n} replans failed order::schedule::validate_continuation"
        ))),
        _ => Ok(()),
    }
}

/// Exit 1 when the wall was not completed (single run).
pub fn exit_for(r: &MissionResult) -> CliResult<()> {
    match r.status {
        MissionStatus::Complete => Ok(()),
        MissionStatus::Incomplete => Err(no_solution(format!(
            "mission incomplete: {}/{} bricks placed",
            r.metrics.bricks_placed, r.metrics.bricks_total
        ))),
        MissionStatus::Timeout => Err(no_solution(format!(
            "mission hit the time limit: {}/{} bricks placed",
            r.metrics.bricks_placed, r.metrics.bricks_total
        ))),
        MissionStatus::Flooded => Err(input_error(match r.flood {
            Some(f) => format!("mission: {f}"),
            None => "mission: stopped at its event cap".to_string(),
        })),
    }
}
