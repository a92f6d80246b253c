//! STEP 5 PG listings and symbolic operands: each element of the listing form in both mnemonic
//! sets, files that mix both forms, segments kept in the bytecode, symbols resolved from an
//! assignment list, and the round trip `awl dump --listing` → parse → the same bytecode.

use awl::compiler::{CompiledBlock, Op, Program};
use awl::frontend::{self, Frontend};
use awl::mnemonics::MnemonicSet;
use awl::profile;
use awl::source::{SourceFile, SourceSet};

fn build(files: &[(&str, &str)], symbols: &[(&str, &str)]) -> Frontend {
    build_on(files, symbols, "sinumerik-840c")
}

fn build_on(files: &[(&str, &str)], symbols: &[(&str, &str)], cpu: &str) -> Frontend {
    let mut sources = SourceSet::default();
    for (name, text) in files {
        sources.add(SourceFile::new(*name, *text));
    }
    let symbol_files = symbols
        .iter()
        .map(|(name, text)| SourceFile::new(*name, *text))
        .collect();
    let cpu = profile::find(cpu).unwrap();
    frontend::build_with_symbols(sources, symbol_files, frontend::Language::default(), cpu)
}

fn clean(files: &[(&str, &str)], symbols: &[(&str, &str)]) -> Program {
    let built = build(files, symbols);
    assert!(built.diagnostics.is_empty(), "{:#?}", built.diagnostics);
    built.compiled.program
}

fn block<'a>(program: &'a Program, name: &str) -> &'a CompiledBlock {
    program
        .blocks
        .iter()
        .find(|block| block.id.to_string() == name)
        .unwrap_or_else(|| panic!("{name}"))
}

fn code(program: &Program, name: &str) -> Vec<Op> {
    block(program, name).code.clone()
}

const PLAIN_DE: &str = "PB 3\n      U  E 1.0\n      U  E 1.1\n      =  A 4.0\n      L  KF +5\nM001 :T  MW 10\n      BE\n";
const PLAIN_EN: &str = "PB 3\n      A  I 1.0\n      A  I 1.1\n      =  Q 4.0\n      L  KF +5\nM001 :T  FW 10\n      BE\n";

const LISTING_DE: &str = "\
PB 3                                  LAE=12
SEGMENT 1                             0000
0000      :U    E   1.0
0001      :U    E   1.1
0002      :=    A   4.0
0003      :***
SEGMENT 2                             0004
0004      :L    KF +5
0005 M001 :T    MW  10
0006      :BE
";

const LISTING_EN: &str = "\
PB 3                                  LEN=12
NETWORK 1                             0000
0000      :A    I   1.0
0001      :A    I   1.1
0002      :=    Q   4.0
0003      :***
NETWORK 2                             0004
0004      :L    KF +5
0005 M001 :T    FW  10
0006      :BE
";

#[test]
fn a_listing_compiles_to_the_plain_form_s_bytecode_in_both_sets() {
    for (plain, listing) in [(PLAIN_DE, LISTING_DE), (PLAIN_EN, LISTING_EN)] {
        let plain = clean(&[("plain.awl", plain)], &[]);
        let listing = clean(&[("listing.awl", listing)], &[]);
        assert_eq!(code(&plain, "PB 3"), code(&listing, "PB 3"));
    }
}

#[test]
fn segments_are_kept_for_every_op() {
    let program = clean(&[("listing.awl", LISTING_DE)], &[]);
    let pb3 = block(&program, "PB 3");
    let segments: Vec<Option<u16>> = (0..pb3.code.len()).map(|pc| pb3.segment_of(pc)).collect();
    assert_eq!(
        segments,
        [Some(1), Some(1), Some(1), Some(2), Some(2), Some(2)]
    );
    let plain = clean(&[("plain.awl", PLAIN_DE)], &[]);
    assert_eq!(block(&plain, "PB 3").segment_of(0), None);
}

#[test]
fn each_listing_element_alone() {
    let cases = [
        // Block information after the header, also without a blank in the header.
        "PB3   LAE=4\n      BE\n",
        "PB 3  LEN=4  BST=2\n      BE\n",
        // A segment heading with and without its address, in each word.
        "PB 3\nSEGMENT 1\n      BE\n",
        "PB 3\nNETZWERK 1   0000\n      BE\n",
        "PB 3\nNETWORK 1    0000\n      BE\n",
        // Statement addresses: a number, then (in a listing) a word of hex digits.
        "PB 3\n0000  :NOP 0\n000F  :NOP 0\nA01F  :NOP 0\n      BE\n",
        // `***` with and without the colon and its address.
        "PB 3\n0000 :NOP 0\n0001 :***\n***\n:***\n      BE\n",
        // A label after the address.
        "PB 3\n0000 M001 :NOP 0\n      BE\n",
        // A label between the address's colon and its own (`0037: M004: L DW12`).
        "PB 3\n0000: M001: NOP 0\n      BE\n",
        "PB 3\n0000 :M001 :NOP 0\n      BE\n",
        "PB 3\n0000 :NOP 0\n001F :M001 :NOP 0\n      BE\n",
    ];
    for case in cases {
        let built = build(&[("case.awl", case)], &[]);
        assert!(
            built.diagnostics.is_empty(),
            "{case}\n{:#?}",
            built.diagnostics
        );
    }
}

#[test]
fn a_hex_word_is_a_label_until_the_file_shows_addresses() {
    // `BEEF :` could be a label; in a plain file it is one.
    let program = clean(
        &[("plain.awl", "FB 1\nNAME :X\n      SPA =BEEF\nBEEF :BE\n")],
        &[],
    );
    assert_eq!(block(&program, "FB 1").code.len(), 2);
}

#[test]
fn fb_calls_and_parameters_in_a_listing() {
    let listing = "\
OB 1                                  LAE=9
SEGMENT 1                             0000
0000      :SPA  FB   5
0001 NAME :MOTOR
0002 EIN  :E    0.0
0003 AUS  :A    4.0
0004      :BE
FB 5                                  LAE=12
SEGMENT 1                             0000
NAME :MOTOR
BEZ  :EIN  E BI
BEZ  :AUS  A BI
0000      :U    =EIN
0001      :=    =AUS
0002      :BE
";
    let program = clean(&[("fb.awl", listing)], &[]);
    assert_eq!(program.param_lists[0].len(), 2);
}

#[test]
fn a_file_may_mix_both_forms() {
    let mixed = "OB 1\n      JU PB 3\n      BE\n".to_string() + LISTING_EN;
    let program = clean(&[("mixed.awl", &mixed)], &[]);
    assert_eq!(block(&program, "PB 3").code.len(), 6);
}

const SYMBOLS_DE: &str = "\
; Zuordnungsliste
E 1.0     START     Taster Start
E 1.1     FREIGABE
A 4.0     MOTOR     Schuetz
MW 10     SOLL
PB 3      FUELLEN   Fuellen
";

#[test]
fn symbols_stand_for_their_operands() {
    let symbolic = "OB 1\n      SPA -FUELLEN\n      BE\nPB 3\n      U  -START\n      U  -FREIGABE\n      =  -MOTOR\n      L  KF +5\nM001 :T  -SOLL\n      BE\n";
    let program = clean(&[("sym.awl", symbolic)], &[("plant.seq", SYMBOLS_DE)]);
    let plain = clean(
        &[(
            "plain.awl",
            &("OB 1\n      SPA PB 3\n      BE\n".to_string() + PLAIN_DE),
        )],
        &[],
    );
    assert_eq!(code(&program, "PB 3"), code(&plain, "PB 3"));
    assert_eq!(code(&program, "OB 1"), code(&plain, "OB 1"));
    assert_eq!(program.symbols.name_of("E 1.0"), Some("START"));
    assert_eq!(program.symbols.name_of("I 1.0"), Some("START"));
    assert_eq!(program.symbols.decorate("PB 3"), "PB 3 (-FUELLEN)");
}

#[test]
fn symbols_in_an_english_csv_list() {
    let csv = "I 1.0,START,\"Start, green\"\nQ 4.0,MOTOR,\n";
    let program = clean(
        &[(
            "sym.awl",
            "PB 3\n      A  -START\n      =  -MOTOR\n      BE\n",
        )],
        &[("plant.csv", csv)],
    );
    let plain = clean(
        &[(
            "plain.awl",
            "PB 3\n      A  I 1.0\n      =  Q 4.0\n      BE\n",
        )],
        &[],
    );
    assert_eq!(code(&program, "PB 3"), code(&plain, "PB 3"));
}

/// Writes `files` as a listing with `awl dump --listing`'s writer and builds it again.
fn round_trip(files: &[(&str, &str)], symbols: &[(&str, &str)]) {
    round_trip_on(files, symbols, "sinumerik-840c");
}

fn round_trip_on(files: &[(&str, &str)], symbols: &[(&str, &str)], cpu: &str) {
    let first = build_on(files, symbols, cpu);
    assert!(!first.has_errors(), "{:#?}", first.diagnostics);
    let listing = awl::dump::listing::listing(&first);
    let again = build_on(&[("listing.awl", &listing)], symbols, cpu);
    assert!(!again.has_errors(), "{listing}\n{:#?}", again.diagnostics);
    let (a, b) = (&first.compiled.program, &again.compiled.program);
    assert_eq!(a.blocks.len(), b.blocks.len());
    for block in &a.blocks {
        let name = block.id.to_string();
        assert_eq!(block.code, code(b, &name), "{name}\n{listing}");
        assert_eq!(
            block.elapsed,
            self::block(b, &name).elapsed,
            "{name}: op times"
        );
    }
    let words = |program: &Program| -> Vec<Vec<u16>> {
        program
            .data_blocks
            .iter()
            .map(|db| db.words.clone())
            .collect()
    };
    assert_eq!(words(a), words(b));
    assert_eq!(a.param_lists.len(), b.param_lists.len());
}

#[test]
fn the_listing_of_every_sample_parses_back_to_the_same_bytecode() {
    let mut count = 0;
    for entry in std::fs::read_dir("programs").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|ext| ext != "awl") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.to_string_lossy().to_string();
        let symbols: Vec<(String, String)> = ["seq", "csv"]
            .iter()
            .map(|ext| path.with_extension(ext))
            .filter(|symbols| symbols.exists())
            .map(|symbols| {
                let text = std::fs::read_to_string(&symbols).unwrap();
                (symbols.to_string_lossy().to_string(), text)
            })
            .collect();
        let symbols: Vec<(&str, &str)> = symbols
            .iter()
            .map(|(name, text)| (name.as_str(), text.as_str()))
            .collect();
        // A sample written for another CPU names it in its scenario (`cpu = "s5-115u"`).
        let scenario = std::fs::read_to_string(path.with_extension("toml")).unwrap_or_default();
        let cpu = scenario
            .lines()
            .find_map(|line| line.strip_prefix("cpu = \""))
            .and_then(|rest| rest.strip_suffix('"'))
            .unwrap_or("sinumerik-840c");
        round_trip_on(&[(&name, &text)], &symbols, cpu);
        count += 1;
    }
    assert!(count >= 17, "{count} samples");
}

#[test]
fn the_listing_of_a_listing_is_stable() {
    round_trip(&[("de.awl", LISTING_DE)], &[]);
    let first = build(&[("en.awl", LISTING_EN)], &[]);
    let once = awl::dump::listing::listing(&first);
    let second = build(&[("once.awl", &once)], &[]);
    assert_eq!(awl::dump::listing::listing(&second), once);
}

#[test]
fn mnemonics_of_a_listing_are_detected() {
    let built = build(&[("de.awl", LISTING_DE)], &[]);
    assert_eq!(built.mnemonics, [MnemonicSet::German]);
    let built = build(&[("en.awl", LISTING_EN)], &[]);
    assert_eq!(built.mnemonics, [MnemonicSet::English]);
}

/// `awl dump --listing` numbers statements by word address as the PG does: a constant after
/// `L` (other than `KB`) takes a word of its own, a 32-bit one two; an FB call takes a jump word
/// (the `NAME :` line) and a word per parameter; `SU` on a data bit takes two words; a function
/// block's statements start after its description (jump, name, three words a parameter); the
/// header carries the block's length with its five-word header.
#[test]
fn statements_are_numbered_by_their_word_address() {
    let source = "\
OB 1
      L  KF +20
      L  KB 7
      T  FW 10
      JU FB 5
NAME :MOTOR
EIN  :I 0.0
AUS  :Q 4.0
      L  DH 0000FFFF
      BE
FB 5
NAME :MOTOR
DES  :EIN  I BI
DES  :AUS  Q BI
      A  =EIN
      SU D 1.0
      =  =AUS
      BE
";
    let expected = "\
OB 1                                  LEN=17
SEGMENT 1                             0000
0000      :L  KF +20
0002      :L  KB 7
0003      :T  FW 10
0004      :JU FB 5
0005 NAME :MOTOR
0006 EIN  :I 0.0
0007 AUS  :Q 4.0
0008      :L  DH 0000FFFF
000B      :BE
FB 5                                  LEN=21
SEGMENT 1                             0000
NAME :MOTOR
DES  :EIN  I BI
DES  :AUS  Q BI
000B      :A  =EIN
000C      :SU D 1.0
000E      :=  =AUS
000F      :BE
";
    let built = build(&[("addresses.awl", source)], &[]);
    assert!(!built.has_errors(), "{:#?}", built.diagnostics);
    assert_eq!(awl::dump::listing::listing(&built), expected);
    round_trip(&[("addresses.awl", source)], &[]);
    let again = build(&[("listing.awl", expected)], &[]);
    assert_eq!(awl::dump::listing::listing(&again), expected);
}

/// Each constant format after `L` in words: `KB` rides in the operation word, the 16-bit
/// formats take one more word, `KG` and `DH` two more.
#[test]
fn every_constant_format_has_its_length() {
    let formats = [
        ("KB 10", 1),
        ("KF -100", 2),
        ("KH 00FF", 2),
        ("KM 0000000011110000", 2),
        ("KY 12,34", 2),
        ("KT 050.1", 2),
        ("KC 500", 2),
        ("KS 'AB'", 2),
        ("KG +1234567+02", 3),
        ("DH 0000FFFF", 3),
    ];
    for (constant, words) in formats {
        let source = format!("PB 1\n      L  {constant}\n      BE\n");
        let built = build(&[("constant.awl", &source)], &[]);
        assert!(!built.has_errors(), "{constant}: {:#?}", built.diagnostics);
        let listing = awl::dump::listing::listing(&built);
        assert!(
            listing.contains(&format!("{words:04X}      :BE")),
            "{constant} should take {words} words:\n{listing}"
        );
    }
}

/// A segment ends with `***`, a word of its own, and the next heading carries the address
/// where its segment starts; a heading's comment stays.
#[test]
fn segment_ends_take_a_word_and_headings_keep_their_comments() {
    let source = "PB 3\nSEGMENT 1 ; filling\n      L  KF +1\nSEGMENT 2\n      BE\n";
    let built = build(&[("segments.awl", source)], &[]);
    let listing = awl::dump::listing::listing(&built);
    assert_eq!(
        listing,
        "\
PB 3                                  LEN=9
SEGMENT 1                             0000  ; filling
0000      :L  KF +1
0002      :***
SEGMENT 2                             0003
0003      :BE
"
    );
}

/// The samples written as PG listings carry the addresses and lengths the PG would print:
/// `awl dump --listing` gives each of them back unchanged.
#[test]
fn the_sample_listings_are_true_to_the_pg() {
    for (program, symbols) in [
        ("programs/filling_de.awl", "programs/filling_de.seq"),
        ("programs/press_en.awl", "programs/press_en.csv"),
    ] {
        let text = std::fs::read_to_string(program).unwrap();
        let list = std::fs::read_to_string(symbols).unwrap();
        let built = build(&[(program, &text)], &[(symbols, &list)]);
        assert!(!built.has_errors(), "{:#?}", built.diagnostics);
        assert_eq!(awl::dump::listing::listing(&built), text, "{program}");
    }
}

#[test]
fn a_label_after_the_address_s_colon_is_the_statement_s_label() {
    let pg = "FB 1\nNAME :X\n0000 :A I 0.0\n0001 :JC =M004\n0002 :L KF +1\n\
              0037: M004: L DW12\n0038 :M005 :T DW 13\n0039 :JU =M005\n003A :BE\n";
    let plain = "FB 1\nNAME :X\n      A I 0.0\n      JC =M004\n      L KF +1\n\
                 M004: L DW12\nM005: T DW 13\n      JU =M005\n      BE\n";
    let listing = clean(&[("pg.awl", pg)], &[]);
    let written = clean(&[("plain.awl", plain)], &[]);
    assert_eq!(code(&listing, "FB 1"), code(&written, "FB 1"));
}
