//! A sink run on the second core: the interpreter hands its events over in
//! chunks, and the formatting (JSON, CSV, G-code, the trace) or the
//! planning happens beside it instead of after every block.
//!
//! ```text
//!   interpreter ─▶ Offload ──chunks (≤ 4 in flight)──▶ worker: S::event …
//!                     ▲                                   │
//!                     └──────── emptied chunks ◀──────────┘
//!                     └──────── done flag (S::is_done) ◀──┘
//! ```
//!
//! The channel is bounded and the emptied chunks come back to be refilled,
//! so memory stays flat and nothing is allocated per chunk once the first
//! few exist. When the worker's sink is done (the reader of stdout went
//! away), the flag tells the interpreter, which stops after its next
//! block; the worker drops what still arrives so the interpreter never
//! waits on it.
//! On one core, or if no thread can be started, the sink runs in line.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, TryRecvError, TrySendError, sync_channel};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use vcnc_interp::{Event, Sink};

/// Events a chunk carries: what the interpreter gathers before it hands
/// them over, so that a batch it hands over (a chunk's worth of whole
/// blocks, rarely more) is a chunk. Large enough that the two channel
/// operations a chunk costs vanish beside its events (~1 µs against
/// ~0.3 ms of interpretation), small enough that the chunks in flight stay
/// a few hundred KB.
const CHUNK: usize = vcnc_interp::HAND_OVER;

/// Chunks the interpreter may run ahead of the worker.
const IN_FLIGHT: usize = 4;

/// How long one side of the channel waits for the other awake before it
/// sleeps. A sleeping worker must be woken by the interpreter's send, a
/// system call and an interrupt to the other core that cost the
/// interpreter some 8 µs a chunk on this VM (6 % of a surfacing run at
/// 7 M blocks/s, where a chunk comes every ~100–140 µs and the worker is
/// done with it in ~70). Awake, it takes the chunk without one.
const AWAKE: Duration = Duration::from_micros(250);

/// A wait longer than this does not pay for the core it keeps busy.
const PAYS: Duration = Duration::from_micros(150);

/// Whether a side waits awake: only while that pays. Awake, a thread is
/// runnable: with the two cores to themselves the threads hand over
/// without system calls, but beside other work (a build, a second vcnc,
/// `cargo test`) a spinning thread takes the core the other needs, and a
/// run took twice as long. Such a wait comes late or not at all, so a
/// wait that took longer than [`PAYS`] makes the next ones sleep at once:
/// 4 of them, then 16, then 64 while they keep coming late; one on time
/// starts the count again. (Measured 2026-12-06: at most 64 lets a quiet
/// run recover from a slow moment of the host within a few chunks, and
/// beside a busy core or a second vcnc a run takes within 10 % of the
/// time it took before any spinning, against 1.4–1.5× with a fixed spin.)
#[derive(Debug, Default)]
struct Patience {
    /// Waits left that sleep at once.
    asleep: u32,
    /// Late waits in a row (at most 3).
    late: u32,
}

impl Patience {
    /// What `attempt` gives, tried awake for up to [`AWAKE`] when waiting
    /// awake pays, else once; `None` when the caller must sleep.
    fn awake<T>(&mut self, mut attempt: impl FnMut() -> Option<T>) -> Option<T> {
        if self.asleep > 0 {
            self.asleep -= 1;
            return attempt();
        }
        let since = Instant::now();
        loop {
            if let Some(got) = attempt() {
                self.judge(since.elapsed() <= PAYS);
                return Some(got);
            }
            if since.elapsed() > AWAKE {
                self.judge(false);
                return None;
            }
            for _ in 0..64 {
                std::hint::spin_loop();
            }
        }
    }

    fn judge(&mut self, on_time: bool) {
        if on_time {
            self.late = 0;
        } else {
            self.late = (self.late + 1).min(3);
            self.asleep = 1 << (2 * self.late);
        }
    }
}

/// The next chunk, or `None` when the interpreter is done: looked for
/// awake while that pays ([`Patience`]), then waited for asleep.
fn next(rx: &Receiver<Vec<Event>>, patience: &mut Patience) -> Option<Vec<Event>> {
    // `Some(None)`: the interpreter is gone, which ends the wait too.
    let got = patience.awake(|| match rx.try_recv() {
        Ok(chunk) => Some(Some(chunk)),
        Err(TryRecvError::Disconnected) => Some(None),
        Err(TryRecvError::Empty) => None,
    });
    got.unwrap_or_else(|| rx.recv().ok())
}

/// A sink `S`, on its own thread when there is a second core.
pub enum Offload<S> {
    /// On this thread.
    Inline(S),
    /// On another.
    Thread(Worker<S>),
}

/// The interpreter's end of a sink running on another thread.
pub struct Worker<S> {
    chunk: Vec<Event>,
    tx: SyncSender<Vec<Event>>,
    emptied: Receiver<Vec<Event>>,
    done: Arc<AtomicBool>,
    handle: JoinHandle<S>,
    /// How the interpreter waits for room in the channel.
    patience: Patience,
}

impl<S: Sink + Send + 'static> Offload<S> {
    /// Starts the sink `make` builds on a second core if there is one.
    /// `make` is called again (for the inline sink) if no thread can be
    /// started, since the first sink went with the failed thread.
    pub fn start(make: impl Fn() -> S) -> Offload<S> {
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        if cores < 2 {
            return Offload::Inline(make());
        }
        let (tx, rx) = sync_channel::<Vec<Event>>(IN_FLIGHT);
        // Room for every chunk there can be, so returning one never blocks.
        let (back, emptied) = sync_channel::<Vec<Event>>(IN_FLIGHT + 2);
        let done = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&done);
        let mut sink = make();
        let spawned = std::thread::Builder::new()
            .name("sink".into())
            .spawn(move || {
                let mut patience = Patience::default();
                while let Some(mut chunk) = next(&rx, &mut patience) {
                    if !flag.load(Ordering::Relaxed) {
                        for e in &chunk {
                            sink.event(e);
                        }
                        if sink.is_done() {
                            flag.store(true, Ordering::Relaxed);
                        }
                    }
                    chunk.clear();
                    // The interpreter may be gone already: then the chunk
                    // is simply freed.
                    let _ = back.try_send(chunk);
                }
                sink
            });
        match spawned {
            Ok(handle) => Offload::Thread(Worker {
                chunk: Vec::with_capacity(CHUNK),
                tx,
                emptied,
                done,
                handle,
                patience: Patience::default(),
            }),
            Err(_) => Offload::Inline(make()),
        }
    }

    /// Hands over what is left, waits for the sink to take it and returns
    /// the sink (not yet finished: call its `finish` or read its result).
    pub fn join(self) -> Result<S, String> {
        match self {
            Offload::Inline(sink) => Ok(sink),
            Offload::Thread(w) => {
                if !w.chunk.is_empty() {
                    // A failed send means the worker panicked: the join
                    // below reports it.
                    let _ = w.tx.send(w.chunk);
                }
                drop(w.tx);
                w.handle
                    .join()
                    .map_err(|_| "the output thread failed".to_string())
            }
        }
    }
}

impl<S: Sink> Sink for Offload<S> {
    #[inline]
    fn event(&mut self, event: &Event) {
        match self {
            Offload::Inline(sink) => sink.event(event),
            Offload::Thread(w) => {
                w.chunk.push(event.clone());
                if w.chunk.len() >= CHUNK {
                    w.hand_over();
                }
            }
        }
    }

    /// The interpreter's events move into the chunk: no clone here, no
    /// drop in the interpreter. A batch of about a chunk (what the
    /// interpreter hands over) takes the empty chunk's place, buffer and
    /// all, and leaves it the emptied buffer to fill: not one event is
    /// copied.
    #[inline]
    fn take_events(&mut self, events: &mut Vec<Event>) {
        match self {
            Offload::Inline(sink) => sink.take_events(events),
            Offload::Thread(w) => {
                if w.chunk.is_empty() && events.len() <= 2 * CHUNK {
                    std::mem::swap(&mut w.chunk, events);
                    if w.chunk.len() >= CHUNK {
                        w.hand_over();
                    }
                    return;
                }
                if w.chunk.len() + events.len() < CHUNK {
                    w.chunk.append(events);
                    return;
                }
                // The events overfill the chunk (or are a block of more
                // than two chunks' worth): they go over in chunks as
                // event() sends them, so that a chunk never outgrows its
                // buffer (a G83 of many holes is hundreds of thousands of
                // events) and a done sink stops at the end of one.
                for e in events.drain(..) {
                    w.chunk.push(e);
                    if w.chunk.len() >= CHUNK {
                        w.hand_over();
                    }
                }
            }
        }
    }

    fn is_done(&self) -> bool {
        match self {
            Offload::Inline(sink) => sink.is_done(),
            Offload::Thread(w) => w.done.load(Ordering::Relaxed),
        }
    }
}

impl<S> Worker<S> {
    /// Sends the full chunk and starts the next in an emptied one. When
    /// the worker is [`IN_FLIGHT`] chunks behind, waits for room awake
    /// while that pays ([`Patience`]), as the worker waits for chunks:
    /// with the two threads at nearly one pace, sleeping on every full
    /// channel made them wake each other chunk by chunk (hundreds of
    /// switches in a run, 30 % slower).
    #[cold]
    fn hand_over(&mut self) {
        let next = self
            .emptied
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(CHUNK));
        let mut full = Some(std::mem::replace(&mut self.chunk, next));
        let tx = &self.tx;
        let sent = self.patience.awake(|| {
            let chunk = full.take()?;
            match tx.try_send(chunk) {
                // A worker gone means it panicked: `join` reports it.
                Ok(()) | Err(TrySendError::Disconnected(_)) => Some(()),
                Err(TrySendError::Full(back)) => {
                    full = Some(back);
                    None
                }
            }
        });
        if sent.is_none()
            && let Some(chunk) = full
        {
            let _ = self.tx.send(chunk);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_interp::{Loc, Pos};

    /// Counts events and says it is done after `stop_after`.
    struct Counter {
        seen: usize,
        stop_after: usize,
    }

    impl Sink for Counter {
        fn event(&mut self, _: &Event) {
            self.seen += 1;
        }
        fn is_done(&self) -> bool {
            self.seen >= self.stop_after
        }
    }

    fn feed() -> Event {
        Event::Rapid {
            loc: Loc::default(),
            to: Pos::default(),
            exact_stop: false,
        }
    }

    #[test]
    fn every_event_arrives_in_chunks_and_the_rest_at_join() {
        let n = 3 * CHUNK + 17;
        let mut off = Offload::start(|| Counter {
            seen: 0,
            stop_after: usize::MAX,
        });
        for _ in 0..n {
            off.event(&feed());
        }
        assert!(!off.is_done());
        assert_eq!(off.join().unwrap().seen, n);
    }

    /// Keeps the line numbers of the events it sees.
    struct Lines(Vec<u64>);

    impl Sink for Lines {
        fn event(&mut self, e: &Event) {
            if let Event::Rapid { loc, .. } = e {
                self.0.push(loc.line);
            }
        }
    }

    #[test]
    fn blocks_handed_over_by_value_arrive_whole_and_in_order() {
        // Blocks of 1 to 2 chunks' worth of events, across chunk ends.
        let sizes = [1, 7, CHUNK - 3, 5, CHUNK, 2 * CHUNK + 1, 3, 1];
        let mut off = Offload::start(|| Lines(Vec::new()));
        let mut block = Vec::new();
        let mut line = 0;
        for n in sizes {
            for _ in 0..n {
                line += 1;
                block.push(Event::Rapid {
                    loc: Loc { line, file: None },
                    to: Pos::default(),
                    exact_stop: false,
                });
            }
            off.take_events(&mut block);
            assert!(block.is_empty(), "the events were taken");
        }
        let seen = off.join().unwrap().0;
        assert_eq!(seen, (1..=line).collect::<Vec<_>>());
    }

    /// What the interpreter hands over (a chunk's worth of whole blocks,
    /// up to two chunks) takes the chunk's place without a copy: the
    /// caller is left the chunk's empty buffer to fill next.
    #[test]
    fn a_batch_of_a_chunk_changes_hands_whole() {
        let mut off = Offload::start(|| Lines(Vec::new()));
        if matches!(off, Offload::Inline(_)) {
            return;
        }
        let mut line = 0;
        for n in [CHUNK, CHUNK + 5, 2 * CHUNK] {
            let mut batch: Vec<Event> = (0..n)
                .map(|_| {
                    line += 1;
                    Event::Rapid {
                        loc: Loc { line, file: None },
                        to: Pos::default(),
                        exact_stop: false,
                    }
                })
                .collect();
            let filled = batch.as_ptr();
            off.take_events(&mut batch);
            assert!(batch.is_empty(), "the events were taken");
            assert_ne!(batch.as_ptr(), filled, "the batch was copied");
            if let Offload::Thread(w) = &off {
                assert!(w.chunk.is_empty(), "the batch went over at once");
            }
        }
        let seen = off.join().unwrap().0;
        assert_eq!(seen, (1..=line).collect::<Vec<_>>());
    }

    /// A block of more events than a chunk holds (G83 with many holes and
    /// pecks) goes over in chunks: a sink that is done after its first
    /// event sees the first chunk only, and no chunk outgrows its buffer
    /// (the worker would format or plan the whole block after its reader
    /// went away, and a chunk of a 225,000-event block doubled the peak
    /// memory, 55 -> 97 MB).
    #[test]
    fn a_block_larger_than_a_chunk_goes_over_in_chunks() {
        let mut off = Offload::start(|| Counter {
            seen: 0,
            stop_after: 1,
        });
        if matches!(off, Offload::Inline(_)) {
            return;
        }
        let mut block: Vec<Event> = (0..5 * CHUNK + 7).map(|_| feed()).collect();
        off.take_events(&mut block);
        assert!(block.is_empty(), "the events were taken");
        if let Offload::Thread(w) = &off {
            assert!(
                w.chunk.len() < CHUNK,
                "left in the chunk: {}",
                w.chunk.len()
            );
        }
        let seen = off.join().unwrap().seen;
        assert_eq!(seen, CHUNK, "a done sink sees one chunk");
    }

    /// A chunk that comes after the worker has gone to sleep still
    /// arrives (it is woken), and the end of the interpreter's side ends
    /// the wait, awake or asleep.
    #[test]
    fn the_worker_takes_a_chunk_awake_or_asleep_and_sees_the_end() {
        let (tx, rx) = sync_channel::<Vec<Event>>(IN_FLIGHT);
        let sender = std::thread::spawn(move || {
            tx.send(vec![feed()]).unwrap();
            std::thread::sleep(AWAKE * 20);
            tx.send(vec![feed(), feed()]).unwrap();
            std::thread::sleep(AWAKE * 20);
        });
        let mut patience = Patience::default();
        assert_eq!(next(&rx, &mut patience).map(|c| c.len()), Some(1));
        assert_eq!(next(&rx, &mut patience).map(|c| c.len()), Some(2));
        assert!(next(&rx, &mut patience).is_none(), "the sender is gone");
        sender.join().unwrap();
    }

    /// A wait that comes late (or not at all) makes the next 4 sleep at
    /// once, then 16, then 64 (and no more); a wait on time starts the
    /// count again. Sleeping at once is one attempt, not a spin. (The
    /// timing of a wait is judged by `judge`, called here directly where
    /// a measured time would make the test depend on the host.)
    #[test]
    fn late_waits_make_the_next_ones_sleep_at_once_more_and_more() {
        let mut p = Patience::default();
        assert_eq!(p.awake(|| Some(1)), Some(1), "what comes at once is taken");
        let mut tries = 0;
        let never = p.awake(|| {
            tries += 1;
            None::<()>
        });
        assert!(never.is_none(), "nothing came within AWAKE");
        assert!(tries > 1, "it waited awake");
        assert_eq!((p.asleep, p.late), (4, 1));
        for _ in 0..4 {
            let mut once = 0;
            let got = p.awake(|| {
                once += 1;
                None::<()>
            });
            assert!(got.is_none());
            assert_eq!(once, 1, "asleep at once: one attempt");
        }
        assert_eq!(p.asleep, 0);
        p.judge(false);
        assert_eq!((p.asleep, p.late), (16, 2));
        p.judge(false);
        assert_eq!((p.asleep, p.late), (64, 3));
        p.judge(false);
        assert_eq!((p.asleep, p.late), (64, 3), "64 at most");
        p.judge(true);
        assert_eq!(p.late, 0, "on time starts the count again");
        p.judge(false);
        assert_eq!((p.asleep, p.late), (4, 1));
    }

    #[test]
    fn a_done_sink_stops_the_run_and_takes_nothing_more() {
        let mut off = Offload::start(|| Counter {
            seen: 0,
            stop_after: 10,
        });
        let mut sent = 0;
        // The flag arrives once the worker has seen a chunk; the bound is
        // only a guard against a test that would never end.
        while !off.is_done() && sent < 1_000 * CHUNK {
            off.event(&feed());
            sent += 1;
        }
        assert!(off.is_done());
        let seen = off.join().unwrap().seen;
        // The worker stops feeding its sink at the end of the first chunk
        // in which the sink was done.
        assert!((10..=CHUNK).contains(&seen), "seen {seen}");
    }
}
