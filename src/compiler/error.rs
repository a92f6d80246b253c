//! Errors and warnings of the static checks. Each variant has a stable code documented in
//! `grammar/errors.md`.

use miette::Diagnostic;
use thiserror::Error;

use crate::source::Span;

#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum CheckError {
    /// A STEP 7 symbol the S7 compiler looked up: unknown, or of the wrong kind.
    #[error(transparent)]
    #[diagnostic(transparent)]
    Symbol(Box<crate::symbols::SymbolError>),

    #[error("{id} is defined twice")]
    #[diagnostic(
        code(awl::check::duplicate_block),
        help("the first definition is at {first}; rename or remove one")
    )]
    DuplicateBlock {
        id: String,
        #[label("second definition")]
        at: Span,
        first: String,
    },

    #[error("{id} has no `BE`")]
    #[diagnostic(code(awl::check::missing_be), help("end every logic block with `BE`"))]
    MissingBlockEnd {
        id: String,
        #[label("this block never ends")]
        at: Span,
    },

    #[error("{id}: the {cpu} CPU has no {kind} blocks")]
    #[diagnostic(
        code(awl::check::extended_block),
        help("FX and DX blocks need a CPU profile that has them, e.g. `--cpu sinumerik-840c`")
    )]
    ExtendedBlock {
        id: String,
        kind: &'static str,
        cpu: &'static str,
        #[label("not available on this CPU")]
        at: Span,
    },

    #[error("`{op}` is a supplementary operation, allowed in function blocks only")]
    #[diagnostic(code(awl::check::supplementary_outside_fb))]
    Supplementary {
        op: String,
        #[label("not allowed in {block}")]
        at: Span,
        block: String,
        #[help]
        help: String,
    },

    #[error("`{op}` cannot take this operand")]
    #[diagnostic(code(awl::check::operand_not_allowed))]
    OperandNotAllowed {
        op: String,
        #[label("not an operand of `{op}`")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("{what} is out of range")]
    #[diagnostic(
        code(awl::check::operand_range),
        help("the {cpu} profile allows {range}")
    )]
    OperandRange {
        what: String,
        #[label("allowed: {range}")]
        at: Span,
        range: String,
        cpu: &'static str,
    },

    #[error("`={name}` is neither a parameter of {block} nor a label in it")]
    #[diagnostic(code(awl::check::undefined_symbol))]
    UndefinedSymbol {
        name: String,
        block: String,
        #[label("undefined")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("formal operand `={name}` outside a function block")]
    #[diagnostic(
        code(awl::check::formal_outside_fb),
        help("formal operands and jump labels exist only in FBs")
    )]
    FormalOutsideFb {
        name: String,
        #[label("only FBs have parameters and labels")]
        at: Span,
    },

    #[error("jump labels need a function block (FB)")]
    #[diagnostic(
        code(awl::check::label_outside_fb),
        help(
            "STEP 5 allows jumps to labels (`{op} ={name}`) in FBs only: move this logic into an FB and call it with `JU FB n`, or write it without the jump"
        )
    )]
    LabelOutsideFb {
        op: &'static str,
        name: String,
        #[label("jump to `{name}` in {block}, which is no FB")]
        at: Span,
        block: String,
    },

    #[error("label `{name}` is defined twice")]
    #[diagnostic(
        code(awl::check::duplicate_label),
        help("labels must be unique within a block")
    )]
    DuplicateLabel {
        name: String,
        #[label("second definition")]
        at: Span,
        #[label("first definition")]
        first: Span,
    },

    #[error("label `{name}` is longer than 4 characters")]
    #[diagnostic(
        code(awl::check::label_too_long),
        help("STEP 5 labels have at most 4 characters, e.g. `M001`")
    )]
    LabelTooLong {
        name: String,
        #[label("{length} characters")]
        at: Span,
        length: usize,
    },

    #[error("{fb} expects {expected} parameters, the call gives {found}")]
    #[diagnostic(code(awl::check::param_count))]
    ParamCount {
        fb: String,
        expected: usize,
        found: usize,
        #[label("call of {fb}")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("parameter `{name}` of {fb} does not accept this operand")]
    #[diagnostic(code(awl::check::param_mismatch))]
    ParamMismatch {
        name: String,
        fb: String,
        #[label("expected {expected}")]
        at: Span,
        expected: String,
    },

    #[error("{fb} has no parameter `{name}`")]
    #[diagnostic(code(awl::check::unknown_param))]
    UnknownParam {
        name: String,
        fb: String,
        #[label("not declared in {fb}")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("{id} is called but defined nowhere")]
    #[diagnostic(
        code(awl::check::undefined_block),
        severity(Warning),
        help("at run time this call is a STOP; add the block or load its file")
    )]
    UndefinedBlock {
        id: String,
        #[label("no such block")]
        at: Span,
    },

    #[error("{called} calls the program's own {block}, not the library's {library}")]
    #[diagnostic(
        code(awl::check::library_block_replaced),
        severity(Advice),
        help("rename or renumber the program's block to call the library's")
    )]
    LibraryReplaced {
        called: String,
        block: String,
        library: String,
        #[label("{why}")]
        at: Span,
        why: String,
    },

    #[error("{id} is not in the program")]
    #[diagnostic(
        code(awl::check::undefined_type),
        help("add the `TYPE {id}` … `END_TYPE` block, or load the file that has it")
    )]
    UndefinedType {
        id: String,
        #[label("no such data type")]
        at: Span,
    },

    #[error("{id} is built into other CPUs, not into {cpu}")]
    #[diagnostic(
        code(awl::check::block_not_on_cpu),
        help(
            "the profiles that have it: {profiles}; choose one with `--cpu`, or add the block's source"
        )
    )]
    BlockNotOnCpu {
        id: String,
        #[label("not built into {cpu}, and the program does not define it")]
        at: Span,
        cpu: &'static str,
        profiles: String,
    },

    #[error("{id} is opened but defined nowhere")]
    #[diagnostic(
        code(awl::check::undefined_db),
        severity(Warning),
        help("at run time opening it is a STOP unless a `G DB` generates it first")
    )]
    UndefinedDb {
        id: String,
        #[label("no such data block")]
        at: Span,
    },

    #[error("the {cpu} CPU has no `{op}`")]
    #[diagnostic(
        code(awl::check::not_on_cpu),
        help("`{op}` exists on CPUs with four accumulators, such as the sinumerik-840c profile")
    )]
    NotOnCpu {
        op: String,
        #[label("{reason}")]
        at: Span,
        cpu: &'static str,
        reason: &'static str,
    },

    #[error("`{op}` needs {feature}: {profiles}")]
    #[diagnostic(
        code(awl::check::operation_not_on_cpu),
        help("choose a CPU that has it with `--cpu NAME` (`awl cpus` lists them)")
    )]
    OperationNotOnCpu {
        op: String,
        #[label("the {cpu} profile has no {feature}")]
        at: Span,
        cpu: &'static str,
        feature: &'static str,
        /// The profiles that have it, by name.
        profiles: String,
    },

    #[error("`{op}` must be followed by the operation it modifies")]
    #[diagnostic(
        code(awl::check::indirect_target),
        help(
            "`DO FW n` applies to the next operation, e.g. `L DW 0` or `A I 0.0`; its parameter is replaced by the word's value"
        )
    )]
    IndirectTarget {
        op: String,
        #[label("no operation with a parameter follows")]
        at: Span,
    },

    #[error("`{open}` is never closed before the block end")]
    #[diagnostic(
        code(awl::check::unclosed_bracket),
        help(
            "close the bracket with `)` before `BE`; an open bracket leaves its logic unfinished"
        )
    )]
    UnclosedBracket {
        open: String,
        #[label("opened here")]
        at: Span,
        #[label("the block ends here")]
        end: Span,
    },

    #[error("`)` closes no bracket")]
    #[diagnostic(
        code(awl::check::unopened_bracket),
        help(
            "every `)` closes an `{and}` or `O(` above it in the block; at run time this `)` is a STOP BCF"
        )
    )]
    UnopenedBracket {
        and: &'static str,
        #[label("no open bracket")]
        at: Span,
    },

    #[error("more than {depth} nested brackets")]
    #[diagnostic(
        code(awl::check::bracket_depth),
        help(
            "the {cpu} CPU's bracket stack holds {depth} open brackets; at run time this one is a STOP BCF. Move inner logic into flags"
        )
    )]
    BracketDepth {
        depth: u8,
        cpu: &'static str,
        #[label("bracket {nth}")]
        at: Span,
        nth: usize,
    },
    #[error("`#{name}` is not declared in {block}")]
    #[diagnostic(code(awl::check::undeclared_local))]
    UndeclaredLocal {
        name: String,
        block: String,
        #[label("not in the block's interface")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("{id} embeds itself as a multi-instance")]
    #[diagnostic(
        code(awl::check::recursive_instance),
        help(
            "an FB's instance data cannot hold an instance of the FB itself; call it with an instance DB of its own (`CALL FB n, DB m`)"
        )
    )]
    RecursiveInstance {
        id: String,
        #[label("an instance of {id}, inside {id}")]
        at: Span,
    },

    #[error("jump to `{name}`, a label {block} does not have")]
    #[diagnostic(code(awl::check::undefined_label), help("{help}"))]
    UndefinedLabel {
        name: String,
        block: String,
        #[label("no such label")]
        at: Span,
        /// The label one edit away, or how labels are written.
        help: String,
    },

    #[error("{what} is not simulated")]
    #[diagnostic(code(awl::check::not_simulated), help("{why}"))]
    NotSimulated {
        what: String,
        why: String,
        #[label("awl cannot run this")]
        at: Span,
    },

    #[error("a STEP 7 program cannot run on the {cpu} CPU")]
    #[diagnostic(
        code(awl::check::step7_on_step5_cpu),
        help("STEP 7 programs run on an S7 CPU: choose one with `--cpu` ({profiles})")
    )]
    Step7OnStep5Cpu {
        cpu: &'static str,
        profiles: String,
        #[label("STEP 7 source")]
        at: Span,
    },
}

crate::source::error_span!(CheckError { CheckError::Symbol(error) => error.span(), }
    DuplicateBlock, MissingBlockEnd, ExtendedBlock, Supplementary, OperandNotAllowed,
    OperandRange, UndefinedSymbol, FormalOutsideFb, LabelOutsideFb, DuplicateLabel,
    LabelTooLong, ParamCount, ParamMismatch, UnknownParam, UndefinedBlock, UndefinedType,
    BlockNotOnCpu, UndefinedDb, IndirectTarget, NotOnCpu, OperationNotOnCpu, UnclosedBracket,
    UnopenedBracket, BracketDepth, UndeclaredLocal, RecursiveInstance, UndefinedLabel,
    NotSimulated, LibraryReplaced, Step7OnStep5Cpu,
);

impl CheckError {
    pub fn is_warning(&self) -> bool {
        matches!(
            self,
            CheckError::UndefinedBlock { .. }
                | CheckError::UndefinedDb { .. }
                | CheckError::LibraryReplaced { .. }
        )
    }
}
