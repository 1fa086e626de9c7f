//! A crew problem: the grid, the moves allowed, where the robots stand and the goals.

use crate::error::{CrewError, Location};
use crate::grid::{Cell, Connectivity, Grid};

/// n robots, m ≥ n goals, on a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The world.
    pub grid: Grid,
    /// Moves allowed.
    pub connectivity: Connectivity,
    /// Robot start cells.
    pub robots: Vec<Cell>,
    /// Goal cells.
    pub goals: Vec<Cell>,
    /// The goal index of each robot when the input pairs them (a MovingAI scenario).
    pub pairing: Option<Vec<usize>>,
}

impl Instance {
    /// Checks the robots and goals: on free cells, pairwise distinct, at least one robot and no
    /// more robots than goals. `source_name` names the input in errors.
    pub fn new(
        grid: Grid,
        connectivity: Connectivity,
        robots: Vec<Cell>,
        goals: Vec<Cell>,
        pairing: Option<Vec<usize>>,
        source_name: &str,
    ) -> Result<Self, CrewError> {
        let at = |c: Cell| {
            let (x, y) = grid.xy(c);
            Location::Cell(x, y)
        };
        if robots.is_empty() {
            return Err(CrewError::new(source_name, Location::Whole, "no robots"));
        }
        if robots.len() > goals.len() {
            return Err(CrewError::new(
                source_name,
                Location::Whole,
                format!("{} robots but only {} goals", robots.len(), goals.len()),
            ));
        }
        for (what, cells) in [("robot", &robots), ("goal", &goals)] {
            let mut seen = rustc_hash::FxHashMap::default();
            for (i, &c) in cells.iter().enumerate() {
                if c.0 as usize >= grid.len() {
                    return Err(CrewError::new(
                        source_name,
                        Location::Whole,
                        format!("{what} {i} is outside the grid"),
                    ));
                }
                if !grid.is_free(c) {
                    return Err(CrewError::new(
                        source_name,
                        at(c),
                        format!("{what} {i} is on an obstacle"),
                    ));
                }
                if let Some(j) = seen.insert(c, i) {
                    return Err(CrewError::new(
                        source_name,
                        at(c),
                        format!("{what}s {j} and {i} share the cell"),
                    ));
                }
            }
        }
        if let Some(p) = &pairing {
            assert_eq!(p.len(), robots.len(), "one paired goal per robot");
        }
        Ok(Instance {
            grid,
            connectivity,
            robots,
            goals,
            pairing,
        })
    }

    /// Number of robots.
    pub fn robot_count(&self) -> usize {
        self.robots.len()
    }
}
