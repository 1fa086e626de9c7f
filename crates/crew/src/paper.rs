//! The crew paper's collision resolution (Upadhyay, Shrimali, Shukla 2018): robots get
//! priorities by path length, longest first, and each lower-priority robot keeps its path but
//! inserts waits before its first conflict with the robots above it, until none is left.
//!
//! A wait goes on the cell just before the conflict; when that wait itself clashes, the next
//! one goes a step earlier. The method is incomplete: when a robot's path crosses the goal of
//! a higher-priority robot that is already resting there, or when waiting at its start cannot
//! help, it reports the deadlock instead of a plan. O(n · (L + W)) table look-ups for n robots,
//! paths of length L and W waits.

use crate::grid::{Cell, Grid};
use crate::outcome::Paths;
use crate::reservation::{Clash, ReservationTable};

/// Why the paper's resolution gave up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Deadlock {
    /// The robot that could not be fitted in.
    pub robot: usize,
    /// The robot it clashes with.
    pub other: usize,
    /// Where.
    pub cell: Cell,
    /// When.
    pub step: u32,
    /// True when `other` rests there on its goal.
    pub blocked_goal: bool,
}

/// Timed paths with waits, or the first deadlock. `order` lists robots by priority, highest
/// first. Also returns the number of waits inserted.
pub fn resolve_by_waiting(
    grid: &Grid,
    paths: &[Vec<Cell>],
    order: &[usize],
) -> (Result<Paths, Deadlock>, u64) {
    let mut table = ReservationTable::new();
    let mut timed: Paths = paths.to_vec();
    let mut waits = 0u64;
    for &r in order {
        let mut path = paths[r].clone();
        let mut last: Option<(u32, usize)> = None;
        let cap = 4 * (table.horizon() as usize + path.len()) + 64;
        let mut added = 0;
        let mut from = 0;
        while let Some((t, clash)) = first_clash(grid, &table, &path, from) {
            let cell = path[(t as usize).min(path.len() - 1)];
            let deadlock = |blocked_goal| Deadlock {
                robot: r,
                other: clash.other as usize,
                cell,
                step: t,
                blocked_goal,
            };
            if clash.resting {
                return (Err(deadlock(true)), waits);
            }
            let natural = (t as usize).min(path.len() - 1) as i64 - 1;
            let at = match last {
                Some((t_prev, s_prev)) if t <= t_prev => s_prev as i64 - 1,
                _ => natural,
            };
            if at < 0 || added >= cap {
                return (Err(deadlock(false)), waits);
            }
            let at = at as usize;
            path.insert(at, path[at]);
            added += 1;
            waits += 1;
            last = Some((t, at));
            from = at as u32;
        }
        table.reserve(r as u32, &path);
        timed[r] = path;
    }
    (Ok(timed), waits)
}

/// The first step at which `path` (resting on its last cell afterwards) clashes with the table,
/// looking at moves from step `from` on (earlier ones are known to be clear).
fn first_clash(
    grid: &Grid,
    table: &ReservationTable,
    path: &[Cell],
    from: u32,
) -> Option<(u32, Clash)> {
    let end = (path.len() as u32 - 1).max(table.horizon() + 1);
    let at = |t: u32| path[(t as usize).min(path.len() - 1)];
    if from == 0 {
        if let Some(c) = table.occupant(at(0), 0) {
            return Some((0, c));
        }
    }
    for t in from..end {
        if let Some(c) = table.move_clash(grid, at(t), at(t + 1), t) {
            return Some((t + 1, c));
        }
    }
    None
}
