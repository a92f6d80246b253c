//! Which status bits each STEP 7 operation reads and which it writes, as the reference manual
//! lists them for each instruction ("Statement List (STL) for S7-300 and S7-400 Programming",
//! the status word rows of each instruction), and each STEP 5 operation on the bits its CPU
//! has: a description of the rules the VM executes, for the editor's hover. Tests run every
//! operation of the tables on the VM with many status words and check each cell.

/// The status word's bits in the manual's order, left to right.
pub const BITS: [&str; 9] = ["BR", "CC 1", "CC 0", "OV", "OS", "OR", "STA", "RLO", "/FC"];

/// One operation's effect on the status word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Effect {
    /// The bits the result depends on, in [`BITS`] order: `x` read, `-` not.
    pub reads: &'static str,
    /// What becomes of each bit, in [`BITS`] order: `-` kept, `x` set by the operation, `0` or
    /// `1` always that, `s` set to 1 by the operation or else kept (OS, the stored overflow, and
    /// the overflow of the conversions that only report an error).
    pub writes: &'static str,
    /// What the operation keeps for later, where it keeps bits aside (empty for none).
    pub keeps: &'static str,
    /// Where the operand changes the rows (empty for none).
    pub note: &'static str,
}

const fn effect(reads: &'static str, writes: &'static str) -> Effect {
    Effect {
        reads,
        writes,
        keeps: "",
        note: "",
    }
}

/// An operation that keeps status bits aside: they are read when a later operation uses them.
const fn keeping(writes: &'static str, keeps: &'static str) -> Effect {
    Effect {
        reads: "---------",
        writes,
        keeps,
        note: "",
    }
}

/// A shift or rotate: a count of 0 changes nothing, the status bits included.
const fn shifting(reads: &'static str, writes: &'static str) -> Effect {
    Effect {
        note: "a count of 0 changes nothing, the status bits included",
        ..effect(reads, writes)
    }
}

/// The operations (English words; with the operand where it makes the difference) and their
/// effect.
const TABLE: &[(&[&str], Effect)] = &[
    (&["A", "AN"], effect("-----x-xx", "-----xxx1")),
    (&["O", "ON", "X", "XN"], effect("-------xx", "-----0xx1")),
    (
        &["A(", "AN(", "O(", "ON(", "X(", "XN("],
        keeping(
            "-----01-0",
            "BR, RLO, OR, /FC and the operation go on the nesting stack; `)` combines with them",
        ),
    ),
    (&[")"], effect("-------x-", "x----x1x1")),
    (&["=", "S", "R"], effect("-------x-", "-----0x-0")),
    (&["SET"], effect("---------", "-----0110")),
    (&["CLR"], effect("---------", "-----0000")),
    (&["NOT"], effect("-------x-", "------1x-")),
    (&["SAVE"], effect("-------x-", "x--------")),
    (&["FP", "FN"], effect("-------x-", "-----0xx1")),
    (
        &["SP", "SE", "SD", "SS", "SF", "CU", "CD"],
        effect("-------x-", "-----0--0"),
    ),
    (
        &["FR"],
        keeping(
            "-----0--0",
            "the RLO's rising edge, which lets the next start restart the timer or counter",
        ),
    ),
    (
        &["+I", "-I", "*I", "/I", "+D", "-D", "*D", "/D", "MOD"],
        effect("---------", "-xxxs----"),
    ),
    (
        &[
            "+R", "-R", "*R", "/R", "SQR", "SQRT", "EXP", "LN", "SIN", "COS", "TAN", "ASIN",
            "ACOS", "ATAN",
        ],
        effect("---------", "-xxxs----"),
    ),
    (&["NEGI", "NEGD"], effect("---------", "-xxxs----")),
    (
        &[
            "==I", "<>I", ">I", "<I", ">=I", "<=I", "==D", "<>D", ">D", "<D", ">=D", "<=D",
        ],
        effect("---------", "-xx0-0xx1"),
    ),
    (
        &["==R", "<>R", ">R", "<R", ">=R", "<=R"],
        effect("---------", "-xxxs0xx1"),
    ),
    (&["ITB", "DTB"], effect("---------", "---xs----")),
    (
        &["RND", "RND+", "RND-", "TRUNC"],
        effect("---------", "---ss----"),
    ),
    (
        &["SSI", "SSD", "SLW", "SRW", "SLD", "SRD", "RLD", "RRD"],
        shifting("---------", "-xx0-----"),
    ),
    (&["RLDA", "RRDA"], effect("-x-------", "-x00-----")),
    (
        &["AW", "OW", "XOW", "AD", "OD", "XOD"],
        effect("---------", "-xx0-----"),
    ),
    (&["JC", "JCN"], effect("-------x-", "-----0110")),
    (&["JCB", "JNB"], effect("-------x-", "x----0110")),
    (&["JBI", "JNBI"], effect("x--------", "-----01-0")),
    (&["JO"], effect("---x-----", "---------")),
    (&["JOS"], effect("----x----", "----0----")),
    (
        &["JZ", "JN", "JP", "JM", "JUO"],
        effect("-xx------", "---------"),
    ),
    (&["JPZ"], effect("--x------", "---------")),
    (&["JMZ"], effect("-x-------", "---------")),
    (
        &["MCR("],
        keeping("-----01-0", "the RLO goes on the MCR stack"),
    ),
    (
        &[")MCR"],
        keeping("-----01-0", "takes the last entry off the MCR stack"),
    ),
    (&["L STW"], effect("xxxxxxxxx", "---------")),
    (&["T STW"], effect("---------", "xxxxxxxxx")),
    (
        &[
            "L", "LC", "T", "LAR1", "LAR2", "TAR1", "TAR2", "CAR", "+AR1", "+AR2", "+", "ABS",
            "NEGR", "INVI", "INVD", "ITD", "DTR", "BTI", "BTD", "CAW", "CAD", "TAK", "PUSH", "POP",
            "ENT", "LEAVE", "INC", "DEC", "JU", "LOOP", "OPN", "CDB", "MCRA", "MCRD", "NOP", "BLD",
        ],
        effect("---------", "---------"),
    ),
];

/// STEP 5 operations with the effect of the STEP 7 operation beside them, on the bits a STEP 5
/// CPU has (the STEP 5 test runs each on the VM).
const STEP5_TWINS: &[(&str, &str)] = &[
    ("A", "A"),
    ("AN", "AN"),
    ("A(", "A("),
    ("O(", "O("),
    ("=", "="),
    ("S", "S"),
    ("R", "R"),
    ("SP", "SP"),
    ("SE", "SE"),
    ("SD", "SD"),
    ("SS", "SS"),
    ("SF", "SF"),
    ("FR", "FR"),
    ("CU", "CU"),
    ("CD", "CD"),
    ("L", "L"),
    ("LC", "LC"),
    ("T", "T"),
    ("+F", "+I"),
    ("-F", "-I"),
    ("JU", "JU"),
    ("JC", "JC"),
    ("JZ", "JZ"),
    ("JN", "JN"),
    ("JP", "JP"),
    ("JM", "JM"),
    ("JO", "JO"),
    ("TAK", "TAK"),
    ("CFW", "INVI"),
    ("CSW", "NEGI"),
    ("NOP", "NOP"),
    ("BLD", "BLD"),
];

/// The bits of the STEP 5 status, as indices into [`BITS`]: CC 1, CC 0, OV, OR, RLO, /FC.
pub const STEP5_BITS: [usize; 6] = [1, 2, 3, 5, 7, 8];

/// Every bit of the STEP 7 status word.
pub const STEP7_BITS: [usize; 9] = [0, 1, 2, 3, 4, 5, 6, 7, 8];

/// STEP 5 operations whose effect is their own: `O` reads the OR bit, a comparison, a shift and
/// word logic leave OV as it was. Only the bits in [`STEP5_BITS`] count.
const STEP5_OWN: &[(&[&str], Effect)] = &[
    (&["O", "ON"], effect("-----x-xx", "-----0-x1")),
    (
        &["!=F", "><F", ">F", ">=F", "<F", "<=F"],
        effect("---------", "-xx--0-x1"),
    ),
    (
        &["SLW", "SRW", "AW", "OW", "XOW"],
        effect("---------", "-xx------"),
    ),
];

/// The effect of the STEP 5 operation written `english` (the English word, upper case), on
/// the bits in [`STEP5_BITS`].
pub fn of_step5(english: &str) -> Option<Effect> {
    step5_all()
        .find(|(word, _)| *word == english)
        .map(|(_, effect)| effect)
}

/// Every STEP 5 operation the table describes, with its effect.
pub fn step5_all() -> impl Iterator<Item = (&'static str, Effect)> {
    let own = STEP5_OWN
        .iter()
        .flat_map(|(words, effect)| words.iter().map(move |word| (*word, *effect)));
    let twins = STEP5_TWINS
        .iter()
        .filter_map(|(step5, step7)| Some((*step5, of(step7)?)));
    own.chain(twins)
}

/// The effect of a STEP 7 statement: its operation's English word and its operand, as written.
pub fn of_statement(english: &str, operand: &str) -> Option<Effect> {
    let operand = operand.trim().trim_end_matches(';').trim().to_uppercase();
    of(&format!("{english} {operand}")).or_else(|| of(english))
}

/// The effect of the STEP 7 operation written `english` (the English word, upper case).
pub fn of(english: &str) -> Option<Effect> {
    TABLE
        .iter()
        .find(|(words, _)| words.contains(&english))
        .map(|(_, effect)| *effect)
}

/// Every operation the table describes, with its effect.
pub fn all() -> impl Iterator<Item = (&'static str, Effect)> {
    TABLE
        .iter()
        .flat_map(|(words, effect)| words.iter().map(move |word| (*word, *effect)))
}

impl Effect {
    /// A Markdown table of the status word as the manual prints it, with the bits `columns`
    /// names (indices into [`BITS`]): a row of what is read and a row of what is written.
    pub fn markdown(self, columns: &[usize]) -> String {
        let row = |marks: &str| {
            let cells: Vec<String> = columns
                .iter()
                .map(|&column| marks[column..=column].to_string())
                .collect();
            format!("| {} |", cells.join(" | "))
        };
        let names: Vec<&str> = columns.iter().map(|&column| BITS[column]).collect();
        let mut table = format!(
            "| | {} |\n|---|{}\n| reads {}\n| writes {}",
            names.join(" | "),
            "---|".repeat(columns.len()),
            row(self.reads),
            row(self.writes)
        );
        if !self.keeps.is_empty() {
            table.push_str(&format!("\n\nKeeps: {}.", self.keeps));
        }
        if !self.note.is_empty() {
            table.push_str(&format!("\n\nNote: {}.", self.note));
        }
        table
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_names_each_bit_once() {
        for (word, effect) in all() {
            assert_eq!(effect.reads.len(), BITS.len(), "{word}");
            assert_eq!(effect.writes.len(), BITS.len(), "{word}");
            assert!(effect.reads.chars().all(|c| "x-".contains(c)), "{word}");
            assert!(effect.writes.chars().all(|c| "x-01s".contains(c)), "{word}");
        }
    }

    #[test]
    fn the_status_word_as_operand_has_its_own_row() {
        assert_eq!(of_statement("T", " STW;").unwrap().writes, "xxxxxxxxx");
        assert_eq!(of_statement("L", "stw").unwrap().reads, "xxxxxxxxx");
        assert_eq!(of_statement("T", "MW 2").unwrap().writes, "---------");
    }

    #[test]
    fn each_operation_stands_in_one_row() {
        let words: Vec<&str> = all().map(|(word, _)| word).collect();
        for word in &words {
            assert_eq!(words.iter().filter(|w| *w == word).count(), 1, "{word}");
        }
    }
}
