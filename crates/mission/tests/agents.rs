//! The agents' protocol on the virtual bus: every run is checked by `check_trace`, and every
//! brick must be placed exactly once.

use mason_mission::agent::{
    Agent, AgentSetup, Arrival, Command, DropCause, DropCounts, Message, MessageKind, Order,
    SimulatedVehicle, DEFAULT_DEAD_AFTER_S, DEFAULT_LEASE_S,
};
use mason_mission::bus::{fly_bus, BusFaults, BusRun};
use mason_mission::{
    check_trace, slot_length, Coord, EventKind, LinkFaults, MissionConfig, UavState, Window,
};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_wall::{BrickId, Wall};

fn wall(name: &str) -> Wall {
    mason_wall::builtin(name).unwrap().wall()
}

fn order(w: &Wall, model: &CostModel) -> Vec<BrickId> {
    let p = BuildProblem::new(w, model.clone()).unwrap();
    PlannerSpec::Exact
        .plan(&p, &mason_order::Budget::unlimited())
        .order
        .unwrap()
}

fn fly(name: &str, uavs: usize, coord: Coord, faults: &BusFaults, seed: u64) -> (BusRun, usize) {
    fly_with(name, uavs, coord, faults, seed, |_| {})
}

fn fly_with(
    name: &str,
    uavs: usize,
    coord: Coord,
    faults: &BusFaults,
    seed: u64,
    tune: impl Fn(&mut MissionConfig),
) -> (BusRun, usize) {
    let (run, bricks, summary) = try_fly(name, uavs, coord, faults, seed, tune);
    assert!(summary.is_ok(), "{name} {coord:?} seed {seed}: {summary:?}");
    (run, bricks)
}

fn try_fly(
    name: &str,
    uavs: usize,
    coord: Coord,
    faults: &BusFaults,
    seed: u64,
    tune: impl Fn(&mut MissionConfig),
) -> (
    BusRun,
    usize,
    Result<mason_mission::TraceSummary, mason_mission::TraceError>,
) {
    let w = wall(name);
    let model = CostModel::default();
    let order = order(&w, &model);
    let mut config = MissionConfig::with_uavs(uavs);
    tune(&mut config);
    let slot = slot_length(&w, &model, &config).unwrap();
    let setup = AgentSetup {
        wall: &w,
        order: &order,
        assignment: None,
        model: &model,
        config: &config,
        coord,
        slot_s: slot,
        uav: 0,
        mission: "test",
        incarnation: 1,
        dead_after_s: DEFAULT_DEAD_AFTER_S,
        lease_s: DEFAULT_LEASE_S,
    };
    let run = fly_bus(setup, faults, seed);
    let summary = check_trace(&w, uavs, &run.events);
    (run, w.len(), summary)
}

fn placed(run: &BusRun) -> usize {
    run.events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Place { .. }))
        .count()
}

#[test]
fn a_fault_free_team_builds_every_wall_with_every_policy() {
    for name in ["thesis-2x5", "levels5-width5", "mbzirc"] {
        for coord in [Coord::Comm, Coord::Windows, Coord::Auto] {
            let (run, bricks) = fly(name, 3, coord, &BusFaults::default(), 1);
            assert!(run.finished, "{name} {coord:?}");
            assert_eq!(placed(&run), bricks, "{name} {coord:?}");
        }
    }
}

#[test]
fn a_killed_agent_is_declared_out_and_the_others_finish_its_work() {
    for at in [40.0, 95.0, 150.0, 260.0] {
        let faults = BusFaults {
            kills: vec![(1, at)],
            ..BusFaults::default()
        };
        let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 3);
        assert!(run.finished, "kill at {at}");
        assert_eq!(placed(&run), bricks, "kill at {at}");
    }
}

#[test]
fn a_cut_sends_auto_to_windows_and_back_without_sharing_the_zone() {
    let faults = BusFaults {
        link: LinkFaults {
            cuts: vec![Window {
                from: 100.0,
                to: 125.0,
            }],
            ..LinkFaults::default()
        },
        ..BusFaults::default()
    };
    let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 5);
    assert!(run.finished);
    assert_eq!(placed(&run), bricks);
    let modes: Vec<_> = run
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Comm { mode } => Some((e.t, mode)),
            _ => None,
        })
        .collect();
    assert!(
        modes
            .iter()
            .any(|(t, m)| *t >= 100.0 && *t <= 110.0 && *m == mason_mission::CommMode::Windows),
        "{modes:?}"
    );
    assert!(
        modes
            .iter()
            .any(|(t, m)| *t >= 125.0 && *m == mason_mission::CommMode::Comm),
        "{modes:?}"
    );
}

#[test]
fn lost_duplicated_and_reordered_messages_do_no_harm() {
    for seed in 1..=10 {
        let faults = BusFaults {
            link: LinkFaults {
                loss: 0.3,
                duplicate: 0.2,
                latency: 0.05,
                jitter: 0.8,
                cuts: Vec::new(),
            },
            ..BusFaults::default()
        };
        for coord in [Coord::Comm, Coord::Auto] {
            let (run, bricks) = fly("mbzirc", 3, coord, &faults, seed);
            assert!(run.finished, "{coord:?} seed {seed}");
            assert_eq!(placed(&run), bricks, "{coord:?} seed {seed}");
        }
    }
}

#[test]
fn a_restarted_agent_rejoins_without_placing_a_brick_twice() {
    for (kill, restart) in [(60.0, 70.0), (150.0, 151.0), (200.0, 260.0)] {
        let faults = BusFaults {
            kills: vec![(2, kill)],
            restarts: vec![(2, restart)],
            ..BusFaults::default()
        };
        let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 9);
        assert!(run.finished, "kill {kill} restart {restart}");
        assert_eq!(placed(&run), bricks, "kill {kill} restart {restart}");
        assert!(
            run.events
                .iter()
                .any(|e| e.uav == 2 && e.t > restart && matches!(e.kind, EventKind::Place { .. })),
            "the restarted agent places bricks again"
        );
    }
}

/// UAV 1's first messages, as it sends them at 0, 1, 2, 3 and 4 s on `name` with `uavs` UAVs.
fn first_messages(name: &str, uavs: usize) -> Vec<Message> {
    let w = wall(name);
    let model = CostModel::default();
    let order = order(&w, &model);
    let config = MissionConfig::with_uavs(uavs);
    let setup = AgentSetup {
        wall: &w,
        order: &order,
        assignment: None,
        model: &model,
        config: &config,
        coord: Coord::Auto,
        slot_s: slot_length(&w, &model, &config).unwrap(),
        uav: 1,
        mission: "test",
        incarnation: 1,
        dead_after_s: DEFAULT_DEAD_AFTER_S,
        lease_s: DEFAULT_LEASE_S,
    };
    let mut agent = Agent::new(setup, Box::new(SimulatedVehicle::new(&config, 1)));
    let mut out = Vec::new();
    for t in 0..5 {
        out.extend(agent.tick(f64::from(t)).messages);
    }
    out
}

/// What a stranger on the network tries (issue #27), with the drops each attempt must cause
/// in a team of three (UAV 1 drops what is sent in its name as `own`).
fn rogue_samples(bricks: usize) -> (Vec<(f64, Arrival)>, DropCounts) {
    let first = first_messages("mbzirc", 3);
    let heartbeat = first[0].clone();
    let mut samples = Vec::new();
    let mut expect = Expect::default();
    // The heartbeat of "UAV 7" that once ended every agent.
    for k in 0..5 {
        let mut m = heartbeat.clone();
        m.uav = 7;
        m.t = 30.0 + f64::from(k);
        samples.push((m.t, Arrival::keyed(m)));
        expect.all(DropCause::UnknownUav);
    }
    // Malformed samples, and one too long to read.
    let junk: [&[u8]; 3] = [b"{", br#"{"v":1,"uav":"one"}"#, b"[1,2,3]"];
    for j in junk {
        samples.push((40.0, Arrival::bytes(None, j.to_vec())));
        expect.all(DropCause::Malformed);
    }
    samples.push((40.0, Arrival::bytes(None, vec![b' '; 1 << 20])));
    expect.all(DropCause::Size);
    // Replays of UAV 1's first messages: while recent, and once old.
    for (at, cause) in [(100.0, DropCause::Replay), (300.0, DropCause::Time)] {
        for m in &first {
            samples.push((at, Arrival::keyed(m.clone())));
            expect.others_of_1(cause);
        }
    }
    // UAV 1's status forged under a higher incarnation: every brick placed.
    let mut forged = heartbeat.clone();
    forged.incarnation = 2;
    forged.t = 60.0;
    forged.kind = MessageKind::Placed;
    forged.status.placed = (0..bricks as u32).collect();
    samples.push((60.0, Arrival::keyed(forged)));
    expect.others_of_1(DropCause::Implausible);
    // A flood: 10 000 samples within one second.
    for i in 0..10_000u64 {
        let mut m = heartbeat.clone();
        m.t = 200.0;
        let at = 200.0 + i as f64 * 1e-4;
        let sample = match i % 4 {
            0 => {
                m.seq = u64::MAX - i;
                expect.others_of_1(DropCause::Jump);
                Arrival::keyed(m)
            }
            1 => {
                m.uav = 9;
                expect.all(DropCause::UnknownUav);
                Arrival::keyed(m)
            }
            2 => {
                m.mission = "elsewhere".into();
                expect.all(DropCause::Mission);
                Arrival::keyed(m)
            }
            _ => {
                let mut a = Arrival::keyed(m);
                if let Some(k) = a.key.as_mut() {
                    k.uav = "2".into();
                }
                expect.others_of_1(DropCause::Key);
                a
            }
        };
        samples.push((at, sample));
    }
    (samples, expect.0)
}

/// The drops a team of three must count.
#[derive(Default)]
struct Expect(DropCounts);

impl Expect {
    /// Every agent drops it for `cause`.
    fn all(&mut self, cause: DropCause) {
        for _ in 0..3 {
            self.0.add(&one(cause));
        }
    }
    /// A sample in UAV 1's name: UAV 1 drops it as its own, the others for `cause`.
    fn others_of_1(&mut self, cause: DropCause) {
        self.0.add(&one(DropCause::Own));
        self.0.add(&one(cause));
        self.0.add(&one(cause));
    }
}

fn one(cause: DropCause) -> DropCounts {
    let mut c = DropCounts::default();
    c.record(cause);
    c
}

#[test]
fn a_rogue_on_the_network_changes_nothing_but_the_counters() {
    let bricks = wall("mbzirc").len();
    let (honest, _) = fly("mbzirc", 3, Coord::Auto, &BusFaults::default(), 4);
    assert_eq!(honest.drops.total(), 0, "{:?}", honest.drops);
    let (rogue, expected) = rogue_samples(bricks);
    let faults = BusFaults {
        injected: rogue.clone(),
        ..BusFaults::default()
    };
    let (attacked, placed_bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 4);
    assert!(attacked.finished);
    assert_eq!(placed(&attacked), placed_bricks);
    // Not one event changed: every sample was dropped, and only counted.
    assert_eq!(attacked.events, honest.events);
    assert_eq!(attacked.drops.total(), 3 * rogue.len() as u64);
    assert_eq!(attacked.drops, expected, "{:?}", attacked.drops);
}

fn command(seq: u64, t: f64, order: Order) -> (f64, Arrival) {
    let c = Command {
        v: 1,
        mission: "test".into(),
        station: 0,
        seq,
        t,
        order,
    };
    (t, Arrival::command(c))
}

fn states(run: &BusRun, uav: u32, outcome: &str) -> Vec<(f64, UavState)> {
    run.events
        .iter()
        .filter(|e| e.uav == uav)
        .filter_map(|e| match e.kind {
            EventKind::State {
                state, outcome: o, ..
            } if o == outcome => Some((e.t, state)),
            _ => None,
        })
        .collect()
}

#[test]
fn a_ground_station_lands_one_uav_and_resumes_it() {
    let faults = BusFaults {
        injected: vec![
            command(1, 100.0, Order::Land { uav: 1 }),
            command(2, 400.0, Order::Resume),
        ],
        ..BusFaults::default()
    };
    let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 6);
    assert!(run.finished);
    assert_eq!(placed(&run), bricks);
    let landed = states(&run, 1, "commanded");
    assert!(
        landed
            .iter()
            .any(|(t, s)| *s == UavState::Land && *t >= 100.0),
        "{landed:?}"
    );
    let held = states(&run, 1, "held");
    assert_eq!(held.len(), 1, "{held:?}");
    // Nothing placed by UAV 1 while it was held, and bricks placed after the resume.
    let placed_by_1: Vec<f64> = run
        .events
        .iter()
        .filter(|e| e.uav == 1 && matches!(e.kind, EventKind::Place { .. }))
        .map(|e| e.t)
        .collect();
    assert!(
        !placed_by_1.iter().any(|&t| t > held[0].0 && t < 400.0),
        "{placed_by_1:?}"
    );
    assert!(placed_by_1.iter().any(|&t| t > 400.0), "{placed_by_1:?}");
    // The other UAVs were not told to land.
    assert!(states(&run, 0, "commanded").is_empty() && states(&run, 2, "held").is_empty());
    assert_eq!(run.drops.total(), 0);
}

#[test]
fn an_abort_lands_the_team_safely() {
    let faults = BusFaults {
        injected: vec![command(1, 300.0, Order::Abort)],
        ..BusFaults::default()
    };
    let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 6);
    assert!(run.finished);
    let n = placed(&run);
    assert!(n > 0 && n < bricks, "{n}");
    for u in 0..3 {
        let aborted = states(&run, u, "aborted");
        assert_eq!(
            aborted.first().map(|s| s.1),
            Some(UavState::Land),
            "UAV {u}"
        );
    }
    // A replayed abort, or one from a station out of range, is dropped.
    let again = BusFaults {
        injected: vec![
            command(1, 300.0, Order::Abort),
            command(1, 310.0, Order::Abort),
        ],
        ..BusFaults::default()
    };
    let (twice, _) = fly("mbzirc", 3, Coord::Auto, &again, 6);
    assert_eq!(twice.drops.count(DropCause::Replay), 3);
}

/// Random faults for case `case` (the same for a case on every machine).
fn random_case(case: usize) -> (BusFaults, Coord, f64) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2026 + case as u64);
    let from = rng.gen_range(0.0..300.0);
    let mut faults = BusFaults {
        link: LinkFaults {
            loss: rng.gen_range(0.0..0.4),
            duplicate: rng.gen_range(0.0..0.3),
            latency: rng.gen_range(0.0..0.3),
            jitter: rng.gen_range(0.0..2.0),
            cuts: vec![Window {
                from,
                to: from + rng.gen_range(1.0..60.0),
            }],
        },
        ..BusFaults::default()
    };
    if rng.gen_bool(0.5) {
        let u = rng.gen_range(0..3);
        let t = rng.gen_range(10.0..400.0);
        faults.kills.push((u, t));
        if rng.gen_bool(0.5) {
            faults.restarts.push((u, t + rng.gen_range(0.5..60.0)));
        }
    }
    let coord = [Coord::Comm, Coord::Windows, Coord::Auto][case % 3];
    (faults, coord, rng.gen_range(0.0..0.3))
}

fn random_cases() -> usize {
    std::env::var("MASON_AGENT_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60)
}

#[test]
fn random_faults_never_break_the_safety_rules() {
    let mut finished = 0;
    let mut broken = Vec::new();
    for case in 0..random_cases() {
        let (faults, coord, grasp) = random_case(case);
        let (run, bricks, summary) = try_fly("mbzirc", 3, coord, &faults, case as u64, |c| {
            c.faults.grasp_fail = grasp;
        });
        // check_trace: no shared zone, no brick before its supports, none placed twice,
        // every grasped brick accounted for.
        if let Err(e) = summary {
            broken.push(format!("case {case} {coord:?}: {e:?}"));
        }
        // The checks on arrival drop nothing an honest teammate sends but duplicates.
        let drops = run.drops;
        if drops.total() != drops.count(DropCause::Replay) {
            broken.push(format!(
                "case {case} {coord:?}: honest samples dropped {drops:?}"
            ));
        }
        if run.finished && placed(&run) == bricks {
            finished += 1;
        }
    }
    assert!(
        broken.is_empty(),
        "{} of {} cases broke a rule:\n{}",
        broken.len(),
        random_cases(),
        broken.join("\n")
    );
    // Faults may leave a wall unfinished (a lone survivor cannot carry orange bricks), but
    // most runs finish.
    assert!(finished * 10 >= random_cases() * 8, "{finished} finished");
}

/// Found by the 3000-case run (cases 701, 1136, 2062): a pair's leader whose partner was
/// killed grasps the orange brick unaware, learns the brick fell, and must report its own
/// loss, since the fall the partner's death reported came before its grasp.
#[test]
fn a_leader_grasping_after_its_partner_died_reports_its_own_loss() {
    for case in [701, 1136, 2062] {
        let (faults, coord, grasp) = random_case(case);
        let (run, _, summary) = try_fly("mbzirc", 3, coord, &faults, case as u64, |c| {
            c.faults.grasp_fail = grasp;
        });
        assert!(summary.is_ok(), "case {case}: {summary:?}");
        assert!(run
            .events
            .iter()
            .any(|e| matches!(e.kind, EventKind::Lost { .. })));
    }
}

#[test]
#[ignore = "debug aid: MASON_CASE=N prints random case N"]
fn dump_case() {
    // Skips with a notice when MASON_CASE is unset or not a number, so that `-- --ignored`
    // runs of the whole file pass through it.
    let Some(case) = std::env::var("MASON_CASE")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
    else {
        println!("dump_case: skipped (set MASON_CASE to a case number)");
        return;
    };
    let (faults, coord, grasp) = random_case(case);
    println!("{faults:?} {coord:?} grasp {grasp}");
    let (run, _, summary) = try_fly("mbzirc", 3, coord, &faults, case as u64, |c| {
        c.faults.grasp_fail = grasp;
    });
    for e in &run.events {
        println!("{:8.2} {} {:?}", e.t, e.uav, e.kind);
    }
    println!("{summary:?}");
}

#[test]
fn on_a_perfect_bus_the_agents_build_as_fast_as_the_simulator() {
    use mason_mission::{make_policy, simulate, MissionInput};
    for name in ["thesis-2x5", "levels5-width5", "mbzirc"] {
        for coord in [Coord::Comm, Coord::Windows, Coord::Auto] {
            let w = wall(name);
            let model = CostModel::default();
            let order = order(&w, &model);
            let config = MissionConfig::with_uavs(3);
            let slot = slot_length(&w, &model, &config).unwrap();
            let input = MissionInput {
                wall: &w,
                order: &order,
                model: &model,
                assignment: None,
                replanner: None,
                config: &config,
            };
            let sim = simulate(input, make_policy(coord, slot).as_mut(), 1, &mut ());
            let (run, _) = fly(name, 3, coord, &BusFaults::default(), 1);
            let end = |events: &[mason_mission::Event]| {
                events
                    .iter()
                    .filter(|e| matches!(e.kind, EventKind::Place { .. }))
                    .map(|e| e.t)
                    .fold(0.0, f64::max)
            };
            let agents = end(&run.events);
            let simulated = sim.metrics.makespan_s.unwrap();
            // Measured: windows equal, comm and auto 1.5-2.7 % slower (a request's round
            // trip, the wait until every teammate has heard a claim).
            assert!(
                (agents - simulated).abs() <= 0.03 * simulated,
                "{name} {coord:?}: simulator {simulated:.1} s, agents {agents:.1} s"
            );
        }
    }
}

/// A kill that breaks an orange pair: the survivor waits at the pile for another partner
/// (`Detect`, outcome `partner_failed`) while a teammate waits at the wall with a later brick.
/// The deadlock rule once counted only `waiting_partner` as waiting at the pile, so such a
/// team waited until `max_time_s`: 34 of 891 kill times (every 3 s from 10 to 900 s, each UAV)
/// stalled on the bus, and real launches did too (`--seed 303 --kill 0@311`, 7 of 42 bricks).
/// These are some of those kill times; after the fix all 891 finish.
#[test]
fn a_pair_broken_by_a_kill_finds_another_partner() {
    for (u, at) in [
        (0, 34.0),
        (0, 61.0),
        (0, 298.0),
        (1, 31.0),
        (1, 565.0),
        (1, 595.0),
        (2, 301.0),
        (2, 328.0),
        (2, 565.0),
    ] {
        let faults = BusFaults {
            kills: vec![(u, at)],
            ..BusFaults::default()
        };
        let (run, bricks) = fly("mbzirc", 3, Coord::Auto, &faults, 3);
        assert!(run.finished, "kill {u}@{at}");
        assert_eq!(placed(&run), bricks, "kill {u}@{at}");
    }
}
