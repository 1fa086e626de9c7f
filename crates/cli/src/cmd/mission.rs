//! The options every command that flies a mission shares (`simulate`, `agent`, `launch`),
//! and their one resolution into a checked wall, model, build order, configuration and
//! coordination policy.

use crate::cmd::plan::{exit_for, solve};
use crate::fail::{input_error, CliResult};
use crate::input::DesignArgs;
use mason_mission::{Coord, Faults, MissionConfig};
use mason_order::{BuildProblem, CheckedPlan, CostModel, PlannerSpec};
use mason_wall::{BrickId, Wall};
use std::path::{Path, PathBuf};

use mason_mission::ORDER_TIME_LIMIT_S;

/// The mission options shared by `simulate`, `agent` and `launch`.
#[derive(clap::Args, Clone)]
pub struct MissionArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// Team size
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Coordination: comm (messages; zone requests acknowledged by every teammate), windows
    /// (fixed time slots) or auto (comm, windows while heartbeats are lost). Default: comm
    /// for simulate, auto for agents
    #[arg(long)]
    pub coord: Option<String>,
    /// Planner of the shared build order (see `mason plan`)
    #[arg(long, default_value = "exact")]
    pub planner: String,
    /// Cost model (grasp and placement times, κ)
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Windows slot length in seconds (default 20, raised to the longest zone time)
    #[arg(long, allow_negative_numbers = true)]
    pub slot: Option<f64>,
    /// Probability that one grasp attempt fails
    #[arg(long, allow_negative_numbers = true)]
    pub grasp_fail: Option<f64>,
    /// Probability that one detection attempt fails
    #[arg(long, allow_negative_numbers = true)]
    pub detect_fail: Option<f64>,
}

/// A mission's setting, checked.
pub struct Mission {
    /// The wall.
    pub wall: Wall,
    /// The cost model.
    pub model: CostModel,
    /// The planner of the order.
    pub spec: PlannerSpec,
    /// The planner's checked outcome.
    pub plan: CheckedPlan,
    /// The shared build order.
    pub order: Vec<BrickId>,
    /// Team, arena, UAV model, coordination timings and faults.
    pub config: MissionConfig,
    /// The policy.
    pub coord: Coord,
    /// The windows slot (s).
    pub slot: f64,
}

impl MissionArgs {
    /// Resolves the options: `mission_file` (its flag is `--mission` for simulate and
    /// `--mission-config` for agents) gives the arena, UAV model, timings and faults;
    /// `faults`, when given, replace the file's faults, else the grasp and detection flags
    /// override the file's. Plans and checks the shared order (exit 2 on bad input, 1 when
    /// the planner finds no order).
    pub fn resolve(
        &self,
        mission_file: Option<&Path>,
        faults: Option<Faults>,
        default_coord: Coord,
    ) -> CliResult<Mission> {
        let coord: Coord = match &self.coord {
            Some(c) => c
                .parse()
                .map_err(|e| input_error(format!("--coord: {e}")))?,
            None => default_coord,
        };
        let spec: PlannerSpec = self
            .planner
            .parse()
            .map_err(|e| input_error(format!("--planner: {e}")))?;
        let mut config = match mission_file {
            Some(p) => mason_io::read_mission(p, self.uavs)?,
            None => MissionConfig::default(),
        };
        config.uavs = self.uavs;
        match faults {
            Some(f) => config.faults = f,
            None => {
                if let Some(p) = self.grasp_fail {
                    config.faults.grasp_fail = p;
                }
                if let Some(p) = self.detect_fail {
                    config.faults.detect_fail = p;
                }
            }
        }
        if self.slot.is_some() {
            config.coord.slot_s = self.slot;
        }
        let wall = self.design.load()?;
        let model = mason_io::load_model(self.model.as_deref())?;
        let slot = prepare(&wall, &model, &config)?;
        let problem =
            BuildProblem::new(&wall, model.clone()).map_err(|e| input_error(e.to_string()))?;
        let plan = solve(&problem, spec, Some(ORDER_TIME_LIMIT_S))?;
        exit_for(&plan)?;
        let order = plan.outcome.order.clone().unwrap_or_default();
        Ok(Mission {
            wall,
            model,
            spec,
            plan,
            order,
            config,
            coord,
            slot,
        })
    }
}

/// Validates a configuration and computes the windows slot for a wall.
pub fn prepare(wall: &Wall, model: &CostModel, config: &MissionConfig) -> CliResult<f64> {
    config
        .validate()
        .map_err(|e| input_error(format!("mission: {e}")))?;
    mason_mission::slot_length(wall, model, config).map_err(|e| input_error(format!("--{e}")))
}
