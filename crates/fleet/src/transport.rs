//! How an agent's messages reach its team: the [`Transport`] trait, and [`Hub`], an in-memory
//! bus between agents on threads of one process (for tests and for trying the runtime
//! without a network). The Zenoh transport is `ZenohLink` (feature `zenoh`).
//!
//! A transport checks nothing: it hands every sample over as an [`Arrival`] (its bytes, or a
//! message in-process, and the key it came on), and the agent checks it on arrival
//! ([`mason_mission::agent::Agent::admit`], called by [`crate::drive()`]).

use mason_mission::agent::{Arrival, Message};
use std::collections::VecDeque;
use std::sync::mpsc;
use std::time::Instant;

/// How messages reach the team and come back from it.
pub trait Transport {
    /// Publishes one message (best effort: a lost message is repaired by the next one).
    fn send(&mut self, m: &Message);
    /// The samples that arrive before `deadline`, unchecked: returns as soon as at least one
    /// has arrived (or at the deadline, possibly with none).
    fn recv(&mut self, deadline: Instant) -> Vec<Arrival>;
    /// Samples dropped unread since the last call because the receive queue was full (a
    /// bounded transport under a flood); 0 by default.
    fn overflowed(&mut self) -> u64 {
        0
    }
}

/// An in-memory bus between agents in one process (threads): every message goes to every
/// other member, on the key of its `uav` and `kind` (as an honest Zenoh peer publishes).
pub struct Hub {
    senders: Vec<mpsc::Sender<Arrival>>,
    receivers: VecDeque<mpsc::Receiver<Arrival>>,
}

/// One member's end of a [`Hub`].
pub struct HubLink {
    me: usize,
    senders: Vec<mpsc::Sender<Arrival>>,
    rx: mpsc::Receiver<Arrival>,
}

impl HubLink {
    /// Sends any sample, on any key, to every other member: what a stranger on a shared
    /// network can do (the tests' rogue).
    pub fn inject(&self, sample: &Arrival) {
        for (v, s) in self.senders.iter().enumerate() {
            if v != self.me {
                let _ = s.send(sample.clone());
            }
        }
    }
}

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
            .filter_map(|me| {
                Some(HubLink {
                    me,
                    senders: senders.clone(),
                    rx: self.receivers.pop_front()?,
                })
            })
            .collect()
    }
}

impl Transport for HubLink {
    fn send(&mut self, m: &Message) {
        self.inject(&Arrival::keyed(m.clone()));
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Arrival> {
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
pub(crate) mod testing {
    //! Messages and transports for the tests of this crate.
    use super::*;

    /// A heartbeat of UAV 1 with sequence number `seq`.
    pub fn message(seq: u64) -> Message {
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

    /// Gives back what it was told to, once.
    pub struct Canned(pub Vec<Message>);

    impl Transport for Canned {
        fn send(&mut self, _: &Message) {}
        fn recv(&mut self, _: Instant) -> Vec<Arrival> {
            std::mem::take(&mut self.0)
                .into_iter()
                .map(Arrival::keyed)
                .collect()
        }
    }

    /// The sequence number of a sample that carries a message.
    pub fn seq_of(a: &Arrival) -> u64 {
        match &a.body {
            mason_mission::agent::Body::Message(m) => m.seq,
            mason_mission::agent::Body::Bytes(_) | mason_mission::agent::Body::Command(_) => 0,
        }
    }

    #[test]
    fn the_hub_delivers_to_every_other_member() {
        let mut links = Hub::new(3).links();
        links[0].send(&message(1));
        let soon = Instant::now() + std::time::Duration::from_millis(50);
        assert!(links[0].recv(soon).is_empty());
        assert_eq!(links[1].recv(soon).len(), 1);
        let got = links[2].recv(soon);
        assert_eq!(seq_of(&got[0]), 1);
        // On its sender's key.
        assert_eq!(got[0].key.as_ref().map(|k| k.uav.as_str()), Some("1"));
    }
}
