//! Ground crew guided by a UAV (Upadhyay, Shrimali, Shukla 2018), and better.
//!
//! A UAV sees a grid world from above. It gives each of n robots one of the goals
//! ([`assign`]), plans each robot's path with A* ([`astar`]) or a probabilistic roadmap
//! ([`prm`]), and resolves collisions: by the paper's priority waits ([`paper`]) or by
//! prioritized space-time A* ([`st`]), or completely by LaCAM over PIBT steps ([`lacam`],
//! [`pibt`]) refined by large neighbourhood search ([`refine`]). For interchangeable robots,
//! TSWAP ([`tswap`]) solves the assignment and the paths together. [`validate`] checks any plan
//! without knowing who made it.
//!
//! Modules, one concept each:
//! - [`grid`]: cells, connectivity and legal moves; [`instance`]: robots and goals on a grid;
//! - [`movingai`]: `.map` and `.scen` readers and writers; [`image`]: occupancy and bird's-eye
//!   PNGs (one pixel per cell); [`aerial`]: photographs of the floor from above (PNG, JPEG);
//! - [`distance`]: BFS step distances and Dijkstra path lengths; [`rra`]: distances on demand;
//! - [`astar`], [`line`], [`prm`]: single-robot paths;
//! - [`hungarian`], [`perm`], [`assign`]: goal assignment;
//! - [`spacetime`]: space-time A*, the one-robot search of [`st`] and [`refine`];
//! - [`reservation`], [`paper`], [`st`]: collision resolution, prioritized (incomplete);
//! - [`moves`], [`scatter`], [`pibt`], [`lacam`], [`refine`]: complete and anytime labelled
//!   MAPF;
//! - [`cbs`]: optimal labelled MAPF for a few robots (the tests' yardstick);
//! - [`tswap`]: unlabelled MAPF (assignment and paths together); [`solve`]: the pipeline;
//! - [`validate`]: the plan checker; [`outcome`]: status, budget, stats; [`generate`]: test worlds.
//!
//! ```
//! use mason_crew::{solve, validate, Budget, Connectivity, CrewConfig, Instance, Status};
//! let grid = mason_crew::movingai::parse_map(
//!     "type octile\nheight 3\nwidth 5\nmap\n.....\n.@@@.\n.....\n", "example.map").unwrap();
//! let cell = |x, y| grid.cell(x, y).unwrap();
//! let robots = vec![cell(0, 0), cell(4, 2)];
//! let goals = vec![cell(4, 0), cell(0, 2)];
//! let inst = Instance::new(grid.clone(), Connectivity::Eight, robots, goals, None, "example").unwrap();
//! let out = solve(&inst, &CrewConfig::default(), &Budget::unlimited()).unwrap();
//! assert_eq!(out.status, Status::Feasible);
//! let paths = out.paths.unwrap();
//! let metrics = validate(&inst.grid, inst.connectivity, &inst.robots, &out.goals, &paths).unwrap();
//! // Hungarian pairs each robot with the goal straight below or above it: 2 steps each.
//! assert_eq!((metrics.sum_of_costs, metrics.makespan), (4, 2));
//! ```

#![deny(missing_docs)]

pub mod aerial;
pub mod assign;
pub mod astar;
pub mod cbs;
pub mod checked;
pub mod distance;
pub mod error;
pub mod generate;
pub mod grid;
pub mod hungarian;
pub mod image;
pub mod instance;
pub mod lacam;
pub mod limits;
pub mod line;
pub mod moves;
pub mod movingai;
pub mod outcome;
pub mod paper;
pub mod perm;
pub mod pibt;
pub mod prm;
pub mod refine;
pub mod reservation;
pub mod restart;
pub mod rra;
pub mod scatter;
pub mod solve;
pub mod spacetime;
pub mod st;
pub mod tswap;
pub mod validate;

pub use assign::{AssignError, AssignMethod};
pub use checked::{shortest_steps, solve_checked, CheckedCrewPlan, CheckedSolveError};
pub use error::{CrewError, Location};
pub use grid::{Cell, Connectivity, Grid};
pub use instance::Instance;
pub use mason_wall::stop::Stop;
pub use outcome::{Budget, CrewOutcome, CrewStats, Paths, Status};
pub use prm::PrmConfig;
pub use refine::RefineConfig;
pub use solve::{solve, CrewConfig, PathMethod, Resolution, SetupError};
pub use validate::{claim_violations, plan_violations, validate, PlanError, PlanMetrics};
