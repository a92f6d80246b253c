//! `awl analyze` on the cases its figures are for: loops with and without `@bound`, recursion,
//! a call chain deeper than the CPU allows (STUEB), the S5-95F's wake-up risk (WECK), the
//! watchdog (ZYK), code and blocks that never run; and every sample's analysis as a snapshot.

use std::sync::Arc;

use awl::analyze::{self, Analysis, Config};
use awl::frontend;
use awl::profile::{self, InterruptPoints};
use awl::runner::{self, RunOptions};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig};

mod common;

fn analysis(source: &str, cpu: &str, points: InterruptPoints, watchdog_ns: u64) -> Analysis {
    let profile = profile::find(cpu).unwrap();
    let built = frontend::build_text("a.awl", source, profile);
    assert!(!built.has_errors(), "{:#?}", built.diagnostics);
    let config = Config {
        profile,
        points,
        special_mode: false,
        ob13_interval_ns: None,
        watchdog_ns,
    };
    analyze::analyze(&built.compiled.program, &built.sources, config)
}

fn on_840c(source: &str) -> Analysis {
    analysis(
        source,
        "sinumerik-840c",
        InterruptPoints::Block,
        150_000_000,
    )
}

fn block<'a>(analysis: &'a Analysis, name: &str) -> &'a analyze::BlockFigures {
    analysis.blocks.iter().find(|b| b.block == name).unwrap()
}

/// Runs `source` one cycle on the 840C: the trace's events.
fn one_cycle(source: &str) -> (Cpu, awl::vm::cycle::RunOutcome) {
    let profile = profile::find("sinumerik-840c").unwrap();
    let built = frontend::build_text("a.awl", source, profile);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    cpu.engine = Engine::new(profile, EngineConfig::default(), Vec::new());
    let outcome = cpu.run(RunLimit::Cycles(1));
    (cpu, outcome)
}

const LOOP: &str = "OB 1\n      JU FB 1\nNAME :COUNT\n      BE\nFB 1\nNAME :COUNT\n      L  KF +25\n      T  FW 0\nM001 :L  FW 0      ; @bound 25\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n";

#[test]
fn a_loop_without_a_bound_makes_the_figures_unbounded() {
    let source = LOOP.replace("; @bound 25", "");
    let analysis = on_840c(&source);
    let fb = block(&analysis, "FB 1");
    assert_eq!(fb.wcet_ns, None);
    assert_eq!(fb.stretch_ns, None);
    assert!(
        fb.unbounded
            .as_deref()
            .unwrap()
            .contains("line 9 has no bound")
    );
    assert_eq!(fb.loops[0].bound, None);
    assert_eq!(analysis.response_bound_ns, None);
    assert_eq!(analysis.watchdog.cycle_ns, None);
    assert_eq!(analysis.watchdog.risk, None);
    let json = serde_json::to_value(&analysis).unwrap();
    assert!(json["blocks"][1]["wcet_ns"].is_null());
}

#[test]
fn an_annotated_loop_is_counted_its_passes_as_the_run_counts_them() {
    let analysis = on_840c(LOOP);
    let fb = block(&analysis, "FB 1");
    assert_eq!(fb.loops[0].bound, Some(25));
    // The run does exactly 25 passes: its cycle is the static worst case.
    let (cpu, outcome) = one_cycle(LOOP);
    assert!(outcome.stop.is_none());
    assert_eq!(analysis.watchdog.cycle_ns, Some(cpu.clock));
    assert_eq!(fb.stretch_ns, fb.wcet_ns, "no point inside the FB");
}

#[test]
fn recursion_is_reported_as_such() {
    let source = "OB 1\n      JU PB 1\n      BE\nPB 1\n      JU PB 2\n      BE\nPB 2\n      A  I 0.0\n      JC PB 1\n      BE\n";
    let analysis = on_840c(source);
    assert_eq!(
        analysis.nesting.recursion.as_deref(),
        Some(&["PB 1".to_string(), "PB 2".into(), "PB 1".into()][..])
    );
    assert_eq!(analysis.nesting.max_depth, None);
    assert!(analysis.nesting.exceeds);
    assert!(
        block(&analysis, "PB 1")
            .unbounded
            .as_deref()
            .unwrap()
            .contains("recursion")
    );
}

/// A chain of `depth` blocks: OB 1 calls PB 1, PB 1 calls PB 2, …
fn chain(depth: u8) -> String {
    let mut text = String::from("OB 1\n      JU PB 1\n      BE\n");
    for n in 1..depth {
        let call = if n + 1 < depth {
            format!("      JU PB {}\n", n + 1)
        } else {
            String::new()
        };
        text.push_str(&format!("PB {n}\n{call}      BE\n"));
    }
    text
}

#[test]
fn a_chain_deeper_than_the_limit_is_flagged_and_stops_with_stueb() {
    let fits = on_840c(&chain(32));
    assert_eq!(fits.nesting.max_depth, Some(32));
    assert!(!fits.nesting.exceeds);
    assert!(one_cycle(&chain(32)).1.stop.is_none());

    let deep = on_840c(&chain(33));
    assert_eq!(deep.nesting.max_depth, Some(33));
    assert!(deep.nesting.exceeds);
    assert_eq!(deep.nesting.path.first().map(String::as_str), Some("OB 1"));
    assert_eq!(deep.nesting.path.last().map(String::as_str), Some("PB 32"));
    let stop = one_cycle(&chain(33)).1.stop.expect("STOP");
    assert_eq!(stop.cause.code(), "STUEB");
}

fn analyze_scenario(path: &str) -> Analysis {
    let prepared = runner::prepare(&RunOptions {
        scenario: Some(path.into()),
        ..RunOptions::default()
    })
    .unwrap_or_else(|_| panic!("{path}"));
    let cpu = &prepared.cpu;
    analyze::analyze(&cpu.program, &prepared.frontend.sources, Config::of(cpu))
}

#[test]
fn the_wake_up_risk_of_the_s5_95f() {
    // programs/weck.awl: OB 13 loops 2000 times, about 22 ms, every 10 ms: the run STOPs WECK.
    let weck = analyze_scenario("programs/weck.toml")
        .weck
        .expect("an S5-95F");
    assert_eq!(weck.interval_ns, Some(10_000_000));
    assert_eq!(weck.risk, Some(true));
    assert!(weck.margin_ns.unwrap() < 0);
    let quiet = analyze_scenario("programs/ob13_images.toml").weck.unwrap();
    assert_eq!(quiet.risk, Some(false));
}

#[test]
fn the_watchdog_risk_and_its_stop() {
    let slow = LOOP
        .replace("KF +25", "KF +30000")
        .replace("@bound 25", "@bound 30000");
    let risky = analysis(&slow, "sinumerik-840c", InterruptPoints::Block, 50_000_000);
    assert_eq!(risky.watchdog.risk, Some(true), "{:?}", risky.watchdog);
    let safe = analysis(
        &slow,
        "sinumerik-840c",
        InterruptPoints::Block,
        1_000_000_000,
    );
    assert_eq!(safe.watchdog.risk, Some(false));
    let profile = profile::find("sinumerik-840c").unwrap();
    let built = frontend::build_text("a.awl", &slow, profile);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    let config = EngineConfig {
        watchdog_ns: 50_000_000,
        ..EngineConfig::default()
    };
    cpu.engine = Engine::new(profile, config, Vec::new());
    let stop = cpu.run(RunLimit::Cycles(2)).stop.expect("STOP");
    assert_eq!(stop.cause.code(), "ZYK");
}

#[test]
fn blocks_never_called_and_code_never_reached() {
    let source = "OB 1\n      JU PB 1\n      BE\nPB 1\n      A  I 0.0\n      BEU\n      =  Q 4.0\n      BE\nPB 7\n      BE\n";
    let analysis = on_840c(source);
    assert_eq!(analysis.unused.blocks, ["PB 7"]);
    assert_eq!(analysis.unused.code.len(), 1);
    assert_eq!(analysis.unused.code[0].block, "PB 1");
    assert_eq!(analysis.unused.code[0].lines, [7, 8]);
}

#[test]
fn the_worse_branch_and_a_conditional_block_end() {
    // JC skips the heavy part; BEC may end early: the worst path runs everything.
    let source = "FB 1\nNAME :B\n      A  I 0.0\n      JC =M001\n      L  FW 2\n      L  FW 4\n      X  F\n      T  FW 6\nM001 :A  I 0.1\n      BEC\n      L  KF +1\n      BE\nOB 1\n      JU FB 1\nNAME :B\n      BE\n";
    let analysis = on_840c(source);
    let fb = block(&analysis, "FB 1");
    let profile = profile::find("sinumerik-840c").unwrap();
    let program = frontend::build_text("a.awl", source, profile)
        .compiled
        .program;
    let code = &program.blocks[usize::from(
        program
            .block_index(awl::ast::BlockId::parse("FB 1").unwrap())
            .unwrap(),
    )];
    let everything: u64 = (0..code.code.len()).map(|pc| code.cost(pc)).sum();
    assert_eq!(fb.wcet_ns, Some(everything));
}

#[test]
fn operation_points_bound_by_the_longest_operation() {
    let analysis = analysis(LOOP, "s5-95f", InterruptPoints::Operation, 150_000_000);
    let longest = analysis
        .blocks
        .iter()
        .filter_map(|b| b.stretch_ns)
        .max()
        .unwrap();
    assert!(analysis.response_bound_ns.unwrap() >= longest);
    assert!(analysis.response_bound_by.contains("operating-system time"));
}

#[test]
fn every_sample_s_analysis() {
    let mut all = String::new();
    for scenario in common::sample_scenarios() {
        let path = scenario.to_string_lossy().to_string();
        all.push_str(&format!("==== {path}\n"));
        all.push_str(&analyze::render(&analyze_scenario(&path)));
    }
    insta::assert_snapshot!(all);
}

/// The README shows the Fig. 5.2 analysis as `awl analyze` prints it now.
#[test]
fn the_readme_shows_the_current_analysis() {
    let text = analyze::render(&analyze_scenario("programs/fig5_2_interrupt.toml"));
    let readme = std::fs::read_to_string("README.md").unwrap();
    assert!(
        readme.contains(&text),
        "README.md's analysis of Fig. 5.2 is stale:\n{text}"
    );
}

fn on_speed7(source: &str) -> Analysis {
    analysis(source, "speed7", InterruptPoints::Operation, 150_000_000)
}

const S7_LOOP: &str = "FUNCTION FC 1 : VOID\nBEGIN\n      L     5;\nnext: T     MW 0;   // @bound 5\n      L     MW 0;\n      LOOP  next;\nEND_FUNCTION\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL FC 1;\nEND_ORGANIZATION_BLOCK\n";

#[test]
fn a_step7_loop_is_a_loop_with_its_bound_and_an_fc_call_is_a_call() {
    let analysis = on_speed7(S7_LOOP);
    let fc = block(&analysis, "FC 1");
    assert_eq!(fc.loops.len(), 1);
    assert_eq!(fc.loops[0].bound, Some(5));
    assert!(fc.wcet_ns.is_some());
    assert_eq!(block(&analysis, "OB 1").calls, vec!["FC 1"]);
    let unbounded = on_speed7(&S7_LOOP.replace("// @bound 5", ""));
    assert_eq!(block(&unbounded, "FC 1").wcet_ns, None);
}

/// A jump list whose second entry leads to the longer branch; `short` makes both as long.
fn jump_list(short: bool) -> String {
    let long = if short {
        ""
    } else {
        "      L 2;\n      T MW 6;\n      L 3;\n      T MW 8;\n"
    };
    format!(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L     MB 0;\n      JL    over;\n      JU    one;\n      JU    two;\nover: JU    done;\none:  L 1;\n      T MW 2;\n      JU    done;\ntwo:  L 1;\n      T MW 4;\n{long}      JU    done;\ndone: BEU;\nEND_ORGANIZATION_BLOCK\n"
    )
}

#[test]
fn every_entry_of_a_jump_list_is_a_path_and_the_end_after_beu_is_no_dead_code() {
    let long = on_speed7(&jump_list(false));
    let short = on_speed7(&jump_list(true));
    assert!(long.unused.code.is_empty(), "{:?}", long.unused.code);
    assert!(
        block(&long, "OB 1").wcet_ns > block(&short, "OB 1").wcet_ns,
        "the longer branch counts"
    );
}

/// OB 1 with a DIS_AIRT section around `inside` (an FC 1 call, a loop …), `after` after it,
/// and FC 1: a 10000-pass loop (about 0.3 ms).
fn airt_program(inside: &str, enable: bool, after: &str) -> String {
    let enable = if enable {
        "      CALL  SFC 42 (RET_VAL := MW 52);\n"
    } else {
        ""
    };
    format!(
        "FUNCTION FC 1 : VOID\nBEGIN\n      L     10000;\nnext: T     MW 0;   // @bound 10000\n      L     MW 0;\n      LOOP  next;\nEND_FUNCTION\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      L     1;\n      CALL  SFC 41 (RET_VAL := MW 50);\n{inside}{enable}{after}END_ORGANIZATION_BLOCK\n\nORGANIZATION_BLOCK OB 40\nBEGIN\n      L     MW 4;\nEND_ORGANIZATION_BLOCK\n"
    )
}

fn section(analysis: &Analysis, name: &str) -> analyze::AirtSection {
    block(analysis, name).airt_section.clone().unwrap()
}

/// "System Software for S7-300/400 System and Standard Functions", 12.4: the interrupts SFC 41
/// DIS_AIRT delays run after SFC 42 EN_AIRT, so a section as long as the called FC 1 sets the
/// response bound, and every interrupt OB's bound has it.
#[test]
fn a_dis_airt_section_with_its_calls_sets_the_response_bound() {
    let analysis = on_speed7(&airt_program("      CALL  FC 1;\n", true, ""));
    let fc = block(&analysis, "FC 1").wcet_ns.unwrap();
    let airt = section(&analysis, "OB 1");
    assert_eq!(airt.lines, Some([12, 14]));
    assert!(airt.ns.unwrap() > fc, "{airt:?} FC 1 {fc}");
    assert_eq!(analysis.response_bound_ns, airt.ns);
    assert!(
        analysis
            .response_bound_by
            .contains("SFC 41 DIS_AIRT section of OB 1, lines 12–14"),
        "{}",
        analysis.response_bound_by
    );
    let ob40 = analysis.obs.iter().find(|ob| ob.ob == 40).unwrap();
    assert!(ob40.response_bound_ns.unwrap() > airt.ns.unwrap());
    // Without DIS_AIRT the operating-system time sets the bound, and there is no section.
    let plain = on_speed7(
        &airt_program("      CALL  FC 1;\n", true, "")
            .replace("      CALL  SFC 41 (RET_VAL := MW 50);\n", ""),
    );
    assert!(block(&plain, "OB 1").airt_section.is_none());
    assert!(plain.response_bound_by.contains("operating-system time"));
}

/// 12.4: a delay without EN_AIRT ends with the OB that called DIS_AIRT: the section runs to
/// OB 1's end, through the work after the call of FC 1.
#[test]
fn a_section_without_en_airt_lasts_to_the_end_of_its_ob() {
    let closed = on_speed7(&airt_program("", true, "      CALL  FC 1;\n"));
    let open = on_speed7(&airt_program("", false, "      CALL  FC 1;\n"));
    let fc = block(&open, "FC 1").wcet_ns.unwrap();
    assert!(section(&closed, "OB 1").ns.unwrap() < fc);
    assert!(section(&open, "OB 1").ns.unwrap() > fc);
    assert_eq!(open.response_bound_ns, section(&open, "OB 1").ns);
}

/// A loop inside a section needs its bound; one after the section does not change the
/// response bound (with operation points only the section and the longest operation count).
#[test]
fn a_loop_without_bound_is_unbounded_only_inside_a_section() {
    let unbounded_loop =
        "      L     100;\nloop: T     MW 2;\n      L     MW 2;\n      LOOP  loop;\n";
    let inside = on_speed7(&airt_program(unbounded_loop, true, ""));
    assert_eq!(inside.response_bound_ns, None);
    assert!(inside.response_bound_by.contains("has no bound"));
    assert_eq!(section(&inside, "OB 1").ns, None);
    let after = on_speed7(&airt_program("", true, unbounded_loop));
    assert!(
        after.response_bound_ns.is_some(),
        "{}",
        after.response_bound_by
    );
    assert_eq!(block(&after, "OB 1").wcet_ns, None);
}

/// The sample: OB 1 copies its record inside a section about 1 ms long; the bound covers the
/// latencies the run shows (OB 40 waited up to 836 us for EN_AIRT).
#[test]
fn the_critical_section_sample_bounds_its_latencies() {
    let analysis = analyze_scenario("programs/s7/speed7_critical.toml");
    let airt = section(&analysis, "OB 1");
    assert!(airt.ns.unwrap() > 1_000_000, "{airt:?}");
    let ran = common::ran(runner::run(&RunOptions {
        scenario: Some("programs/s7/speed7_critical.toml".into()),
        ..RunOptions::default()
    }));
    let latest = ran.cpu.engine.stats(40).latency_max;
    let ob40 = analysis.obs.iter().find(|ob| ob.ob == 40).unwrap();
    assert!(latest > 800_000 && latest <= ob40.response_bound_ns.unwrap());
}
