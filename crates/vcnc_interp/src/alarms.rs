//! The interpreter's alarms, one named constructor each (codes in
//! `docs/alarms.md`). Formatting happens only here and only when an alarm is
//! raised, never on the per-block hot path. Every constructor is `#[cold]`:
//! the compiler then lays the paths that raise an alarm out of the way of
//! the ones a block takes, which keeps a block's code dense in the
//! instruction cache.

use vcnc_syntax::{Code, Diagnostic, Span};

fn d(code: Code, span: Span, message: String, help: &str) -> Diagnostic {
    Diagnostic::new(code, span, message, help)
}

fn letter(l: u8) -> char {
    char::from(l)
}

/// E106: a physical line too long to read.
#[cold]
pub fn line_too_long() -> Diagnostic {
    d(
        Code::E106,
        Span::new(0, 1),
        "line is longer than 64 KiB".into(),
        "split it into several blocks",
    )
}

/// E108: a decimal point in a word that counts or numbers things.
#[cold]
pub fn no_decimal_point(span: Span, l: u8, why: &str) -> Diagnostic {
    d(
        Code::E108,
        span,
        format!("{} does not take a decimal point: {why}", letter(l)),
        "write a whole number",
    )
}

/// E109: a value outside what the word allows.
#[cold]
pub fn value_out_of_range(span: Span, l: u8, value: f64, allowed: &str) -> Diagnostic {
    d(
        Code::E109,
        span,
        format!("{}{value} is out of range: {allowed}", letter(l)),
        "use a value in the allowed range",
    )
}

/// E109 for lathe G08/G09 steps leaving 10 %–200 %.
#[cold]
pub fn feed_steps_out_of_range(span: Span, pct: i32) -> Diagnostic {
    d(
        Code::E109,
        span,
        format!(
            "this feed step would make the feed {pct} % of F; G08/G09 stay within 10 % to 200 %"
        ),
        "remove a G08 or G09, or cancel with G30 and program F again",
    )
}

/// E201: unknown G code; `help` names the dialects that know it and how
/// each reads an integer (`crate::detect::g_hint`).
#[cold]
pub fn unknown_g(span: Span, value: f64, dialect: &str, help: String) -> Diagnostic {
    let mut diag = d(
        Code::E201,
        span,
        format!("G{value} is not a G code of the {dialect} dialect"),
        "",
    );
    diag.help = help;
    diag
}

/// E201 for a code the dialect's document lists but vcnc does not run.
#[cold]
pub fn unsupported_g(span: Span, why: &str) -> Diagnostic {
    d(
        Code::E201,
        span,
        why.to_string(),
        "see docs/dialects.md for what vcnc runs in this dialect",
    )
}

/// E202: unknown M code.
#[cold]
pub fn unknown_m(span: Span, value: f64, dialect: &str) -> Diagnostic {
    d(
        Code::E202,
        span,
        format!("M{value} is not an M code of the {dialect} dialect"),
        "check the code against the controller's M-code list",
    )
}

/// E203: a word nothing in the block uses.
#[cold]
pub fn word_not_allowed(span: Span, l: u8) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!("{} is not used by any command in this block", letter(l)),
        "remove it, or add the G or M code that uses it",
    )
}

/// E203: a lathe cycle's value written in both of its spellings (the
/// two-block form's `two`, the one-block form's `one`).
#[cold]
pub fn spelled_twice(span: Span, two: u8, one: u8) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!(
            "{} and {} are the same value of this cycle, in its two-block and its one-block form",
            letter(two),
            letter(one)
        ),
        "keep one of them",
    )
}

/// E203: a word of the other form of a lathe cycle (`form`: what the
/// word belongs to).
#[cold]
pub fn other_cycle_form(span: Span, l: u8, form: &str) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!("{} belongs to {form}", letter(l)),
        "write the block in one form: the first block (P, Q, R) and a second with X/Z, or one block with X/Z and the one-block words",
    )
}

/// E203 for an extended address (`CR=`, `IX`) nothing in the block uses.
#[cold]
pub fn extended_not_allowed(span: Span, name: &str) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!("{name} is not used by any command in this block"),
        if matches!(name, "@" | "^") {
            "@ and ^ give X and Y of a G0, G1, G2, G3 or canned-cycle move only (LinuxCNC: \"polar coordinates can only be used for motion\")"
        } else {
            "CR= and D belong to G02/G03, IX and IZ to G05"
        },
    )
}

/// E203 for a multi-character address the dialect does not have.
#[cold]
pub fn address_not_in_dialect(span: Span, dialect: &str) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!("this address does not exist in the {dialect} dialect"),
        "check --dialect",
    )
}

/// E204 for an extended address written twice.
#[cold]
pub fn duplicate_extended(span: Span, name: &str) -> Diagnostic {
    d(
        Code::E204,
        span,
        format!("{name} appears twice in this block"),
        "keep one of them",
    )
}

/// E204: an axis written both absolute and incremental (`X10 U5`).
#[cold]
pub fn absolute_and_incremental(span: Span, abs: u8, inc: u8) -> Diagnostic {
    d(
        Code::E204,
        span,
        format!(
            "{} and {} both address the {} axis in this block",
            letter(abs),
            letter(inc),
            letter(abs)
        ),
        "write either the absolute or the incremental word",
    )
}

/// E204: a LinuxCNC polar word beside the X or Y it stands for.
#[cold]
pub fn polar_and_axis(span: Span, polar: String, axis: u8) -> Diagnostic {
    d(
        Code::E204,
        span,
        format!(
            "{polar} and {} both give the {} axis in this block",
            letter(axis),
            letter(axis)
        ),
        "write the point either with @ and ^ (polar) or with X and Y",
    )
}

/// E203: LinuxCNC's polar words outside the G17 plane.
#[cold]
pub fn polar_outside_xy(span: Span, name: &str) -> Diagnostic {
    d(
        Code::E203,
        span,
        format!(
            "{name} is read in the G17 (XY) plane only (LinuxCNC: \"cannot use polar coordinate except in G17 plane\")"
        ),
        "select G17 in a block before this one, or write the point with X, Y and Z",
    )
}

/// E312: LinuxCNC's polar words under G91 at the program origin, where the
/// current point has no angle to add to.
#[cold]
pub fn polar_incremental_at_origin(span: Span) -> Diagnostic {
    d(
        Code::E312,
        span,
        "incremental (G91) polar words at the program origin: the point has no angle to add to (LinuxCNC: \"indeterminate when at the origin\")".into(),
        "move off the origin first, or give the point under G90",
    )
}

/// E209: a code that must stand alone shares its block.
#[cold]
pub fn not_alone(span: Span, code: Span) -> Diagnostic {
    let _ = code;
    d(
        Code::E209,
        span,
        "this word shares a block with a code that must stand alone in its block".into(),
        "move it to a block of its own (the lathe document: G08/G09, G20, G22/G23, G24, G30, G74 occupy a line alone)",
    )
}

/// E209: a G or M code in the block of a macro call (G65, G66, an
/// extended G-code or an M-code macro), which passes no G or M argument.
#[cold]
pub fn call_not_alone(span: Span, call: &str) -> Diagnostic {
    d(
        Code::E209,
        span,
        format!("{call} takes P, L and argument letters only: this code cannot share its block"),
        "move the code to a block of its own before or after the call",
    )
}

/// E313: G05 through three points on one line.
#[cold]
pub fn three_points_on_a_line(span: Span) -> Diagnostic {
    d(
        Code::E313,
        span,
        "G05: start, middle point (IX IZ) and end point lie on one line, so no arc passes through them".into(),
        "check IX/IZ, or use G01 for a straight move",
    )
}

/// E314: a turning cycle's parameters contradict each other.
#[cold]
pub fn cycle_parameters(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E314,
        span,
        format!("cycle parameters do not fit: {what}"),
        "check the cycle's words against the document",
    )
}

/// E409: G24 with no G20 to return to.
#[cold]
pub fn return_without_call(span: Span) -> Diagnostic {
    d(
        Code::E409,
        span,
        "G24 with no G20 subroutine call to return to".into(),
        "call the subroutine with G20 L…",
    )
}

/// E204: the same address twice.
#[cold]
pub fn duplicate_word(span: Span, l: u8) -> Diagnostic {
    d(
        Code::E204,
        span,
        format!("{} appears twice in this block", letter(l)),
        "keep one of them",
    )
}

/// E205: two G codes of one modal group.
#[cold]
pub fn same_group(span: Span) -> Diagnostic {
    d(
        Code::E205,
        span,
        "two G codes of the same modal group in one block".into(),
        "keep one of them (parameter same_group_in_block = \"last_wins\" takes the last, as Fanuc does)",
    )
}

/// E206: two M codes of one group.
#[cold]
pub fn same_m_group(span: Span) -> Diagnostic {
    d(
        Code::E206,
        span,
        "two M codes of the same group in one block".into(),
        "put them in separate blocks",
    )
}

/// E207: two G codes both taking the axis words.
#[cold]
pub fn axis_conflict(span: Span) -> Diagnostic {
    d(
        Code::E207,
        span,
        "two G codes in this block both use the axis words".into(),
        "put each in its own block",
    )
}

/// E208: G92 (a Fanuc lathe's G50, named by `code`) with axes and S.
#[cold]
pub fn g92_axes_and_s(span: Span, code: &str) -> Diagnostic {
    d(
        Code::E208,
        span,
        format!(
            "{code} with axis words presets coordinates, {code} with S clamps the spindle: not both at once"
        ),
        &format!("write {code} S… and {code} X… in separate blocks"),
    )
}

/// E301: zero feed on a cutting move.
#[cold]
pub fn zero_feed(span: Span) -> Diagnostic {
    d(
        Code::E301,
        span,
        "cutting move with zero feed".into(),
        "program F before or in this block, e.g. F300",
    )
}

/// E302: chord longer than the diameter.
#[cold]
pub fn radius_too_small(span: Span, r: f64, chord: f64) -> Diagnostic {
    d(
        Code::E302,
        span,
        format!("arc radius {r:.4} mm is too small for the {chord:.4} mm between start and end"),
        "make R at least half the distance between start and end point",
    )
}

/// E303: end point off the circle.
#[cold]
pub fn end_off_circle(span: Span, r_start: f64, r_end: f64) -> Diagnostic {
    d(
        Code::E303,
        span,
        format!(
            "arc end point is not on the circle: start radius {r_start:.4} mm, end radius {r_end:.4} mm"
        ),
        "check the end point and I/J/K (I/J/K are measured from the start point to the centre)",
    )
}

/// E304: zero radius.
#[cold]
pub fn zero_radius(span: Span) -> Diagnostic {
    d(
        Code::E304,
        span,
        "arc has zero radius".into(),
        "give the centre offset (I/J/K) or a non-zero R",
    )
}

/// E305: neither centre nor radius.
#[cold]
pub fn arc_without_center(span: Span, plane: &str) -> Diagnostic {
    d(
        Code::E305,
        span,
        format!("arc without centre or radius in the {plane} plane"),
        "add the centre offsets of the plane (G17: I J, G18: I K, G19: J K) or R",
    )
}

/// E306: R arc from a point to itself.
#[cold]
pub fn r_full_circle(span: Span) -> Diagnostic {
    d(
        Code::E306,
        span,
        "an R arc needs an end point different from its start".into(),
        "program a full circle with I/J/K instead of R",
    )
}

/// E307: G29 before any G28/G30.
#[cold]
pub fn g29_without_g28(span: Span, axis: u8) -> Diagnostic {
    d(
        Code::E307,
        span,
        format!(
            "G29 has no intermediate point for {}: no G28/G30 moved that axis before",
            letter(axis)
        ),
        "run G28 or G30 with that axis first",
    )
}

/// E308: G53 under G91.
#[cold]
pub fn g53_incremental(span: Span) -> Diagnostic {
    d(
        Code::E308,
        span,
        "G53 takes absolute machine coordinates and is not effective in incremental mode (G91)"
            .into(),
        "write G90 before G53 (manual 1.2.23, note 2)",
    )
}

/// W110: G53 under G91 where the control ignores it (Fanuc, Haas).
#[cold]
pub fn g53_ignored_incremental(span: Span) -> Diagnostic {
    d(
        Code::W110,
        span,
        "G53 in incremental mode (G91) is ignored: its axis words make no move in machine coordinates, though the rest of the block (an H0 cancelling the tool length offset) still acts (Fanuc: \"when an incremental command is specified, the G53 command is ignored\")".into(),
        "write G90 before G53 to move to the machine position (e.g. G90 G53 Z0. for Z home)",
    )
}

/// E309: M06 without T.
#[cold]
pub fn m06_without_tool(span: Span) -> Diagnostic {
    d(
        Code::E309,
        span,
        "M06 with no tool selected".into(),
        "select the tool with T in this or an earlier block",
    )
}

/// E310: G96 without a tool diameter.
#[cold]
pub fn css_without_diameter(span: Span) -> Diagnostic {
    d(
        Code::E310,
        span,
        "constant surface speed (G96) needs the tool diameter, and the active tool has none".into(),
        "change to a tool with d_mm in the machine's tool table, or use G97 S… rpm",
    )
}

/// E311: a thread (G33, a lathe's G32, G76, G92) without a lead.
#[cold]
pub fn thread_without_lead(span: Span) -> Diagnostic {
    d(
        Code::E311,
        span,
        "a thread without a lead (F is 0 or was never given)".into(),
        "give the lead per revolution with F, e.g. F1.5 for a 1.5 mm pitch",
    )
}

/// E312: a code that needs axis words has none.
#[cold]
pub fn needs_axes(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E312,
        span,
        format!("{what} needs axis words"),
        "name the axes it applies to, e.g. X0 Y0",
    )
}

/// E312: a code without a (non-axis) word it needs.
#[cold]
pub fn needs_word(span: Span, code: &str, words: &str) -> Diagnostic {
    d(
        Code::E312,
        span,
        format!("{code} needs {words}"),
        "add the missing word to the block",
    )
}

/// E349: LinuxCNC's G71/G72 under a mode rs274 refuses them in (G41/G42)
/// or runs them strangely in (G91).
#[cold]
pub fn ngc_cycle_mode(span: Span, code: &str, needs: &str) -> Diagnostic {
    d(
        Code::E349,
        span,
        format!("LinuxCNC's {code} runs only under {needs}"),
        "change the mode before the cycle block",
    )
}

/// E401: program not found.
#[cold]
pub fn program_not_found(span: Span, number: u32) -> Diagnostic {
    let mut diag = d(
        Code::E401,
        span,
        format!("program O{number:04} not found"),
        "",
    );
    diag.help = format!(
        "add it to this file after the main program, or put O{number:04}.nc in the --program-dir"
    );
    diag
}

/// E402: sequence number not found.
#[cold]
pub fn sequence_not_found(span: Span, seq: u32) -> Diagnostic {
    d(
        Code::E402,
        span,
        format!("sequence number N{seq} not found in the program"),
        "check the N number",
    )
}

/// E403: nesting too deep.
#[cold]
pub fn nesting_too_deep(span: Span, max: u32) -> Diagnostic {
    d(
        Code::E403,
        span,
        format!("subprogram calls nested deeper than {max} levels"),
        "check for a program that calls itself; the depth is limits.max_call_depth",
    )
}

/// E404: too many blocks.
#[cold]
pub fn block_limit(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E404,
        span,
        format!(
            "more than {max} blocks executed beyond the program's own length: it runs in a loop"
        ),
        "check for an endless loop (repeats, jumps back), or raise limits.max_executed_blocks in the machine file",
    )
}

/// E405: too many jumps.
#[cold]
pub fn jump_limit(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E405,
        span,
        format!(
            "more than {max} jumps (subprogram and macro calls, M99 returns and repeats, GOTOs, loop passes)"
        ),
        "check for an endless loop (M99, GOTO, WHILE or FOR that never ends), or raise limits.max_jumps in the machine file",
    )
}

/// E406: subprogram without its return (M99, or G24 after a lathe G20).
#[cold]
pub fn sub_without_return(span: Span, code: &str) -> Diagnostic {
    let mut diag = d(
        Code::E406,
        span,
        format!("subprogram ended without {code}"),
        "",
    );
    diag.help = format!("end the subprogram with {code}");
    diag
}

/// E408: called program unreadable.
#[cold]
pub fn program_unreadable(span: Span, number: u32, err: &std::io::Error) -> Diagnostic {
    d(
        Code::E408,
        span,
        format!("program O{number:04} could not be read: {err}"),
        "check the file's permissions",
    )
}

/// E408: LinuxCNC's subroutine file `name.ngc` could not be read (or
/// the store refused it: a link leading outside the program directory).
#[cold]
pub fn sub_file_unreadable(span: Span, name: &str, err: &std::io::Error) -> Diagnostic {
    d(
        Code::E408,
        span,
        format!("subroutine file {name}.ngc could not be read: {err}"),
        "check the file's permissions; a subroutine file lives in the --program-dir itself",
    )
}

/// E501: soft over-travel.
#[cold]
pub fn over_travel(span: Span, axis: u8, value: f64, min: f64, max: f64) -> Diagnostic {
    d(
        Code::E501,
        span,
        format!(
            "over-travel: the path takes {} to {value:.4} mm, outside its travel {min} .. {max} mm",
            letter(axis)
        ),
        "check the coordinates and the work offset, or the machine's travel limits",
    )
}

/// E502: reference point not defined.
#[cold]
pub fn no_reference(span: Span, n: usize) -> Diagnostic {
    d(
        Code::E502,
        span,
        format!("reference point {n} is not defined for this machine"),
        "define reference.p{n} in the machine file, or use another P",
    )
}

/// E503: work offset number out of range.
#[cold]
pub fn bad_offset_number(span: Span, p: f64) -> Diagnostic {
    d(
        Code::E503,
        span,
        format!("G10 L2 P{p}: no such work coordinate system"),
        "use P1 (G54) to P6 (G59)",
    )
}

/// E503: an H, D or G10 P offset number beyond the machine's offset registers.
#[cold]
pub fn bad_tool_offset_number(span: Span, l: u8, value: f64, max: u32) -> Diagnostic {
    d(
        Code::E503,
        span,
        format!(
            "{}{value}: no such tool offset (this machine has offsets 0 to {max})",
            letter(l)
        ),
        "use an offset number the machine has, or raise parameters.offset_registers in the machine file",
    )
}

/// E210: G92 while a rotation, scaling or mirror is active.
#[cold]
pub fn g92_under_transform(span: Span) -> Diagnostic {
    d(
        Code::E210,
        span,
        "G92 cannot set the position while a rotation, scaling or mirror image is active".into(),
        "cancel G68/G51/G51.1 (G69, G50, G50.1) before G92, or use G52 or G54-G59",
    )
}

/// E210: G31 while cutter compensation is on (Fanuc PS0035): the skip
/// stops where the signal fires, off the end the corner was worked out for.
#[cold]
pub fn skip_under_comp(span: Span) -> Diagnostic {
    d(
        Code::E210,
        span,
        "G31 cannot skip while cutter compensation (G41/G42) is on".into(),
        "cancel compensation with G40 before G31, and start it again afterwards",
    )
}

/// E312: tool length compensation on a machine without a Z axis.
#[cold]
pub fn tool_length_without_z(span: Span) -> Diagnostic {
    d(
        Code::E312,
        span,
        "tool length compensation needs a Z axis, and this machine has none".into(),
        "remove G43/G44, or run on a machine file with a Z axis",
    )
}

/// E315: an arc under different scale factors on its plane's axes.
#[cold]
pub fn arc_uneven_scale(span: Span) -> Diagnostic {
    d(
        Code::E315,
        span,
        "this arc is scaled by different factors on its two axes and would become an ellipse"
            .into(),
        "scale the plane's axes by one factor (G51 P), or cancel scaling (G50) around the arc",
    )
}

/// E315: an arc in another plane than the active rotation.
#[cold]
pub fn arc_tilted(span: Span) -> Diagnostic {
    d(
        Code::E315,
        span,
        "this arc's plane is not the plane of the coordinate rotation, which would tilt it".into(),
        "cut the arc in the rotation's plane, or cancel the rotation (G69) first",
    )
}

/// E316: a scale factor of zero or beyond 999.999.
#[cold]
pub fn bad_scale_factor(span: Span, l: u8, k: f64) -> Diagnostic {
    d(
        Code::E316,
        span,
        format!(
            "scale factor {}{k} is out of range: it must be non-zero and at most 999.999",
            letter(l)
        ),
        "write the factor with a decimal point (P0.5) or in 0.001 units (P500)",
    )
}

/// E316: G51 with both P and I/J/K.
#[cold]
pub fn scale_p_and_ijk(span: Span) -> Diagnostic {
    d(
        Code::E316,
        span,
        "G51 takes either P (one factor) or I/J/K (a factor per axis), not both".into(),
        "remove P or remove I/J/K",
    )
}

/// E316: transforms whose composition cannot be undone (never raised by a
/// valid factor; a guard for the frame's inverse).
#[cold]
pub fn singular_transform(span: Span) -> Diagnostic {
    d(
        Code::E316,
        span,
        "this transform flattens the program onto a line or a point".into(),
        "use non-zero scale factors",
    )
}

/// E317: an arc where compensation starts or ends (or G41/G42/G40 with G02/G03).
#[cold]
pub fn comp_arc_startup(span: Span) -> Diagnostic {
    d(
        Code::E317,
        span,
        "cutter compensation starts and ends only on a straight move (G00 or G01), not on an arc"
            .into(),
        "add a G01 move to start or cancel compensation before or after the arc",
    )
}

/// E318: an arc too small for the cutter on its centre's side.
#[cold]
pub fn comp_arc_too_small(span: Span) -> Diagnostic {
    d(
        Code::E318,
        span,
        "over-cut: the tool is on the centre side of this arc and its radius is not larger than the tool's"
            .into(),
        "use a smaller tool (D), a larger arc, or compensate on the other side",
    )
}

/// E318: an entry move (the first move after G41/G42 where compensation
/// may start on an arc: rs274's) not longer than the tool radius in the
/// plane, or an entry arc whose start is within the tool radius of its end.
#[cold]
pub fn comp_entry_short(span: Span, r: f64) -> Diagnostic {
    d(
        Code::E318,
        span,
        format!(
            "cutter compensation cannot start on this move: it does not go farther than the tool radius ({r:.4} mm) in the plane"
        ),
        "make the first move after G41/G42 a move in the plane longer than the tool radius",
    )
}

/// E318: a compensated path that would cut into the part.
#[cold]
pub fn comp_overcut(span: Span) -> Diagnostic {
    d(
        Code::E318,
        span,
        "over-cut: with the tool's radius this block cannot be cut without cutting into the part (a groove or step narrower than the tool)"
            .into(),
        "use a smaller tool (D) or change the contour",
    )
}

/// E319: too many blocks without motion in the compensation plane.
#[cold]
pub fn comp_lookahead(span: Span, limit: u32) -> Diagnostic {
    d(
        Code::E319,
        span,
        format!(
            "more than {limit} blocks in a row without motion in the compensation plane: the controller cannot see where the tool goes next"
        ),
        "move in the plane sooner, or cancel compensation (G40) before the blocks; parameters.comp_lookahead_blocks sets the limit",
    )
}

/// E320: a new cutter radius in force at an arc while compensating: the
/// compensated arc would start at one radius from its centre and end at
/// another (Fanuc PS0020).
#[cold]
pub fn comp_radius_change_on_arc(span: Span, old_mm: f64, new_mm: f64) -> Diagnostic {
    d(
        Code::E320,
        span,
        format!(
            "the cutter radius cannot change on an arc (from {old_mm:.4} mm to {new_mm:.4} mm): the compensated arc would not be a circle"
        ),
        "give the new D in a straight (G00/G01) block, or with compensation cancelled",
    )
}

/// E320: a code that must not change while cutter compensation is on.
#[cold]
pub fn not_while_compensating(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E320,
        span,
        format!("{what} cannot change while cutter compensation (G41/G42) is on"),
        "cancel compensation with G40 first, and start it again afterwards",
    )
}

/// E320: G41/G42 (G41.1/G42.1) while compensation is on, in a dialect
/// that refuses it (rs274: "Cannot turn cutter radius comp on when on").
#[cold]
pub fn comp_on_when_on(span: Span, code: &str) -> Diagnostic {
    d(
        Code::E320,
        span,
        format!("{code} cannot turn cutter compensation on while it is already on"),
        "cancel compensation with G40 (and move off the contour) before starting it again with another side or diameter",
    )
}

/// E321: a tapping cycle with the spindle stopped or turning the wrong
/// way (`cw`: the direction it must turn, `None`: either).
#[cold]
pub fn tapping_spindle(span: Span, code: &str, cw: Option<bool>) -> Diagnostic {
    let (msg, help) = match cw {
        Some(true) => (
            format!(
                "{code} taps with the spindle turning clockwise, but it is stopped or turning the other way"
            ),
            "start the spindle with M03 and an S speed before the tapping cycle",
        ),
        Some(false) => (
            format!(
                "{code} taps with the spindle turning counter-clockwise, but it is stopped or turning the other way"
            ),
            "start the spindle with M04 and an S speed before the tapping cycle",
        ),
        None => (
            format!("{code} taps with the spindle turning, but it is stopped"),
            "start the spindle (M03, or M04 for a left-hand tap) with an S speed before the tapping cycle",
        ),
    };
    d(Code::E321, span, msg, help)
}

/// E322: a hole pattern with no canned cycle to drill its holes.
#[cold]
pub fn pattern_without_cycle(span: Span) -> Diagnostic {
    d(
        Code::E322,
        span,
        "a hole pattern needs a canned cycle: no cycle is active".to_string(),
        "select the cycle first (e.g. G81 Z.. R.. K0 stores it without drilling), then the pattern",
    )
}

/// E323: the hole bottom on the wrong side of the R level.
#[cold]
pub fn cycle_direction(span: Span, upward: bool) -> Diagnostic {
    let (msg, help) = if upward {
        (
            "G87 bores upwards: its Z point must be above the R level",
            "R is below the part for back boring; give Z above R",
        )
    } else {
        (
            "the hole bottom Z is not below the R level",
            "give Z below R (under G91, Z is measured from the R level and is negative)",
        )
    };
    d(Code::E323, span, msg.to_string(), help)
}

/// E324: G17/G18/G19 changing the plane while a cycle is active.
#[cold]
pub fn cycle_plane(span: Span) -> Diagnostic {
    d(
        Code::E324,
        span,
        "the plane cannot change while a canned cycle is active".to_string(),
        "cancel the cycle with G80, change the plane, then select the cycle again",
    )
}

/// E325: a pocket not larger than the tool.
#[cold]
pub fn pocket_too_small(span: Span, what: &str, tool_mm: f64) -> Diagnostic {
    d(
        Code::E325,
        span,
        format!("the pocket's {what} is not larger than the tool's diameter {tool_mm:.4} mm"),
        "make the pocket larger, or change to a smaller tool (its radius is d_mm + d_wear_mm of the tool in the spindle)",
    )
}

/// E109: a Syntec G33 lead without a decimal point under inch: the manual
/// gives that form's unit in mm only (1.2.17, "F: the thread of a screw
/// (0.01mm)").
#[cold]
pub fn lead_without_point_in_inch(span: Span) -> Diagnostic {
    d(
        Code::E109,
        span,
        "a thread lead F without a decimal point is in 0.01 mm (\"F: the thread of a screw (0.01mm)\"), and the manual gives no unit for it in inch".to_string(),
        "write the lead with a decimal point in inches (F0.0625), or program the thread in metric (G71)",
    )
}

/// E325: a pocket cycle with no tool to size it by: none in the spindle
/// (`tool` is `None`), or one whose radius register holds no radius.
#[cold]
pub fn pocket_without_tool(span: Span, tool: Option<u32>) -> Diagnostic {
    let message = match tool {
        None => "no tool is loaded: a pocket cycle steps over and leaves its wall by the diameter of the tool in the spindle".to_string(),
        Some(t) => format!("tool T{t} in the spindle has no radius (its d_mm + d_wear_mm is 0): a pocket cycle steps over and leaves its wall by the tool's diameter"),
    };
    d(
        Code::E325,
        span,
        message,
        "load the tool before the cycle (T… M06) and give it a radius in the tool table (--tools or the machine file's d_mm)",
    )
}

/// E326: one block asks for more holes than the bound.
#[cold]
pub fn too_many_holes(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E326,
        span,
        format!("this block drills more than {max} holes"),
        "split the pattern or the K count over several blocks",
    )
}

/// E326: a peck depth so small against the hole depth that the block
/// would peck more often than the bound.
#[cold]
pub fn too_many_pecks(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E326,
        span,
        format!("this block pecks more than {max} times over its holes"),
        "use a larger peck depth (Q; on a Haas the least peck K) or fewer holes per block",
    )
}

/// E210: G12/G13 outside the XY plane.
#[cold]
pub fn circle_cut_plane(span: Span, code: &str) -> Diagnostic {
    d(
        Code::E210,
        span,
        format!(
            "{code} cuts its circle in the XY plane (G17) only (Haas: \"both G codes use the default XY circular plane\"; Mach3: \"its effect is undefined if the current plane is not XY\")"
        ),
        "select G17 before the circular pocket",
    )
}

/// E325: a G12/G13 radius I not larger than the cutter's radius D.
#[cold]
pub fn circle_cut_too_small(span: Span, radius_mm: f64, tool_mm: f64) -> Diagnostic {
    d(
        Code::E325,
        span,
        format!(
            "the circle's radius I ({radius_mm:.4} mm) is not larger than the cutter's radius D ({tool_mm:.4} mm)"
        ),
        "give an I larger than the tool's radius (Haas: \"I value must be greater than tool radius\"), or D0 to program the tool centre",
    )
}

/// E326: a G12/G13 with more full circles than the bound.
#[cold]
pub fn too_many_circles(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E326,
        span,
        format!("this circular pocket cuts more than {max} circles over its repeats"),
        "use a larger step Q or fewer repeats L",
    )
}

/// E326: a pocket with more passes than the bound.
#[cold]
pub fn too_many_passes(span: Span, max: u64) -> Diagnostic {
    d(
        Code::E326,
        span,
        format!("this pocket cuts more than {max} rings over all its levels"),
        "use a larger depth per pass Q, a larger stepover (parameters.pocket_stepover_pct) or a larger tool",
    )
}

/// E326: a lathe cycle with more passes or moves than the bound.
#[cold]
pub fn too_many_cycle_moves(span: Span) -> Diagnostic {
    d(
        Code::E326,
        span,
        "this cycle needs more passes or moves than one block may make (10,000 passes, 200,000 moves)".to_string(),
        "use a larger depth of cut, peck or step",
    )
}

/// E340: a probing move that never tripped.
#[cold]
pub fn probe_not_tripped(span: Span) -> Diagnostic {
    d(
        Code::E340,
        span,
        "the probe signal did not change along this move".to_string(),
        "probe toward the part far enough to touch it, or use G38.3/G38.5 (no alarm); the signal is the machine file's [[skip]] trigger",
    )
}

/// E341: a thread too fast for the machine's feed.
#[cold]
pub fn thread_too_fast(span: Span, rpm: f64, lead_mm: f64, max_feed: f64) -> Diagnostic {
    d(
        Code::E341,
        span,
        format!(
            "the spindle at {rpm:.0} rpm with a {lead_mm:.4} mm lead feeds {:.1} mm/min, above the machine's maximum {max_feed:.1} mm/min",
            rpm * lead_mm
        ),
        &format!(
            "lower S to at most {:.0} rpm (maximum feed / lead)",
            (max_feed / lead_mm).floor()
        ),
    )
}

/// E342: a feed per revolution or a thread with the spindle stopped.
/// `per_minute` is the dialect's feed-per-minute code (G94, a Fanuc
/// lathe's G98); `None` for a thread, which always follows the spindle.
#[cold]
pub fn per_rev_spindle_stopped(span: Span, per_minute: Option<f64>) -> Diagnostic {
    let help = match per_minute {
        Some(g) => {
            format!("start the spindle (M03/M04 with S) first, or feed per minute (G{g:02})")
        }
        None => "start the spindle (M03/M04 with S) first: a thread follows its turns".to_string(),
    };
    d(
        Code::E342,
        span,
        "this move feeds per spindle revolution, but the spindle is stopped".to_string(),
        &help,
    )
}

/// E210: an M code in G05 high-speed mode.
#[cold]
pub fn m_code_in_high_speed(span: Span) -> Diagnostic {
    d(
        Code::E210,
        span,
        "M codes are not allowed in high-speed mode (G05 P…)".to_string(),
        "leave the mode with G05 P0 before the M code (Syntec 1.2.6)",
    )
}

// ---------------------------------------------------------------------------
// Warnings: the run goes on.
// ---------------------------------------------------------------------------

/// W101: a length without a decimal point where the program writes points.
/// `shown` is the value read, in `unit` (" mm", " in" or "°").
#[cold]
pub fn least_increment_trap(span: Span, l: u8, value: f64, shown: f64, unit: &str) -> Diagnostic {
    let shown = (shown * 1e6).round() / 1e6;
    d(
        Code::W101,
        span,
        format!(
            "{}{value} has no decimal point: it is read as {shown}{unit} (least input increments), while this program writes its other values with a point",
            letter(l)
        ),
        &format!(
            "write {}{value}. if {value}{unit} is meant, or run with --dialect grbl if the program counts whole units",
            letter(l)
        ),
    )
}

/// W102: a feed above the machine's maximum, clamped.
#[cold]
pub fn feed_clamped(span: Span, asked: f64, max: f64) -> Diagnostic {
    d(
        Code::W102,
        span,
        format!(
            "the feed {asked:.1} mm/min is above the machine's maximum {max:.1} mm/min: it is clamped"
        ),
        "lower F, or raise max_feed_mm_per_min in the machine file",
    )
}

/// W103: a spindle speed above the machine's maximum, clamped.
#[cold]
pub fn spindle_clamped(span: Span, asked: f64, max: f64) -> Diagnostic {
    d(
        Code::W103,
        span,
        format!(
            "the spindle speed {asked:.0} rpm is above the machine's maximum {max:.0} rpm: it is clamped"
        ),
        "lower S, or raise parameters.max_spindle_rpm in the machine file",
    )
}

/// W104: a cutting move with the spindle stopped.
#[cold]
pub fn cut_spindle_stopped(span: Span) -> Diagnostic {
    d(
        Code::W104,
        span,
        "this cut runs with the spindle stopped".to_string(),
        "start the spindle (M03/M04 with S) before cutting; a laser, plotter or drag knife program can ignore this",
    )
}

/// W105: an M code neither the dialect nor the machine file knows.
#[cold]
pub fn unknown_m_ignored(span: Span, value: u32, dialect: &str) -> Diagnostic {
    d(
        Code::W105,
        span,
        format!(
            "M{value} is not an M code of the {dialect} dialect nor of this machine: it is ignored"
        ),
        "list the machine builder's M codes under [m_codes] in the machine file, or set parameters.strict_m_codes = true to make this an alarm",
    )
}

/// W106: the program ends without M02 or M30.
#[cold]
pub fn no_program_end(span: Span) -> Diagnostic {
    d(
        Code::W106,
        span,
        "the program ends without M02 or M30".to_string(),
        "end the program with M30 (or M02); a controller would otherwise wait at the last block",
    )
}

/// W109: no length of the program has a decimal point, and read in least
/// increments its longest length and its moves are under 1 mm: it was
/// probably written in whole units. Located at its first such word
/// (`first`, W101's diagnostic of it); `longest` is the longest one's
/// letter, value and length as read (mm), `whole` the dialects of the
/// program's kind that read it in whole units.
#[cold]
pub fn whole_units_likely(
    first: &Diagnostic,
    (letter_of, value, read_mm): (u8, f64, f64),
    whole: &[&str],
) -> Diagnostic {
    let word = format!("{}{value}", letter(letter_of));
    let dialects = whole
        .iter()
        .map(|n| format!("--dialect {n}"))
        .collect::<Vec<_>>()
        .join(" or ");
    let mut w = d(
        Code::W109,
        first.span,
        format!(
            "no length in this program has a decimal point: read in least input increments the longest, {word}, is {read_mm:.4} mm and the whole program moves within a millimetre, so it was probably written in whole units"
        ),
        &format!(
            "if {word} means {value} mm (or inches under G20), run it with {dialects}, or set parameters.decimal_input = \"calculator\" in the machine file"
        ),
    );
    w.line = first.line;
    w.column = first.column;
    w.line_offset = first.line_offset;
    w.file = first.file.clone();
    w
}

/// W107: M99 in the main program repeats it for ever on a machine.
#[cold]
pub fn main_program_repeats(span: Span) -> Diagnostic {
    d(
        Code::W107,
        span,
        "M99 in the main program runs it again for ever on a machine (a bar-feeder loop): vcnc runs one pass".to_string(),
        "end the program with M30 if it should stop here",
    )
}

/// W108: G41/G42 or G43/G44 reads an offset register that holds 0 (the
/// built-in machines' offset memory is empty): the path is not offset.
#[cold]
pub fn zero_offset(span: Span, what: &str) -> Diagnostic {
    d(
        Code::W108,
        span,
        format!("compensation with {what} changes nothing"),
        "give the tools' sizes with --tools FILE (a LinuxCNC .tbl or a CSV) or in the machine file's [tools]; a program written for wear compensation may leave this register near 0",
    )
}

/// E327: G05.1 Q1 under G61 or G63 (Syntec 1.2.7, condition 1).
#[cold]
pub fn smoothing_in_exact_stop(span: Span) -> Diagnostic {
    d(
        Code::E327,
        span,
        "path smoothing (G05.1 Q1) cannot start under G61 exact stop or G63 tapping mode".into(),
        "give G64 first, or start smoothing before G61/G63 (it is then suspended until G64)",
    )
}

/// E328: G06.2 outside G05 P10000 (Syntec 1.2.8).
#[cold]
pub fn nurbs_outside_high_speed(span: Span) -> Diagnostic {
    d(
        Code::E328,
        span,
        "NURBS interpolation (G06.2) runs only in high-speed high-precision mode".into(),
        "give G05 P10000 before the G06.2 blocks and G05 P0 after them",
    )
}

/// E329: a NURBS definition that cannot be a curve.
#[cold]
pub fn bad_nurbs(span: Span, why: &str) -> Diagnostic {
    d(
        Code::E329,
        span,
        format!("NURBS definition: {why}"),
        "a curve of order P has n control points (K X Y Z R blocks) and n + P non-decreasing knots (the K-only blocks end it)",
    )
}

// Macros (docs/macros.md): Custom Macro B and the Syntec MACRO language.

/// E204: an argument letter twice in a macro call (Fanuc's argument
/// specification II, I J K repeated, is not supported).
#[cold]
pub fn duplicate_argument(span: Span, l: u8) -> Diagnostic {
    d(
        Code::E204,
        span,
        format!("argument {} is given twice in this call", letter(l)),
        "give each argument letter once (argument specification II, repeated I J K, is not supported)",
    )
}

/// E401: the file of an extended G-code or an M-code macro is missing.
#[cold]
pub fn macro_file_not_found(span: Span, name: &str) -> Diagnostic {
    let mut diag = d(
        Code::E401,
        span,
        format!("macro program {name} not found"),
        "",
    );
    diag.help = format!("put the file {name} (no extension, or {name}.nc) in the --program-dir");
    diag
}

/// E603: a Syntec statement that never ends.
#[cold]
pub fn statement_too_long(span: Span, lines: usize, bytes: usize) -> Diagnostic {
    d(
        Code::E603,
        span,
        format!("this statement runs over more than {lines} lines or {bytes} bytes without ending"),
        "end statements with `;` (a missing `;` joins the next line)",
    )
}

/// E605: a variable number the controller does not have.
#[cold]
pub fn no_such_variable(span: Span, sigil: char, n: f64) -> Diagnostic {
    d(
        Code::E605,
        span,
        format!("{sigil}{n} is not a variable of this controller"),
        "check the number against the variable table (docs/macros.md)",
    )
}

/// E605: a system variable that exists but cannot be used as written.
#[cold]
pub fn no_such_variable_why(span: Span, n: u32, why: &str) -> Diagnostic {
    d(
        Code::E605,
        span,
        format!("#{n} cannot be read or written here: {why}"),
        "check the number against the variable table (docs/macros.md)",
    )
}

/// E605: a system variable vcnc does not provide (I/O signals, the date,
/// the real machine's data).
#[cold]
pub fn system_variable_missing(span: Span, n: u32) -> Diagnostic {
    d(
        Code::E605,
        span,
        format!(
            "system variable #{n} is not available: it is not a variable of this controller or needs the real machine"
        ),
        "see the system variables vcnc provides in docs/macros.md",
    )
}

/// E606: a write to a read-only variable.
#[cold]
pub fn read_only_variable(span: Span, sigil: char, n: u32) -> Diagnostic {
    d(
        Code::E606,
        span,
        format!("{sigil}{n} is read-only"),
        "write to a local or common variable instead",
    )
}

/// E606: a setting of one of LinuxCNC's predefined named parameters.
#[cold]
pub fn read_only_named(span: Span, name: &str) -> Diagnostic {
    d(
        Code::E606,
        span,
        format!("#<{name}> is read-only: it is one of LinuxCNC's predefined named parameters"),
        "keep the value in a parameter of your own (a name of your choice: #<_mine> is global, #<mine> local to a subroutine)",
    )
}

/// E607: a vacant value where a number is required.
#[cold]
pub fn vacant_value(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E607,
        span,
        format!("{what} is vacant (#0): a number is required"),
        "give the variable a value before this statement",
    )
}

/// E608: division by zero.
#[cold]
pub fn division_by_zero(span: Span) -> Diagnostic {
    d(
        Code::E608,
        span,
        "division by zero".to_string(),
        "check the divisor before dividing (IF [#2 EQ 0] GOTO …)",
    )
}

/// E609: a function outside its domain.
#[cold]
pub fn macro_domain(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E609,
        span,
        what.to_string(),
        "check the argument's range before the call",
    )
}

/// E609: a result out of range.
#[cold]
pub fn macro_range(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E609,
        span,
        what.to_string(),
        "check the magnitudes the expression works with",
    )
}

/// E610: an operator that needs whole numbers (Syntec Longs) got a Double.
#[cold]
pub fn type_mismatch(span: Span, op: &str) -> Diagnostic {
    d(
        Code::E610,
        span,
        format!(
            "{op} works on Longs (numbers written without a decimal point), and an operand is a Double"
        ),
        "convert with ROUND(…) or FLOOR(…), or write the number without a decimal point",
    )
}

/// E611: loops or branches that do not pair.
#[cold]
pub fn bad_structure(span: Span, what: String, help: &str) -> Diagnostic {
    d(Code::E611, span, what, help)
}

/// E612: an alarm the program raises (#3000, ALARM()).
#[cold]
pub fn program_alarm(span: Span, id: f64, text: &str) -> Diagnostic {
    let message = if text.is_empty() {
        format!("program alarm {id}")
    } else {
        format!("program alarm {id}: {text}")
    };
    d(
        Code::E612,
        span,
        message,
        "the program stopped itself here: read its message",
    )
}

/// E613: the PUSH stack is full.
#[cold]
pub fn macro_stack_full(span: Span, max: usize) -> Diagnostic {
    d(
        Code::E613,
        span,
        format!("more than {max} values pushed on the macro stack"),
        "POP what is no longer needed",
    )
}

/// E614: a Macro B GOTO whose target lies inside a DO–END loop that does
/// not hold the GOTO.
#[cold]
pub fn goto_into_loop(span: Span, n: u32, m: u8, line: u64) -> Diagnostic {
    d(
        Code::E614,
        span,
        format!(
            "GOTO {n} jumps into the DO {m} loop of line {line} from outside it: N{n} lies inside the loop, before its END {m}"
        ),
        &format!(
            "a GOTO may leave a loop but not enter one: jump to the WHILE block (label it), or move N{n} out of the loop"
        ),
    )
}

/// E343: the profile (P..Q) of a turning cycle cannot be cut: not
/// monotone where the cycle needs it, a first block the cycle does not
/// accept, a start point on the wrong side.
#[cold]
pub fn profile_not_cut(span: Span, why: &str) -> Diagnostic {
    d(
        Code::E343,
        span,
        format!("this profile cannot be cut by the cycle: {why}"),
        "check the profile blocks between P and Q and the cycle's start point",
    )
}

/// E344: a code or word a profile block may not carry.
#[cold]
pub fn profile_word(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E344,
        span,
        format!("{what} is not allowed in a profile block (between P and Q)"),
        "a profile holds G00-G03 moves (X/Z/U/W, I/K or R, ,C/,R, G40-G42) and beside them F, S, T, G04, G96/G97, G98/G99 and M codes other than stops, ends and calls",
    )
}

/// E345: the profile's last block (N of Q) is not found after its first.
#[cold]
pub fn profile_end_missing(span: Span, nf: u32) -> Diagnostic {
    d(
        Code::E345,
        span,
        format!(
            "the profile's last block N{nf} (Q) does not follow its first block (P) in this program"
        ),
        "number the profile's last block with the Q value, after the block P names",
    )
}

/// E345: a profile longer than the bound.
#[cold]
pub fn profile_too_long(span: Span, max: usize) -> Diagnostic {
    d(
        Code::E345,
        span,
        format!("the profile between P and Q has more than {max} blocks"),
        "check that Q names the profile's last block",
    )
}

/// E346: a depth of cut, step or pass count of zero.
#[cold]
pub fn zero_amount(span: Span, what: &str) -> Diagnostic {
    d(
        Code::E346,
        span,
        format!("{what} is zero or missing: the cycle would never advance"),
        "give it a positive value (a first block, or the one-block form's own word, sets the depth of cut)",
    )
}

/// E347: a chamfer or corner R (`,C`/`,R`) that cannot be made.
#[cold]
pub fn corner_fault(span: Span, why: &str) -> Diagnostic {
    d(
        Code::E347,
        span,
        format!("the chamfer or corner R cannot be made: {why}"),
        "a ,C or ,R needs a G01 in the next block, at an angle to this one, and both moves longer than the chamfer or round",
    )
}

/// E348: G96 at diameter 0 with no clamp and no spindle maximum.
#[cold]
pub fn css_at_center_unclamped(span: Span) -> Diagnostic {
    d(
        Code::E348,
        span,
        "under G96 the tool reaches the spindle axis (diameter 0), where the surface speed asks for an infinite spindle speed".to_string(),
        "clamp the spindle with G50 S before G96, or give the machine a parameters.max_spindle_rpm",
    )
}
