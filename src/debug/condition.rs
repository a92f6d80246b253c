//! What qualifies a breakpoint: a condition on an operand in the program's notation
//! (`MW 4 > 5`, `I 0.0 = 1`), a hit count (`3`, `>= 3`, `% 2`), and a log point's message with
//! operands in braces (`level {FW 10}`). Each is checked against the program when it is set,
//! so an unknown operand is refused then, not when the breakpoint is reached.

use crate::mnemonics::MnemonicSet;
use crate::scenario::operand::Target;
use crate::state::watch::{natural, number};
use crate::vm::Cpu;

use super::show::target;

/// A comparison, as STL writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    Equal,
    NotEqual,
    Less,
    Greater,
    LessOrEqual,
    GreaterOrEqual,
}

/// Longest first, so `<=` is not taken for `<`.
const COMPARISONS: &[(&str, Comparison)] = &[
    ("<>", Comparison::NotEqual),
    ("<=", Comparison::LessOrEqual),
    (">=", Comparison::GreaterOrEqual),
    ("==", Comparison::Equal),
    ("=", Comparison::Equal),
    ("<", Comparison::Less),
    (">", Comparison::Greater),
];

impl Comparison {
    fn holds(self, left: i64, right: i64) -> bool {
        match self {
            Comparison::Equal => left == right,
            Comparison::NotEqual => left != right,
            Comparison::Less => left < right,
            Comparison::Greater => left > right,
            Comparison::LessOrEqual => left <= right,
            Comparison::GreaterOrEqual => left >= right,
        }
    }
}

/// `OPERAND COMPARISON VALUE`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Condition {
    target: Target,
    comparison: Comparison,
    value: i64,
}

/// `42`, `-3`, `16#2A`, `0x2A`.
pub fn parse_number(text: &str) -> Option<i64> {
    let text = text.trim();
    match text.strip_prefix("16#").or_else(|| text.strip_prefix("0x")) {
        Some(hex) => i64::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

impl Condition {
    /// Reads `MW 4 > 5` against the program; why not, in words.
    pub fn parse(cpu: &Cpu, text: &str, set: MnemonicSet) -> Result<Condition, String> {
        let (at, symbol, comparison) = COMPARISONS
            .iter()
            .filter_map(|(symbol, comparison)| {
                text.find(symbol).map(|at| (at, *symbol, *comparison))
            })
            .min_by_key(|(at, symbol, _)| (*at, usize::MAX - symbol.len()))
            .ok_or_else(|| {
                format!(
                    "`{text}` compares nothing; write an operand, a comparison (= <> < > <= >=) and a number, e.g. `MW 4 > 5`"
                )
            })?;
        let operand = text[..at].trim();
        let number = text[at + symbol.len()..].trim();
        if operand.is_empty() {
            return Err(format!("`{text}` names no operand before `{symbol}`"));
        }
        let target =
            target(cpu, operand, set).map_err(|reason| format!("`{operand}`: {reason}"))?;
        let value = parse_number(number).ok_or_else(|| format!("`{number}` is not a number"))?;
        Ok(Condition {
            target,
            comparison,
            value,
        })
    }

    pub fn holds(&self, cpu: &Cpu) -> bool {
        self.comparison.holds(number(cpu, self.target), self.value)
    }
}

/// When a breakpoint whose condition holds pauses, by how often it was reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HitCondition {
    /// `3` or `= 3`: at the third time only.
    Exactly(u64),
    /// `>= 3`: from the third time on.
    AtLeast(u64),
    /// `> 3`: from the fourth time on.
    After(u64),
    /// `% 3`: every third time.
    Every(u64),
}

impl HitCondition {
    pub fn parse(text: &str) -> Result<HitCondition, String> {
        let text = text.trim();
        let (make, rest): (fn(u64) -> HitCondition, &str) =
            if let Some(rest) = text.strip_prefix(">=") {
                (HitCondition::AtLeast, rest)
            } else if let Some(rest) = text.strip_prefix('>') {
                (HitCondition::After, rest)
            } else if let Some(rest) = text.strip_prefix('%') {
                (HitCondition::Every, rest)
            } else {
                (
                    HitCondition::Exactly,
                    text.strip_prefix('=').unwrap_or(text),
                )
            };
        match rest.trim().parse::<u64>() {
            Ok(count) if count > 0 => Ok(make(count)),
            _ => Err(format!(
                "`{text}` is no hit count; write a number (`3`: the third time), `>= 3`, `> 3` or `% 3` (every third time)"
            )),
        }
    }

    pub fn reached(self, hits: u64) -> bool {
        match self {
            HitCondition::Exactly(count) => hits == count,
            HitCondition::AtLeast(count) => hits >= count,
            HitCondition::After(count) => hits > count,
            HitCondition::Every(count) => hits.is_multiple_of(count),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Piece {
    Text(String),
    Value(Target),
}

/// A log point's message: its text with the values of the operands in braces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogMessage(Vec<Piece>);

impl LogMessage {
    pub fn parse(cpu: &Cpu, text: &str, set: MnemonicSet) -> Result<LogMessage, String> {
        let mut pieces = Vec::new();
        let mut rest = text;
        while let Some(open) = rest.find('{') {
            pieces.push(Piece::Text(rest[..open].to_string()));
            let after = &rest[open + 1..];
            let close = after
                .find('}')
                .ok_or_else(|| format!("`{text}`: a `{{` is not closed"))?;
            let operand = after[..close].trim();
            let target =
                target(cpu, operand, set).map_err(|reason| format!("`{operand}`: {reason}"))?;
            pieces.push(Piece::Value(target));
            rest = &after[close + 1..];
        }
        pieces.push(Piece::Text(rest.to_string()));
        Ok(LogMessage(pieces))
    }

    pub fn render(&self, cpu: &Cpu) -> String {
        self.0
            .iter()
            .map(|piece| match piece {
                Piece::Text(text) => text.clone(),
                Piece::Value(target) => natural(cpu, *target),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_counts() {
        assert_eq!(HitCondition::parse("3"), Ok(HitCondition::Exactly(3)));
        assert_eq!(HitCondition::parse(">= 2"), Ok(HitCondition::AtLeast(2)));
        assert_eq!(HitCondition::parse("> 2"), Ok(HitCondition::After(2)));
        assert_eq!(HitCondition::parse("%2"), Ok(HitCondition::Every(2)));
        assert!(HitCondition::parse("often").is_err());
        assert!(HitCondition::parse("0").is_err());
        assert!(HitCondition::Every(2).reached(4));
        assert!(!HitCondition::Exactly(3).reached(4));
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_number("16#2A"), Some(42));
        assert_eq!(parse_number(" -5 "), Some(-5));
        assert_eq!(parse_number("x"), None);
    }
}
