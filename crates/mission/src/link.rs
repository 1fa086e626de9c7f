//! PLACEHOLDER (replaced by the mission helper's version at merge): the one link fault model.

use crate::config::Window;

/// Faults of a radio link between agents: loss, duplication, latency, jitter, cuts.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LinkFaults {
    /// Probability that a message is lost.
    pub loss: f64,
    /// Probability that a message is delivered twice.
    pub duplicate: f64,
    /// Fixed latency (s).
    pub latency: f64,
    /// Extra random delay up to this (s).
    pub jitter: f64,
    /// Nothing gets through in these windows.
    pub cuts: Vec<Window>,
}

/// What the link does to one message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate {
    /// Cut.
    Cut,
    /// Lost.
    Lost,
    /// Delivered.
    Delivered {
        /// Delay of the first copy.
        first: f64,
        /// Delay of the second copy.
        second: Option<f64>,
    },
}

impl LinkFaults {
    /// Whether `t` is in a cut.
    pub fn is_cut(&self, t: f64) -> bool {
        self.cuts.iter().any(|w| w.contains(t))
    }
    /// One message's fate.
    pub fn fate<R: rand::Rng + ?Sized>(&self, t: f64, rng: &mut R) -> Fate {
        if self.is_cut(t) {
            return Fate::Cut;
        }
        if self.loss > 0.0 && rng.gen::<f64>() < self.loss {
            return Fate::Lost;
        }
        let twice = self.duplicate > 0.0 && rng.gen::<f64>() < self.duplicate;
        let delay = |rng: &mut R| {
            self.latency
                + if self.jitter > 0.0 {
                    self.jitter * rng.gen::<f64>()
                } else {
                    0.0
                }
        };
        let first = delay(rng);
        let second = twice.then(|| delay(rng));
        Fate::Delivered { first, second }
    }
}
