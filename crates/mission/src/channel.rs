//! The simulated radio: messages may be lost, arrive late, or not at all during a blackout.
//! A lost message is repeated by the next heartbeat, so a fact sent at time s is known at the
//! first successful send s + k·heartbeat (k ≥ 0), plus the latency.

use crate::config::{CoordParams, Faults, Window};
use rand::Rng;

/// Message delivery between UAVs.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    loss: f64,
    latency: f64,
    heartbeat: f64,
    blackouts: Vec<Window>,
}

/// Sends give up after this many heartbeats (a permanent blackout or loss = 1).
const MAX_REPEATS: u32 = 1_000_000;

impl Channel {
    /// The channel of a fault set.
    pub fn new(faults: &Faults, coord: &CoordParams) -> Self {
        Channel {
            loss: faults.msg_loss,
            latency: faults.latency,
            heartbeat: coord.heartbeat_s,
            blackouts: faults.blackout.clone(),
        }
    }

    /// Whether every message gets through: no loss and no blackout. Heartbeats then carry
    /// no news, and the simulator need not fly them.
    pub fn perfect(&self) -> bool {
        self.loss == 0.0 && self.blackouts.is_empty()
    }

    /// Whether a message sent at `t` falls in a blackout.
    pub fn blacked_out(&self, t: f64) -> bool {
        self.blackouts.iter().any(|w| w.contains(t))
    }

    /// Whether one message sent at `t` gets through.
    pub fn delivers(&self, t: f64, rng: &mut impl Rng) -> bool {
        !self.blacked_out(t) && (self.loss == 0.0 || rng.gen::<f64>() >= self.loss)
    }

    /// When a fact first sent at `sent` (and repeated every heartbeat) is known to a receiver;
    /// `f64::INFINITY` if never.
    pub fn known_at(&self, sent: f64, rng: &mut impl Rng) -> f64 {
        let mut s = sent;
        for _ in 0..MAX_REPEATS {
            if let Some(w) = self.blackouts.iter().find(|w| w.contains(s)) {
                // Skip the rest of the blackout in whole heartbeats.
                let k = ((w.to - s) / self.heartbeat).ceil().max(1.0);
                s += k * self.heartbeat;
                continue;
            }
            if self.loss == 0.0 || rng.gen::<f64>() >= self.loss {
                return s + self.latency;
            }
            s += self.heartbeat;
        }
        f64::INFINITY
    }
}
