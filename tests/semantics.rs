//! The STEP 5 semantics of each operation, including the edge cases the manuals call out.

mod common;

use awl::vm::Mode;
use awl::vm::stop::StopCause;
use common::*;

/// Wraps statements in an FB called from OB 1 (so supplementary operations are allowed).
fn fb(body: &str) -> String {
    format!(
        "OB 1\n      JU FB 1\nNAME :T\n      BE\nFB 1\nNAME :T\n{body}\n      BE\nDB 5\n 0: KF +1\n 1: KH ABCD\n 2: KF -2\n 3: KF +0\n"
    )
}

#[test]
fn first_check_after_assignment_starts_a_new_string() {
    let (cpu, _) = run_once(&fb(
        "      A  F 0.0\n      =  F 1.0\n      AN F 0.0\n      =  F 1.1\n      =  F 1.2",
    ));
    assert!(!flag(&cpu, 1, 0));
    assert!(
        flag(&cpu, 1, 1),
        "AN after = loads, it does not AND with the old RLO"
    );
    assert!(flag(&cpu, 1, 2), "the RLO stays for a second assignment");
}

#[test]
fn or_without_operand_ors_and_functions() {
    // F 0.0 = 1, F 0.1 = 0, F 0.2 = 1, F 0.3 = 1: 1&0 | 1&1 = 1; 1&0 | 1&0 = 0
    let body = "      S  F 0.0\n      S  F 0.2\n      S  F 0.3\n      A  F 0.0\n      A  F 0.1\n      O\n      A  F 0.2\n      A  F 0.3\n      =  F 1.0\n      A  F 0.0\n      A  F 0.1\n      O\n      A  F 0.2\n      A  F 0.1\n      =  F 1.1";
    let body = format!("      A  F 9.0\n      ON F 9.0\n{body}");
    let (cpu, _) = run_once(&fb(&body));
    assert!(flag(&cpu, 1, 0));
    assert!(!flag(&cpu, 1, 1));
}

#[test]
fn nested_brackets() {
    // F 1.0 = F 0.0 & (F 0.1 | (F 0.2 & F 0.3)) with F 0.0, F 0.2, F 0.3 = 1
    let body = "      ON F 9.0\n      S  F 0.0\n      S  F 0.2\n      S  F 0.3\n      A  F 0.0\n      A(\n      O  F 0.1\n      O(\n      A  F 0.2\n      A  F 0.3\n      )\n      )\n      =  F 1.0\n      A  F 0.0\n      A(\n      O  F 0.1\n      O(\n      A  F 0.2\n      A  F 0.1\n      )\n      )\n      =  F 1.1";
    let (cpu, _) = run_once(&fb(body));
    assert!(flag(&cpu, 1, 0));
    assert!(!flag(&cpu, 1, 1));
}

#[test]
fn eight_brackets_overflow_the_bracket_stack() {
    // Four brackets in the text, eight at run time: the loop opens them twice.
    let body = "      L  KF +0\n      T  FW 60\nLOOP :A(\n      A(\n      A(\n      A(\n      L  FW 60\n      I  1\n      T  FW 60\n      L  KF +2\n      ><F\n      JC =LOOP\n      )\n      )\n      )\n      )";
    let (cpu, outcome) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 60), 1, "the loop went round once");
    assert_eq!(outcome.stop.unwrap().cause, StopCause::Bcf);
}

#[test]
fn fixed_point_arithmetic_sets_overflow() {
    let body = "      L  KF +30000\n      L  KF +10000\n      +F\n      T  FW 0\n      JO =OVF\n      L  KF +0\n      T  FW 2\n      BEU\nOVF  :L  KF +1\n      T  FW 2";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 40000u16 as i16);
    assert_eq!(fw(&cpu, 2), 1, "JO jumps on the overflow of +F");
}

#[test]
fn sub_mul_div_work_on_accu_2_and_accu_1() {
    let body = "      L  KF +7\n      L  KF +10\n      -F\n      T  FW 0\n      L  KF -6\n      L  KF +7\n      X  F\n      T  FW 2\n      L  KF +100\n      L  KF +7\n      :F\n      T  FW 4";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!((fw(&cpu, 0), fw(&cpu, 2), fw(&cpu, 4)), (-3, -42, 14));
}

#[test]
fn division_by_zero_leaves_accu_1_and_sets_cc_11_and_ov() {
    // FW 0 starts at 77, so the 0 read back is the divisor left in ACCU 1; JZ/JN/JP/JM tell
    // CC1 CC0 = 1 1 apart: only "not zero" jumps (CC1 != CC0 is false, so JN does not).
    let body = "      L  KF +77\n      T  FW 0\n      L  KF +100\n      L  KF +0\n      :F\n      T  FW 0\n      JO =OVF\n      BEU\nOVF  :L  KF +9\n      T  FW 2\n      L  KF +100\n      L  KF +0\n      :F\n      JP =POS\n      JM =NEG\n      JZ =ZER\n      L  KF +11\n      T  FW 4\n      BEU\nPOS  :L  KF +1\n      T  FW 4\n      BEU\nNEG  :L  KF +2\n      T  FW 4\n      BEU\nZER  :L  KF +3\n      T  FW 4";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 0, "ACCU 1 still holds the divisor 0");
    assert_eq!(fw(&cpu, 2), 9, "OV is set");
    assert_eq!(
        fw(&cpu, 4),
        11,
        "CC1 CC0 = 1 1: neither positive, minus nor zero"
    );
}

#[test]
fn jumps_on_each_condition_code() {
    // For each jump: a result that takes it and one that does not; FW n counts the taken ones.
    let cases = [
        ("JZ", "KF +5", "KF +5", "KF +5", "KF +4"),
        ("JN", "KF +5", "KF +4", "KF +5", "KF +5"),
        ("JP", "KF +5", "KF +4", "KF +4", "KF +5"),
        ("JM", "KF +4", "KF +5", "KF +5", "KF +4"),
    ];
    for (jump, a1, b1, a2, b2) in cases {
        let body = format!(
            "      L  {a1}\n      L  {b1}\n      -F\n      {jump} =T1\n      BEU\nT1   :L  KF +1\n      T  FW 0\n      L  {a2}\n      L  {b2}\n      -F\n      {jump} =T2\n      BEU\nT2   :L  KF +1\n      T  FW 2"
        );
        let (cpu, _) = run_once(&fb(&body));
        assert_eq!((fw(&cpu, 0), fw(&cpu, 2)), (1, 0), "{jump}");
    }
}

#[test]
fn comparisons_form_the_rlo() {
    let body = "      L  KF -3\n      L  KF +2\n      <F\n      =  F 1.0\n      >F\n      =  F 1.1\n      !=F\n      =  F 1.2\n      ><F\n      =  F 1.3\n      <=F\n      =  F 1.4\n      >=F\n      =  F 1.5";
    let (cpu, _) = run_once(&fb(body));
    let bits: Vec<bool> = (0..6).map(|bit| flag(&cpu, 1, bit)).collect();
    assert_eq!(bits, [true, false, false, true, true, false]);
}

#[test]
fn load_and_transfer_every_memory_operand() {
    let body = "      C  DB 5\n      L  DW 1\n      T  FW 0\n      L  DL 1\n      T  FY 2\n      L  DR 1\n      T  FY 3\n      L  DD 1\n      T  FD 4\n      L  KF +77\n      T  DW 3\n      L  DW 3\n      T  FW 8\n      L  FW 0\n      T  QW 2\n      L  QB 2\n      T  FY 10\n      L  KB 200\n      T  PY 5\n      L  KH 1234\n      T  OW 6";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0) as u16, 0xABCD);
    assert_eq!(fw(&cpu, 2) as u16, 0xABCD, "DL then DR");
    assert_eq!(fd(&cpu, 4), 0xABCD_FFFE);
    assert_eq!(fw(&cpu, 8), 77);
    assert_eq!(cpu.image[2 * 128 + 10], 0xAB);
    assert_eq!(
        cpu.outputs[5], 200,
        "T PY writes the output module directly"
    );
    assert_eq!(cpu.image[128 + 5], 200, "and the PIQ of a digital output");
    assert_eq!(cpu.extended_outputs[6..8], [0x12, 0x34]);
}

#[test]
fn every_constant_format_loads() {
    let body = "      L  KB 255\n      T  FW 0\n      L  KF -1\n      T  FW 2\n      L  KM 0000000011110000\n      T  FW 4\n      L  KY 1,2\n      T  FW 6\n      L  KT 123.2\n      T  FW 8\n      L  KC 456\n      T  FW 10\n      L  KS 'AB'\n      T  FW 12\n      L  DH 12345678\n      T  FD 14\n      L  KG +5000000+01\n      T  FD 18\n      L  KG -7500000+00\n      T  FD 22";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 255);
    assert_eq!(fw(&cpu, 2), -1);
    assert_eq!(fw(&cpu, 4), 0x00F0);
    assert_eq!(fw(&cpu, 6), 0x0102);
    assert_eq!(fw(&cpu, 8), 0x2123, "KT: base 2 in bits 12-13, BCD value");
    assert_eq!(fw(&cpu, 10), 0x0456, "KC: BCD");
    assert_eq!(fw(&cpu, 12), 0x4142);
    assert_eq!(fd(&cpu, 14), 0x1234_5678);
    assert_eq!(
        fd(&cpu, 18),
        0x0350_0000,
        "KG 5.0: exponent 3, mantissa +0.625 (sign and 23 bits)"
    );
    assert_eq!(
        fd(&cpu, 22),
        0x00A0_0000,
        "KG -0.75: exponent 0, mantissa -0.75 in two's complement"
    );
}

#[test]
fn accumulator_operations() {
    let body = "      L  KF +1\n      L  KF +2\n      TAK\n      T  FW 0\n      L  KH 00FF\n      I  1\n      T  FW 2\n      L  KH 0100\n      D  1\n      T  FW 4\n      L  KH 0001\n      SLW 4\n      T  FW 6\n      SRW 2\n      T  FW 8\n      L  KH 0F0F\n      CFW\n      T  FW 10\n      L  KF +5\n      CSW\n      T  FW 12\n      L  KH 00FF\n      L  KH 0F0F\n      AW\n      T  FW 14\n      L  KH 00FF\n      L  KH 0F0F\n      OW\n      T  FW 16\n      L  KH 00FF\n      L  KH 0F0F\n      XOW\n      T  FW 18";
    let (cpu, _) = run_once(&fb(body));
    let words: Vec<u16> = (0..10).map(|i| fw(&cpu, 2 * i) as u16).collect();
    assert_eq!(
        words,
        [
            1,
            0x0000,
            0x01FF,
            0x0010,
            0x0004,
            0xF0F0,
            (-5i16) as u16,
            0x000F,
            0x0FFF,
            0x0FF0
        ]
    );
}

#[test]
fn indirect_addressing_with_do() {
    // DO FW 20 with FW 20 = 2 makes `L DW 0` load DW 2 (= -2); for a bit, high byte = bit.
    let body = "      C  DB 5\n      L  KF +2\n      T  FW 20\n      DO FW 20\n      L  DW 0\n      T  FW 0\n      L  KH 0304\n      T  FW 22\n      DO FW 22\n      S  F 30.0";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), -2);
    assert!(flag(&cpu, 4, 3), "S F 4.3 through DO");
    assert!(!flag(&cpu, 30, 0), "the written operand is replaced");
}

#[test]
fn bit_test_and_unconditional_set_and_reset() {
    let body = "      C  DB 5\n      SU D 3.4\n      TB D 3.4\n      =  F 1.0\n      RU D 3.4\n      TBN D 3.4\n      =  F 1.1\n      SU F 2.2\n      TB F 2.2\n      =  F 1.2";
    let (cpu, _) = run_once(&fb(body));
    assert!(flag(&cpu, 1, 0) && flag(&cpu, 1, 1) && flag(&cpu, 1, 2));
}

#[test]
fn counters_stay_within_0_and_999() {
    // Each operation first sees RLO 0 (A F 9.0), then RLO 1 (AN F 9.0): a rising edge.
    let edge = |op: &str| format!("      A  F 9.0\n      {op}\n      AN F 9.0\n      {op}\n");
    let body = [
        "      L  KC 5\n".to_string(),
        edge("S  C 1"),
        edge("CU C 1"),
        "      L  C 1\n      T  FW 0\n      L  KC 999\n".to_string(),
        edge("S  C 1"),
        edge("CU C 1"),
        "      L  C 1\n      T  FW 2\n      L  KC 3\n".to_string(),
        edge("S  C 2"),
        edge("CD C 2"),
        "      L  C 2\n      T  FW 4\n".to_string(),
        edge("R  C 2"),
        edge("CD C 2"),
        "      L  C 2\n      T  FW 8\n      A  C 2\n      =  F 4.0\n      L  KC 123\n".to_string(),
        edge("S  C 3"),
        "      LC C 3\n      T  FW 6".to_string(),
    ]
    .concat();
    let (cpu, _) = run_once(&fb(&body));
    assert_eq!(fw(&cpu, 0), 6, "CU counts 5 up to 6");
    assert_eq!(fw(&cpu, 2), 999, "no count above 999");
    assert_eq!(fw(&cpu, 4), 2, "CD counts 3 down to 2");
    assert_eq!(fw(&cpu, 8), 0, "no count below 0");
    assert!(!flag(&cpu, 4, 0), "a counter at 0 reads 0");
    assert_eq!(fw(&cpu, 6), 0x0123);
}

#[test]
fn open_data_block_is_restored_after_a_call() {
    let source = "OB 1\n      C  DB 5\n      JU PB 2\n      L  DW 0\n      T  FW 0\n      BE\nPB 2\n      C  DB 6\n      L  DW 0\n      T  FW 2\n      BE\nDB 5\n 0: KF +55\nDB 6\n 0: KF +66\n";
    let (cpu, _) = run_once(source);
    assert_eq!((fw(&cpu, 0), fw(&cpu, 2)), (55, 66));
}

#[test]
fn fb_parameters_of_every_kind() {
    let source = "OB 1\n      L  KF +1234\n      T  FW 10\n      JU FB 3\nNAME :ALL\nBIT  :F 0.1\nOUT  :F 0.2\nWORD :FW 10\nKON  :KF +42\nBLK  :PB 7\nTIM  :T 4\nCNT  :C 5\n      BE\n\
FB 3\nNAME :ALL\nDES  :BIT  I BI\nDES  :OUT  Q BI\nDES  :WORD I W\nDES  :KON  D KF\nDES  :BLK  B\nDES  :TIM  T\nDES  :CNT  C\n      ON =BIT\n      =  =OUT\n      L  =KON\n      T  FW 20\n      L  =WORD\n      T  FW 22\n      JU =BLK\n      L  KT 010.2\n      ON =BIT\n      SE =TIM\n      A  =TIM\n      =  F 3.0\n      ON =BIT\n      CU =CNT\n      L  =CNT\n      T  FW 24\n      BE\nPB 7\n      L  KF +7\n      T  FW 26\n      BE\n";
    let (cpu, _) = run_once(source);
    assert!(flag(&cpu, 0, 2));
    assert_eq!(
        (fw(&cpu, 20), fw(&cpu, 22), fw(&cpu, 24), fw(&cpu, 26)),
        (42, 1234, 1, 7)
    );
    assert!(flag(&cpu, 3, 0), "the extended pulse on T 4 runs");
}

#[test]
fn stp_stops_at_the_end_of_the_cycle() {
    let (cpu, outcome) = run_once("OB 1\n      STP\n      ON F 9.0\n      =  Q 4.0\n      BE\n");
    assert_eq!(outcome.mode, Mode::Stop);
    assert_eq!(outcome.stop.unwrap().cause, StopCause::Stp);
    assert!(output(&cpu, 4, 0), "the rest of the cycle ran");
}

#[test]
fn runtime_faults_stop_the_cpu() {
    let cases = [
        (
            "OB 1\n      JU PB 1\n      BE\nPB 1\n      JU PB 1\n      BE\n",
            StopCause::Stueb,
        ),
        ("OB 1\n      JU PB 9\n      BE\n", StopCause::LzfBlock),
        ("OB 1\n      L  DW 0\n      BE\n", StopCause::LzfData),
        (
            "OB 1\n      C  DB 5\n      L  DW 7\n      BE\nDB 5\n 0: KF +1\n",
            StopCause::LzfData,
        ),
        (
            "OB 1\n      JU FB 1\n      BE\nFB 1\nNAME :SKIP\n      JU =OVER\n      A(\nOVER :)\n      BE\n",
            StopCause::Bcf,
        ),
    ];
    for (source, cause) in cases {
        let (_, outcome) = run_once(source);
        let stop = outcome
            .stop
            .unwrap_or_else(|| panic!("no STOP for {source}"));
        assert_eq!(stop.cause, cause, "{source}");
        assert!(!stop.stack.is_empty());
    }
}

#[test]
fn generated_data_blocks_can_be_used() {
    let body = "      L  KF +10\n      G  DB 40\n      C  DB 40\n      L  KF +9\n      T  DW 9\n      L  DW 9\n      T  FW 0";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 9);
}

#[test]
fn watchdog_stops_an_endless_loop() {
    let (_, outcome) = run_once(&fb("LOOP :JU =LOOP"));
    let stop = outcome.stop.unwrap();
    assert_eq!(stop.cause, StopCause::Zyk);
    assert_eq!(stop.stack[0].block, "FB 1");
}

#[test]
fn do_must_not_modify_another_do() {
    let built = awl::frontend::build_text(
        "do.awl",
        &fb("      DO FW 0\n      DO FW 2\n      L  DW 0"),
        awl::profile::find("sinumerik-840c").unwrap(),
    );
    assert!(built.diagnostics.iter().any(|d| matches!(
        d,
        awl::diagnostics::SourceDiagnostic::Check(awl::compiler::CheckError::IndirectTarget { .. })
    )));
}

#[test]
fn data_bits_take_every_logic_and_write_operation() {
    // DW 3 starts at 0: = D 3.0 with RLO 1, S D 3.1, R D 3.0 again; A D / O D read them back.
    let body = "      C  DB 5\n      ON F 9.0\n      =  D 3.0\n      S  D 3.1\n      A  D 3.0\n      A  D 3.1\n      =  F 1.0\n      ON F 9.0\n      R  D 3.0\n      A  D 3.0\n      O  D 3.1\n      =  F 1.1\n      AN D 3.0\n      ON D 3.1\n      =  F 1.2\n      L  DW 3\n      T  FW 20";
    let (cpu, _) = run_once(&fb(body));
    assert!(flag(&cpu, 1, 0), "= D and S D set the bits");
    assert!(flag(&cpu, 1, 1), "O D 3.1 is 1 after R D 3.0");
    assert!(flag(&cpu, 1, 2), "AN D 3.0 is 1");
    assert_eq!(fw(&cpu, 20), 0b10, "only D 3.1 is left set");
}

#[test]
fn timer_and_counter_bits_in_logic_and_loads() {
    // T 1 runs (extended pulse, bit 1); C 1 counted to 1 (bit 1); C 2 stays 0.
    let body = "      ON F 9.0\n      L  KT 500.0\n      SE T 1\n      ON F 9.0\n      CU C 1\n      A  F 9.0\n      O  T 1\n      =  F 1.0\n      A  F 9.0\n      O  C 1\n      =  F 1.1\n      AN C 2\n      ON C 2\n      =  F 1.2\n      A  F 9.0\n      ON T 1\n      =  F 1.3\n      L  T 1\n      T  FW 20\n      L  C 1\n      T  FW 22";
    let (cpu, _) = run_once(&fb(body));
    assert!(flag(&cpu, 1, 0), "O T 1");
    assert!(flag(&cpu, 1, 1), "O C 1");
    assert!(flag(&cpu, 1, 2), "AN C 2 / ON C 2");
    assert!(!flag(&cpu, 1, 3), "ON T 1 of a running pulse is 0");
    assert_eq!(
        fw(&cpu, 20),
        500,
        "L T 1: the remaining time, nothing elapsed yet"
    );
    assert_eq!(fw(&cpu, 22), 1);
}

#[test]
fn enabling_a_counter_lets_it_count_again() {
    // CU with RLO 1 twice counts once; FR C 1 on a rising edge lets the next CU count again.
    let body = "      ON F 9.0\n      CU C 1\n      CU C 1\n      A  F 9.0\n      FR C 1\n      ON F 9.0\n      FR C 1\n      CU C 1\n      L  C 1\n      T  FW 0";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0), 2);
}

#[test]
fn indirect_data_word_and_peripheral_words() {
    // DO DW 2: DW 2 holds -2 → 0xFFFE, out of range: use DW 0 = 1 to make `L DW 0` load DW 1.
    let body = "      C  DB 5\n      DO DW 0\n      L  DW 3\n      T  FW 0\n      L  KH 1234\n      T  PW 4\n      L  PW 4\n      T  FW 2\n      L  KB 9\n      T  OY 7\n      L  OY 7\n      T  FW 4";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 0) as u16, 0xABCD, "DO DW 0 made it L DW 1");
    assert_eq!(
        cpu.outputs[4..6],
        [0x12, 0x34],
        "T PW writes the output module"
    );
    assert_eq!(
        cpu.extended_outputs[7], 9,
        "T OY writes the extended module"
    );
    // L PW / L OY read the input modules, which hold 0.
    assert_eq!((fw(&cpu, 2), fw(&cpu, 4)), (0, 0));
}

/// Comparisons of equal values: `>F` and `<F` are 0, `>=F`, `<=F` and `!=F` 1, and the
/// condition codes say "zero" (CC1 CC0 = 0 0), so JZ jumps; greater gives 1 0 (JP), less
/// 0 1 (JM).
#[test]
fn comparisons_of_equal_values_and_their_condition_codes() {
    let body = "      L  KF +4\n      L  KF +4\n      >F\n      =  F 1.0\n      <F\n      =  F 1.1\n      >=F\n      =  F 1.2\n      <=F\n      =  F 1.3\n      !=F\n      =  F 1.4\n      ><F\n      =  F 1.5\n      JZ =ZER\n      BEU\nZER  :L  KF +5\n      L  KF +4\n      >F\n      JP =POS\n      BEU\nPOS  :L  KF +3\n      L  KF +4\n      >F\n      JM =NEG\n      BEU\nNEG  :L  KF +1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    let bits: Vec<bool> = (0..6).map(|bit| flag(&cpu, 1, bit)).collect();
    assert_eq!(bits, [false, false, true, true, true, false]);
    assert_eq!(fw(&cpu, 10), 1, "JZ on equal, JP on greater, JM on less");
}

/// Shifts put the last bit shifted out into CC1: 1 jumps with JN (not zero), 0 with JZ.
#[test]
fn shifts_report_the_last_bit_shifted_out() {
    let body = "      L  KH 4000\n      SLW 1\n      JZ =Z1\n      BEU\nZ1   :L  KH 8000\n      SLW 1\n      JN =N1\n      BEU\nN1   :L  KH 0002\n      SRW 1\n      JZ =Z2\n      BEU\nZ2   :L  KH 0001\n      SRW 1\n      JN =N2\n      BEU\nN2   :L  KF +1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10), 1, "0 out: JZ; 1 out: JN, both directions");
}

/// `S C n` sets the count only on a rising edge of the RLO: not with RLO 0, not again while
/// the RLO stays 1.
#[test]
fn setting_a_counter_needs_a_rising_edge() {
    let body = "      L  KC 7\n      A  F 9.0\n      S  C 1\n      L  C 1\n      T  FW 10\n      L  KC 7\n      ON F 9.0\n      S  C 1\n      CU C 1\n      L  KC 7\n      ON F 9.0\n      S  C 1\n      L  C 1\n      T  FW 12";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10), 0, "RLO 0: not set");
    assert_eq!(
        fw(&cpu, 12),
        8,
        "the second S with RLO still 1 does not set 7 again"
    );
}

#[test]
fn flag_double_words_load_with_their_byte_order() {
    let body = "      L  DH 11223344\n      T  FD 4\n      L  FD 4\n      T  FD 8\n      L  FD 5\n      T  FD 12";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fd(&cpu, 8), 0x1122_3344);
    assert_eq!(
        fd(&cpu, 12),
        0x2233_4411,
        "FD 5: bytes 5 to 8, the last one FD 8's first"
    );
}

/// JZ jumps only on CC1 CC0 = 0 0: not after a positive or a negative result.
#[test]
fn jump_on_zero_needs_both_condition_codes_clear() {
    let body = "      L  KF +5\n      L  KF +3\n      -F\n      JZ =BAD\n      L  KF +3\n      L  KF +5\n      -F\n      JZ =BAD\n      L  KF +1\n      T  FW 10\n      BEU\nBAD  :L  KF +2\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10), 1);
}

/// `BEC` ends the block only when the RLO is 1; `BE` passes the RLO back to the caller,
/// `BEU` and a taken `BEC` leave it 1.
#[test]
fn block_ends_and_the_rlo_they_pass_back() {
    let source = "OB 1\n      JU PB 1\n      =  F 1.0\n      JU PB 2\n      =  F 1.1\n      JU PB 3\n      =  F 1.2\n      BE\n\
PB 1\n      A  F 9.0\n      BEC\n      L  KF +7\n      T  FW 10\n      A  F 9.0\n      BE\n\
PB 2\n      ON F 9.0\n      BEC\n      L  KF +8\n      T  FW 12\n      BE\n\
PB 3\n      A  F 9.0\n      BEU\n      BE\n";
    let (cpu, _) = run_once(source);
    assert_eq!(fw(&cpu, 10), 7, "BEC with RLO 0 goes on");
    assert_eq!(fw(&cpu, 12), 0, "BEC with RLO 1 ends the block");
    assert!(!flag(&cpu, 1, 0), "BE passes the RLO 0 back");
    assert!(flag(&cpu, 1, 1), "a taken BEC leaves RLO 1");
    assert!(flag(&cpu, 1, 2), "BEU leaves RLO 1");
}

/// `DO` also replaces the number of operations that take one (`SLW n`).
#[test]
fn indirect_shift_count() {
    let body = "      L  KF +3\n      T  FW 10\n      L  KH 0001\n      DO FW 10\n      SLW 0\n      T  FW 12";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 12), 8);
}

/// `T DL` and `T DR` replace one byte of the data word and keep the other; `T DD` writes two
/// words, and one that would reach past the DB's end is STOP LZF.
#[test]
fn data_byte_and_double_word_transfers() {
    // DW 1 = ABCD, DW 2 = FFFE (-2).
    let body = "      C  DB 5\n      L  KB 18\n      T  DL 1\n      L  KB 52\n      T  DR 2\n      L  DH 01020304\n      T  DD 0\n      L  DW 1\n      T  FW 10\n      L  DW 0\n      T  FW 12\n      L  DL 1\n      T  FW 14";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 12) as u16, 0x0102, "DD 0: DW 0 the high word");
    assert_eq!(fw(&cpu, 10) as u16, 0x0304, "DD 0: DW 1 the low word");
    assert_eq!(fw(&cpu, 14), 0x03);
    let words = cpu.data_blocks[5].as_ref().unwrap();
    assert_eq!(words[2], 0xFF34, "T DR 2 kept the left byte FF");
    let (cpu, _) = run_once(&fb(
        "      C  DB 5\n      L  KB 18\n      T  DL 2\n      L  DW 2\n      T  FW 10",
    ));
    assert_eq!(fw(&cpu, 10) as u16, 0x12FE, "T DL 2 kept the right byte FE");
    let (_, outcome) = run_once(&fb("      C  DB 5\n      L  DH 01020304\n      T  DD 3"));
    assert_eq!(
        outcome.stop.unwrap().cause,
        StopCause::LzfData,
        "DD 3 needs DW 4"
    );
}

/// Setting a data bit that is already set keeps it set, and the other bits.
#[test]
fn setting_a_set_data_bit_keeps_it() {
    let body = "      C  DB 5\n      SU D 1.0\n      SU D 1.0\n      ON F 9.0\n      =  D 1.0\n      S  D 1.0\n      L  DW 1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10) as u16, 0xABCD, "bit 0 of ABCD was already 1");
}

/// A direct output reaches the PIQ only for a digital module: a word at the end of the image
/// is not copied into the PIQ (nor past it, into the flags).
#[test]
fn direct_outputs_follow_the_piq_only_inside_it() {
    let body = "      L  KH 1234\n      T  PW 126\n      L  KH 5678\n      T  PW 127\n      L  KB 9\n      T  PY 127";
    let (cpu, _) = run_once(&fb(body));
    let piq = 128;
    assert_eq!(cpu.image[piq + 126], 0x12, "PW 126 fits the PIQ");
    assert_eq!(cpu.image[piq + 127], 9, "PY 127 is the last PIQ byte");
    assert_eq!(fw(&cpu, 0), 0, "PW 127 did not spill into the flags");
    assert_eq!(cpu.outputs[127..129], [9, 0x78]);
}

/// `G DB` may create a data block of up to the CPU's data words, not one more.
#[test]
fn generated_data_block_size_limit() {
    let (_, outcome) = run_once(&fb("      L  KF +2048\n      G  DB 40"));
    assert!(outcome.stop.is_none(), "2048 words fit the 840C");
    let (_, outcome) = run_once(&fb("      L  KF +2049\n      G  DB 40"));
    assert_eq!(outcome.stop.unwrap().cause, StopCause::LzfData);
}

/// After a conditional jump the RLO is 1 and a new logic string starts: neither the first
/// check nor the OR of `O` carries over.
#[test]
fn a_logic_string_ends_at_a_conditional_jump() {
    let body = "      A  F 9.0\n      JC =L1\nL1   :O  F 9.0\n      =  F 1.0\n      ON F 9.0\n      O\n      A  F 9.0\n      JC =L2\n      BEU\nL2   :A  F 9.0\n      =  F 1.1";
    let (cpu, _) = run_once(&fb(body));
    assert!(
        !flag(&cpu, 1, 0),
        "O after JC loads, it does not OR with the old RLO"
    );
    assert!(!flag(&cpu, 1, 1), "the OR of `O` ends at the taken JC");
}

/// `CSW` sets the condition codes of its result.
#[test]
fn twos_complement_sets_the_condition_codes() {
    let body = "      L  KF +5\n      CSW\n      JM =M1\n      BEU\nM1   :L  KF -5\n      CSW\n      JP =M2\n      BEU\nM2   :L  KF +0\n      CSW\n      JZ =M3\n      BEU\nM3   :L  KF +1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10), 1);
}

/// S5 floating point (CPU 928B programming guide, 2.2 and table 3-7): 12.5 and −2.5 as the PG
/// writes them, each result's bits in FD.
#[test]
fn floating_point_arithmetic_gives_the_s5_bits() {
    let operations = [("+G", 0), ("-G", 4), ("X G", 8), (":G", 12)];
    let body: String = operations
        .iter()
        .map(|(op, at)| {
            format!(
                "      L  KG +1250000+02\n      L  KG -2500000+01\n      {op}\n      T  FD {at}\n"
            )
        })
        .collect();
    let (cpu, _) = run_once(&fb(&body));
    assert_eq!(fd(&cpu, 0), 0x0450_0000, "10.0");
    assert_eq!(fd(&cpu, 4), 0x0478_0000, "15.0");
    assert_eq!(fd(&cpu, 8), 0x0583_0000, "-31.25");
    assert_eq!(fd(&cpu, 12), 0x03B0_0000, "-5.0");
}

#[test]
fn floating_point_comparisons_and_overflow() {
    let body = "      L  KG +2500000+01\n      L  KG -1000000+01\n      >G\n      =  F 20.0\n      <=G\n      =  F 20.1\n      !=G\n      =  F 20.2\n      L  KG +1000000+38\n      L  KG +1000000+38\n      X G\n      T  FD 24\n      JO =OVF\n      BEU\nOVF  :L  KF +1\n      T  FW 30";
    let (cpu, _) = run_once(&fb(body));
    assert!(flag(&cpu, 20, 0), "2.5 > -1");
    assert!(!flag(&cpu, 20, 1));
    assert!(!flag(&cpu, 20, 2));
    assert_eq!(fw(&cpu, 30), 1, "10^37 × 10^37 overflows: OV");
    assert_eq!(fd(&cpu, 24), 0x7F7F_FFFF, "the largest number");
}

#[test]
fn conversions_of_accu_1() {
    let body = "      L  DH FFFFFB2E\n      FDG\n      T  FD 0\n      GFD\n      T  FD 4\n      L  KH F123\n      DEF\n      T  FW 8\n      L  DH 0012D687\n      DUD\n      T  FD 12\n      L  DH F7654321\n      DED\n      T  FD 16\n      L  KF -45\n      DUF\n      T  FW 20";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(awl::s5_float::decode(fd(&cpu, 0)), -1234.0, "FDG");
    assert_eq!(fd(&cpu, 4) as i32, -1234, "GFD");
    assert_eq!(fw(&cpu, 8), -123, "DEF");
    assert_eq!(fd(&cpu, 12), 0x0123_4567, "DUD");
    assert_eq!(fd(&cpu, 16) as i32, -7_654_321, "DED");
    assert_eq!(fw(&cpu, 20) as u16, 0xF045, "DUF");
}

#[test]
fn floating_point_is_an_error_on_a_cpu_without_it() {
    let program = "OB 1\n      L  KG +1000000+01\n      L  KG +2000000+01\n      +G\n      T  FD 0\n      BE\n";
    let profile = awl::profile::find("s5-95f").unwrap();
    let built = awl::frontend::build_text("fp.awl", program, profile);
    let messages: Vec<String> = built
        .diagnostics
        .iter()
        .map(|diagnostic| diagnostic.to_string())
        .collect();
    let having = awl::profile::having(awl::profile::Feature::FloatingPoint).join(", ");
    assert!(having.starts_with("sinumerik-840c, "), "{having}");
    assert_eq!(messages, [format!("`+G` needs floating point: {having}")]);
    let default = awl::profile::default_for(awl::dialect::Dialect::Step5);
    assert!(!awl::frontend::build_text("fp.awl", program, default).has_errors());
}
