//! The supplementary operations added for real STEP 5 texts: the formal-operand operations
//! (`RB RD LW LD`, `DO =`/`B =`, `SU RU TB TBN`/`P PN` on a formal operand), `ADD KB/KF/DH`,
//! and the system and register operations that parse but stop the CPU when run.

mod common;

use awl::compiler::CheckError;
use awl::diagnostics::SourceDiagnostic;
use awl::vm::stop::{StopCause, StopDetail};
use common::*;

/// OB 1 calls FB 1 with these actual-parameter lines; FB 1 declares these parameters.
fn called_fb(actuals: &str, decls: &str, body: &str) -> String {
    format!(
        "OB 1\n      JU FB 1\nNAME :T\n{actuals}      BE\nFB 1\nNAME :T\n{decls}{body}\n      BE\nPB 2\n      L  KF +7\n      T  FW 30\n      BE\nDB 5\n 0: KF +55\n"
    )
}

fn check_errors(source: &str) -> Vec<SourceDiagnostic> {
    let built = awl::frontend::build_text(
        "ops.awl",
        source,
        awl::profile::find("sinumerik-840c").unwrap(),
    );
    built.diagnostics
}

#[test]
fn rb_and_rd_reset_the_bit_and_the_timer_their_parameters_name() {
    let actuals = "BIT  :F 0.1\nTIM  :T 3\n";
    let decls = "DES  :BIT  I BI\nDES  :TIM  T\n";
    // F 0.1 set, then RB =BIT with RLO 1 resets it; T 3 started, then RD =TIM resets it, so
    // its bit reads 0 although an on-delay with KT 010.2 still would be running.
    let body = "      S  F 0.1\n      RB =BIT\n      A  F 0.1\n      =  F 1.0\n      L  KT 010.2\n      ON F 9.0\n      SE =TIM\n      ON F 9.0\n      RD =TIM\n      L  =TIM\n      T  FW 20\n      ON F 9.0\n      =  F 1.1";
    let (cpu, _) = run_once(&called_fb(actuals, decls, body));
    assert!(!flag(&cpu, 0, 1), "RB =BIT reset F 0.1");
    assert!(!flag(&cpu, 1, 0));
    assert_eq!(fw(&cpu, 20), 0, "RD =TIM reset T 3: its time value is 0");
    assert!(flag(&cpu, 1, 1));
}

#[test]
fn rb_does_nothing_when_the_rlo_is_0() {
    let body = "      S  F 0.1\n      AN F 0.1\n      RB =BIT";
    let (cpu, _) = run_once(&called_fb("BIT  :F 0.1\n", "DES  :BIT  I BI\n", body));
    assert!(flag(&cpu, 0, 1));
}

#[test]
fn lw_and_ld_load_the_constant_of_a_d_parameter() {
    let actuals = "HEX  :KH 1234\nNUM  :KF -20\n";
    let decls = "DES  :HEX  D KH\nDES  :NUM  D KF\n";
    let body = "      LW =HEX\n      T  FW 10\n      LD =NUM\n      T  FW 12\n      LW =NUM\n      LD =HEX\n      -F\n      T  FW 14";
    let (cpu, _) = run_once(&called_fb(actuals, decls, body));
    assert_eq!(fw(&cpu, 10), 0x1234);
    assert_eq!(fw(&cpu, 12), -20);
    // LW moved ACCU 1 to ACCU 2 as L does: -20 - 0x1234.
    assert_eq!(fw(&cpu, 14), -20 - 0x1234);
}

#[test]
fn do_processes_a_block_parameter_in_both_sets() {
    let english = called_fb(
        "DAT  :DB 5\nPRG  :PB 2\n",
        "DES  :DAT  B\nDES  :PRG  B\n",
        "      DO =DAT\n      L  DW 0\n      T  FW 10\n      DO =PRG",
    );
    let (cpu, _) = run_once(&english);
    assert_eq!(fw(&cpu, 10), 55, "DO =DAT opened DB 5");
    assert_eq!(fw(&cpu, 30), 7, "DO =PRG called PB 2");
    // In a German parameter line `PB 2` reads as the peripheral byte: the German text uses an SB.
    let german = "OB 1\n      SPA FB 1\nNAME :T\nDAT  :DB 5\nPRG  :SB 2\n      BE\nFB 1\nNAME :T\nBEZ  :DAT  B\nBEZ  :PRG  B\n      B  =DAT\n      L  DW 0\n      T  MW 10\n      B  =PRG\n      BE\nSB 2\n      L  KF +7\n      T  MW 30\n      BE\nDB 5\n 0: KF +55\n";
    let (cpu, _) = run_once(german);
    assert_eq!(fw(&cpu, 10), 55);
    assert_eq!(fw(&cpu, 30), 7);
}

#[test]
fn do_on_a_parameter_passed_on_from_a_calling_fb_runs_at_run_time() {
    // FB 2 passes its own parameter on, so FB 1 is not specialised: the VM resolves `DO =`.
    let source = "OB 1\n      JU FB 2\nNAME :OUTER\nBLK  :PB 2\n      BE\nFB 2\nNAME :OUTER\nDES  :BLK  B\n      JU FB 1\nNAME :T\nPRG  :=BLK\n      BE\nFB 1\nNAME :T\nDES  :PRG  B\n      DO =PRG\n      BE\nPB 2\n      L  KF +7\n      T  FW 30\n      BE\n";
    let (cpu, outcome) = run_once(source);
    assert!(outcome.stop.is_none(), "{:?}", outcome.stop);
    assert_eq!(fw(&cpu, 30), 7);
}

#[test]
fn german_formal_bit_operations_set_reset_and_test() {
    let source = "OB 1\n      SPA FB 1\nNAME :T\nBIT  :M 0.1\n      BE\nFB 1\nNAME :T\nBEZ  :BIT  E BI\n      SU =BIT\n      P  =BIT\n      =  M 1.0\n      RU =BIT\n      PN =BIT\n      =  M 1.1\n      P  =BIT\n      =  M 1.2\n      BE\n";
    let (cpu, _) = run_once(source);
    assert!(flag(&cpu, 1, 0), "P =BIT after SU =BIT");
    assert!(flag(&cpu, 1, 1), "PN =BIT after RU =BIT");
    assert!(!flag(&cpu, 1, 2));
    assert!(!flag(&cpu, 0, 1));
}

#[test]
fn formal_operations_reject_parameters_of_the_wrong_kind() {
    for (decl, body) in [
        ("DES  :TIM  T\n", "      RB =TIM"),
        ("DES  :BIT  I BI\n", "      RD =BIT"),
        ("DES  :BIT  I BI\n", "      LW =BIT"),
        ("DES  :WRD  I W\n", "      DO =WRD"),
    ] {
        let source = format!("FB 1\nNAME :T\n{decl}{body}\n      BE\n");
        let errors = check_errors(&source);
        assert!(
            errors.iter().any(|d| matches!(
                d,
                SourceDiagnostic::Check(CheckError::OperandNotAllowed { .. })
            )),
            "{body}: {errors:#?}"
        );
    }
}

#[test]
fn formal_operations_take_only_a_formal_operand() {
    let errors = check_errors("FB 1\nNAME :T\n      RB F 0.1\n      BE\n");
    assert!(
        errors.iter().any(|d| matches!(
            d,
            SourceDiagnostic::Check(CheckError::OperandNotAllowed { .. })
        )),
        "{errors:#?}"
    );
}

#[test]
fn formal_operations_outside_an_fb_are_supplementary_errors() {
    for body in [
        "      RB =BIT",
        "      LW =KON",
        "      ADD KF +1",
        "      TNB 4",
    ] {
        let errors = check_errors(&format!("PB 1\n{body}\n      BE\n"));
        assert!(
            errors
                .iter()
                .any(|d| matches!(d, SourceDiagnostic::Check(CheckError::Supplementary { .. }))),
            "{body}: {errors:#?}"
        );
    }
}

fn fb(body: &str) -> String {
    format!("OB 1\n      JU FB 1\nNAME :T\n      BE\nFB 1\nNAME :T\n{body}\n      BE\n")
}

#[test]
fn add_adds_to_the_low_word_or_all_of_accu_1_and_leaves_the_status() {
    let body = "      L  KF +100\n      ADD KF -3\n      T  FW 0\n      L  KF +32767\n      ADD KB 1\n      T  FW 2\n      L  DH 0001FFFF\n      ADD DH 00000001\n      T  FD 4\n      L  DH 0001FFFF\n      ADD KF +1\n      T  FD 8\n      L  KF +5\n      L  KF +6\n      !=F\n      L  KF -1\n      ADD KF +1\n      =  F 20.0\n      JZ =ZERO\n      L  KF +1\n      T  FW 40\nZERO :NOP 0";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 97);
    assert_eq!(fw(&cpu, 2), i16::MIN, "16-bit addition wraps");
    assert_eq!(fd(&cpu, 4), 0x0002_0000, "DH adds all 32 bits");
    assert_eq!(fd(&cpu, 8), 0x0001_0000, "KF leaves ACCU 1-H alone");
    assert!(
        !flag(&cpu, 20, 0),
        "the RLO of the comparison (5 = 6: 0) stays"
    );
    assert_eq!(
        fw(&cpu, 40),
        1,
        "CC 1/CC 0 stay those of 5 = 6 (not zero) although ADD gave 0: ADD sets no status"
    );
}

#[test]
fn add_in_german_spelling() {
    let source = "OB 1\n      SPA FB 1\nNAME :T\n      BE\nFB 1\nNAME :T\n      L  KF +10\n      ADD KF +5\n      T  MW 0\n      BE\n";
    let (cpu, _) = run_once(source);
    assert_eq!(fw(&cpu, 0), 15);
}

#[test]
fn add_takes_only_kb_kf_and_dh() {
    let errors = check_errors(&fb("      ADD KH 0010"));
    assert!(
        errors.iter().any(|d| matches!(
            d,
            SourceDiagnostic::Check(CheckError::OperandNotAllowed { .. })
        )),
        "{errors:#?}"
    );
}

#[test]
fn operations_awl_cannot_simulate_stop_the_cpu_naming_themselves() {
    for (statement, word) in [
        ("TNB 10", "TNB 10"),
        ("LIR 2", "LIR 2"),
        ("TIR 2", "TIR 2"),
        ("MBA", "MBA"),
        ("MAB", "MAB"),
        ("MSA", "MSA"),
        ("MAS", "MAS"),
        ("ABR 4", "ABR 4"),
        ("LRB 4", "LRB 4"),
        ("TRB 4", "TRB 4"),
    ] {
        let (_, outcome) = run_once(&fb(&format!("      L  KF +1\n      {statement}")));
        let stop = outcome
            .stop
            .unwrap_or_else(|| panic!("{statement} ran without a STOP"));
        assert_eq!(stop.cause, StopCause::Bcf, "{statement}");
        let StopDetail::Text(text) = &stop.detail else {
            panic!("{statement}: {:?}", stop.detail);
        };
        assert!(
            text.contains(&format!("`{word}` is not simulated")),
            "{text}"
        );
        assert!(text.contains("no S5 memory map"), "{text}");
        assert_eq!(stop.stack[0].block, "FB 1");
    }
}

#[test]
fn system_operation_numbers_are_range_checked() {
    for body in [
        "      TNB 0",
        "      TNB 256",
        "      LIR 16",
        "      TIR 16",
    ] {
        let errors = check_errors(&fb(body));
        assert!(
            errors
                .iter()
                .any(|d| matches!(d, SourceDiagnostic::Check(CheckError::OperandRange { .. }))),
            "{body}: {errors:#?}"
        );
    }
}

#[test]
fn each_new_operation_names_its_feature() {
    use awl::mnemonics::{OpCode, op_info};
    use awl::profile::Feature;
    let supplementary_feature = |op| op_info(op).feature;
    assert_eq!(
        supplementary_feature(OpCode::AddConstant),
        Some(Feature::AddConstant)
    );
    for op in [
        OpCode::TransferBytes,
        OpCode::LoadIndirect,
        OpCode::TransferIndirect,
    ] {
        assert_eq!(supplementary_feature(op), Some(Feature::SystemOperations));
    }
    for op in [
        OpCode::MoveBrToAccu,
        OpCode::MoveAccuToBr,
        OpCode::MoveSaToAccu,
        OpCode::MoveAccuToSa,
        OpCode::AddToBr,
        OpCode::LoadRelativeBr,
        OpCode::TransferRelativeBr,
    ] {
        assert_eq!(supplementary_feature(op), Some(Feature::RegisterOperations));
    }
    assert_eq!(supplementary_feature(OpCode::ResetBinary), None);
}
