//! Under the zone rule, a makespan schedule is a zone sequence (the bricks in the order they
//! place, which must respect precedence) and a crew for each brick; given both, the earliest
//! times follow: a brick starts when the zone is free and its UAVs are back (the bricks under
//! it come earlier in the sequence, so they are placed by then).
//!
//! The list search ([`super::search`]) reaches schedules through its decoder, which picks each
//! brick's crew by a fixed rule. This polish searches zone sequences instead, and gives each
//! sequence its best crews exactly ([`best_crews`]): a dynamic programme over the sequence
//! whose states are the zone's free time and the UAVs' sorted ready times (UAVs are
//! interchangeable), keeping only states no other state dominates (earlier zone, and every
//! ready time no later). A ready time before the zone is free counts as the zone's free time:
//! the next brick cannot start earlier anyway, and later ones even less. Over sequences it
//! runs simulated annealing (move a brick, or swap two, where precedence allows) from the
//! search's best schedule, with a fixed number of moves and a seeded generator, so the result
//! depends only on the seed.

use super::problem::{Placement, Schedule, TeamProblem};
use crate::outcome::Budget;
use mason_wall::BrickId;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// The most states [`best_crews`] keeps per step. With more, the least makespan is found over
/// more crew choices; with this cap it is still a valid schedule's, and on the MBZIRC wall it
/// equals the exact one (measured with 10 000).
pub const CREW_STATES: usize = 32;

/// Work of one polish run, in bricks decoded (moves × bricks): 150 000 moves on a 42-brick
/// wall. Larger walls get fewer moves; above [`MAX_BRICKS`] the polish does not run.
pub const POLISH_WORK: u64 = 6_300_000;

/// The largest wall the polish runs on.
pub const MAX_BRICKS: usize = 512;

/// One step's state: the zone's free time, the UAVs' sorted ready times, and how it was
/// reached (the previous step's state and the UAVs, by rank there, that placed the brick).
#[derive(Clone)]
struct Node {
    zone: f64,
    ready: Vec<f64>,
    parent: usize,
    crew: [usize; 2],
}

/// The least makespan of the zone sequence `seq` over crew choices (at most `cap` states per
/// step), and each brick's crew (UAV numbers) in a schedule that reaches it.
pub fn best_crews(p: &TeamProblem<'_>, seq: &[BrickId], cap: usize) -> (f64, Vec<[usize; 2]>) {
    let m = p.uavs();
    let mut layers: Vec<Vec<Node>> = vec![vec![Node {
        zone: 0.0,
        ready: vec![0.0; m],
        parent: 0,
        crew: [0, 0],
    }]];
    for &b in seq {
        let need = p.need(b) as usize;
        let mut next: Vec<Node> = Vec::new();
        let prev = layers.last().expect("one layer at least");
        for (k, s) in prev.iter().enumerate() {
            let mut add = |crew: [usize; 2]| {
                let t = crew[..need]
                    .iter()
                    .map(|&u| s.ready[u])
                    .fold(s.zone, f64::max);
                let z = t + p.place_s(b);
                let mut r = s.ready.clone();
                for &u in &crew[..need] {
                    r[u] = z + p.rest_s(b);
                }
                for x in r.iter_mut() {
                    *x = x.max(z);
                }
                r.sort_by(f64::total_cmp);
                next.push(Node {
                    zone: z,
                    ready: r,
                    parent: k,
                    crew,
                });
            };
            for u in 0..m {
                // UAVs with the same ready time are interchangeable: try the first of them.
                if u > 0 && s.ready[u] == s.ready[u - 1] {
                    continue;
                }
                if need == 1 {
                    add([u, u]);
                } else {
                    for v in u + 1..m {
                        if v > u + 1 && s.ready[v] == s.ready[v - 1] {
                            continue;
                        }
                        add([u, v]);
                    }
                }
            }
        }
        next.sort_by(|a, b| {
            a.zone
                .total_cmp(&b.zone)
                .then_with(|| {
                    let sa: f64 = a.ready.iter().sum();
                    sa.total_cmp(&b.ready.iter().sum())
                })
                .then_with(|| a.parent.cmp(&b.parent))
        });
        let mut kept: Vec<Node> = Vec::new();
        for s in next {
            let dominated = kept
                .iter()
                .any(|k| k.zone <= s.zone && k.ready.iter().zip(&s.ready).all(|(x, y)| x <= y));
            if !dominated {
                kept.push(s);
                if kept.len() >= cap {
                    break;
                }
            }
        }
        layers.push(kept);
    }
    // The best last state, then back to the first, turning ranks into UAV numbers: the UAV
    // numbers sorted by ready time at each step play the ranks.
    let last = layers.last().expect("one layer at least");
    let (mut at, makespan) = last
        .iter()
        .enumerate()
        .map(|(i, s)| (i, s.zone))
        .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
    let mut ranks: Vec<[usize; 2]> = vec![[0, 0]; seq.len()];
    for step in (1..layers.len()).rev() {
        let s = &layers[step][at];
        ranks[step - 1] = s.crew;
        at = s.parent;
    }
    // Forward: keep the UAVs in ready-time order exactly as the states did.
    let mut ready = vec![0.0f64; m];
    let mut by_rank: Vec<usize> = (0..m).collect();
    let mut zone = 0.0f64;
    let mut crews = Vec::with_capacity(seq.len());
    for (&b, r) in seq.iter().zip(&ranks) {
        let need = p.need(b) as usize;
        let crew = [by_rank[r[0]], by_rank[r[1]]];
        let t = crew[..need].iter().map(|&u| ready[u]).fold(zone, f64::max);
        zone = t + p.place_s(b);
        for &u in &crew[..need] {
            ready[u] = zone + p.rest_s(b);
        }
        for x in ready.iter_mut() {
            *x = x.max(zone);
        }
        // The same order as the state's sort: by ready time; ties keep the previous order,
        // which is harmless since tied UAVs are interchangeable.
        by_rank.sort_by(|&a, &b| ready[a].total_cmp(&ready[b]));
        crews.push(crew);
    }
    (makespan, crews)
}

/// The makespan part of [`best_crews`] with the states of every step kept, so that a sequence
/// that differs from the last accepted one from some place on is evaluated from there.
/// A layer is a flat list of states `[zone, ready₀, …, ready_{m−1}]`.
struct Evaluator {
    m: usize,
    cap: usize,
    /// Layers of the accepted sequence (index k: after its first k bricks).
    cur: Vec<Vec<f64>>,
    /// Layers of the candidate from its first change on.
    scratch: Vec<Vec<f64>>,
    next: Vec<f64>,
    order: Vec<usize>,
}

impl Evaluator {
    fn new(m: usize, n: usize, cap: usize) -> Self {
        // The start: the zone and every UAV free at 0.
        let first = vec![0.0; m + 1];
        Evaluator {
            m,
            cap,
            cur: std::iter::once(first)
                .chain((0..n).map(|_| Vec::new()))
                .collect(),
            scratch: vec![Vec::new(); n + 1],
            next: Vec::new(),
            order: Vec::new(),
        }
    }

    /// The least makespan of `seq`, equal to the accepted sequence before place `from`; its
    /// layers go to the scratch ([`Evaluator::accept`] keeps them).
    fn eval(&mut self, p: &TeamProblem<'_>, seq: &[BrickId], from: usize) -> f64 {
        let w = self.m + 1;
        for (k, &b) in seq.iter().enumerate().skip(from) {
            let need = p.need(b) as usize;
            let (place, rest) = (p.place_s(b), p.rest_s(b));
            let prev = if k == from {
                &self.cur[k]
            } else {
                &self.scratch[k]
            };
            self.next.clear();
            for s in prev.chunks_exact(w) {
                let (zone, ready) = (s[0], &s[1..]);
                for u in 0..self.m {
                    if u > 0 && ready[u] == ready[u - 1] {
                        continue;
                    }
                    let vs = if need == 1 { u..u + 1 } else { u + 1..self.m };
                    for v in vs {
                        if need > 1 && v > u + 1 && ready[v] == ready[v - 1] {
                            continue;
                        }
                        let z = zone.max(ready[u]).max(ready[v]) + place;
                        let at = self.next.len();
                        self.next.push(z);
                        for (x, &r) in ready.iter().enumerate() {
                            let r = if x == u || x == v { z + rest } else { r };
                            self.next.push(r.max(z));
                        }
                        self.next[at + 1..at + w].sort_by(f64::total_cmp);
                    }
                }
            }
            let count = self.next.len() / w;
            self.order.clear();
            self.order.extend(0..count);
            let next = &self.next;
            let key = |i: usize| -> (f64, f64) {
                let s = &next[i * w..(i + 1) * w];
                (s[0], s[1..].iter().sum())
            };
            self.order.sort_by(|&a, &b| {
                let (ka, kb) = (key(a), key(b));
                ka.0.total_cmp(&kb.0)
                    .then(ka.1.total_cmp(&kb.1))
                    .then(a.cmp(&b))
            });
            let out = &mut self.scratch[k + 1];
            out.clear();
            for &i in &self.order {
                let s = &next[i * w..(i + 1) * w];
                let dominated = out
                    .chunks_exact(w)
                    .any(|o| o.iter().zip(s).all(|(x, y)| x <= y));
                if !dominated {
                    out.extend_from_slice(s);
                    if out.len() / w >= self.cap {
                        break;
                    }
                }
            }
        }
        let last = if from == seq.len() {
            &self.cur[from]
        } else {
            &self.scratch[seq.len()]
        };
        last.chunks_exact(w)
            .map(|s| s[0])
            .fold(f64::INFINITY, f64::min)
    }

    /// Keeps the candidate just evaluated from place `from` as the accepted sequence.
    fn accept(&mut self, from: usize) {
        for k in from + 1..self.cur.len() {
            std::mem::swap(&mut self.cur[k], &mut self.scratch[k]);
        }
    }
}

/// The schedule of `seq` with `crews` at the earliest times.
fn timed(p: &TeamProblem<'_>, seq: &[BrickId], crews: &[[usize; 2]]) -> Schedule {
    let mut ready = vec![0.0f64; p.uavs()];
    let mut zone = 0.0f64;
    let mut out = Schedule::default();
    for (&b, c) in seq.iter().zip(crews) {
        let need = p.need(b) as usize;
        let t = c[..need].iter().map(|&u| ready[u]).fold(zone, f64::max);
        zone = t + p.place_s(b);
        for &u in &c[..need] {
            ready[u] = zone + p.rest_s(b);
        }
        let mut uavs = c[..need].to_vec();
        uavs.sort_unstable();
        out.placements.push(Placement {
            brick: b,
            uavs,
            start_s: t,
        });
    }
    out.sort();
    out
}

/// Whether every brick of `seq` comes after the bricks under it.
fn respects_precedence(p: &TeamProblem<'_>, seq: &[BrickId], done: &mut [bool]) -> bool {
    done.iter_mut().for_each(|d| *d = false);
    for &b in seq {
        if p.wall().supports(b).iter().any(|s| !done[s.index()]) {
            return false;
        }
        done[b.index()] = true;
    }
    true
}

/// Polishes a whole-wall makespan schedule under the zone rule with `moves` annealing moves
/// from `seed` (the temperature falls from 1 s to 0.01 s; under `budget`'s deadline, by the
/// time used, and it stops there or at its stop flag); returns a schedule with a smaller
/// makespan, if it finds one. `None` under the distance rule, for a replan (a start state), for
/// walls above [`MAX_BRICKS`] or when `s` does not place every brick.
pub fn polish_zone_makespan(
    p: &TeamProblem<'_>,
    s: &Schedule,
    moves: u64,
    seed: u64,
    budget: &Budget,
) -> Option<Schedule> {
    let n = p.len();
    if !p.zone_rule()
        || p.start().is_some()
        || s.placements.len() != n
        || !(2..=MAX_BRICKS).contains(&n)
    {
        return None;
    }
    let mut placements = s.placements.clone();
    placements.sort_by(|a, b| a.start_s.total_cmp(&b.start_s).then(a.brick.cmp(&b.brick)));
    let mut seq: Vec<BrickId> = placements.iter().map(|pl| pl.brick).collect();
    let mut done = vec![false; n];
    if !respects_precedence(p, &seq, &mut done) {
        return None;
    }
    let start = s
        .placements
        .iter()
        .map(|pl| pl.start_s + p.place_s(pl.brick))
        .fold(0.0, f64::max);
    let mut ev = Evaluator::new(p.uavs(), n, CREW_STATES);
    let mut cur = ev.eval(p, &seq, 0);
    ev.accept(0);
    let mut best = (cur, seq.clone());
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x9011_5a11);
    let (t_hi, t_lo) = (1.0f64, 0.01f64);
    let mut cand = seq.clone();
    // Under a deadline, the temperature follows the time used instead of the moves made.
    let began = Instant::now();
    let span = budget
        .deadline
        .map(|d| d.saturating_duration_since(began).as_secs_f64());
    for it in 0..moves {
        if it % 256 == 0 && budget.out_of_time() {
            break;
        }
        let done_part = match span {
            Some(total) if total > 0.0 => began.elapsed().as_secs_f64() / total,
            _ => it as f64 / moves as f64,
        };
        let temp = t_hi * (t_lo / t_hi).powf(done_part.min(1.0));
        cand.clone_from(&seq);
        let i = rng.gen_range(0..n);
        let j = rng.gen_range(0..n);
        if rng.gen_bool(0.5) {
            let b = cand.remove(i);
            cand.insert(j, b);
        } else {
            cand.swap(i, j);
        }
        if i == j || !respects_precedence(p, &cand, &mut done) {
            continue;
        }
        let from = i.min(j);
        let v = ev.eval(p, &cand, from);
        if v <= cur + 1e-9 || rng.gen::<f64>() < (-(v - cur) / temp).exp() {
            cur = v;
            ev.accept(from);
            std::mem::swap(&mut seq, &mut cand);
            if cur < best.0 - 1e-9 {
                best = (cur, seq.clone());
            }
        }
    }
    if best.0 >= start - 1e-9 {
        return None;
    }
    let (_, crews) = best_crews(p, &best.1, CREW_STATES);
    Some(timed(p, &best.1, &crews))
}

/// Moves of one polish run on `n` bricks: [`POLISH_WORK`] / n.
pub fn polish_moves(n: usize) -> u64 {
    POLISH_WORK / n.max(1) as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{validate_schedule, Objective, TeamModel};

    /// The least makespan of `seq` over every crew choice, by enumeration.
    fn brute(p: &TeamProblem<'_>, seq: &[BrickId]) -> f64 {
        fn go(p: &TeamProblem<'_>, seq: &[BrickId], zone: f64, ready: &mut Vec<f64>) -> f64 {
            let Some((&b, rest)) = seq.split_first() else {
                return zone;
            };
            let m = ready.len();
            let mut best = f64::INFINITY;
            for u in 0..m {
                for v in u..m {
                    if (p.need(b) == 1) != (u == v) {
                        continue;
                    }
                    let z = zone.max(ready[u]).max(ready[v]) + p.place_s(b);
                    let (ru, rv) = (ready[u], ready[v]);
                    ready[u] = z + p.rest_s(b);
                    ready[v] = z + p.rest_s(b);
                    best = best.min(go(p, rest, z, ready));
                    ready[u] = ru;
                    ready[v] = rv;
                }
            }
            best
        }
        go(p, seq, 0.0, &mut vec![0.0; p.uavs()])
    }

    #[test]
    fn best_crews_is_exact_on_small_sequences_and_its_schedule_validates() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let texts = [
            "R G O\nB O R G",
            "O R\nG B O",
            "R R G\nO B G R",
            "B G\nR O G B",
        ];
        let mut checked = 0;
        for text in texts {
            let wall = mason_wall::parse_layer_text(text, "t").unwrap();
            for m in 2..=3 {
                let p = TeamProblem::new(&wall, TeamModel::thesis(), m, None, Objective::Makespan)
                    .unwrap();
                let mut done = vec![false; p.len()];
                for _ in 0..20 {
                    let mut seq: Vec<BrickId> = wall.ids().collect();
                    for i in (1..seq.len()).rev() {
                        seq.swap(i, rng.gen_range(0..=i));
                    }
                    if !respects_precedence(&p, &seq, &mut done) {
                        continue;
                    }
                    let (v, crews) = best_crews(&p, &seq, 10_000);
                    assert!((v - brute(&p, &seq)).abs() < 1e-9, "{text} m={m}");
                    let mut ev = Evaluator::new(m, seq.len(), 10_000);
                    assert!((ev.eval(&p, &seq, 0) - v).abs() < 1e-9);
                    let s = timed(&p, &seq, &crews);
                    let e = validate_schedule(&wall, p.model(), m, None, &s).unwrap();
                    assert_eq!(e.bricks, p.len());
                    assert!((e.makespan_s - v).abs() < 1e-9);
                    checked += 1;
                }
            }
        }
        assert!(checked > 20, "{checked}");
    }

    #[test]
    fn the_polish_only_returns_shorter_valid_schedules() {
        let wall = mason_wall::builtin("mbzirc").unwrap().wall();
        let p = TeamProblem::new(&wall, TeamModel::thesis(), 5, None, Objective::Makespan).unwrap();
        // A poor start: the bricks level by level, each by the earliest-free UAV.
        let mut seq: Vec<BrickId> = wall.ids().collect();
        seq.sort_by_key(|&b| wall.brick(b).level);
        let crews: Vec<[usize; 2]> = {
            let mut ready = [0.0f64; 5];
            seq.iter()
                .map(|&b| {
                    let mut by: Vec<usize> = (0..5).collect();
                    by.sort_by(|&a, &c| ready[a].total_cmp(&ready[c]));
                    let c = if p.need(b) == 2 {
                        [by[0], by[1]]
                    } else {
                        [by[0], by[0]]
                    };
                    let t = ready[c[0]].max(ready[c[1]]);
                    for u in c {
                        ready[u] = t + p.place_s(b) + p.rest_s(b);
                    }
                    c
                })
                .collect()
        };
        let start = timed(&p, &seq, &crews);
        let before = validate_schedule(&wall, p.model(), 5, None, &start)
            .unwrap()
            .makespan_s;
        let after = polish_zone_makespan(&p, &start, 2_000, 1, &Budget::unlimited())
            .expect("a level-by-level schedule can be shortened");
        let e = validate_schedule(&wall, p.model(), 5, None, &after).unwrap();
        assert_eq!(e.bricks, 42);
        assert!(e.makespan_s < before - 1.0, "{} vs {before}", e.makespan_s);
        // Deterministic for a seed.
        let again = polish_zone_makespan(&p, &start, 2_000, 1, &Budget::unlimited()).unwrap();
        assert_eq!(again, after);
        // Not under the distance rule.
        let q = TeamProblem::new(&wall, TeamModel::cmcp(), 5, None, Objective::Makespan).unwrap();
        assert!(polish_zone_makespan(&q, &start, 100, 1, &Budget::unlimited()).is_none());
    }
}
