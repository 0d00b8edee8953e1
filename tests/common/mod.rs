//! An in-memory CAN bus with simulated time, for integration tests (DESIGN.md "Testing").
//!
//! Stations are sans-IO nodes. The bus delivers every transmitted frame to every other station at the
//! instant it was sent (in transmit order, like a real bus's arbitration of queued frames), keeps a log of
//! everything on the wire, and jumps simulated time from deadline to deadline. A test plays the master by
//! injecting frames and may make the bus lose chosen frames.
#![allow(dead_code)]

use canopen::core::{
    node::{Node, NodeSizes},
    od::ObjectDictionary,
    storage::Storage,
    CanFrame, Event, Instant,
};

/// Something that can sit on the bus: any sans-IO node (the core's own runner contract).
pub use canopen::core::node::SansIo as Station;

/// Who put a frame on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sender {
    /// The test, playing the master.
    Master,
    /// Station number `n` (index into `Bus::stations`).
    Station(usize),
}

/// One frame seen on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seen {
    pub at: Instant,
    pub from: Sender,
    pub frame: CanFrame,
}

type LossRule = Box<dyn FnMut(&CanFrame) -> bool>;

pub struct Bus<S> {
    pub now: Instant,
    pub stations: Vec<S>,
    pub log: Vec<Seen>,
    /// Frames to the master (everything any station sends), drained by the test.
    pub master_rx: Vec<Seen>,
    loss: Vec<LossRule>,
}

impl<S: Station> Bus<S> {
    pub fn new(stations: Vec<S>) -> Self {
        Bus { now: Instant::ZERO, stations, log: Vec::new(), master_rx: Vec::new(), loss: Vec::new() }
    }

    /// A bus whose stations have powered on (time 0), with the master's received boot-up traffic and every
    /// station's events dropped (the log keeps the boot-ups).
    pub fn booted(stations: Vec<S>) -> Self {
        let mut bus = Bus::new(stations);
        bus.run_until(Instant::ZERO);
        bus.take_master_rx();
        for s in &mut bus.stations {
            while s.poll_event().is_some() {}
        }
        bus
    }

    /// Loses (does not deliver, does not log) the next frame that matches `pred`, once.
    pub fn lose_next(&mut self, mut pred: impl FnMut(&CanFrame) -> bool + 'static) {
        let mut armed = true;
        self.loss.push(Box::new(move |f| {
            if armed && pred(f) {
                armed = false;
                true
            } else {
                false
            }
        }));
    }

    /// The master sends a frame now.
    pub fn inject(&mut self, frame: CanFrame) {
        self.put_on_wire(Sender::Master, frame);
        self.settle();
    }

    /// Runs the bus until `t` (inclusive): every deadline up to `t` fires, every frame is delivered.
    pub fn run_until(&mut self, t: Instant) {
        self.settle();
        loop {
            let next = self.stations.iter().filter_map(|s| s.poll_timeout()).min();
            match next {
                Some(d) if d <= t => {
                    self.now = self.now.max(d);
                    let now = self.now;
                    for s in &mut self.stations {
                        if s.poll_timeout().is_some_and(|d| d <= now) {
                            s.handle_timeout(now);
                        }
                    }
                    self.settle();
                }
                _ => break,
            }
        }
        self.now = self.now.max(t);
    }

    /// Runs for `ms` milliseconds from now.
    pub fn run_for_ms(&mut self, ms: u64) {
        let t = Instant::from_micros(self.now.as_micros() + ms * 1000);
        self.run_until(t);
    }

    /// Drains every station's transmit queue and delivers, until the bus is quiet.
    fn settle(&mut self) {
        loop {
            let mut any = false;
            for i in 0..self.stations.len() {
                while let Some(f) = self.stations[i].poll_transmit() {
                    any = true;
                    self.put_on_wire(Sender::Station(i), f);
                }
            }
            if !any {
                break;
            }
        }
    }

    fn put_on_wire(&mut self, from: Sender, frame: CanFrame) {
        if self.loss.iter_mut().any(|rule| rule(&frame)) {
            return;
        }
        let seen = Seen { at: self.now, from, frame };
        self.log.push(seen);
        if from != Sender::Master {
            self.master_rx.push(seen);
        }
        let now = self.now;
        for (i, s) in self.stations.iter_mut().enumerate() {
            if from != Sender::Station(i) {
                s.handle_frame(now, &frame);
            }
        }
    }

    /// Frames seen on the wire with this COB-ID, as (time in ms, data).
    pub fn frames_on(&self, cob_id: u16) -> Vec<(u64, Vec<u8>)> {
        self.log
            .iter()
            .filter(|s| s.frame.cob_id() == cob_id && !s.frame.is_rtr())
            .map(|s| (s.at.as_micros() / 1000, s.frame.data().to_vec()))
            .collect()
    }

    /// Takes what the master received so far.
    pub fn take_master_rx(&mut self) -> Vec<Seen> {
        std::mem::take(&mut self.master_rx)
    }
}

/// Builds a frame from the notation "COB-ID [DLC] bytes" (hex): `frame("000 [2] 01 05")`, `frame("705 [RTR]")`.
pub fn frame(text: &str) -> CanFrame {
    let mut parts = text.split_whitespace();
    let id = u16::from_str_radix(parts.next().expect("id"), 16).expect("hex id");
    let len = parts.next().expect("[len]");
    if len == "[RTR]" {
        return CanFrame::new_rtr(id, 0).expect("rtr");
    }
    let data: Vec<u8> = parts.map(|b| u8::from_str_radix(b, 16).expect("hex byte")).collect();
    assert_eq!(len, format!("[{}]", data.len()), "length field of {text}");
    CanFrame::new(id, &data).expect("frame")
}

/// Drains a node's events.
pub fn events<A: ObjectDictionary, Z: NodeSizes, S: Storage>(node: &mut Node<A, Z, S>) -> Vec<Event> {
    std::iter::from_fn(|| node.poll_event()).collect()
}

pub fn ms(v: u64) -> Instant {
    Instant::from_millis(v)
}

use canopen::core::sdo::client::{ClientData, ClientEvent, SdoClient};

/// Runs one SDO transfer of `client` against the bus, as the master: sends the client's frames, feeds it the
/// server's responses, and lets simulated time run when neither side has anything to say.
pub fn sdo_transfer<S: Station>(bus: &mut Bus<S>, client: &mut SdoClient, data: &mut dyn ClientData) -> ClientEvent {
    let rx = client.params().rx_cob_id();
    let tx = client.params().tx_cob_id();
    for _ in 0..1_000_000 {
        let mut progressed = false;
        while let Some(f) = client.poll_transmit(bus.now, data) {
            progressed = true;
            bus.inject(CanFrame::new(tx, &f).expect("8-byte SDO frame"));
        }
        for seen in bus.take_master_rx() {
            if seen.frame.cob_id() == rx {
                progressed = true;
                if let Some(ev) = client.handle_response(bus.now, seen.frame.data(), data) {
                    return ev;
                }
            }
        }
        if !progressed {
            let step = Instant::from_micros(bus.now.as_micros() + 1_000);
            let until = client.poll_timeout().map_or(step, |t| t.min(step));
            bus.run_until(until);
            if client.poll_timeout().is_some_and(|t| t <= bus.now) {
                if let Some(ev) = client.handle_timeout(bus.now) {
                    return ev;
                }
            }
        }
    }
    panic!("SDO transfer did not finish");
}
