//! Follow-ups of the macro review: a GOTO into a loop from outside it,
//! clearer messages for a variable in the block-delete position and for a
//! Syntec `@` variable in an ISO program, and Syntec string assignment.
//! Each test names what it guards; expected values, lines and columns are
//! worked out by hand in the comments from the program text, the Fanuc 0i
//! "Custom macro" chapter, the Syntec MACRO specification
//! (`docs/macro-handbook/03-syntax.md`, §4.2, §4.8; `02-variables.md`,
//! §2.1, §2.5, §2.8) and `docs/macros.md`.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common;

use common::{Ran, Store, alarm, at, ended, xs};
use vcnc_syntax::Code;

fn run(dialect: &str, program: &str, names: &[&str]) -> Ran {
    common::run(dialect, program, Store::default(), names)
}

// ---------------------------------------------------------------------------
// 1. GOTO into a loop from outside it
// ---------------------------------------------------------------------------

/// A loop whose body a GOTO before it jumps into: N10 lies between
/// `WHILE … DO 1` and `END 1`, the GOTO does not.
const INTO_LOOP: &str = "G90 G00 X5.\n\
                         #1 = 0\n\
                         IF [#1 EQ 0] GOTO 10\n\
                         WHILE [#1 LT 3] DO 1\n\
                         N10 G00 X1.\n\
                         #1 = #1 + 1\n\
                         END 1\n\
                         M30\n";

#[test]
fn goto_into_a_loop_from_outside_alarms_at_the_goto_word() {
    // Fanuc 0i: a branch into a DO–END range from outside is not allowed.
    // Line 3 `IF [#1 EQ 0] GOTO 10`: "IF [#1 EQ 0] " is 13 characters, so
    // the GOTO word is column 14. The move of line 1 (X5) ran; N10's X1
    // must not.
    let r = run("fanuc", INTO_LOOP, &[]);
    let d = alarm(&r);
    assert_eq!(at(d), (Code::E614, 3, 14));
    assert!(d.message.contains("N10"), "{}", d.message);
    assert!(d.message.contains("loop"), "{}", d.message);
    assert_eq!(xs(&r.events), vec![5.0]);
    // Syntec ISO programs read Macro B (docs/macros.md): the same alarm.
    let r = run("syntec", INTO_LOOP, &[]);
    assert_eq!(at(alarm(&r)), (Code::E614, 3, 14));
    assert_eq!(xs(&r.events), vec![5.0]);
}

#[test]
fn plain_goto_to_a_loop_end_from_outside_alarms() {
    // `N20 END 1` is inside the loop's range too: jumping there from line
    // 2 would run the END, which jumps back to the WHILE. The GOTO of line
    // 2 is column 1.
    let p = "#1 = 0\nGOTO 20\nWHILE [#1 LT 2] DO 1\n#1 = #1 + 1\nN20 END 1\nM30\n";
    let r = run("fanuc", p, &["#1"]);
    assert_eq!(at(alarm(&r)), (Code::E614, 2, 1));
    // Nothing after the GOTO ran: #1 is still 0.
    assert_eq!(r.values, vec![Some(0.0)]);
}

#[test]
fn goto_from_an_outer_loop_into_an_inner_loop_alarms() {
    // The GOTO of line 4 is inside DO 1 but not inside DO 2, where N30
    // lies: a branch into DO 2 from outside it. Column 1.
    let p = "#1 = 0\n\
             WHILE [#1 LT 2] DO 1\n\
             #1 = #1 + 1\n\
             GOTO 30\n\
             WHILE [#1 LT 5] DO 2\n\
             N30 #1 = #1 + 1\n\
             END 2\n\
             END 1\n\
             M30\n";
    let r = run("fanuc", p, &["#1"]);
    assert_eq!(at(alarm(&r)), (Code::E614, 4, 1));
    // Line 3 ran once before the alarm.
    assert_eq!(r.values, vec![Some(1.0)]);
}

#[test]
fn goto_out_of_a_loop_and_within_it_stays_allowed() {
    // Out of a loop (Fanuc 0i allows it): the loop counts #1 to 3, then
    // leaves for N20, which moves to X3.
    let p = "#1 = 0\n\
             WHILE [#1 LT 10] DO 1\n\
             #1 = #1 + 1\n\
             IF [#1 EQ 3] GOTO 20\n\
             END 1\n\
             N20 G00 X#1\n\
             M30\n";
    let r = run("fanuc", p, &[]);
    ended(&r);
    assert_eq!(xs(&r.events), vec![3.0]);
    // Within one loop: the GOTO skips `#2 = #2 + 100` on each of three
    // passes, so #2 counts only the N5 block: 3.
    let p = "#1 = 0\n\
             #2 = 0\n\
             WHILE [#1 LT 3] DO 1\n\
             #1 = #1 + 1\n\
             GOTO 5\n\
             #2 = #2 + 100\n\
             N5 #2 = #2 + 1\n\
             END 1\n\
             M30\n";
    let r = run("fanuc", p, &["#2"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(3.0)]);
    // From an inner loop to the outer loop's body: allowed. DO 2 leaves at
    // once for N40 (in DO 1, which holds the GOTO too); DO 1 runs twice,
    // so #2 = 2 and #3 (the line after DO 2's END) stays vacant.
    let p = "#1 = 0\n\
             WHILE [#1 LT 2] DO 1\n\
             #1 = #1 + 1\n\
             WHILE [1 EQ 1] DO 2\n\
             GOTO 40\n\
             END 2\n\
             #3 = 1\n\
             N40 #2 = #1\n\
             END 1\n\
             M30\n";
    let r = run("fanuc", p, &["#2", "#3"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(2.0), None]);
}

#[test]
fn goto_to_the_loop_head_from_outside_enters_the_loop_normally() {
    // N10 labels the WHILE itself: the jump enters the loop at its test,
    // as running into it does. #1 = 100 is skipped; the loop counts 0 → 2.
    let p = "#1 = 0\nGOTO 10\n#1 = 100\nN10 WHILE [#1 LT 2] DO 1\n#1 = #1 + 1\nEND 1\nM30\n";
    let r = run("fanuc", p, &["#1"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(2.0)]);
}

#[test]
fn syntec_goto_back_into_a_for_loop_runs_as_its_specification_shows() {
    // Syntec §4.8's example (its M00 left out): each pass leaves the FOR
    // for N12, adds 5 to @1 and jumps back to N13 inside the loop, whose
    // END_FOR steps #10. The specification advises against it but shows
    // it running, so it is no alarm: 100 passes, @1 = 500, and #10 = 101
    // when the loop ends.
    let p = "%@MACRO\n\
             FOR #10 := 1 TO 100 BY 1 DO\n\
             GOTO 12;\n\
             N13;\n\
             END_FOR;\n\
             M30;\n\
             N12;\n\
             @1 := @1 + 5;\n\
             GOTO 13;\n\
             M99;\n";
    let r = run("syntec", p, &["@1", "#10"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(500.0), Some(101.0)]);
}

// ---------------------------------------------------------------------------
// 2. Clearer messages
// ---------------------------------------------------------------------------

#[test]
fn a_variable_in_the_block_delete_position_says_so() {
    // Fanuc 0i: "optional block skip numbers cannot be referenced using
    // variables". `/#2 G00 X1.` alarms at `#2` (column 2), naming the
    // block delete, not "expected `=`"; nothing moves.
    let r = run("fanuc", "/#2 G00 X1.\nM30\n", &[]);
    let d = alarm(&r);
    assert_eq!(at(d), (Code::E601, 1, 2));
    assert!(d.message.contains("block delete"), "{}", d.message);
    assert!(!d.message.contains("expected"), "{}", d.message);
    assert!(xs(&r.events).is_empty());
    // A block-deleted assignment stays one: with block delete off (the
    // default) `/#2 = 5` sets #2.
    let r = run("fanuc", "/#2 = 5\nM30\n", &["#2"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(5.0)]);
}

#[test]
fn an_at_variable_in_a_syntec_iso_program_names_macro_files() {
    // `@1` is a Syntec global, which only `%@MACRO` files read (Syntec
    // §2.5, §2.8: MACRO syntax in an ISO file is an error). The word
    // `Y@1` starts at column 5 of line 2; nothing of the block moves.
    let r = run("syntec", "G90 G00 X2.\nG00 Y@1 X3.\nM30\n", &[]);
    let d = alarm(&r);
    assert_eq!(at(d), (Code::E104, 2, 5));
    assert!(d.message.contains("%@MACRO"), "{}", d.message);
    assert_eq!(xs(&r.events), vec![2.0]);
    // Fanuc has no `@` variables: its message stays the plain one.
    let r = run("fanuc", "G00 Y@1\nM30\n", &[]);
    assert!(!alarm(&r).message.contains("%@MACRO"));
}
// ---------------------------------------------------------------------------
// 3. Syntec string assignment
// ---------------------------------------------------------------------------

#[test]
fn syntec_string_assigned_to_a_local_is_its_number() {
    // Syntec §4.2: `#10 := "12";  // 区域变量 #10 内容为 12` (local #10
    // holds 12; locals are numbers, §2.1). 12 + 1 = 13 proves it is a
    // number; "2.5" gives 2.5.
    let p = "%@MACRO\n#10 := \"12\";\n#11 := #10 + 1;\n#12 := \"2.5\";\nM30;\n";
    let r = run("syntec", p, &["#10", "#11", "#12"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(12.0), Some(13.0), Some(2.5)]);
}

#[test]
fn syntec_string_that_is_no_number_alarms() {
    // A text that spells no number cannot be a local's value: E601 at the
    // string, line 2 column 8 (`#10 := ` is 7 characters).
    let r = run("syntec", "%@MACRO\n#10 := \"AB\";\nM30;\n", &["#10"]);
    let d = alarm(&r);
    assert_eq!(at(d), (Code::E601, 2, 8));
    assert!(d.message.contains("not a number"), "{}", d.message);
    assert_eq!(r.values, vec![None]);
}

#[test]
fn syntec_string_assigned_to_a_global_needs_the_controller() {
    // Syntec §2.5: a global stores text as ASCII codes that SCANTEXT reads
    // back; vcnc has no SCANTEXT, so E604 at the string (line 2, column 8:
    // `@10 := ` is 7 characters), and @10 stays vacant.
    let r = run("syntec", "%@MACRO\n@10 := \"12\";\nM30;\n", &["@10"]);
    let d = alarm(&r);
    assert_eq!(at(d), (Code::E604, 2, 8));
    assert!(d.message.contains("SCANTEXT"), "{}", d.message);
    assert_eq!(r.values, vec![None]);
}
