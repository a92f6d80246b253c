//! Brackets in the order they stand in a block: each `A(`/`O(` closed by a `)` before `BE`, no
//! `)` without an open bracket, and no more open at once than the CPU's bracket stack holds.
//! Jumps can make run time differ from the text; the VM still stops with BCF then.

use crate::ast::LogicBody;
use crate::mnemonics::{self, MnemonicSet, OpCode};
use crate::profile::Profile;
use crate::source::Span;

use super::CheckError;
use super::needs::{Need, Needs};

/// The bracket errors of a block; the most brackets open at once go to `needs`.
pub fn check(
    body: &LogicBody,
    set: MnemonicSet,
    profile: &Profile,
    needs: &mut Needs,
) -> Vec<CheckError> {
    let mut errors = Vec::new();
    let mut open: Vec<(OpCode, Span)> = Vec::new();
    let mut most_open = 0;
    for statement in &body.statements {
        match statement.op {
            OpCode::AndBracket | OpCode::OrBracket => {
                open.push((statement.op, statement.op_span));
                most_open = most_open.max(open.len());
                if open.len() == usize::from(profile.bracket_depth) + 1 {
                    errors.push(CheckError::BracketDepth {
                        depth: profile.bracket_depth,
                        cpu: profile.name,
                        at: statement.op_span,
                        nth: open.len(),
                    });
                }
            }
            OpCode::CloseBracket if open.pop().is_none() => {
                errors.push(CheckError::UnopenedBracket {
                    and: mnemonics::op_word(set, OpCode::AndBracket),
                    at: statement.op_span,
                });
            }
            _ => {}
        }
    }
    needs.ask(
        Need::Brackets(u8::try_from(most_open).unwrap_or(u8::MAX)),
        profile,
    );
    if let Some(end) = body.end {
        errors.extend(
            open.into_iter()
                .map(|(op, at)| CheckError::UnclosedBracket {
                    open: mnemonics::op_word(set, op).to_string(),
                    at,
                    end,
                }),
        );
    }
    errors
}
