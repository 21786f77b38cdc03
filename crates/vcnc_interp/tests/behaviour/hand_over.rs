//! How events reach the sink: gathered over whole blocks and handed over
//! a thousand or so at a time (`HAND_OVER`), the rest when the run ends,
//! an alarmed block's own events never, and a sink that is done stops the
//! run within a batch.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, HAND_OVER, Interpreter, Machine, Options, Outcome, Sink};

/// Keeps every event and the size of every hand-over; done after `done_after`
/// events when that is set.
#[derive(Default)]
struct Batches {
    events: Vec<Event>,
    sizes: Vec<usize>,
    done_after: Option<usize>,
}

impl Sink for Batches {
    fn event(&mut self, e: &Event) {
        self.events.push(e.clone());
    }
    fn take_events(&mut self, events: &mut Vec<Event>) {
        self.sizes.push(events.len());
        self.events.append(events);
    }
    fn is_done(&self) -> bool {
        self.done_after.is_some_and(|n| self.events.len() >= n)
    }
}

fn run(program: &str, sink: &mut Batches) -> Outcome {
    let (machine, dialect) = (Machine::default_mill(), Dialect::fanuc());
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    interp.run_str(program, sink)
}

/// `n` feed moves, one a line (line 2 on), after a header line.
fn moves(n: usize) -> String {
    let mut p = String::from("G21 G90 G17 S1000 M03\n");
    // Every move moves (from the origin too): a move that would not move
    // reports no event.
    for i in 0..n {
        p.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 97 + 1, i % 89));
    }
    p
}

fn line_of(e: &Event) -> u64 {
    e.loc().map_or(0, |l| l.line)
}

#[test]
fn events_go_over_in_batches_of_whole_blocks() {
    // Every tenth block is a G28 of two legs: a batch must not split it.
    let mut p = String::from("G21 G90 G17 S1000 M03\n");
    for i in 0..5000 {
        if i % 10 == 0 {
            p.push_str("G91 G28 Z0.\nG90\n");
        } else {
            p.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 97, i % 89));
        }
    }
    p.push_str("M30\n");
    let mut sink = Batches::default();
    assert!(matches!(run(&p, &mut sink), Outcome::Ended(_)));
    let (last, full) = sink.sizes.split_last().unwrap();
    assert!(full.len() >= 4, "{} hand-overs", sink.sizes.len());
    assert!(full.iter().all(|n| *n >= HAND_OVER), "{:?}", sink.sizes);
    assert!(*last > 0);
    assert_eq!(sink.sizes.iter().sum::<usize>(), sink.events.len());
    let mut at = 0;
    for n in full {
        at += n;
        let (before, after) = (&sink.events[at - 1], &sink.events[at]);
        assert_ne!(
            line_of(before),
            line_of(after),
            "a block split at event {at}"
        );
    }
    // The same stream as one event at a time would give.
    assert!(matches!(sink.events.last(), Some(Event::End { .. })));
    let feeds = sink
        .events
        .iter()
        .filter(|e| matches!(e, Event::Feed { .. }))
        .count();
    assert_eq!(feeds, 4500);
}

#[test]
fn an_alarm_follows_every_block_before_it_and_none_of_its_own() {
    // The alarming block turns the coolant on (an event) before its F0
    // alarms: that event must not reach the sink.
    let mut p = moves(2500);
    p.push_str("M08 G01 X1. F0.\nG01 X2. F100.\n");
    let mut sink = Batches::default();
    let outcome = run(&p, &mut sink);
    let Outcome::Alarm(d) = outcome else {
        panic!("no alarm: {outcome:?}");
    };
    assert_eq!(d.line, 2502);
    let n = sink.events.len();
    assert!(matches!(sink.events[n - 1], Event::Alarm(_)));
    let feeds = sink.events[..n - 1]
        .iter()
        .filter(|e| matches!(e, Event::Feed { .. }))
        .count();
    assert_eq!(feeds, 2500);
    assert!(
        sink.events[..n - 1].iter().all(|e| line_of(e) < 2502),
        "an event of the alarmed block reached the sink"
    );
}

#[test]
fn a_done_sink_stops_the_run_within_a_batch() {
    let mut sink = Batches {
        done_after: Some(1),
        ..Batches::default()
    };
    let outcome = run(&moves(20_000), &mut sink);
    assert!(matches!(outcome, Outcome::Stopped), "{outcome:?}");
    assert!(
        sink.events.len() <= HAND_OVER + 8,
        "{} events after the sink was done",
        sink.events.len()
    );
    assert!(!sink.events.is_empty());
}

/// Runs `program` under the Syntec dialect.
fn run_syntec(program: &str, sink: &mut Batches) -> Outcome {
    let (machine, dialect) = (Machine::default_mill(), Dialect::syntec());
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    interp.run_str(program, sink)
}

#[test]
fn a_message_made_while_evaluating_a_word_block_is_dropped_as_before() {
    // A Syntec MSG() in a word's expression runs before the block's mark:
    // the block's start used to clear it away, so no `message` reached the
    // sink, whether the block then ran, was empty or alarmed. Kept in
    // `pending`, it would now be handed over with the batch.
    for tail in [
        "G01 X(MSG(\"in a move\")+1.) Y1. F100;\nM30;\n",
        "G01 X[MSG(\"all vacant\")];\nM30;\n",
        "G01 X(MSG(\"then an alarm\")+1.) F0;\nM30;\n",
        "G01 X(MSG(\"then no end\")+1.) Y1. F100;\n",
    ] {
        for before in [0, 1500] {
            let mut p = String::from("%@MACRO\nS1000 M03;\n");
            for i in 0..before {
                p.push_str(&format!("G01 X{}. Y{}. F500.;\n", i % 97, i % 89));
            }
            p.push_str(tail);
            let mut sink = Batches::default();
            run_syntec(&p, &mut sink);
            assert!(
                !sink
                    .events
                    .iter()
                    .any(|e| matches!(e, Event::Message { .. })),
                "{tail:?} after {before} moves: a message reached the sink"
            );
        }
    }
    // A MSG statement of its own still speaks.
    let mut sink = Batches::default();
    run_syntec("%@MACRO\nMSG(\"alone\");\nM30;\n", &mut sink);
    assert!(
        sink.events
            .iter()
            .any(|e| matches!(e, Event::Message { .. }))
    );
}
