//! What `mason agent` runs its decision core against: a real clock ([`MissionClock`], wall
//! time × `--speed` since `--start-at`), a [`Transport`] (Zenoh in `zenoh_link.rs`, or the
//! in-memory [`Hub`] of the tests), and the [`FaultLayer`] that sits between the agent and the
//! transport and loses, duplicates, delays and cuts messages on purpose.
//!
//! Both traits are small so that the driver loop (`agent_cmd::drive`) is tested without Zenoh.

use mason_mission::agent::Message;
use mason_mission::Window;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Where and how an agent talks, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    /// The mission id (one key chunk).
    pub mission: String,
    /// The key prefix (key chunks, no wildcard).
    pub prefix: String,
    /// Endpoints to listen on.
    pub listen: Vec<String>,
    /// Endpoints to connect to.
    pub connect: Vec<String>,
}

#[cfg(test)]
use std::collections::VecDeque;
#[cfg(test)]
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// Mission time.
pub trait Clock {
    /// Mission time now (s; negative before the start).
    fn now(&self) -> f64;
    /// The wall-clock instant at which mission time reaches `t`.
    fn instant_at(&self, t: f64) -> Instant;
}

/// The real clock: mission time = (wall time − `start_at`) × `speed`. Read from the system
/// clock once, then from the monotonic clock, so that it never goes back; processes on one
/// machine agree on it.
#[derive(Clone, Copy, Debug)]
pub struct MissionClock {
    origin: Instant,
    /// Mission time at `origin` (s).
    origin_t: f64,
    speed: f64,
}

/// Seconds since the Unix epoch, now.
pub fn unix_now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

impl MissionClock {
    /// A clock whose mission time 0 is `start_at` (Unix seconds), running `speed` times
    /// faster than the wall clock.
    pub fn new(start_at: f64, speed: f64) -> Self {
        MissionClock {
            origin: Instant::now(),
            origin_t: (unix_now() - start_at) * speed,
            speed,
        }
    }
}

impl Clock for MissionClock {
    fn now(&self) -> f64 {
        self.origin_t + self.origin.elapsed().as_secs_f64() * self.speed
    }

    fn instant_at(&self, t: f64) -> Instant {
        let wall = ((t - self.origin_t) / self.speed).clamp(0.0, 1e6);
        self.origin + Duration::from_secs_f64(wall)
    }
}

/// How messages reach the team and come back from it.
pub trait Transport {
    /// Publishes one message (best effort: a lost message is repaired by the next one).
    fn send(&mut self, m: &Message);
    /// The teammates' messages that arrive before `deadline`: returns as soon as at least
    /// one has arrived (or at the deadline, possibly with none).
    fn recv(&mut self, deadline: Instant) -> Vec<Message>;
}

/// Faults put between an agent and its transport (`--drop`, `--duplicate`, `--delay-jitter`,
/// `--cut`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinkFaults {
    /// Probability that a received message is lost.
    pub drop: f64,
    /// Probability that a received message is delivered twice.
    pub duplicate: f64,
    /// A received message is held back a random time up to this (mission s): messages
    /// overtake each other.
    pub delay_jitter: f64,
    /// Nothing is sent or received in these windows (mission s).
    pub cuts: Vec<Window>,
}

/// A transport with faults on purpose, seeded. A cut stops both directions; loss,
/// duplication and delay are drawn per received message, so that each receiver loses its own
/// messages independently, as on a radio link (and as on the simulator's virtual bus).
pub struct FaultLayer<T, C> {
    inner: T,
    clock: C,
    faults: LinkFaults,
    rng: ChaCha8Rng,
    /// Held-back messages and the mission time they are delivered at.
    held: Vec<(f64, Message)>,
    /// Counters: sent, suppressed by a cut, received, dropped, duplicated.
    pub stats: FaultStats,
}

/// What a [`FaultLayer`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FaultStats {
    /// Messages passed on to the transport.
    pub sent: u64,
    /// Messages not sent or not delivered because of a cut.
    pub cut: u64,
    /// Messages received from the transport.
    pub received: u64,
    /// Messages dropped on purpose.
    pub dropped: u64,
    /// Extra copies delivered.
    pub duplicated: u64,
}

impl<T: Transport, C: Clock> FaultLayer<T, C> {
    /// `inner` with `faults`, drawn from `seed`.
    pub fn new(inner: T, clock: C, faults: LinkFaults, seed: u64) -> Self {
        FaultLayer {
            inner,
            clock,
            faults,
            rng: ChaCha8Rng::seed_from_u64(seed),
            held: Vec::new(),
            stats: FaultStats::default(),
        }
    }

    /// The transport inside.
    pub fn into_inner(self) -> T {
        self.inner
    }

    fn cut(&self, t: f64) -> bool {
        self.faults.cuts.iter().any(|w| w.contains(t))
    }

    /// Held-back messages due by `now`, in delivery order.
    fn due(&mut self, now: f64) -> Vec<Message> {
        self.held.sort_by(|a, b| a.0.total_cmp(&b.0));
        let n = self.held.iter().take_while(|(t, _)| *t <= now).count();
        self.held.drain(..n).map(|(_, m)| m).collect()
    }
}

impl<T: Transport, C: Clock> Transport for FaultLayer<T, C> {
    fn send(&mut self, m: &Message) {
        if self.cut(self.clock.now()) {
            self.stats.cut += 1;
            return;
        }
        self.stats.sent += 1;
        self.inner.send(m);
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Message> {
        loop {
            let now = self.clock.now();
            let mut out = self.due(now);
            if !out.is_empty() {
                return out;
            }
            let next_held = self
                .held
                .iter()
                .map(|(t, _)| *t)
                .fold(f64::INFINITY, f64::min);
            let until = if next_held.is_finite() {
                deadline.min(self.clock.instant_at(next_held))
            } else {
                deadline
            };
            let arrived = self.inner.recv(until);
            let now = self.clock.now();
            for m in arrived {
                self.stats.received += 1;
                if self.cut(now) {
                    self.stats.cut += 1;
                    continue;
                }
                if self.faults.drop > 0.0 && self.rng.gen::<f64>() < self.faults.drop {
                    self.stats.dropped += 1;
                    continue;
                }
                let twice =
                    self.faults.duplicate > 0.0 && self.rng.gen::<f64>() < self.faults.duplicate;
                if twice {
                    self.stats.duplicated += 1;
                }
                for _ in 0..1 + usize::from(twice) {
                    let delay = if self.faults.delay_jitter > 0.0 {
                        self.faults.delay_jitter * self.rng.gen::<f64>()
                    } else {
                        0.0
                    };
                    self.held.push((now + delay, m.clone()));
                }
            }
            out = self.due(now);
            if !out.is_empty() || Instant::now() >= deadline {
                return out;
            }
        }
    }
}

/// An in-memory bus between agents in one process (threads): every message goes to every
/// other member. For tests of the driver loop without Zenoh.
#[cfg(test)]
pub struct Hub {
    senders: Vec<mpsc::Sender<Message>>,
    receivers: VecDeque<mpsc::Receiver<Message>>,
}

/// One member's end of a [`Hub`].
#[cfg(test)]
pub struct HubLink {
    me: usize,
    senders: Vec<mpsc::Sender<Message>>,
    rx: mpsc::Receiver<Message>,
}

#[cfg(test)]
impl Hub {
    /// A bus for `n` members.
    pub fn new(n: usize) -> Self {
        let (senders, receivers) = (0..n).map(|_| mpsc::channel()).unzip();
        Hub { senders, receivers }
    }

    /// The links, member 0 first.
    pub fn links(mut self) -> Vec<HubLink> {
        let senders = self.senders.clone();
        (0..senders.len())
            .map(|me| HubLink {
                me,
                senders: senders.clone(),
                rx: self.receivers.pop_front().expect("one per member"),
            })
            .collect()
    }
}

#[cfg(test)]
impl Transport for HubLink {
    fn send(&mut self, m: &Message) {
        for (v, s) in self.senders.iter().enumerate() {
            if v != self.me {
                let _ = s.send(m.clone());
            }
        }
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Message> {
        let wait = deadline.saturating_duration_since(Instant::now());
        let mut out = Vec::new();
        if let Ok(m) = self.rx.recv_timeout(wait) {
            out.push(m);
            out.extend(self.rx.try_iter());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;
    use std::rc::Rc;

    /// A clock the test moves by hand; mission time = wall seconds since creation.
    #[derive(Clone)]
    struct HandClock(Rc<Cell<f64>>, Instant);

    impl Clock for HandClock {
        fn now(&self) -> f64 {
            self.0.get()
        }
        fn instant_at(&self, t: f64) -> Instant {
            self.1 + Duration::from_secs_f64(t.max(0.0))
        }
    }

    /// Gives back what it was told to, once.
    struct Canned(Vec<Message>);

    impl Transport for Canned {
        fn send(&mut self, _: &Message) {}
        fn recv(&mut self, _: Instant) -> Vec<Message> {
            std::mem::take(&mut self.0)
        }
    }

    fn message(seq: u64) -> Message {
        serde_json::from_value(serde_json::json!({
            "v": 1, "mission": "m", "uav": 1, "incarnation": 1, "seq": seq, "t": 0.0,
            "kind": "heartbeat",
            "status": {"state": "Check", "outcome": "start", "x": 0.0, "y": 0.0, "z": 0.0,
                "mode": "comm", "brick": null, "claimed_at": 0.0, "grasped": false,
                "in_zone": false, "request": null, "acks": [], "placed": [],
                "heard": [-1.0, 0.0], "out": []}
        }))
        .expect("a message")
    }

    #[test]
    fn a_cut_stops_both_directions() {
        let clock = HandClock(Rc::new(Cell::new(5.0)), Instant::now());
        let faults = LinkFaults {
            cuts: vec![Window { from: 4.0, to: 6.0 }],
            ..LinkFaults::default()
        };
        let mut layer = FaultLayer::new(Canned(vec![message(1)]), clock.clone(), faults, 1);
        layer.send(&message(2));
        assert!(layer.recv(Instant::now()).is_empty());
        assert_eq!(layer.stats.cut, 2);
        clock.0.set(6.5);
        layer.inner.0.push(message(3));
        assert_eq!(layer.recv(Instant::now()).len(), 1);
    }

    #[test]
    fn duplicates_and_drops_follow_the_seed() {
        let run = |seed| {
            let clock = HandClock(Rc::new(Cell::new(1.0)), Instant::now());
            let faults = LinkFaults {
                drop: 0.3,
                duplicate: 0.3,
                ..LinkFaults::default()
            };
            let all = (1..=200).map(message).collect();
            let mut layer = FaultLayer::new(Canned(all), clock, faults, seed);
            let got: Vec<u64> = layer.recv(Instant::now()).iter().map(|m| m.seq).collect();
            (got, layer.stats)
        };
        let (a, stats) = run(7);
        assert_eq!(run(7).0, a);
        assert!(stats.dropped > 30 && stats.dropped < 100, "{stats:?}");
        assert!(stats.duplicated > 20, "{stats:?}");
        assert_eq!(
            a.len() as u64,
            200 - stats.dropped + stats.duplicated,
            "{stats:?}"
        );
    }

    #[test]
    fn jitter_holds_messages_back_until_due() {
        let clock = HandClock(Rc::new(Cell::new(10.0)), Instant::now());
        let faults = LinkFaults {
            delay_jitter: 2.0,
            ..LinkFaults::default()
        };
        let all = (1..=50).map(message).collect();
        let mut layer = FaultLayer::new(Canned(all), clock.clone(), faults, 3);
        let first = layer.recv(Instant::now()).len();
        assert!(first < 50);
        clock.0.set(12.0);
        let rest: Vec<u64> = layer.recv(Instant::now()).iter().map(|m| m.seq).collect();
        assert_eq!(first + rest.len(), 50);
        assert!(rest.windows(2).any(|w| w[0] > w[1]), "reordered: {rest:?}");
    }
}
