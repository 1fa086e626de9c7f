//! The decision core: what one UAV decides, as pure functions of what it knows.
//!
//! Both backends run this same code. The simulator ([`crate::sim`]) keeps one [`Board`] for
//! the team, because with a perfect view every UAV knows the same; an agent
//! ([`crate::agent`]) keeps its own [`Board`], built from the messages it has heard. The
//! state machine's timed steps ([`after`]), the brick choice ([`Board::pick`]), the brick next
//! needed ([`Board::needed`]), the expected zone time ([`Board::zone_time`]), the deadlock
//! rule ([`put_down`]) and the `auto` mode rule ([`heard_mode`]) live here and nowhere else.

use crate::state::{CommMode, UavState};
use mason_order::CostModel;
use mason_wall::{BrickId, BrickType, Wall};

/// What is known of one brick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Brick {
    /// In its pile; nobody has taken it.
    Untaken,
    /// Somebody took it (its carriers are in [`Board::carriers`]).
    Taken,
    /// On the wall.
    Placed,
}

/// What a UAV knows of the team's work: the order, the schedule's lists, every brick's state
/// and carriers, and who is still flying.
#[derive(Clone, Debug, PartialEq)]
pub struct Board {
    order: Vec<BrickId>,
    rank: Vec<usize>,
    /// Each UAV's own bricks under a schedule (replaced by a replan).
    pub lists: Option<Vec<Vec<BrickId>>>,
    bricks: Vec<Brick>,
    carriers: Vec<Vec<usize>>,
    placed: usize,
    alive: Vec<bool>,
}

/// What [`Board::pick`] decides for a UAV without a brick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pick {
    /// Take this brick (or join its pair).
    Brick(BrickId),
    /// Every brick is placed: land.
    Land,
    /// What is left needs a pair that no longer exists: land.
    CannotFinish,
    /// Nothing to take now: wait.
    Idle,
}

impl Board {
    /// A board at the start: nothing taken, every UAV flying.
    pub fn new(
        wall: &Wall,
        order: &[BrickId],
        lists: Option<&[Vec<BrickId>]>,
        uavs: usize,
    ) -> Self {
        let mut b = Board {
            order: Vec::new(),
            rank: vec![usize::MAX; wall.len()],
            lists: lists.map(<[Vec<BrickId>]>::to_vec),
            bricks: vec![Brick::Untaken; wall.len()],
            carriers: vec![Vec::new(); wall.len()],
            placed: 0,
            alive: vec![true; uavs],
        };
        b.set_order(order.to_vec());
        b
    }

    /// Replaces the shared order (a replan).
    pub fn set_order(&mut self, order: Vec<BrickId>) {
        for (i, b) in order.iter().enumerate() {
            self.rank[b.index()] = i;
        }
        self.order = order;
    }

    /// The shared order.
    pub fn order(&self) -> &[BrickId] {
        &self.order
    }

    /// Where `b` is in the order (`usize::MAX` when it is not).
    pub fn rank(&self, b: BrickId) -> usize {
        self.rank[b.index()]
    }

    /// What is known of `b`.
    pub fn brick(&self, b: BrickId) -> Brick {
        self.bricks[b.index()]
    }

    /// Who carries `b`, the first taker first.
    pub fn carriers(&self, b: BrickId) -> &[usize] {
        &self.carriers[b.index()]
    }

    /// How many bricks are placed.
    pub fn placed(&self) -> usize {
        self.placed
    }

    /// Whether every brick is placed.
    pub fn finished(&self) -> bool {
        self.placed == self.bricks.len()
    }

    /// Whether some brick is still in its pile.
    pub fn untaken_left(&self) -> bool {
        self.bricks.contains(&Brick::Untaken)
    }

    /// Whether UAV `u` is still flying.
    pub fn alive(&self, u: usize) -> bool {
        self.alive[u]
    }

    /// Marks UAV `u` out (failed) or back.
    pub fn set_alive(&mut self, u: usize, alive: bool) {
        self.alive[u] = alive;
    }

    /// How many UAVs are still flying.
    pub fn live(&self) -> usize {
        self.alive.iter().filter(|a| **a).count()
    }

    /// `u` takes `b` (or joins its pair); returns the first taker when `u` joins a pair.
    pub fn take(&mut self, b: BrickId, u: usize) -> Option<usize> {
        let first = self.carriers[b.index()].first().copied();
        self.bricks[b.index()] = Brick::Taken;
        self.carriers[b.index()].push(u);
        first
    }

    /// `u` no longer carries `b`; the brick stays taken by the others.
    pub fn drop_carrier(&mut self, b: BrickId, u: usize) {
        self.carriers[b.index()].retain(|&c| c != u);
    }

    /// `b` goes back to its pile.
    pub fn release(&mut self, b: BrickId) {
        self.bricks[b.index()] = Brick::Untaken;
        self.carriers[b.index()].clear();
    }

    /// `b` is on the wall; returns who carried it.
    pub fn place(&mut self, b: BrickId) -> Vec<usize> {
        if self.bricks[b.index()] != Brick::Placed {
            self.bricks[b.index()] = Brick::Placed;
            self.placed += 1;
        }
        std::mem::take(&mut self.carriers[b.index()])
    }

    /// Whether every support of `b` is placed.
    pub fn supported(&self, wall: &Wall, b: BrickId) -> bool {
        wall.supports(b)
            .iter()
            .all(|s| self.bricks[s.index()] == Brick::Placed)
    }

    /// Whether every support of `b` is at least taken by somebody.
    fn supports_taken(&self, wall: &Wall, b: BrickId) -> bool {
        wall.supports(b)
            .iter()
            .all(|s| self.bricks[s.index()] != Brick::Untaken)
    }

    /// `b` is out of the piles but nobody is known to carry it: a UAV declared out was
    /// holding it, and whether it was placed is not known (agents only).
    pub fn hold_unknown(&mut self, b: BrickId) {
        self.bricks[b.index()] = Brick::Taken;
        self.carriers[b.index()].clear();
    }

    /// The brick next needed: the earliest taken, unplaced brick of the order that somebody
    /// carries.
    pub fn needed(&self) -> Option<BrickId> {
        self.bricks
            .iter()
            .enumerate()
            .filter(|(i, s)| **s == Brick::Taken && !self.carriers[*i].is_empty())
            .min_by_key(|(i, _)| self.rank[*i])
            .map(|(i, _)| BrickId(i as u32))
    }

    /// The expected time in the zone for `b` now: the transit plus the drop time scaled by
    /// κ of its placed neighbours (DESIGN §4).
    pub fn zone_time(&self, wall: &Wall, model: &CostModel, transit_s: f64, b: BrickId) -> f64 {
        let placed = wall
            .neighbours(b)
            .iter()
            .filter(|n| self.bricks[n.index()] == Brick::Placed)
            .count()
            .min(2);
        transit_s + model.kappa[placed] * model.times(wall.brick(b).kind).drop
    }

    /// The brick UAV `u`, holding nothing, takes next (DESIGN §5): an open orange pair whose
    /// scheduled partner is gone, else its own next scheduled brick, else an open orange pair,
    /// else the next untaken brick of the shared order.
    pub fn pick(&self, wall: &Wall, u: usize) -> Pick {
        if self.finished() {
            return Pick::Land;
        }
        let kind = |b: BrickId| wall.brick(b).kind;
        let live = self.live();
        // A scheduled UAV takes its own next brick (joining its pair for an orange).
        let own = self.lists.as_ref().and_then(|a| a.get(u)).and_then(|list| {
            list.iter()
                .copied()
                .find(|&b| match self.bricks[b.index()] {
                    Brick::Untaken => true,
                    Brick::Taken => {
                        kind(b).uavs_needed() == 2
                            && self.carriers[b.index()].len() == 1
                            && self.carriers[b.index()][0] != u
                    }
                    Brick::Placed => false,
                })
        });
        // Not a brick whose support nobody has taken (a failed teammate's): the shared order
        // comes first then.
        let own = own
            .filter(|&b| (kind(b).uavs_needed() == 1 || live >= 2) && self.supports_taken(wall, b));
        // Join an open orange pair first: it was taken earlier in the order.
        let open = self.order.iter().copied().find(|&b| {
            self.bricks[b.index()] == Brick::Taken
                && kind(b).uavs_needed() == 2
                && self.carriers[b.index()].len() == 1
        });
        // Under a schedule, an open pair whose scheduled partner is gone goes before one's own.
        let orphan = open.filter(|&b| {
            self.lists.as_ref().is_some_and(|a| {
                !a.iter().enumerate().any(|(w, list)| {
                    w != self.carriers[b.index()][0] && self.alive[w] && list.contains(&b)
                })
            })
        });
        let pick = orphan.or(own).or(open).or_else(|| {
            let alone = live < 2;
            self.order.iter().copied().find(|&b| {
                self.bricks[b.index()] == Brick::Untaken
                    && (!alone || (kind(b).uavs_needed() == 1 && self.supports_taken(wall, b)))
            })
        });
        match pick {
            Some(b) => Pick::Brick(b),
            None if self.untaken_left() && live < 2 => Pick::CannotFinish,
            None => Pick::Idle,
        }
    }
}

/// What happens when a timed state of the state machine (thesis Fig. 4.3) ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum After {
    /// Move on to `state` for `duration` seconds.
    Go {
        /// The next state.
        state: UavState,
        /// The outcome that leads there.
        outcome: &'static str,
        /// How long it lasts.
        duration: f64,
    },
    /// Airborne: choose a brick.
    Choose,
    /// At the pile: detect alone, or wait for the pair's partner.
    AtPile,
    /// Detection ended: it fails with the detection failure probability.
    Detected,
    /// Above the brick: grasp for the brick's grasp time.
    Above,
    /// The grasp ended: it fails with the grasp failure probability.
    Grasped,
    /// At the wall's waiting point: wait for the zone.
    AtWall,
    /// The brick is on the wall.
    Placed,
    /// On the ground at the start.
    Landed,
    /// Not a timed state.
    Nothing,
}

/// What follows the end of timed state `state`; `takeoff_s` is the take-off time.
pub fn after(state: UavState, takeoff_s: f64) -> After {
    match state {
        UavState::Check => After::Go {
            state: UavState::TakeOff,
            outcome: "ok",
            duration: takeoff_s,
        },
        UavState::TakeOff => After::Choose,
        UavState::FlyToPile => After::AtPile,
        UavState::Detect => After::Detected,
        UavState::FlyAbove => After::Above,
        UavState::Grasp => After::Grasped,
        UavState::FlyToWallWait => After::AtWall,
        UavState::EnterAndPlace => After::Placed,
        UavState::Land => After::Landed,
        _ => After::Nothing,
    }
}

/// The `auto` rule: a UAV falls back to `windows` when it has not heard some teammate that is
/// still flying for longer than `timeout_s`. `last_heard[v]` is when it last heard `v`;
/// `flying(v)` says whether `v` should still be heard.
pub fn heard_mode(
    now: f64,
    me: usize,
    last_heard: &[f64],
    flying: impl Fn(usize) -> bool,
    timeout_s: f64,
) -> CommMode {
    let lost =
        (0..last_heard.len()).any(|v| v != me && flying(v) && now - last_heard[v] > timeout_s);
    if lost {
        CommMode::Windows
    } else {
        CommMode::Comm
    }
}

/// What one teammate is doing, as far as the deadlock rule needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seen {
    /// Still flying.
    pub alive: bool,
    /// Its state.
    pub state: UavState,
    /// At the pile, waiting for its pair's partner.
    pub waiting_partner: bool,
    /// The brick it carries.
    pub brick: Option<BrickId>,
}

/// The deadlock rule: when every live UAV waits and nobody may enter (a brick they need was
/// lost), the holder of the latest brick of the order puts it down and fetches what is
/// missing. Returns that holder, or `None` when somebody can still move.
pub fn put_down(board: &Board, team: &[Seen]) -> Option<usize> {
    let stuck = team.iter().filter(|u| u.alive).all(|u| {
        u.state == UavState::WaitForZone || (u.state == UavState::Detect && u.waiting_partner)
    });
    if !stuck || !team.iter().any(|u| u.alive) {
        return None;
    }
    (0..team.len())
        .filter(|&i| team[i].alive && team[i].state == UavState::WaitForZone)
        .filter_map(|i| team[i].brick.map(|b| (i, board.rank(b))))
        .max_by_key(|&(_, r)| r)
        .map(|(i, _)| i)
}

/// The brick type of `b`.
pub fn kind(wall: &Wall, b: BrickId) -> BrickType {
    wall.brick(b).kind
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thesis() -> Wall {
        mason_wall::builtin("thesis-2x5").unwrap().wall()
    }

    #[test]
    fn the_next_untaken_brick_of_the_order_is_picked_and_supports_come_first() {
        let w = thesis();
        let order: Vec<BrickId> = w.ids().collect();
        let mut board = Board::new(&w, &order, None, 3);
        let Pick::Brick(first) = board.pick(&w, 0) else {
            panic!("a brick")
        };
        assert_eq!(first, order[0]);
        board.take(first, 0);
        assert_eq!(board.pick(&w, 1), Pick::Brick(order[1]));
        assert_eq!(board.needed(), Some(first));
        assert!(board.supported(&w, first));
        // A brick of the second level is not supported before the first level is placed.
        let top = *order.last().unwrap();
        assert!(!board.supported(&w, top));
        for &b in &order {
            board.take(b, 0);
            board.place(b);
        }
        assert!(board.finished());
        assert_eq!(board.pick(&w, 2), Pick::Land);
    }

    #[test]
    fn a_lone_survivor_cannot_finish_what_needs_a_pair() {
        let w = mason_wall::builtin("mbzirc").unwrap().wall();
        let order: Vec<BrickId> = w.ids().collect();
        let mut board = Board::new(&w, &order, None, 2);
        board.set_alive(1, false);
        for &b in &order {
            if kind(&w, b).uavs_needed() == 1 {
                board.take(b, 0);
                board.place(b);
            }
        }
        assert_eq!(board.pick(&w, 0), Pick::CannotFinish);
    }

    #[test]
    fn auto_falls_back_only_for_a_teammate_still_flying() {
        let heard = [10.0, 2.0, 9.5];
        assert_eq!(
            heard_mode(10.0, 0, &heard, |_| true, 3.0),
            CommMode::Windows
        );
        assert_eq!(heard_mode(10.0, 0, &heard, |v| v != 1, 3.0), CommMode::Comm);
        assert_eq!(heard_mode(4.0, 0, &heard, |_| true, 3.0), CommMode::Comm);
    }

    #[test]
    fn the_holder_of_the_latest_brick_puts_it_down_when_all_wait() {
        let w = thesis();
        let order: Vec<BrickId> = w.ids().collect();
        let mut board = Board::new(&w, &order, None, 2);
        board.take(order[3], 0);
        board.take(order[6], 1);
        let waiting = |b| Seen {
            alive: true,
            state: UavState::WaitForZone,
            waiting_partner: false,
            brick: Some(b),
        };
        let team = [waiting(order[3]), waiting(order[6])];
        assert_eq!(put_down(&board, &team), Some(1));
        let moving = [
            waiting(order[3]),
            Seen {
                state: UavState::FlyToPile,
                ..waiting(order[6])
            },
        ];
        assert_eq!(put_down(&board, &moving), None);
    }
}
