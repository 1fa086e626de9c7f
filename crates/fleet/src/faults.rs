//! The fault layer: faults on purpose between an agent and its transport, drawn from the same
//! fault model as the simulator's virtual bus ([`mason_mission::LinkFaults`]).

use crate::clock::Clock;
use crate::transport::Transport;
use mason_mission::agent::{Arrival, Message};
use mason_mission::{Fate, LinkFaults};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// A transport with faults on purpose, seeded. A cut stops both directions; loss,
/// duplication and delay are drawn per received message ([`LinkFaults::fate`]), so that each
/// receiver loses its own messages independently, as on a radio link and on the virtual bus.
pub struct FaultLayer<T, C> {
    inner: T,
    clock: C,
    faults: LinkFaults,
    rng: ChaCha8Rng,
    /// Held-back messages and the mission time they are delivered at.
    held: Vec<(f64, Arrival)>,
    /// What the layer did so far.
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

    /// The transport inside, borrowed.
    pub fn inner_mut(&mut self) -> &mut T {
        &mut self.inner
    }

    /// Held-back messages due by `now`, in delivery order.
    fn due(&mut self, now: f64) -> Vec<Arrival> {
        self.held.sort_by(|a, b| a.0.total_cmp(&b.0));
        let n = self.held.iter().take_while(|(t, _)| *t <= now).count();
        self.held.drain(..n).map(|(_, m)| m).collect()
    }

    /// One received message through the fault model.
    fn arrive(&mut self, now: f64, m: Arrival) {
        self.stats.received += 1;
        match self.faults.fate(now, &mut self.rng) {
            Fate::Cut => self.stats.cut += 1,
            Fate::Lost => self.stats.dropped += 1,
            Fate::Delivered { first, second } => {
                if let Some(d) = second {
                    self.stats.duplicated += 1;
                    self.held.push((now + d, m.clone()));
                }
                self.held.push((now + first, m));
            }
        }
    }
}

impl<T: Transport, C: Clock> Transport for FaultLayer<T, C> {
    fn send(&mut self, m: &Message) {
        if self.faults.is_cut(self.clock.now()) {
            self.stats.cut += 1;
            return;
        }
        self.stats.sent += 1;
        self.inner.send(m);
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Arrival> {
        loop {
            let now = self.clock.now();
            let out = self.due(now);
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
                self.arrive(now, m);
            }
            let out = self.due(now);
            if !out.is_empty() || Instant::now() >= deadline {
                return out;
            }
        }
    }
    fn overflowed(&mut self) -> u64 {
        self.inner.overflowed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transport::testing::{message, seq_of, Canned};
    use mason_mission::Window;
    use std::cell::Cell;
    use std::rc::Rc;
    use std::time::Duration;

    /// A clock the test moves by hand.
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

    fn clock_at(t: f64) -> HandClock {
        HandClock(Rc::new(Cell::new(t)), Instant::now())
    }

    #[test]
    fn a_cut_stops_both_directions() {
        let clock = clock_at(5.0);
        let faults = LinkFaults {
            cuts: vec![Window { from: 4.0, to: 6.0 }],
            ..LinkFaults::default()
        };
        let mut layer = FaultLayer::new(Canned(vec![message(1)]), clock.clone(), faults, 1);
        layer.send(&message(2));
        assert!(layer.recv(Instant::now()).is_empty());
        assert_eq!(layer.stats.cut, 2);
        clock.0.set(6.5);
        layer.inner_mut().0.push(message(3));
        assert_eq!(layer.recv(Instant::now()).len(), 1);
    }

    #[test]
    fn duplicates_and_drops_follow_the_seed() {
        let run = |seed| {
            let faults = LinkFaults {
                loss: 0.3,
                duplicate: 0.3,
                ..LinkFaults::default()
            };
            let all = (1..=200).map(message).collect();
            let mut layer = FaultLayer::new(Canned(all), clock_at(1.0), faults, seed);
            let got: Vec<u64> = layer.recv(Instant::now()).iter().map(seq_of).collect();
            (got, layer.stats)
        };
        let (a, stats) = run(7);
        assert_eq!(run(7).0, a);
        assert_ne!(run(8).0, a);
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
        let clock = clock_at(10.0);
        let faults = LinkFaults {
            jitter: 2.0,
            ..LinkFaults::default()
        };
        let all = (1..=50).map(message).collect();
        let mut layer = FaultLayer::new(Canned(all), clock.clone(), faults, 3);
        let first = layer.recv(Instant::now()).len();
        assert!(first < 50);
        clock.0.set(12.0);
        let rest: Vec<u64> = layer.recv(Instant::now()).iter().map(seq_of).collect();
        assert_eq!(first + rest.len(), 50);
        assert!(rest.windows(2).any(|w| w[0] > w[1]), "reordered: {rest:?}");
    }

    #[test]
    fn latency_delays_every_message() {
        let clock = clock_at(0.0);
        let faults = LinkFaults {
            latency: 1.0,
            ..LinkFaults::default()
        };
        let mut layer = FaultLayer::new(Canned(vec![message(1)]), clock.clone(), faults, 3);
        assert!(layer.recv(Instant::now()).is_empty());
        clock.0.set(1.0);
        assert_eq!(layer.recv(Instant::now()).len(), 1);
    }
}
