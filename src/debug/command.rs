//! The debugger's commands, parsed from one line each.

use miette::Diagnostic;
use thiserror::Error;

use crate::ast::BlockId;

/// Where a breakpoint stops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BreakAt {
    /// Before the first operation of a block, or of one of its lines.
    Block { block: BlockId, line: Option<u32> },
    /// When the engine takes in a request for the OB.
    Request(u8),
    /// Before the first operation of the OB, when it is serviced.
    Service(u8),
}

/// How `until` gives its time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Until {
    /// `until 250ms`: simulated time since the start.
    At(u64),
    /// `until +20ms`: from now.
    After(u64),
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Command {
    Break(BreakAt),
    /// `break "Valve" [line N]`, `break -FILL`: a block by its symbol, which the session
    /// looks up in the program's symbols.
    BreakNamed {
        symbol: String,
        line: Option<u32>,
    },
    /// `break` alone: the breakpoints.
    Breakpoints,
    /// `delete` (all) or `delete N`.
    Delete(Option<usize>),
    Step,
    Next,
    Finish,
    Continue,
    Until(Until),
    Print(Vec<String>),
    Accu,
    Status,
    Stack,
    Levels,
    List,
    Set {
        operand: String,
        value: i64,
    },
    Fire(u8),
    State,
    Help,
    Quit,
}

impl Command {
    pub fn name(&self) -> &'static str {
        match self {
            Command::Break(_) | Command::BreakNamed { .. } | Command::Breakpoints => "break",
            Command::Delete(_) => "delete",
            Command::Step => "step",
            Command::Next => "next",
            Command::Finish => "finish",
            Command::Continue => "continue",
            Command::Until(_) => "until",
            Command::Print(_) => "print",
            Command::Accu => "accu",
            Command::Status => "status",
            Command::Stack => "stack",
            Command::Levels => "levels",
            Command::List => "list",
            Command::Set { .. } => "set",
            Command::Fire(_) => "fire",
            Command::State => "state",
            Command::Help => "help",
            Command::Quit => "quit",
        }
    }

    /// Whether the command lets the CPU run on.
    pub fn resumes(&self) -> bool {
        matches!(
            self,
            Command::Step | Command::Next | Command::Finish | Command::Continue | Command::Until(_)
        )
    }
}

/// A command line the debugger cannot take.
#[derive(Debug, Clone, PartialEq, Eq, Error, Diagnostic)]
pub enum CommandError {
    #[error("unknown command `{command}`")]
    #[diagnostic(code(awl::debug::unknown_command), help("{help}"))]
    Unknown { command: String, help: String },
    #[error("`{command}`: the run has ended")]
    #[diagnostic(
        code(awl::debug::run_ended),
        help(
            "after the run the CPU can be inspected (print, accu, status, stack, levels, list, state); quit ends"
        )
    )]
    RunEnded { command: &'static str },
    #[error("`{command}`: {reason}")]
    #[diagnostic(code(awl::debug::usage), help("write it as `{usage}`"))]
    Usage {
        command: &'static str,
        reason: String,
        usage: &'static str,
    },
}

/// Each command with its short form and how it is written; `help` prints this.
pub const COMMANDS: &[(&str, &str, &str)] = &[
    (
        "break",
        "b",
        "break BLOCK [line N] | break request OB n | break service OB n  (BLOCK: PB 3, -FILL or \"Valve\")",
    ),
    ("delete", "d", "delete [N]  (all breakpoints, or number N)"),
    (
        "step",
        "s",
        "step  (one operation, into called blocks and interrupt OBs)",
    ),
    (
        "next",
        "n",
        "next  (one operation of this block, over block calls)",
    ),
    ("finish", "f", "finish  (until this block has returned)"),
    (
        "continue",
        "c",
        "continue  (until a breakpoint or the end of the run)",
    ),
    (
        "until",
        "u",
        "until TIME | until +DURATION  (e.g. until 250ms, until +10ms)",
    ),
    (
        "print",
        "p",
        "print OPERAND[, OPERAND…]  (e.g. print Q 4.0, FW 10, T 1, DB 10 DW 3; STEP 7: MW 10, DB5.DBW 4, DB5.level)",
    ),
    ("accu", "a", "accu  (the accumulators)"),
    ("status", "st", "status  (the status word)"),
    (
        "stack",
        "bt",
        "stack  (the block stack, the running block first)",
    ),
    (
        "levels",
        "lv",
        "levels  (the ISTACK: running and interrupted levels)",
    ),
    ("list", "l", "list  (the source around the next operation)"),
    (
        "set",
        "",
        "set OPERAND VALUE  (force an input, flag, output or data word, e.g. set I 0.0 1)",
    ),
    ("fire", "", "fire OB n  (request an interrupt now)"),
    (
        "state",
        "",
        "state  (everything, as `awl run --state` prints it)",
    ),
    ("help", "h", "help"),
    ("quit", "q", "quit"),
];

/// A usage error of `command`, with how it is written.
pub fn usage(command: &'static str, reason: impl Into<String>) -> CommandError {
    let usage = COMMANDS
        .iter()
        .find(|(name, _, _)| *name == command)
        .map_or("help", |(_, _, usage)| usage);
    CommandError::Usage {
        command,
        reason: reason.into(),
        usage,
    }
}

/// `OB 2`, `OB2` → 2.
fn ob_number(words: &[&str]) -> Option<u8> {
    match BlockId::parse(&words.join(" ")) {
        Some(BlockId {
            kind: crate::mnemonics::BlockKind::Ob,
            number,
        }) => u8::try_from(number).ok(),
        _ => None,
    }
}

fn parse_break(words: &[&str]) -> Result<Command, CommandError> {
    let Some(first) = words.first() else {
        return Ok(Command::Breakpoints);
    };
    let kind = first.to_ascii_lowercase();
    if kind == "request" || kind == "service" {
        let ob = ob_number(&words[1..])
            .ok_or_else(|| usage("break", format!("`{kind}` needs an OB, e.g. OB 2")))?;
        return Ok(Command::Break(if kind == "request" {
            BreakAt::Request(ob)
        } else {
            BreakAt::Service(ob)
        }));
    }
    let line_at = words
        .iter()
        .position(|word| word.eq_ignore_ascii_case("line"));
    let block_words = words[..line_at.unwrap_or(words.len())].join(" ");
    let line = match line_at {
        None => None,
        Some(at) => match words.get(at + 1..) {
            Some([number]) => Some(
                number
                    .parse()
                    .map_err(|_| usage("break", format!("`{number}` is not a line number")))?,
            ),
            _ => return Err(usage("break", "`line` needs one line number")),
        },
    };
    if crate::symbols::symbol_written(&block_words).is_some() {
        return Ok(Command::BreakNamed {
            symbol: block_words,
            line,
        });
    }
    let block = BlockId::parse(&block_words)
        .ok_or_else(|| usage("break", format!("`{block_words}` is not a block")))?;
    Ok(Command::Break(BreakAt::Block { block, line }))
}

fn parse_until(words: &[&str]) -> Result<Command, CommandError> {
    let [time] = words else {
        return Err(usage("until", "give one time"));
    };
    let (relative, text) = match time.strip_prefix('+') {
        Some(rest) => (true, rest),
        None => (false, *time),
    };
    let ns = crate::scenario::parse_duration(text)
        .ok_or_else(|| usage("until", format!("`{time}` is not a time")))?;
    Ok(Command::Until(if relative {
        Until::After(ns)
    } else {
        Until::At(ns)
    }))
}

fn parse_set(words: &[&str]) -> Result<Command, CommandError> {
    let Some((value, operand)) = words
        .split_last()
        .filter(|(_, operand)| !operand.is_empty())
    else {
        return Err(usage("set", "give an operand and a value"));
    };
    let value = super::condition::parse_number(value)
        .ok_or_else(|| usage("set", format!("`{value}` is not a number")))?;
    Ok(Command::Set {
        operand: operand.join(" "),
        value,
    })
}

/// `Q 4.0, FW 10` or `Q 4.0 FW 10`: operands are an area and an address, `DB n DW m`, or a
/// STEP 7 data block's value by name (`DB5.level`).
fn operands(words: &[&str]) -> Vec<String> {
    let listed = crate::address::operand::list(&words.join(" "));
    let [one] = listed.as_slice() else {
        return listed;
    };
    let words: Vec<&str> = one.split_whitespace().collect();
    let mut out = Vec::new();
    let mut rest = words.as_slice();
    while !rest.is_empty() {
        let take = if rest[0].eq_ignore_ascii_case("DB") {
            4
        } else if is_value_name(rest[0]) {
            1
        } else {
            2
        };
        let (operand, tail) = rest.split_at(take.min(rest.len()));
        out.push(operand.join(" "));
        rest = tail;
    }
    out
}

/// `DB5.level`, `DB5.table[2]`: a data block's value by name, one word (where `DB5.DBW` needs
/// its address after it).
fn is_value_name(word: &str) -> bool {
    let Some((block, name)) = word.split_once('.') else {
        return false;
    };
    let is_area = ["DBX", "DBB", "DBW", "DBD"]
        .iter()
        .any(|area| name.eq_ignore_ascii_case(area));
    block.len() > 2 && block[..2].eq_ignore_ascii_case("DB") && !is_area
}

fn no_arguments(
    command: &'static str,
    words: &[&str],
    done: Command,
) -> Result<Command, CommandError> {
    if words.is_empty() {
        Ok(done)
    } else {
        Err(usage(command, "takes no arguments"))
    }
}

/// Parses one line; `None` for an empty line or a comment.
pub fn parse(line: &str) -> Option<Result<Command, CommandError>> {
    let line = line.trim();
    if line.starts_with('#') {
        return None;
    }
    let words: Vec<&str> = line.split_whitespace().collect();
    let (first, args) = words.split_first()?;
    let word = first.to_ascii_lowercase();
    let name = COMMANDS
        .iter()
        .find(|(name, short, _)| *name == word || (!short.is_empty() && *short == word))
        .map(|(name, _, _)| *name);
    Some(match name {
        Some("break") => parse_break(args),
        Some("delete") => match args {
            [] => Ok(Command::Delete(None)),
            [number] => number
                .parse()
                .map(|n| Command::Delete(Some(n)))
                .map_err(|_| usage("delete", format!("`{number}` is not a breakpoint number"))),
            _ => Err(usage("delete", "give at most one breakpoint number")),
        },
        Some("step") => no_arguments("step", args, Command::Step),
        Some("next") => no_arguments("next", args, Command::Next),
        Some("finish") => no_arguments("finish", args, Command::Finish),
        Some("continue") => no_arguments("continue", args, Command::Continue),
        Some("until") => parse_until(args),
        Some("print") if args.is_empty() => Err(usage("print", "name at least one operand")),
        Some("print") => Ok(Command::Print(operands(args))),
        Some("accu") => no_arguments("accu", args, Command::Accu),
        Some("status") => no_arguments("status", args, Command::Status),
        Some("stack") => no_arguments("stack", args, Command::Stack),
        Some("levels") => no_arguments("levels", args, Command::Levels),
        Some("list") => no_arguments("list", args, Command::List),
        Some("set") => parse_set(args),
        Some("fire") => ob_number(args)
            .map(Command::Fire)
            .ok_or_else(|| usage("fire", "name an interrupt OB, e.g. fire OB 2")),
        Some("state") => no_arguments("state", args, Command::State),
        Some("help") => Ok(Command::Help),
        Some("quit") => Ok(Command::Quit),
        _ => Err(CommandError::Unknown {
            command: first.to_string(),
            help: match crate::suggest::did_you_mean(
                &word,
                COMMANDS.iter().map(|(name, _, _)| *name),
            ) {
                Some(near) => format!("did you mean `{near}`? `help` lists the commands"),
                None => "`help` lists the commands".to_string(),
            },
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(line: &str) -> Command {
        parse(line).unwrap().unwrap()
    }

    #[test]
    fn parses_every_command_form() {
        let pb3 = BlockId::parse("PB 3").unwrap();
        assert_eq!(
            ok("break PB 3 line 12"),
            Command::Break(BreakAt::Block {
                block: pb3,
                line: Some(12)
            })
        );
        assert_eq!(
            ok("b pb3"),
            Command::Break(BreakAt::Block {
                block: pb3,
                line: None
            })
        );
        assert_eq!(
            ok("break request OB 2"),
            Command::Break(BreakAt::Request(2))
        );
        assert_eq!(
            ok("break service OB13"),
            Command::Break(BreakAt::Service(13))
        );
        assert_eq!(ok("break"), Command::Breakpoints);
        assert_eq!(
            ok("break \"Function  Block 2\" line 4"),
            Command::BreakNamed {
                symbol: "\"Function Block 2\"".into(),
                line: Some(4)
            }
        );
        assert_eq!(
            ok("b -FILL"),
            Command::BreakNamed {
                symbol: "-FILL".into(),
                line: None
            }
        );
        assert_eq!(ok("delete 2"), Command::Delete(Some(2)));
        assert_eq!(ok("until 250ms"), Command::Until(Until::At(250_000_000)));
        assert_eq!(ok("u +1ms"), Command::Until(Until::After(1_000_000)));
        assert_eq!(
            ok("print Q 4.0 FW 10 DB 10 DW 3"),
            Command::Print(vec!["Q 4.0".into(), "FW 10".into(), "DB 10 DW 3".into()])
        );
        assert_eq!(
            ok("print DB5.level MW 10 DB5.DBW 4 DB5.grid[1,2]"),
            Command::Print(vec![
                "DB5.level".into(),
                "MW 10".into(),
                "DB5.DBW 4".into(),
                "DB5.grid[1,2]".into()
            ])
        );
        assert_eq!(
            ok("p Q 4.0, T 1"),
            Command::Print(vec!["Q 4.0".into(), "T 1".into()])
        );
        assert_eq!(
            ok("set IW 2 0x7B"),
            Command::Set {
                operand: "IW 2".into(),
                value: 123
            }
        );
        assert_eq!(ok("fire OB 2"), Command::Fire(2));
        assert!(parse("   # a comment").is_none());
        assert_eq!(
            ok("set FW 10 16#FF"),
            Command::Set {
                operand: "FW 10".into(),
                value: 255
            }
        );
    }

    #[test]
    fn explains_what_it_cannot_take() {
        let error = parse("stpe").unwrap().unwrap_err();
        assert!(matches!(&error, CommandError::Unknown { help, .. } if help.contains("`step`")));
        assert!(parse("break PB 3 line x").unwrap().is_err());
        assert!(parse("set I 0.0").unwrap().is_err());
        assert!(parse("fire PB 2").unwrap().is_err());
        assert!(parse("step 2").unwrap().is_err());
        assert!(parse("until soon").unwrap().is_err());
    }
}
