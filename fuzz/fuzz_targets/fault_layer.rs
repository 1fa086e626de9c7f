//! The fault layer between an agent and its transport (`--drop`, `--duplicate`,
//! `--delay-jitter`, `--cut`): any faults and any schedule of sends, arrivals and clock steps.
//! It never panics or delivers a message before it is due, and once the clock has passed
//! every delay, each message received was delivered exactly as the counters say.
#![no_main]
use libfuzzer_sys::fuzz_target;
use mason_fleet::{Clock, FaultLayer, Transport};
use mason_mission::agent::{Arrival, Message};
use mason_mission::{LinkFaults, Window};
use std::cell::Cell;
use std::rc::Rc;
use std::time::{Duration, Instant};

#[derive(Clone)]
struct HandClock(Rc<Cell<f64>>, Instant);

impl Clock for HandClock {
    fn now(&self) -> f64 {
        self.0.get()
    }
    fn instant_at(&self, t: f64) -> Instant {
        self.1 + Duration::from_secs_f64(t.clamp(0.0, 1e6))
    }
}

/// Hands over the messages queued for it.
struct Queue(Rc<std::cell::RefCell<Vec<Message>>>);

impl Transport for Queue {
    fn send(&mut self, _: &Message) {}
    fn recv(&mut self, _: Instant) -> Vec<Arrival> {
        std::mem::take(&mut *self.0.borrow_mut())
            .into_iter()
            .map(Arrival::keyed)
            .collect()
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

fuzz_target!(|data: &[u8]| {
    if data.len() < 8 {
        return;
    }
    let unit = |b: u8| f64::from(b) / 255.0;
    let cuts = if data[4] & 1 == 1 {
        vec![Window {
            from: f64::from(data[5] % 20),
            to: f64::from(data[5] % 20) + f64::from(data[6] % 10) + 0.5,
        }]
    } else {
        Vec::new()
    };
    let faults = LinkFaults {
        loss: unit(data[0]),
        duplicate: unit(data[1]),
        latency: f64::from(data[2] % 4) * 0.5,
        jitter: f64::from(data[3] % 8) * 0.25,
        cuts,
    };
    let clock = HandClock(Rc::new(Cell::new(0.0)), Instant::now());
    let inbox = Rc::new(std::cell::RefCell::new(Vec::new()));
    let mut layer = FaultLayer::new(
        Queue(inbox.clone()),
        clock.clone(),
        faults.clone(),
        u64::from(data[7]),
    );
    let (mut sends, mut sends_cut) = (0u64, 0u64);
    let mut seq = 0u64;
    let mut delivered = 0u64;
    for &op in &data[8..] {
        match op % 4 {
            0 => {
                for _ in 0..(op >> 2) % 8 + 1 {
                    seq += 1;
                    inbox.borrow_mut().push(message(seq));
                }
            }
            1 => clock.0.set(clock.0.get() + f64::from(op >> 2) * 0.05),
            2 => {
                sends += 1;
                sends_cut += u64::from(faults.is_cut(clock.0.get()));
                layer.send(&message(0));
            }
            _ => {}
        }
        delivered += layer.recv(Instant::now()).len() as u64;
    }
    // Past every delay, everything held is delivered.
    clock.0.set(clock.0.get() + 100.0);
    delivered += layer.recv(Instant::now()).len() as u64;
    let s = layer.stats;
    assert_eq!(s.received, seq, "{s:?}");
    assert_eq!(s.sent + sends_cut, sends, "{s:?}");
    let cut_received = s.cut - sends_cut;
    assert_eq!(
        delivered,
        s.received - s.dropped - cut_received + s.duplicated,
        "{s:?}"
    );
});
