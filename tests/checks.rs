//! The compiler's static checks and lowering, case by case: operand ranges per area and CPU,
//! plain-number ranges, which operand each operation takes, FB parameter checks, execution
//! times and data block images.

mod common;

use awl::diagnostics::{SourceDiagnostic, render_plain, report};
use awl::frontend::{self, Frontend};
use awl::profile;
use awl::program_files;
use awl::source::Files;

fn build(cpu: &str, source: &str) -> Frontend {
    frontend::build_text("check.awl", source, profile::find(cpu).unwrap())
}

/// The rendered diagnostics of a program.
fn rendered(cpu: &str, source: &str) -> String {
    let built = build(cpu, source);
    built
        .diagnostics
        .iter()
        .map(|d| render_plain(&report(&built.sources, d)))
        .collect::<Vec<_>>()
        .join("\n")
}

fn codes(cpu: &str, source: &str) -> Vec<String> {
    build(cpu, source)
        .diagnostics
        .iter()
        .map(|d| miette::Diagnostic::code(d).unwrap().to_string())
        .collect()
}

fn in_pb(statement: &str) -> String {
    format!("PB 1\n      {statement}\n      BE\n")
}

fn in_fb(body: &str) -> String {
    format!("OB 1\n      JU FB 1\nNAME :X\n      BE\nFB 1\nNAME :X\n{body}      BE\n")
}

/// Each area's highest address is accepted and the next one is out of range, with the range
/// the CPU allows in the message.
#[test]
fn operand_ranges_per_area_and_cpu() {
    let cases = [
        ("sinumerik-840c", "A  I", "127.7", "128.0", "I 0…127"),
        ("sinumerik-840c", "=  Q", "127.0", "128.0", "Q 0…127"),
        ("sinumerik-840c", "L  IB", "127", "128", "IB 0…127"),
        ("sinumerik-840c", "T  QB", "127", "128", "QB 0…127"),
        ("sinumerik-840c", "L  IW", "126", "127", "IW 0…126"),
        ("sinumerik-840c", "T  QW", "126", "127", "QW 0…126"),
        ("sinumerik-840c", "A  F", "255.0", "256.0", "F 0…255"),
        ("sinumerik-840c", "L  FY", "255", "256", "FY 0…255"),
        ("sinumerik-840c", "L  FW", "254", "255", "FW 0…254"),
        ("sinumerik-840c", "L  FD", "252", "253", "FD 0…252"),
        ("sinumerik-840c", "A  T", "255", "256", "T 0…255"),
        ("sinumerik-840c", "A  C", "255", "256", "C 0…255"),
        ("sinumerik-840c", "L  DW", "2047", "2048", "DW 0…2047"),
        ("sinumerik-840c", "L  DL", "2047", "2048", "DL 0…2047"),
        ("sinumerik-840c", "L  DR", "2047", "2048", "DR 0…2047"),
        ("sinumerik-840c", "A  D", "2047.0", "2048.0", "D 0…2047"),
        ("sinumerik-840c", "L  DD", "2046", "2047", "DD 0…2046"),
        ("sinumerik-840c", "L  PY", "255", "256", "PY 0…255"),
        ("sinumerik-840c", "L  PW", "254", "255", "PW 0…254"),
        ("sinumerik-840c", "L  OY", "255", "256", "OY 0…255"),
        ("sinumerik-840c", "L  OW", "254", "255", "OW 0…254"),
        ("s5-95f", "A  T", "127", "128", "T 0…127"),
        ("s5-95f", "A  C", "127", "128", "C 0…127"),
        ("s5-95f", "L  DW", "255", "256", "DW 0…255"),
        ("speed7", "A  F", "8191.0", "8192.0", "F 0…8191"),
        ("speed7", "L  IW", "254", "255", "IW 0…254"),
        ("speed7", "A  T", "511", "512", "T 0…511"),
        ("speed7", "A  C", "511", "512", "C 0…511"),
    ];
    for (cpu, op, highest, beyond, range) in cases {
        let ok = in_pb(&format!("{op} {highest}"));
        assert!(codes(cpu, &ok).is_empty(), "{cpu}: {op} {highest}");
        let bad = in_pb(&format!("{op} {beyond}"));
        let text = rendered(cpu, &bad);
        assert_eq!(
            codes(cpu, &bad),
            ["awl::check::operand_range"],
            "{cpu}: {op} {beyond}"
        );
        assert!(text.contains(range), "{cpu}: {op} {beyond}: {text}");
    }
    let text = rendered("sinumerik-840c", &in_pb("A  I 1.8"));
    assert!(text.contains("bits 0…7"), "{text}");
    let text = rendered("sinumerik-840c", &in_pb("A  D 1.16"));
    assert!(text.contains("bits 0…15"), "{text}");
    assert!(codes("sinumerik-840c", &in_pb("A  D 1.15")).is_empty());
}

/// Operations on plain numbers name their range; the highest number is accepted.
#[test]
fn plain_number_ranges() {
    for (ok, bad, range) in [
        ("NOP 1", "NOP 2", "NOP 0 or NOP 1"),
        ("BLD 255", "BLD 256", "0…255"),
        ("I  255", "I  256", "0…255"),
        ("D  255", "D  256", "0…255"),
        ("SLW 15", "SLW 16", "0…15"),
        ("SRW 15", "SRW 16", "0…15"),
    ] {
        assert!(
            codes("sinumerik-840c", &in_fb(&format!("      {ok}\n"))).is_empty(),
            "{ok}"
        );
        let source = in_fb(&format!("      {bad}\n"));
        assert_eq!(
            codes("sinumerik-840c", &source),
            ["awl::check::operand_range"]
        );
        let text = rendered("sinumerik-840c", &source);
        assert!(text.contains(range), "{bad}: {text}");
    }
}

/// Operations take only the operand kinds they are defined for.
#[test]
fn operations_reject_operands_of_the_wrong_kind() {
    for statement in [
        "SP C 1", "SE C 1", "SD C 1", "SS C 1", "SF C 1", "CU T 1", "CD T 1", "LC F 1.0",
        "FR F 1.0", "L  Q 4.0", "T  T 1", "T  C 1",
    ] {
        assert_eq!(
            codes("sinumerik-840c", &in_pb(statement)),
            ["awl::check::operand_not_allowed"],
            "{statement}"
        );
    }
    for statement in [
        "SP T 1", "CU C 1", "CD C 1", "LC T 1", "LC C 1", "FR T 1", "FR C 1", "L  T 1", "L  C 1",
        "R  T 1", "R  C 1", "S  C 1", "O  T 1", "ON C 1", "A  D 1.0", "=  D 1.0", "S  D 1.0",
        "R  D 1.0", "L  PW 2", "T  OY 3", "L  OW 4",
    ] {
        assert!(
            codes("sinumerik-840c", &in_pb(statement)).is_empty(),
            "{statement}"
        );
    }
}

/// The help of a wrong operand says what to write instead.
#[test]
fn operand_help_fits_the_mistake() {
    let text = rendered("sinumerik-840c", &in_pb("JU DB 5"));
    assert!(
        text.contains("data blocks are opened, not called"),
        "{text}"
    );
    let text = rendered(
        "sinumerik-840c",
        &in_fb("      JP PB 3\n").replace("      BE\nFB 1", "      BE\nPB 3\n      BE\nFB 1"),
    );
    assert!(text.contains("jumps to a label in this FB"), "{text}");
    let text = rendered("sinumerik-840c", &in_pb("L  Q 4.0"));
    assert!(text.contains("for example `L FW 10`"), "{text}");
    let text = rendered("sinumerik-840c", &in_pb("+F T 1"));
    assert!(
        !text.contains("for example"),
        "no example for an operation without operand"
    );
}

/// A `DO` costs what loading its word and the modified operation cost; a formal operand what
/// the substituted operation costs.
#[test]
fn execution_times_of_indirect_and_formal_operations() {
    let cpu = profile::find("sinumerik-840c").unwrap();
    let built = build(
        "sinumerik-840c",
        "FB 1\nNAME :X\nDES  :W I W\n      DO FW 0\n      L  DW 0\n      L  =W\n      BE\n",
    );
    let block = &built.compiled.program.blocks[0];
    let times = cpu.timings;
    assert_eq!(block.cost(0), u64::from(times.load_word + times.other));
    assert_eq!(block.cost(2), u64::from(times.load_word), "L =W costs L IW");
}

/// Data blocks: wide constants take two words, high word first; character strings fill
/// words two characters each, and the next word follows them.
#[test]
fn data_block_images() {
    let built = build(
        "sinumerik-840c",
        "DB 5\n  0: DH 12345678\n  2: KS 'ABCDE'\n     KF +7\n",
    );
    let words = &built.compiled.program.data_blocks[0].words;
    assert_eq!(
        words,
        &[0x1234, 0x5678, 0x4142, 0x4344, 0x4520, 7],
        "DH high word first; KS two characters a word"
    );
}

/// A wide constant without a word number moves the next unnumbered word on by two, so the next
/// value does not overwrite its low word.
#[test]
fn an_unnumbered_wide_constant_takes_two_words() {
    let built = build(
        "sinumerik-840c",
        "DB 5\n     DH 12345678\n     KF +7\n     KG +5000000+01\n     KF +8\n",
    );
    let words = &built.compiled.program.data_blocks[0].words;
    assert_eq!(words, &[0x1234, 0x5678, 7, 0x0350, 0x0000, 8]);
}

fn call(params: &str) -> String {
    format!(
        "OB 1\n      JU FB 2\nNAME :TWO\n{params}      BE\nFB 2\nNAME :TWO\nDES  :EIN I BI\nDES  :BYT I BY\n      A  =EIN\n      L  =BYT\n      T  FY 9\n      BE\n"
    )
}

#[test]
fn fb_call_parameters_are_checked() {
    assert!(codes("sinumerik-840c", &call("EIN  :I 0.0\nBYT  :IB 2\n")).is_empty());
    for byte in ["QB 3", "FY 4", "DL 5", "DR 5", "PY 6"] {
        let source = call(&format!("EIN  :I 0.0\nBYT  :{byte}\n"));
        assert!(codes("sinumerik-840c", &source).is_empty(), "{byte}");
    }
    assert_eq!(
        codes("sinumerik-840c", &call("EIN  :I 0.0\nBYT  :IW 2\n")),
        ["awl::check::param_mismatch"]
    );
    // A parameter given twice: the count is wrong although none is missing.
    assert_eq!(
        codes(
            "sinumerik-840c",
            &call("EIN  :I 0.0\nEIN  :I 0.1\nBYT  :IB 2\n")
        ),
        ["awl::check::param_count"]
    );
}

/// An FB passes its own formal operand on only to a parameter of the same kind and format.
#[test]
fn formal_operands_passed_on_must_match() {
    let nested = |outer: &str| {
        format!(
            "OB 1\n      JU FB 1\nNAME :ONE\nX    :I 0.0\n      BE\nFB 1\nNAME :ONE\nDES  :X {outer}\n      JU FB 2\nNAME :TWO\nEIN  :=X\n      BE\nFB 2\nNAME :TWO\nDES  :EIN I BI\n      A  =EIN\n      =  F 1.0\n      BE\n"
        )
    };
    assert!(codes("sinumerik-840c", &nested("I BI")).is_empty());
    let wrong_format = nested("I W").replace("X    :I 0.0", "X    :IW 0");
    assert_eq!(
        codes("sinumerik-840c", &wrong_format),
        ["awl::check::param_mismatch"]
    );
    let wrong_kind = nested("Q BI").replace("X    :I 0.0", "X    :Q 4.0");
    assert_eq!(
        codes("sinumerik-840c", &wrong_kind),
        ["awl::check::param_mismatch"]
    );
}

/// A mismatch names the declaration in the file's own words (`D KC` / `D KZ`).
#[test]
fn declarations_are_described_in_the_files_set() {
    let english = "OB 1\n      JU FB 3\nNAME :N\nZ    :I 0.0\n      BE\nFB 3\nNAME :N\nDES  :Z D KC\n      L  =Z\n      BE\n";
    assert!(rendered("sinumerik-840c", english).contains("expected D KC"));
    let german = "OB 1\n      SPA FB 3\nNAME :N\nZ    :E 0.0\n      BE\nFB 3\nNAME :N\nBEZ  :Z D KZ\n      L  =Z\n      BE\n";
    assert!(rendered("sinumerik-840c", german).contains("expected D KZ"));
}

/// `C =DAT` opens the data block a B parameter names.
#[test]
fn block_parameters_open_data_blocks() {
    let source = "OB 1\n      JU FB 4\nNAME :OPEN\nDAT  :DB 7\n      BE\nFB 4\nNAME :OPEN\nDES  :DAT B\n      C  =DAT\n      L  DW 1\n      T  FW 0\n      BE\nDB 7\n  0: KF +1\n  1: KF +77\n";
    let (cpu, outcome) = common::run_once(source);
    assert!(outcome.stop.is_none(), "{:?}", outcome.stop);
    assert_eq!(common::fw(&cpu, 0), 77);
}

/// A diagnostic of the front end is either a parse or a check error, never both.
#[test]
fn diagnostics_keep_their_stage() {
    let built = build("sinumerik-840c", &in_pb("JUU PB 2"));
    assert!(matches!(
        built.diagnostics.as_slice(),
        [SourceDiagnostic::Parse(_)]
    ));
}

/// An unknown parameter name far from every declared one lists the declared names; `C` with
/// a block that is no DB says what `C` opens.
#[test]
fn help_lists_declared_parameters_and_what_c_opens() {
    let program = "OB 1\n      JU FB 1\nNAME :X\nSPEED :I 0.0\n      BE\nFB 1\nNAME :X\nDES  :IN1 I BI\nDES  :IN2 I BI\n      BE\n";
    assert!(
        rendered("sinumerik-840c", program).contains("FB 1 declares: IN1, IN2"),
        "{}",
        rendered("sinumerik-840c", program)
    );
    let open = format!("{}PB 3\n      BE\n", in_pb("C  PB 3"));
    assert!(
        rendered("sinumerik-840c", &open).contains("opens a data block"),
        "{}",
        rendered("sinumerik-840c", &open)
    );
}

/// The profiles `awl check` names without `--cpu`, compiled for each profile one by one: what
/// the single compile's needs must give.
fn compiled_per_profile(
    sources: &awl::source::SourceSet,
    symbols: &[awl::source::SourceFile],
) -> Vec<&'static str> {
    profile::PROFILES
        .iter()
        .filter(|cpu| {
            !frontend::build_with_symbols(
                sources.clone(),
                symbols.to_vec(),
                frontend::Language::default(),
                cpu,
            )
            .has_errors()
        })
        .map(|cpu| cpu.name)
        .collect()
}

/// The profiles named from one compile for the default profile.
fn from_one_compile(
    sources: &awl::source::SourceSet,
    symbols: &[awl::source::SourceFile],
) -> Vec<&'static str> {
    let language = frontend::Language::default();
    let cpu = frontend::default_profile(sources, language);
    let built = frontend::build_with_symbols(sources.clone(), symbols.to_vec(), language, cpu);
    frontend::profiles_without_errors(&built, sources, symbols, language)
}

fn one_file(text: &str) -> awl::source::SourceSet {
    let mut sources = awl::source::SourceSet::default();
    sources.add(awl::source::SourceFile::new("runs_on.awl", text));
    sources
}

#[test]
fn one_compile_names_the_profiles_each_compile_would() {
    let mut files: Vec<std::path::PathBuf> = Vec::new();
    let mut dirs = vec![std::path::PathBuf::from("programs"), "tests".into()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|ext| ext == "awl") {
                files.push(path);
            }
        }
    }
    assert!(files.len() > 50, "{} program files", files.len());
    for path in files {
        // The binary files that test the reader are not programs.
        let Ok(read) = program_files::read_program(&Files::Disk, std::slice::from_ref(&path), &[])
        else {
            continue;
        };
        let sources = read.sources;
        assert_eq!(
            from_one_compile(&sources, &[]),
            compiled_per_profile(&sources, &[]),
            "{}",
            path.display()
        );
    }
}

#[test]
fn one_compile_names_the_profiles_of_each_need() {
    let programs = [
        // Each need met by some profiles only, alone and behind another need's error.
        in_pb("      XG\n"),
        in_pb("      ENT\n"),
        in_pb("      L  FW 300\n"),
        in_pb("      SD T 200\n"),
        in_pb("      L  FW 300\n      DED\n"),
        in_pb("      L  PW 300\n      XG\n"),
        in_pb("      JU FB 240\n"),
        in_pb("      JU FB 250\n"),
        in_pb("      JU OB 160\n"),
        in_pb("      JU OB 251\n"),
        in_pb("      JU FB 99\n"),
        in_pb(&"      A(\n".repeat(8)),
        "FX 1\n      BE\nOB 1\n      BE\n".to_string(),
        "DX 1\n  0: KF +1\nOB 1\n      BE\n".to_string(),
        // A need hides another error of its statement on the default profile.
        in_pb("      L  FW 8000\n      DO FW 8000\n"),
        in_pb("      XG FW 10\n"),
        in_pb("      L  T 200.0\n"),
    ];
    for program in programs {
        let sources = one_file(&program);
        assert_eq!(
            from_one_compile(&sources, &[]),
            compiled_per_profile(&sources, &[]),
            "{program}"
        );
    }
    let symbols = [awl::source::SourceFile::new(
        "symbols.seq",
        "F 200.0  -HIGH\nT 200  -LATE\n",
    )];
    let sources = one_file(&in_pb("      A  -HIGH\n"));
    assert_eq!(
        from_one_compile(&sources, &symbols),
        compiled_per_profile(&sources, &symbols)
    );
}
