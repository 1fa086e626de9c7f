//! `mason bench SUITE`: the suites of [`mason_bench`], each with its own options.

use crate::cmd::plan::time_limit;
use crate::fail::{input_error, CliResult};
use std::path::PathBuf;

/// `--runs`, checked: at least 1.
fn runs(n: usize) -> CliResult<usize> {
    if n == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    Ok(n)
}

/// The bench suites.
#[derive(clap::Subcommand)]
pub enum Suite {
    /// The thesis's Tables 3.3–3.5 beside ours, planner by planner
    Thesis {
        /// Seconds brute force and improved greedy may search per wall
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        time_limit: f64,
    },
    /// Whole-process time of `mason plan --planner exact` on 50- and 5 000-brick walls
    Planning {
        /// Runs per wall
        #[arg(long, default_value_t = 20, allow_negative_numbers = true)]
        runs: usize,
    },
    /// The crew paper's Table 1 example and Table 2 setting, and the MovingAI warehouse
    Paper {
        /// Random instances per robot count
        #[arg(long, default_value_t = 20, allow_negative_numbers = true)]
        runs: usize,
    },
    /// The thesis's Table 5.1 setting: the 2×5 wall, 3 UAVs, three planners, comm and windows
    ThesisMission {
        /// Monte Carlo runs per row (at least 100 are flown)
        #[arg(long, default_value_t = 100, allow_negative_numbers = true)]
        runs: usize,
    },
    /// Simulator throughput on the 42-brick wall
    Missions {
        /// Thousands of missions per row
        #[arg(long, default_value_t = 20, allow_negative_numbers = true)]
        runs: usize,
    },
    /// Team schedules on the CMCP walls beside GRASP's published runs
    Cmcp {
        /// The benchmark directory holding config/ and GRASP-RESULTS.md (default
        /// ../shared/benchmarks/walls-cmcp)
        #[arg(long)]
        data: Option<PathBuf>,
    },
    /// Static against re-planned team schedules under UAV failures
    Replan {
        /// Fifties of missions per policy (20: 1000)
        #[arg(long, default_value_t = 20, allow_negative_numbers = true)]
        runs: usize,
    },
    /// The cost of an agent's check on arrival, per message (issue #27: under 5 µs)
    Arrivals {
        /// Hundred thousands of checks per row
        #[arg(long, default_value_t = 10, allow_negative_numbers = true)]
        runs: usize,
    },
    /// MovingAI maps at rising agent counts: lacam and joint, one child `mason crew` per case
    Mapf {
        /// The directory holding maps/ and scen/ (default ../shared/benchmarks/mapf)
        #[arg(long)]
        data: Option<PathBuf>,
        /// The long sweep (more maps, 30 s per case) instead of the default few minutes
        #[arg(long)]
        long: bool,
    },
}

/// The `mason` program itself, for the suites that run it as child processes.
fn this_program() -> CliResult<PathBuf> {
    std::env::current_exe().map_err(|e| input_error(format!("cannot find the mason program: {e}")))
}

/// Runs one suite and prints its table.
pub fn run(suite: Suite, quiet: bool) -> CliResult<()> {
    let text = match suite {
        Suite::Thesis { time_limit: t } => {
            mason_bench::thesis(time_limit(Some(t))?.unwrap_or(60.0))?
        }
        Suite::Planning { runs: n } => mason_bench::planning(&this_program()?, runs(n)?)?,
        Suite::Paper { runs: n } => {
            let n = runs(n)?;
            let bar = crate::progress::bar(
                (mason_bench::PAPER_ROBOTS.len() * n) as u64,
                "bench paper",
                !quiet,
            );
            let text = mason_bench::paper(n, &|| bar.inc(1))?;
            bar.finish_and_clear();
            text
        }
        Suite::ThesisMission { runs: n } => mason_bench::thesis_mission(runs(n)?.max(100))?,
        Suite::Missions { runs: n } => mason_bench::throughput(runs(n)?)?,
        Suite::Cmcp { data } => mason_bench::cmcp(data.as_deref(), None)?,
        Suite::Replan { runs: n } => mason_bench::replan(runs(n)? * 50)?,
        Suite::Arrivals { runs: n } => mason_bench::arrivals(runs(n)?)?,
        Suite::Mapf { data, long } => {
            let mut note = |line: &str| {
                if !quiet {
                    eprintln!("{line}");
                }
            };
            mason_bench::mapf(&this_program()?, data.as_deref(), long, &mut note)?
        }
    };
    print!("{text}");
    Ok(())
}
