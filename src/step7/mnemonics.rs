//! The STEP 7 mnemonics in both sets: each operation's English (international) and German
//! (SIMATIC) word ("Statement List (STL) for S7-300 and S7-400 Programming", appendix:
//! the instruction overviews by English and German mnemonics).

use crate::mnemonics::MnemonicSet;

use super::ast::{Cmp, S7Op};

/// (English, German, operation); a word both sets share is written twice.
const TABLE: &[(&str, &str, S7Op)] = &[
    ("A", "U", S7Op::And),
    ("AN", "UN", S7Op::AndNot),
    ("O", "O", S7Op::Or),
    ("ON", "ON", S7Op::OrNot),
    ("X", "X", S7Op::Xor),
    ("XN", "XN", S7Op::XorNot),
    ("A(", "U(", S7Op::AndBracket),
    ("AN(", "UN(", S7Op::AndNotBracket),
    ("O(", "O(", S7Op::OrBracket),
    ("ON(", "ON(", S7Op::OrNotBracket),
    ("X(", "X(", S7Op::XorBracket),
    ("XN(", "XN(", S7Op::XorNotBracket),
    (")", ")", S7Op::CloseBracket),
    ("=", "=", S7Op::Assign),
    ("S", "S", S7Op::Set),
    ("R", "R", S7Op::Reset),
    ("SET", "SET", S7Op::SetRlo),
    ("CLR", "CLR", S7Op::ClearRlo),
    ("NOT", "NOT", S7Op::Not),
    ("SAVE", "SAVE", S7Op::Save),
    ("FP", "FP", S7Op::EdgePositive),
    ("FN", "FN", S7Op::EdgeNegative),
    ("L", "L", S7Op::Load),
    ("LC", "LC", S7Op::LoadCoded),
    ("T", "T", S7Op::Transfer),
    ("LAR1", "LAR1", S7Op::LoadAr1),
    ("LAR2", "LAR2", S7Op::LoadAr2),
    ("TAR1", "TAR1", S7Op::TransferAr1),
    ("TAR2", "TAR2", S7Op::TransferAr2),
    ("CAR", "TAR", S7Op::SwapAr),
    ("+AR1", "+AR1", S7Op::AddAr1),
    ("+AR2", "+AR2", S7Op::AddAr2),
    ("SP", "SI", S7Op::TimerPulse),
    ("SE", "SV", S7Op::TimerExtendedPulse),
    ("SD", "SE", S7Op::TimerOnDelay),
    ("SS", "SS", S7Op::TimerRetentiveOnDelay),
    ("SF", "SA", S7Op::TimerOffDelay),
    ("FR", "FR", S7Op::Enable),
    ("CU", "ZV", S7Op::CountUp),
    ("CD", "ZR", S7Op::CountDown),
    ("+I", "+I", S7Op::AddInt),
    ("-I", "-I", S7Op::SubInt),
    ("*I", "*I", S7Op::MulInt),
    ("/I", "/I", S7Op::DivInt),
    ("+D", "+D", S7Op::AddDint),
    ("-D", "-D", S7Op::SubDint),
    ("*D", "*D", S7Op::MulDint),
    ("/D", "/D", S7Op::DivDint),
    ("MOD", "MOD", S7Op::ModDint),
    ("+R", "+R", S7Op::AddReal),
    ("-R", "-R", S7Op::SubReal),
    ("*R", "*R", S7Op::MulReal),
    ("/R", "/R", S7Op::DivReal),
    ("+", "+", S7Op::AddConstant),
    ("ABS", "ABS", S7Op::Abs),
    ("SQR", "SQR", S7Op::Sqr),
    ("SQRT", "SQRT", S7Op::Sqrt),
    ("EXP", "EXP", S7Op::Exp),
    ("LN", "LN", S7Op::Ln),
    ("SIN", "SIN", S7Op::Sin),
    ("COS", "COS", S7Op::Cos),
    ("TAN", "TAN", S7Op::Tan),
    ("ASIN", "ASIN", S7Op::Asin),
    ("ACOS", "ACOS", S7Op::Acos),
    ("ATAN", "ATAN", S7Op::Atan),
    ("NEGI", "NEGI", S7Op::NegInt),
    ("NEGD", "NEGD", S7Op::NegDint),
    ("NEGR", "NEGR", S7Op::NegReal),
    ("INVI", "INVI", S7Op::InvInt),
    ("INVD", "INVD", S7Op::InvDint),
    ("==I", "==I", S7Op::CmpInt(Cmp::Eq)),
    ("<>I", "<>I", S7Op::CmpInt(Cmp::Ne)),
    (">I", ">I", S7Op::CmpInt(Cmp::Gt)),
    ("<I", "<I", S7Op::CmpInt(Cmp::Lt)),
    (">=I", ">=I", S7Op::CmpInt(Cmp::Ge)),
    ("<=I", "<=I", S7Op::CmpInt(Cmp::Le)),
    ("==D", "==D", S7Op::CmpDint(Cmp::Eq)),
    ("<>D", "<>D", S7Op::CmpDint(Cmp::Ne)),
    (">D", ">D", S7Op::CmpDint(Cmp::Gt)),
    ("<D", "<D", S7Op::CmpDint(Cmp::Lt)),
    (">=D", ">=D", S7Op::CmpDint(Cmp::Ge)),
    ("<=D", "<=D", S7Op::CmpDint(Cmp::Le)),
    ("==R", "==R", S7Op::CmpReal(Cmp::Eq)),
    ("<>R", "<>R", S7Op::CmpReal(Cmp::Ne)),
    (">R", ">R", S7Op::CmpReal(Cmp::Gt)),
    ("<R", "<R", S7Op::CmpReal(Cmp::Lt)),
    (">=R", ">=R", S7Op::CmpReal(Cmp::Ge)),
    ("<=R", "<=R", S7Op::CmpReal(Cmp::Le)),
    ("ITD", "ITD", S7Op::IntToDint),
    ("ITB", "ITB", S7Op::IntToBcd),
    ("BTI", "BTI", S7Op::BcdToInt),
    ("BTD", "BTD", S7Op::BcdToDint),
    ("DTB", "DTB", S7Op::DintToBcd),
    ("DTR", "DTR", S7Op::DintToReal),
    ("RND", "RND", S7Op::Round),
    ("RND+", "RND+", S7Op::RoundUp),
    ("RND-", "RND-", S7Op::RoundDown),
    ("TRUNC", "TRUNC", S7Op::Truncate),
    ("CAW", "TAW", S7Op::SwapBytesWord),
    ("CAD", "TAD", S7Op::SwapBytesDouble),
    ("SSI", "SSI", S7Op::ShiftSignedInt),
    ("SSD", "SSD", S7Op::ShiftSignedDint),
    ("SLW", "SLW", S7Op::ShiftLeftWord),
    ("SRW", "SRW", S7Op::ShiftRightWord),
    ("SLD", "SLD", S7Op::ShiftLeftDouble),
    ("SRD", "SRD", S7Op::ShiftRightDouble),
    ("RLD", "RLD", S7Op::RotateLeftDouble),
    ("RRD", "RRD", S7Op::RotateRightDouble),
    ("RLDA", "RLDA", S7Op::RotateLeftViaCc1),
    ("RRDA", "RRDA", S7Op::RotateRightViaCc1),
    ("AW", "UW", S7Op::AndWord),
    ("OW", "OW", S7Op::OrWord),
    ("XOW", "XOW", S7Op::XorWord),
    ("AD", "UD", S7Op::AndDouble),
    ("OD", "OD", S7Op::OrDouble),
    ("XOD", "XOD", S7Op::XorDouble),
    ("TAK", "TAK", S7Op::SwapAccus),
    ("PUSH", "PUSH", S7Op::Push),
    ("POP", "POP", S7Op::Pop),
    ("ENT", "ENT", S7Op::Enter),
    ("LEAVE", "LEAVE", S7Op::Leave),
    ("INC", "INC", S7Op::Increment),
    ("DEC", "DEC", S7Op::Decrement),
    ("JU", "SPA", S7Op::JumpAlways),
    ("JC", "SPB", S7Op::JumpIfRlo),
    ("JCN", "SPBN", S7Op::JumpIfNotRlo),
    ("JCB", "SPBB", S7Op::JumpIfRloSave),
    ("JNB", "SPBNB", S7Op::JumpIfNotRloSave),
    ("JBI", "SPBI", S7Op::JumpIfBr),
    ("JNBI", "SPBIN", S7Op::JumpIfNotBr),
    ("JO", "SPO", S7Op::JumpIfOverflow),
    ("JOS", "SPS", S7Op::JumpIfStoredOverflow),
    ("JZ", "SPZ", S7Op::JumpIfZero),
    ("JN", "SPN", S7Op::JumpIfNotZero),
    ("JP", "SPP", S7Op::JumpIfPositive),
    ("JM", "SPM", S7Op::JumpIfMinus),
    ("JPZ", "SPPZ", S7Op::JumpIfPositiveOrZero),
    ("JMZ", "SPMZ", S7Op::JumpIfMinusOrZero),
    ("JUO", "SPU", S7Op::JumpIfUnordered),
    ("LOOP", "LOOP", S7Op::Loop),
    ("JL", "SPL", S7Op::JumpList),
    ("OPN", "AUF", S7Op::OpenDb),
    ("CDB", "TDB", S7Op::ExchangeDbRegisters),
    ("CALL", "CALL", S7Op::Call),
    ("UC", "UC", S7Op::CallUnconditional),
    ("CC", "CC", S7Op::CallConditional),
    ("BE", "BE", S7Op::BlockEnd),
    ("BEU", "BEA", S7Op::BlockEndUnconditional),
    ("BEC", "BEB", S7Op::BlockEndConditional),
    ("MCRA", "MCRA", S7Op::McrActivate),
    ("MCRD", "MCRD", S7Op::McrDeactivate),
    ("MCR(", "MCR(", S7Op::McrOpen),
    (")MCR", ")MCR", S7Op::McrClose),
    ("NOP", "NOP", S7Op::Nop),
    ("BLD", "BLD", S7Op::Display),
    ("__ASSERT==", "__ASSERT==", S7Op::Assert(Cmp::Eq)),
    ("__ASSERT<>", "__ASSERT<>", S7Op::Assert(Cmp::Ne)),
    ("__ASSERT>", "__ASSERT>", S7Op::Assert(Cmp::Gt)),
    ("__ASSERT<", "__ASSERT<", S7Op::Assert(Cmp::Lt)),
    ("__ASSERT>=", "__ASSERT>=", S7Op::Assert(Cmp::Ge)),
    ("__ASSERT<=", "__ASSERT<=", S7Op::Assert(Cmp::Le)),
    ("__STWRST", "__STWRST", S7Op::ResetStatusWord),
    ("__SLEEP", "__SLEEP", S7Op::Sleep),
    ("__FEATURE", "__FEATURE", S7Op::Feature),
];

/// The operation a word names in `set`.
pub fn lookup(word: &str, set: MnemonicSet) -> Option<S7Op> {
    TABLE.iter().find_map(|(english, german, op)| {
        let spelled = match set {
            MnemonicSet::English => english,
            MnemonicSet::German => german,
        };
        spelled.eq_ignore_ascii_case(word).then_some(*op)
    })
}

/// The word of `op` in `set`.
pub fn word(op: S7Op, set: MnemonicSet) -> &'static str {
    TABLE
        .iter()
        .find(|(_, _, candidate)| *candidate == op)
        .map_or("?", |(english, german, _)| match set {
            MnemonicSet::English => english,
            MnemonicSet::German => german,
        })
}

/// Whether `word` is an operation only in `set` (so it shows which set a file uses).
pub fn only_in(word: &str, set: MnemonicSet) -> bool {
    lookup(word, set).is_some() && lookup(word, set.other()).is_none()
}

/// Operation words of `set` close to `word` (same first letter, at most two edits).
pub fn suggestions(word: &str, set: MnemonicSet) -> Vec<&'static str> {
    let word = word.to_ascii_uppercase();
    TABLE
        .iter()
        .map(|(english, german, _)| match set {
            MnemonicSet::English => *english,
            MnemonicSet::German => *german,
        })
        .filter(|candidate| candidate.chars().next() == word.chars().next())
        .filter(|candidate| edit_distance(candidate, &word) <= 1)
        .take(3)
        .collect()
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let current = row[j + 1];
            row[j + 1] = (previous + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(current + 1);
            previous = current;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_sets_name_the_same_operations() {
        assert_eq!(
            lookup("SPBN", MnemonicSet::German),
            Some(S7Op::JumpIfNotRlo)
        );
        assert_eq!(
            lookup("jcn", MnemonicSet::English),
            Some(S7Op::JumpIfNotRlo)
        );
        assert_eq!(
            lookup("SE", MnemonicSet::English),
            Some(S7Op::TimerExtendedPulse)
        );
        assert_eq!(lookup("SE", MnemonicSet::German), Some(S7Op::TimerOnDelay));
        assert!(only_in("U", MnemonicSet::German));
        assert!(!only_in("L", MnemonicSet::German));
        // `SE` is a timer operation in both sets (with different timers): it decides nothing.
        assert!(!only_in("SE", MnemonicSet::English));
        assert!(only_in("SD", MnemonicSet::English));
        assert_eq!(word(S7Op::CountUp, MnemonicSet::German), "ZV");
    }

    #[test]
    fn suggestions_keep_the_first_letter() {
        assert_eq!(
            suggestions("JCC", MnemonicSet::English),
            vec!["JC", "JCN", "JCB"]
        );
    }
}
