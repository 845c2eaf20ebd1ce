//! Point-to-point exchange on the world communicator: probes that never block, sends that
//! drain incoming messages while they complete (two ranks sending to each other cannot
//! deadlock), and the pacing of polling loops (no busy core).

use std::time::Duration;

use mpi::point_to_point::MatchedReceiveVec;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// Sleeps between polls: 20 us, doubling to 1 ms while nothing happens.
pub(super) struct Nap(Duration);

impl Nap {
    pub(super) fn new() -> Self {
        Nap(Duration::from_micros(20))
    }
    pub(super) fn reset(&mut self) {
        self.0 = Duration::from_micros(20);
    }
    pub(super) fn sleep(&mut self) {
        std::thread::sleep(self.0);
        self.0 = (self.0 * 2).min(Duration::from_millis(1));
    }
    /// After a round of a polling loop: no wait if it did something (`busy`), else a nap.
    pub(super) fn pace(&mut self, busy: bool) {
        if busy {
            self.reset();
        } else {
            self.sleep();
        }
    }
}

/// A received message: source rank, tag, bytes.
pub(super) type Incoming = (usize, i32, Vec<u8>);

/// Receives one message with `tag` (any tag if `None`) from `from` (any rank if `None`) if one
/// has arrived.
pub(super) fn try_receive(
    world: &SimpleCommunicator,
    from: Option<usize>,
    tag: Option<i32>,
) -> Option<Incoming> {
    let probe = match (from, tag) {
        (Some(r), Some(t)) => world
            .process_at_rank(r as i32)
            .immediate_matched_probe_with_tag(t),
        (Some(r), None) => world.process_at_rank(r as i32).immediate_matched_probe(),
        (None, Some(t)) => world.any_process().immediate_matched_probe_with_tag(t),
        (None, None) => world.any_process().immediate_matched_probe(),
    }?;
    let (bytes, status) = probe.matched_receive_vec::<u8>();
    Some((status.source_rank() as usize, status.tag(), bytes))
}

/// Sends `bytes` to `dest` without blocking the exchange: while the send is under way, messages
/// with `expect` from any rank are received and returned (so two ranks sending to each other at
/// once cannot deadlock).
pub(super) fn send(
    world: &SimpleCommunicator,
    dest: usize,
    tag: i32,
    bytes: &[u8],
    expect: Option<i32>,
) -> Vec<Incoming> {
    let mut got = Vec::new();
    let mut nap = Nap::new();
    mpi::request::scope(|scope| {
        let mut req = world
            .process_at_rank(dest as i32)
            .immediate_send_with_tag(scope, bytes, tag);
        loop {
            match req.test() {
                Ok(_) => break,
                Err(r) => req = r,
            }
            match try_receive(world, None, expect) {
                Some(m) => {
                    got.push(m);
                    nap.reset();
                }
                None => nap.sleep(),
            }
        }
    });
    got
}
