//! Constructs that real programs of the corpus (`corpus/`) use and a
//! controller of their dialect accepts; each test names the program that
//! showed it and works out the expected motion by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Outcome};

mod common;

use common::{run_str as run, xs};

/// `:0097` heads `corpus/mill-fanuc/gcodeworkshop-FANUC0M.nc` and
/// `:0100( FLANGE OP.2 )` the Fanuc 0T lathe program beside it: in ISO
/// code the colon is the program number's O, on the mill, the Haas mill
/// and the Fanuc lathe. The program then runs as `O0097` would: one rapid
/// to X1. (a radius of 0.5 on the lathe, which reads X as a diameter).
#[test]
fn a_colon_is_the_program_numbers_o_in_the_fanuc_dialects() {
    let program = ":0097 (FANUC 0M)\nG0 X1.\nM30\n";
    for dialect in [Dialect::fanuc(), Dialect::haas(), Dialect::fanuc_lathe()] {
        let (ev, out) = run(&dialect, program);
        assert!(
            matches!(out, Outcome::Ended(_)),
            "{}: {out:?}",
            dialect.name
        );
        let x = if dialect.name == "fanuc-lathe" {
            0.5
        } else {
            1.0
        };
        assert_eq!(xs(&ev), vec![x], "{}", dialect.name);
        let o = run(&dialect, &program.replacen(':', "O", 1)).0;
        assert_eq!(ev, o, "{}", dialect.name);
    }
    // Syntec's manual does not name it: still an illegal character.
    let (ev, out) = run(&Dialect::syntec(), program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line, d.column), ("E101", 1, 1));
    assert!(!ev.iter().any(|e| matches!(e, Event::Rapid { .. })));
}
