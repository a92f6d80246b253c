//! Reading a STEP 7 symbol table: the SIMATIC Manager's ASCII export (`.ASC`, the "SEQ"
//! format: each line `126,` then the symbol in 24 columns, the address in 12, the data type in
//! 10, then the comment), its System Data Format export (`.SDF`: the four fields quoted and
//! separated by `,`, `"Motor","Q       4.0","BOOL","Motor contactor"`), or the same four fields
//! as CSV separated by `;` (`"Motor";"Q 4.0";"BOOL";"Motor contactor"`, quotes optional, `""` a
//! quote inside quotes, a header line `Symbol;Address;…` allowed). Addresses are read in either mnemonic set (`E 0.0`/`I 0.0`,
//! `PEW 256`/`PIW 256`, `Z 1`/`C 1`); the data type must fit the address (STEP 7's symbol
//! editor refuses `MW 10` as BOOL).

use crate::mnemonics::MnemonicSet;
use crate::profile::Profile;
use crate::source::{FileId, Span};
use crate::step7::ast::{AccessWidth, S7Address, S7Area, S7BlockKind};

use super::{Entry, S7Symbol, Stands, SymbolError};

/// How a symbol file is written, told from its first line that is not blank.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// STEP 7's ASCII export: `126,` and fixed columns.
    Asc,
    /// STEP 7's fields separated by `;`.
    Csv,
    /// STEP 7's System Data Format: the fields quoted, separated by `,`.
    Sdf,
    /// A STEP 5 assignment list (`E 1.0  START  comment`, or CSV with commas).
    Step5,
}

/// The lengths of the ASCII export's columns after `126,`, in characters.
const NAME_COLUMNS: usize = 24;
const ADDRESS_COLUMNS: usize = 12;
const TYPE_COLUMNS: usize = 10;

impl Format {
    /// The format of `text`: ASC when its first line starts with `126,`, CSV when it splits
    /// into three or four `;` fields (a STEP 5 list only starts comment lines with `;`), else
    /// a STEP 5 list; SDF when it is three or four quoted fields separated by `,` (a STEP 5 CSV
    /// list does not quote its fields).
    pub fn detect(text: &str) -> Format {
        let Some(first) = text
            .lines()
            .map(|line| line.trim_start_matches('\u{feff}'))
            .find(|line| !line.trim().is_empty())
        else {
            return Format::Step5;
        };
        if first.starts_with("126,") {
            return Format::Asc;
        }
        let trimmed = first.trim_start();
        let sdf = separated_fields(first, 0, ',');
        let all_quoted = sdf.iter().all(|field| field.quoted);
        if trimmed.starts_with('"') && (3..=4).contains(&sdf.len()) && all_quoted {
            return Format::Sdf;
        }
        let fields = csv_fields(first, 0).len();
        if !trimmed.starts_with(';') && !trimmed.starts_with('#') && (3..=4).contains(&fields) {
            Format::Csv
        } else {
            Format::Step5
        }
    }
}

/// A field of a line: its text (unquoted) and where it is in the file.
#[derive(Debug, Clone)]
struct Field {
    text: String,
    start: usize,
    end: usize,
    /// It was written in quotes.
    quoted: bool,
}

impl Field {
    fn span(&self, file: FileId) -> Span {
        Span {
            file,
            start: self.start as u32,
            end: self.end.max(self.start) as u32,
        }
    }
}

/// `;`-separated fields, each trimmed; a quoted field loses its quotes and `""` in it is `"`.
fn csv_fields(line: &str, at: usize) -> Vec<Field> {
    separated_fields(line, at, ';')
}

/// The fields of `line` separated by `separator` outside quotes, as [`csv_fields`] reads them.
fn separated_fields(line: &str, at: usize, separator: char) -> Vec<Field> {
    let mut fields = Vec::new();
    let mut start = 0;
    let mut quoted = false;
    for (index, c) in line.char_indices().chain([(line.len(), separator)]) {
        if c == '"' {
            quoted = !quoted;
        } else if c == separator && !quoted {
            fields.push(trimmed_field(&line[start..index], at + start, true));
            start = index + c.len_utf8();
        }
    }
    fields
}

/// `raw` without its surrounding blanks (and quotes, in CSV), with where that text is.
fn trimmed_field(raw: &str, at: usize, csv: bool) -> Field {
    let leading = raw.len() - raw.trim_start().len();
    let text = raw.trim();
    let start = at + leading;
    let unquoted = text
        .strip_prefix('"')
        .and_then(|inner| inner.strip_suffix('"'))
        .filter(|_| csv && text.len() >= 2);
    match unquoted {
        Some(inner) => Field {
            text: inner.replace("\"\"", "\""),
            start: start + 1,
            end: start + 1 + inner.len(),
            quoted: true,
        },
        None => Field {
            text: text.to_string(),
            start,
            end: start + text.len(),
            quoted: false,
        },
    }
}

/// The byte offset of character `column` of `line` (its end when shorter).
fn column(line: &str, column: usize) -> usize {
    line.char_indices()
        .nth(column)
        .map_or(line.len(), |(index, _)| index)
}

/// An ASCII export line's fields: symbol, address, data type, comment.
fn asc_fields(line: &str, at: usize) -> Vec<Field> {
    let bounds = [
        4,
        4 + NAME_COLUMNS,
        4 + NAME_COLUMNS + ADDRESS_COLUMNS,
        4 + NAME_COLUMNS + ADDRESS_COLUMNS + TYPE_COLUMNS,
    ];
    let offsets: Vec<usize> = bounds.iter().map(|&c| column(line, c)).collect();
    (0..4)
        .map(|i| {
            let end = offsets.get(i + 1).copied().unwrap_or(line.len());
            trimmed_field(&line[offsets[i]..end], at + offsets[i], false)
        })
        .collect()
}

/// What a table file holds: its entries, the names of the lines with errors (so a use of
/// one is not said to be unknown) and the errors.
pub struct Read {
    pub entries: Vec<Entry>,
    pub rejected: Vec<(String, Span)>,
    pub errors: Vec<SymbolError>,
}

/// Reads the STEP 7 table in `text` (file `file`, in `format`).
pub fn read(file: FileId, text: &str, format: Format, profile: &'static Profile) -> Read {
    let mut entries = Vec::new();
    let mut rejected = Vec::new();
    let mut errors = Vec::new();
    let mut start = 0;
    let mut first = true;
    for raw in text.split_inclusive('\n') {
        let at = start;
        start += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        let (line, at) = match line.strip_prefix('\u{feff}') {
            Some(rest) => (rest, at + '\u{feff}'.len_utf8()),
            None => (line, at),
        };
        if line.trim().is_empty() {
            continue;
        }
        let whole = Span {
            file,
            start: at as u32,
            end: (at + line.len()) as u32,
        };
        let fields = match format {
            Format::Asc if line.starts_with("126,") => asc_fields(line, at),
            Format::Asc => {
                errors.push(SymbolError::BadTableLine {
                    reason: "an ASCII export line starts with `126,`".into(),
                    at: whole,
                });
                continue;
            }
            Format::Sdf => separated_fields(line, at, ','),
            _ => csv_fields(line, at),
        };
        let header = std::mem::take(&mut first)
            && format == Format::Csv
            && fields[0].text.eq_ignore_ascii_case("symbol");
        if header {
            continue;
        }
        match entry(file, &fields, whole, profile) {
            Ok(entry) => entries.push(entry),
            Err(error) => {
                if !fields[0].text.is_empty() {
                    rejected.push((fields[0].text.clone(), fields[0].span(file)));
                }
                errors.push(error);
            }
        }
    }
    let set = majority(&entries);
    for entry in &mut entries {
        if let Some(set) = set {
            // Words of both sets (`M`, `T`, `FC`) are shown in the set the rest is in.
            if entry_evidence(entry).is_none() {
                entry.set = set;
            }
        }
    }
    Read {
        entries,
        rejected,
        errors,
    }
}

/// The mnemonic set an entry's address word shows (`E`: German, `I`: English).
fn entry_evidence(entry: &Entry) -> Option<MnemonicSet> {
    let Stands::Step7(S7Symbol::Address(address)) = &entry.stands else {
        return None;
    };
    let word = crate::step7::text::area_word(address.area, address.width, MnemonicSet::English);
    let german = crate::step7::text::area_word(address.area, address.width, MnemonicSet::German);
    (word != german).then_some(entry.set)
}

/// The set most entries that show one are written in.
fn majority(entries: &[Entry]) -> Option<MnemonicSet> {
    let mut votes = [0usize; 2];
    for entry in entries {
        if let Some(set) = entry_evidence(entry) {
            votes[set as usize] += 1;
        }
    }
    match votes {
        [english, german] if english > german => Some(MnemonicSet::English),
        [english, german] if german > english => Some(MnemonicSet::German),
        _ => None,
    }
}

fn entry(
    file: FileId,
    fields: &[Field],
    whole: Span,
    profile: &'static Profile,
) -> Result<Entry, SymbolError> {
    if !(3..=4).contains(&fields.len()) {
        return Err(SymbolError::BadTableLine {
            reason: format!(
                "{} fields; a line has symbol, address, data type and comment",
                fields.len()
            ),
            at: whole,
        });
    }
    let (name, address, ty) = (&fields[0], &fields[1], &fields[2]);
    if name.text.is_empty() {
        return Err(SymbolError::BadTableLine {
            reason: "no symbol name".into(),
            at: whole,
        });
    }
    if name.text.contains('"') {
        return Err(SymbolError::BadName {
            name: name.text.clone(),
            written: format!("\"{}\"", name.text),
            help: "a STEP 7 symbol is written in quotes, so it cannot hold one".into(),
            at: name.span(file),
        });
    }
    if address.text.is_empty() {
        return Err(SymbolError::BadTableLine {
            reason: format!("the symbol \"{}\" has no address", name.text),
            at: whole,
        });
    }
    let operand_span = address.span(file);
    let (symbol, set) = parse_address(&address.text).map_err(|reason| SymbolError::BadOperand {
        operand: address.text.clone(),
        at: operand_span,
        reason,
        help: S7_FORMS.into(),
    })?;
    check_range(&symbol, profile).map_err(|range| SymbolError::OutOfRange {
        operand: address.text.clone(),
        at: operand_span,
        range,
        cpu: profile.name,
    })?;
    let vat = matches!(symbol, S7Symbol::VariableTable(_));
    // A variable table's type may be left out (it is the address again).
    if !(vat && ty.text.is_empty()) {
        check_type(&symbol, &ty.text).map_err(|expected| SymbolError::TypeMismatch {
            ty: ty.text.clone(),
            operand: address
                .text
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" "),
            expected,
            at: if ty.text.is_empty() {
                whole
            } else {
                ty.span(file)
            },
        })?;
    }
    Ok(Entry {
        name: name.text.clone(),
        stands: Stands::Step7(symbol),
        comment: fields
            .get(3)
            .map_or(String::new(), |field| field.text.clone()),
        set: set.unwrap_or(MnemonicSet::English),
        name_span: name.span(file),
        operand_span,
    })
}

/// The address forms of a STEP 7 symbol table, for the help of one that is none.
const S7_FORMS: &str = "a STEP 7 symbol stands for `I 0.0`/`E 0.0`, `Q 4.0`/`A 4.0`, `M 0.0`, IB IW ID, QB QW QD (German EB EW ED, AB AW AD), MB MW MD, PIB PIW PID, PQB PQW PQD (German PEB PEW PED, PAB PAW PAD), `T 5`, `C 3`/`Z 3`, or a block: `OB 1`, `FC 1`, `FB 1`, `DB 1`, `SFC 46`, `SFB 0`, `UDT 1`, `VAT 1`";

/// `I 0.0`, `MW 10`, `PEW 256`, `Z 3`, `FC 1`: what it names and the set its word shows.
fn parse_address(text: &str) -> Result<(S7Symbol, Option<MnemonicSet>), String> {
    let upper = text.trim().to_ascii_uppercase();
    let word_end = upper
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(upper.len());
    let (word, number) = (&upper[..word_end], upper[word_end..].trim());
    if word.is_empty() {
        return Err("no area or block word".into());
    }
    let whole = |number: &str| {
        number
            .parse::<u16>()
            .map_err(|_| format!("`{number}` is not a number"))
    };
    let block = match word {
        "OB" => Some(S7BlockKind::Ob),
        "FC" => Some(S7BlockKind::Fc),
        "FB" => Some(S7BlockKind::Fb),
        "DB" => Some(S7BlockKind::Db),
        "SFC" => Some(S7BlockKind::Sfc),
        "SFB" => Some(S7BlockKind::Sfb),
        "UDT" => Some(S7BlockKind::Udt),
        _ => None,
    };
    if let Some(kind) = block {
        // awlsim's own system functions `SFC -1` to `SFC -4` (its test files name them in
        // their tables), numbered as the STL front end numbers them: 16-bit two's complements.
        let awlsim = number
            .strip_prefix('-')
            .and_then(|digits| digits.trim().parse::<u8>().ok())
            .filter(|n| kind == S7BlockKind::Sfc && (1..=4).contains(n));
        let number = match awlsim {
            Some(n) => (-i16::from(n)) as u16,
            None => whole(number)?,
        };
        return Ok((S7Symbol::Block { kind, number }, None));
    }
    if word == "VAT" {
        return Ok((S7Symbol::VariableTable(whole(number)?), None));
    }
    let set = crate::step7::mnemonics::operand_evidence(word);
    let (area, width) = [MnemonicSet::English, MnemonicSet::German]
        .into_iter()
        .find_map(|set| crate::step7::mnemonics::area(set, word))
        .filter(|(area, _)| {
            matches!(
                area,
                S7Area::Input
                    | S7Area::Output
                    | S7Area::Flag
                    | S7Area::PeripheralInput
                    | S7Area::PeripheralOutput
                    | S7Area::Timer
                    | S7Area::Counter
            )
        })
        .ok_or_else(|| format!("`{word}` is no area or block a symbol can name"))?;
    let (byte, bit) = match (width, number.split_once('.')) {
        (AccessWidth::Bit, Some((byte, bit))) => {
            let bit = bit
                .trim()
                .parse::<u8>()
                .ok()
                .filter(|bit| *bit < 8)
                .ok_or_else(|| format!("`{bit}` is not a bit number (0 to 7)"))?;
            (byte.trim(), bit)
        }
        (AccessWidth::Bit, None) => return Err(format!("a bit address is `{word} byte.bit`")),
        (_, Some(_)) => return Err(format!("`{word}` takes a byte number, not a bit")),
        (_, None) => (number, 0),
    };
    let byte = byte
        .parse::<u32>()
        .map_err(|_| format!("`{byte}` is not a number"))?;
    Ok((
        S7Symbol::Address(S7Address {
            area,
            width,
            byte,
            bit,
            db: None,
        }),
        set,
    ))
}

/// The address is on the CPU, or the range it has.
fn check_range(symbol: &S7Symbol, profile: &'static Profile) -> Result<(), String> {
    let S7Symbol::Address(address) = symbol else {
        return Ok(());
    };
    let sizes = &profile.sizes;
    let (name, count) = match address.area {
        S7Area::Input => ("I bytes", u32::from(sizes.image_bytes)),
        S7Area::Output => ("Q bytes", u32::from(sizes.image_bytes)),
        S7Area::Flag => ("M bytes", u32::from(sizes.flag_bytes)),
        S7Area::PeripheralInput | S7Area::PeripheralOutput => {
            ("peripheral bytes", u32::from(sizes.peripheral_bytes))
        }
        S7Area::Timer => ("T", u32::from(sizes.timers)),
        _ => ("C", u32::from(sizes.counters)),
    };
    let last = match address.area {
        S7Area::Timer | S7Area::Counter => address.byte,
        _ => address.byte + address.width.bytes() - 1,
    };
    if last < count {
        Ok(())
    } else {
        Err(format!("{name} 0 to {}", count.saturating_sub(1)))
    }
}

/// The data type fits the address, or the types that would.
fn check_type(symbol: &S7Symbol, ty: &str) -> Result<(), String> {
    let upper = ty.split_whitespace().collect::<Vec<_>>().join(" ");
    let upper = upper.to_ascii_uppercase();
    let fits: &[&str] = match symbol {
        S7Symbol::Address(address) => match (address.area, address.width) {
            (S7Area::Timer, _) => &["TIMER"],
            (S7Area::Counter, _) => &["COUNTER"],
            (_, AccessWidth::Bit) => &["BOOL"],
            (_, AccessWidth::Byte) => &["BYTE", "CHAR"],
            (_, AccessWidth::Word) => &["WORD", "INT", "S5TIME", "DATE"],
            (_, AccessWidth::Double) => &["DWORD", "DINT", "REAL", "TIME", "TOD", "TIME_OF_DAY"],
        },
        S7Symbol::Block { kind, number } => {
            // awlsim's own system functions are written with their negative numbers.
            let shown = match (*kind, *number as i16) {
                (S7BlockKind::Sfc, -4..=-1) => i32::from(*number as i16),
                _ => i32::from(*number),
            };
            let same = format!("{} {shown}", kind.name());
            let number_of = |prefix: &str| {
                upper
                    .strip_prefix(prefix)
                    .and_then(|rest| rest.trim().parse::<u16>().ok())
                    .is_some()
            };
            // A DB is typed by itself (a global DB), by an FB or SFB (an instance DB) or by
            // a UDT.
            let instance = *kind == S7BlockKind::Db
                && ["FB", "SFB", "UDT"].iter().any(|prefix| number_of(prefix));
            if upper.replace(' ', "") == same.replace(' ', "") || instance {
                return Ok(());
            }
            return Err(if *kind == S7BlockKind::Db {
                format!("`{same}`, or the FB, SFB or UDT it is made from (`FB 1`)")
            } else {
                format!("`{same}`")
            });
        }
        S7Symbol::VariableTable(number) => {
            let same = format!("VAT {number}");
            if upper.replace(' ', "") == same.replace(' ', "") {
                return Ok(());
            }
            return Err(format!("`{same}`"));
        }
    };
    if fits.contains(&upper.as_str()) {
        Ok(())
    } else {
        let words: Vec<String> = fits.iter().map(|word| format!("`{word}`")).collect();
        Err(words.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_text(text: &str) -> (Vec<Entry>, Vec<SymbolError>) {
        let profile = crate::profile::default_for(crate::dialect::Dialect::Step7);
        let read = read(0, text, Format::detect(text), profile);
        (read.entries, read.errors)
    }

    fn asc(name: &str, address: &str, ty: &str, comment: &str) -> String {
        format!("126,{name:<24}{address:<12}{ty:<10}{comment:<80}\r\n")
    }

    fn address_of(entry: &Entry) -> S7Address {
        match entry.stands {
            Stands::Step7(S7Symbol::Address(address)) => address,
            ref other => panic!("not an address: {other:?}"),
        }
    }

    #[test]
    fn awlsim_s_own_system_functions_have_negative_numbers() {
        let text = [
            asc("__CLKRST", "SFC -4", "SFC -4", ""),
            asc("__REBOOT", "SFC -2", "SFC -2", ""),
        ]
        .concat();
        let (entries, errors) = read_text(&text);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(
            entries[0].stands,
            Stands::Step7(S7Symbol::Block {
                kind: S7BlockKind::Sfc,
                number: 65532
            })
        );
        for bad in [
            asc("X", "SFC -5", "SFC -5", ""),
            asc("Y", "FC -1", "FC -1", ""),
        ] {
            let (_, errors) = read_text(&bad);
            assert_eq!(errors.len(), 1, "{bad}");
        }
    }

    #[test]
    fn formats_are_told_by_content() {
        assert_eq!(
            Format::detect(&asc("Start", "I 0.0", "BOOL", "")),
            Format::Asc
        );
        assert_eq!(Format::detect("Start;I 0.0;BOOL;Button\n"), Format::Csv);
        assert_eq!(
            Format::detect("\"Start\";\"I 0.0\";\"BOOL\"\n"),
            Format::Csv
        );
        assert_eq!(Format::detect("; plant\nE 1.0  START\n"), Format::Step5);
        assert_eq!(Format::detect("I 1.0,START,\"a; b\"\n"), Format::Step5);
    }

    #[test]
    fn ascii_export_in_fixed_columns() {
        let text = [
            asc("Start button", "I       0.0", "BOOL", "Green, at the door"),
            asc("Speed", "MW     10", "INT", ""),
            asc("Valve", "FB     100", "FB     100", "Valve control"),
            asc("ValveDB", "DB 100", "FB 100", ""),
            asc("Watch", "VAT    1", "", ""),
            // A line with the blanks after the type cut off, as an editor leaves it.
            "126,Stop                    I 0.1       BOOL\n".to_string(),
        ]
        .concat();
        let (entries, errors) = read_text(&text);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(entries.len(), 6);
        assert_eq!(entries[0].name, "Start button");
        assert_eq!(entries[0].comment, "Green, at the door");
        assert_eq!(address_of(&entries[0]).area, S7Area::Input);
        assert_eq!(address_of(&entries[1]).width, AccessWidth::Word);
        assert_eq!(
            entries[2].stands,
            Stands::Step7(S7Symbol::Block {
                kind: S7BlockKind::Fb,
                number: 100
            })
        );
        assert_eq!(entries[4].stands, Stands::Step7(S7Symbol::VariableTable(1)));
        assert_eq!(address_of(&entries[5]).bit, 1);
        // The name's span is its text in the file, without the padding.
        assert_eq!(&text[entries[1].name_span.start as usize..][..5], "Speed");
    }

    #[test]
    fn the_system_data_format_export_is_read() {
        let text = "\"Start\",\"I       0.0\",\"BOOL\",\"start, the button\"\r\n\
                    \"Valve\",\"FB    5\",\"FB    5\",\"\"\r\n";
        assert_eq!(Format::detect(text), Format::Sdf);
        let (entries, errors) = read_text(text);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(entries.len(), 2);
        assert_eq!(entries[0].name, "Start");
        assert_eq!(Format::detect("E 1.0,START,button\n"), Format::Step5);
    }

    #[test]
    fn csv_with_header_quotes_and_german_addresses() {
        let text = "\"Symbol\";\"Address\";\"Data type\";\"Comment\"\n\
                    \"Start\";\"E 0.0\";\"BOOL\";\"Say \"\"go\"\"; then\"\n\
                    Level;PEW 128;INT;\n\
                    Parts;Z 3;COUNTER\n\
                    Out;A 4.0;BOOL;\n";
        let (entries, errors) = read_text(text);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(entries.len(), 4);
        assert_eq!(entries[0].comment, "Say \"go\"; then");
        assert_eq!(address_of(&entries[0]).area, S7Area::Input);
        assert_eq!(address_of(&entries[1]).area, S7Area::PeripheralInput);
        assert_eq!(address_of(&entries[2]).area, S7Area::Counter);
        assert_eq!(address_of(&entries[3]).area, S7Area::Output);
        assert!(entries.iter().all(|entry| entry.set == MnemonicSet::German));
    }

    #[test]
    fn english_addresses_set_the_list_english() {
        let (entries, errors) = read_text("Start;I 0.0;BOOL;\nFlag;M 1.0;BOOL;\nOut;Q 4.0;BOOL;\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert!(
            entries
                .iter()
                .all(|entry| entry.set == MnemonicSet::English)
        );
    }

    fn kinds(errors: &[SymbolError]) -> Vec<&'static str> {
        errors
            .iter()
            .map(|error| match error {
                SymbolError::TypeMismatch { .. } => "type",
                SymbolError::BadOperand { .. } => "operand",
                SymbolError::OutOfRange { .. } => "range",
                SymbolError::BadTableLine { .. } => "line",
                SymbolError::BadName { .. } => "name",
                _ => "other",
            })
            .collect()
    }

    #[test]
    fn a_type_that_does_not_fit_the_address_is_an_error() {
        let text = "A;M 0.0;WORD;\nB;MW 2;BOOL;\nC;MD 4;REAL;\nD;MB 8;CHAR;\nE;FC 1;FB 1;\nF;DB 2;DB 2;\nG;T 1;INT;\n";
        let (entries, errors) = read_text(text);
        assert_eq!(entries.len(), 3);
        assert_eq!(kinds(&errors), ["type", "type", "type", "type"]);
        let SymbolError::TypeMismatch { at, expected, .. } = &errors[0] else {
            unreachable!()
        };
        assert_eq!(&text[at.start as usize..at.end as usize], "WORD");
        assert_eq!(expected, "`BOOL`");
    }

    #[test]
    fn every_bad_line_is_reported() {
        let text = "A;X 1.0;BOOL;\nB;M 9999.0;BOOL;\nC;M 0.9;BOOL;\n;M 1.0;BOOL;\nD;M 1.0\nE;;BOOL;\n\"F\"\"\";M 2.0;BOOL;\n";
        let (entries, errors) = read_text(text);
        assert!(entries.is_empty());
        assert_eq!(
            kinds(&errors),
            [
                "operand", "range", "operand", "line", "line", "line", "name"
            ]
        );
        let (_, errors) = read_text(&format!("{}not ascii\n", asc("A", "M 0.0", "BOOL", "")));
        assert_eq!(kinds(&errors), ["line"]);
    }
}
