//! The fault model of the radio link between agents, shared by the simulated bus
//! ([`crate::bus`]) and the real transport's fault layer (`mason agent`), so that a fault
//! setting means the same thing on both.
//!
//! A message sent at mission time `t` meets one [`Fate`] per receiver: inside a cut window
//! nothing gets through; otherwise it is lost with probability `loss`, and a message that gets
//! through arrives once, or twice with probability `duplicate`, each copy after `latency` plus
//! a uniform extra delay in `[0, jitter)`, so that copies and messages overtake each other.
//!
//! **The draw order.** [`LinkFaults::fate`] draws uniform `f64`s in `[0, 1)` from the
//! generator it is given, in this fixed order, and only those a setting needs:
//!
//! 1. inside a cut: nothing, the message is [`Fate::Cut`];
//! 2. if `loss > 0`: one draw; below `loss`, the message is [`Fate::Lost`];
//! 3. if `duplicate > 0`: one draw; below `duplicate`, a second copy arrives;
//! 4. if `jitter > 0`: one draw for the first copy's delay, then one for the second copy's.
//!
//! A fault-free link draws nothing, so adding it changes no other random stream.

use crate::config::Window;
use rand::Rng;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Faults of a radio link between agents: loss, duplication, latency, jitter, cuts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LinkFaults {
    /// Probability that a message is lost (per receiver), in `[0, 1]`.
    pub loss: f64,
    /// Probability that a message that gets through arrives twice, in `[0, 1]`.
    pub duplicate: f64,
    /// Fixed delay of every copy (s, ≥ 0).
    pub latency: f64,
    /// Extra delay of each copy, uniform in `[0, jitter)` (s, ≥ 0).
    pub jitter: f64,
    /// Nothing gets through in these windows of mission time (s).
    pub cuts: Vec<Window>,
}

/// What the link does to one message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate {
    /// Sent inside a cut window: nothing gets through.
    Cut,
    /// Lost on the way.
    Lost,
    /// Delivered once, `first` seconds after it was sent, and again `second` seconds after it
    /// was sent if it was duplicated.
    Delivered {
        /// The delay of the first copy (s).
        first: f64,
        /// The delay of the duplicate, if any (s).
        second: Option<f64>,
    },
}

/// A link fault setting out of range.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum LinkFaultsError {
    /// `loss` or `duplicate` is not a probability.
    #[error("{field} = {value}: expected a probability in [0, 1]")]
    Probability {
        /// The setting (`loss` or `duplicate`).
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// `latency` or `jitter` is not a finite time ≥ 0.
    #[error("{field} = {value} s: expected a finite number ≥ 0")]
    Time {
        /// The setting (`latency` or `jitter`).
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A cut window that does not run forward from a finite time ≥ 0.
    #[error("cut {from}-{to}: expected finite times 0 ≤ from < to")]
    Cut {
        /// Its start (s).
        from: f64,
        /// Its end (s).
        to: f64,
    },
}

impl LinkFaults {
    /// Whether mission time `t` lies in a cut window.
    pub fn is_cut(&self, t: f64) -> bool {
        self.cuts.iter().any(|w| w.contains(t))
    }

    /// Decides one message's fate at mission time t, drawing from rng in a fixed, documented
    /// order (see the [module documentation](self)): nothing for a cut, then loss, then
    /// duplication, then the delay of each copy, each only if its setting is not zero.
    pub fn fate<R: Rng + ?Sized>(&self, t: f64, rng: &mut R) -> Fate {
        if self.is_cut(t) {
            return Fate::Cut;
        }
        if self.loss > 0.0 && rng.gen::<f64>() < self.loss {
            return Fate::Lost;
        }
        let twice = self.duplicate > 0.0 && rng.gen::<f64>() < self.duplicate;
        let first = self.delay(rng);
        let second = twice.then(|| self.delay(rng));
        Fate::Delivered { first, second }
    }

    /// One copy's delay: the latency, plus the jitter's draw if there is jitter.
    fn delay<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        if self.jitter > 0.0 {
            self.latency + self.jitter * rng.gen::<f64>()
        } else {
            self.latency
        }
    }

    /// Checks every setting: probabilities in `[0, 1]`, times finite and ≥ 0, and cut windows
    /// with finite times `0 ≤ from < to`.
    pub fn validate(&self) -> Result<(), LinkFaultsError> {
        for (field, value) in [("loss", self.loss), ("duplicate", self.duplicate)] {
            if !(0.0..=1.0).contains(&value) {
                return Err(LinkFaultsError::Probability { field, value });
            }
        }
        for (field, value) in [("latency", self.latency), ("jitter", self.jitter)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(LinkFaultsError::Time { field, value });
            }
        }
        for w in &self.cuts {
            if !(w.from.is_finite() && w.to.is_finite() && 0.0 <= w.from && w.from < w.to) {
                return Err(LinkFaultsError::Cut {
                    from: w.from,
                    to: w.to,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngCore, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A generator that counts its draws.
    struct Counting(ChaCha8Rng, usize);

    impl RngCore for Counting {
        fn next_u32(&mut self) -> u32 {
            self.1 += 1;
            self.0.next_u32()
        }
        fn next_u64(&mut self) -> u64 {
            self.1 += 1;
            self.0.next_u64()
        }
        fn fill_bytes(&mut self, dest: &mut [u8]) {
            self.1 += 1;
            self.0.fill_bytes(dest)
        }
        fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), rand::Error> {
            self.1 += 1;
            self.0.try_fill_bytes(dest)
        }
    }

    fn counting() -> Counting {
        Counting(ChaCha8Rng::seed_from_u64(1), 0)
    }

    #[test]
    fn a_fault_free_link_delivers_at_once_and_draws_nothing() {
        let mut rng = counting();
        for t in [0.0, 1.0, 1e5] {
            assert_eq!(
                LinkFaults::default().fate(t, &mut rng),
                Fate::Delivered {
                    first: 0.0,
                    second: None
                }
            );
        }
        assert_eq!(rng.1, 0);
    }

    #[test]
    fn latency_alone_delays_every_message_and_draws_nothing() {
        let link = LinkFaults {
            latency: 0.25,
            ..LinkFaults::default()
        };
        let mut rng = counting();
        assert_eq!(
            link.fate(3.0, &mut rng),
            Fate::Delivered {
                first: 0.25,
                second: None
            }
        );
        assert_eq!(rng.1, 0);
    }

    #[test]
    fn a_cut_stops_everything_without_a_draw_and_ends_at_its_end() {
        let link = LinkFaults {
            loss: 0.5,
            duplicate: 0.5,
            jitter: 1.0,
            cuts: vec![Window { from: 2.0, to: 4.0 }],
            ..LinkFaults::default()
        };
        let mut rng = counting();
        assert!(!link.is_cut(1.999));
        assert!(link.is_cut(2.0));
        assert!(link.is_cut(3.999));
        assert!(!link.is_cut(4.0));
        assert_eq!(link.fate(2.5, &mut rng), Fate::Cut);
        assert_eq!(rng.1, 0);
    }

    #[test]
    fn the_draws_follow_the_documented_order() {
        let link = LinkFaults {
            loss: 0.3,
            duplicate: 0.4,
            latency: 0.1,
            jitter: 2.0,
            cuts: Vec::new(),
        };
        let mut fates = ChaCha8Rng::seed_from_u64(9);
        let mut by_hand = ChaCha8Rng::seed_from_u64(9);
        for _ in 0..500 {
            let fate = link.fate(0.0, &mut fates);
            let expected = if by_hand.gen::<f64>() < 0.3 {
                Fate::Lost
            } else {
                let twice = by_hand.gen::<f64>() < 0.4;
                let first = 0.1 + 2.0 * by_hand.gen::<f64>();
                let second = twice.then(|| 0.1 + 2.0 * by_hand.gen::<f64>());
                Fate::Delivered { first, second }
            };
            assert_eq!(fate, expected);
        }
    }

    #[test]
    fn loss_and_duplication_happen_at_their_rates() {
        let link = LinkFaults {
            loss: 0.25,
            duplicate: 0.5,
            latency: 1.0,
            jitter: 0.5,
            cuts: Vec::new(),
        };
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut lost, mut twice) = (0, 0);
        let n = 20_000;
        for _ in 0..n {
            match link.fate(0.0, &mut rng) {
                Fate::Lost => lost += 1,
                Fate::Delivered { first, second } => {
                    assert!((1.0..1.5).contains(&first), "{first}");
                    if let Some(s) = second {
                        assert!((1.0..1.5).contains(&s), "{s}");
                        twice += 1;
                    }
                }
                Fate::Cut => unreachable!("no cut"),
            }
        }
        let lost = f64::from(lost) / f64::from(n);
        let twice = f64::from(twice) / (f64::from(n) * 0.75);
        assert!((lost - 0.25).abs() < 0.02, "{lost}");
        assert!((twice - 0.5).abs() < 0.02, "{twice}");
    }

    #[test]
    fn certain_loss_loses_everything() {
        let link = LinkFaults {
            loss: 1.0,
            ..LinkFaults::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        assert!((0..100).all(|_| link.fate(0.0, &mut rng) == Fate::Lost));
    }

    #[test]
    fn validate_names_the_setting_out_of_range() {
        assert_eq!(LinkFaults::default().validate(), Ok(()));
        let bad = |f: LinkFaults| f.validate().unwrap_err();
        assert_eq!(
            bad(LinkFaults {
                loss: 1.5,
                ..LinkFaults::default()
            }),
            LinkFaultsError::Probability {
                field: "loss",
                value: 1.5
            }
        );
        assert!(matches!(
            bad(LinkFaults {
                duplicate: f64::NAN,
                ..LinkFaults::default()
            }),
            LinkFaultsError::Probability {
                field: "duplicate",
                ..
            }
        ));
        assert_eq!(
            bad(LinkFaults {
                latency: -0.1,
                ..LinkFaults::default()
            }),
            LinkFaultsError::Time {
                field: "latency",
                value: -0.1
            }
        );
        assert!(matches!(
            bad(LinkFaults {
                jitter: f64::INFINITY,
                ..LinkFaults::default()
            }),
            LinkFaultsError::Time {
                field: "jitter",
                ..
            }
        ));
        for (from, to) in [(5.0, 5.0), (6.0, 5.0), (-1.0, 2.0), (0.0, f64::INFINITY)] {
            assert_eq!(
                bad(LinkFaults {
                    cuts: vec![Window { from, to }],
                    ..LinkFaults::default()
                }),
                LinkFaultsError::Cut { from, to }
            );
        }
        assert_eq!(
            bad(LinkFaults {
                loss: 2.0,
                ..LinkFaults::default()
            })
            .to_string(),
            "loss = 2: expected a probability in [0, 1]"
        );
    }

    #[test]
    fn link_faults_read_from_json_with_defaults() {
        let f: LinkFaults =
            serde_json::from_str(r#"{"loss": 0.1, "cuts": [{"from": 1.0, "to": 2.0}]}"#).unwrap();
        assert_eq!(
            f,
            LinkFaults {
                loss: 0.1,
                cuts: vec![Window { from: 1.0, to: 2.0 }],
                ..LinkFaults::default()
            }
        );
        assert!(serde_json::from_str::<LinkFaults>(r#"{"drop": 0.1}"#).is_err());
    }
}
