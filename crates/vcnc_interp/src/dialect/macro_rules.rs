//! What a dialect's controller does with macros, as data: which language
//! its ISO programs may use, whether `%@MACRO` files are Syntec MACRO, which
//! variables exist, how many locals a call level has, how call arguments map
//! to locals, and whether G200–G999 call macro files. The interpreter reads
//! these policies; it never asks which dialect it runs.

use vcnc_syntax::macros::{Lang, MacroSyntax};

/// The macro language of ISO-format programs (`#` in word-address blocks).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IsoMacros {
    /// No macros: `#` is an illegal character (grbl, EIA, the seed lathe).
    None,
    /// Fanuc Custom Macro B.
    CustomMacroB,
    /// LinuxCNC's numbered and named parameters and `[ ]` expressions
    /// (`macros/ngc.rs`), and its O-word flow (`macros/structure/owords.rs`, `macros/exec.rs`).
    Ngc,
    /// The same parameters and expressions without O-word flow: Mach3,
    /// whose subprograms are O numbers called by M98.
    NgcParams,
}

/// Programs whose first line is `%@MACRO`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MacroFiles {
    /// Read like any other program (the `%` is a tape mark).
    None,
    /// The Syntec MACRO language.
    Syntec,
}

/// Which variable numbers exist and what they mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarTable {
    /// Fanuc 0i: locals #1–#33, commons #100–#199 and #500–#999, system
    /// variables from #1000 (positions #5001…, offsets #2001…, #3000 …).
    Fanuc,
    /// Syntec: locals #1–#400, retained #401–#999, modal #2001–#3100,
    /// globals @1–@165535, a few system variables (`docs/macros.md`).
    Syntec,
}

/// The locals of a G66 modal call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModalLocals {
    /// Each call starts from the G66 block's arguments (Fanuc 0i).
    FreshEachCall,
    /// One set of locals from G66 to G67, shared by every call (Syntec's
    /// §2.3).
    SharedUntilG67,
}

/// How G200–G999 are read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtendedG {
    /// Unknown G codes (E201).
    None,
    /// A call of the macro file `G0200` (`G200.1`: `G200001`) found in the
    /// program directory, with the block's words as arguments (Syntec §1.3).
    Files,
}

/// A dialect's macro rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MacroRules {
    /// ISO programs.
    pub iso: IsoMacros,
    /// `%@MACRO` programs.
    pub files: MacroFiles,
    /// Variable numbering.
    pub variables: VarTable,
    /// Locals per call level (#1 to this).
    pub locals: u16,
    /// G66 locals.
    pub modal_locals: ModalLocals,
    /// G200–G999.
    pub extended_g: ExtendedG,
    /// Most nested brackets in a Macro B expression (Fanuc: five, function
    /// brackets included).
    pub macro_b_nesting: u8,
    /// System variables beyond Fanuc's.
    pub machine_vars: MachineVars,
}

/// System variables a machine builder adds to the Fanuc table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MachineVars {
    /// None.
    None,
    /// Haas's tool-life and tool-load monitor (#5401–#6000: feed and total
    /// timers, limits, counters, loads; Haas mill operator's manual, macro
    /// system variables), read as on a machine whose tools have not cut
    /// yet: 0.
    HaasToolLife,
}

impl MacroRules {
    /// No macros at all.
    pub const NONE: MacroRules = MacroRules {
        iso: IsoMacros::None,
        files: MacroFiles::None,
        variables: VarTable::Fanuc,
        locals: 33,
        modal_locals: ModalLocals::FreshEachCall,
        extended_g: ExtendedG::None,
        macro_b_nesting: 5,
        machine_vars: MachineVars::None,
    };

    /// Fanuc 0i Custom Macro B (also Haas).
    pub const FANUC: MacroRules = MacroRules {
        iso: IsoMacros::CustomMacroB,
        ..MacroRules::NONE
    };

    /// LinuxCNC: its parameters and expressions.
    pub const NGC: MacroRules = MacroRules {
        iso: IsoMacros::Ngc,
        ..MacroRules::NONE
    };
    /// Mach3: LinuxCNC's parameters and expressions, no O-word flow.
    pub const MACH3: MacroRules = MacroRules {
        iso: IsoMacros::NgcParams,
        ..MacroRules::NONE
    };
    /// Haas: Fanuc's Custom Macro B and Haas's tool-life variables.
    pub const HAAS: MacroRules = MacroRules {
        machine_vars: MachineVars::HaasToolLife,
        ..MacroRules::FANUC
    };

    /// Syntec: Macro B in ISO programs, the MACRO language in `%@MACRO`
    /// files, Syntec's variables and extended G-code macros.
    pub const SYNTEC: MacroRules = MacroRules {
        iso: IsoMacros::CustomMacroB,
        files: MacroFiles::Syntec,
        variables: VarTable::Syntec,
        locals: 400,
        modal_locals: ModalLocals::SharedUntilG67,
        extended_g: ExtendedG::Files,
        macro_b_nesting: 5,
        machine_vars: MachineVars::None,
    };

    /// Whether any macro syntax is read at all.
    pub fn enabled(&self) -> bool {
        self.iso != IsoMacros::None || self.files != MacroFiles::None
    }

    /// The parser's settings for a language.
    pub fn syntax(&self, lang: Lang, lex: &vcnc_syntax::LexRules) -> MacroSyntax {
        match lang {
            Lang::MacroB => MacroSyntax {
                lang,
                max_nesting: self.macro_b_nesting,
                slash_comments: lex.slash_comments,
                extended: lex.extended.all(),
            },
            // The Syntec manual names no bracket limit, only "too complex"
            // (COM-005): 32 keeps recursion small.
            Lang::Syntec => MacroSyntax {
                lang,
                max_nesting: 32,
                slash_comments: true,
                extended: &[],
            },
            // rs274's recursion limit (`vcnc_syntax::macros::parse_ngc_line`
            // brings its own settings).
            Lang::Ngc => MacroSyntax {
                lang,
                max_nesting: 64,
                slash_comments: false,
                extended: &[],
            },
        }
    }
}
