//! `awl test` over many scenario files: run in parallel, reported in the order given, and as
//! JUnit XML that a CI system reads (parsed here by roxmltree).

mod common;

use std::process::{Command, Output};

fn awl_test(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_awl"))
        .arg("test")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("awl runs")
}

/// The sample scenarios, three times over: about 120 files.
fn many() -> Vec<String> {
    let samples: Vec<String> = common::sample_scenarios()
        .iter()
        .map(|path| path.to_str().unwrap().to_string())
        .collect();
    samples
        .iter()
        .chain(&samples)
        .chain(&samples)
        .cloned()
        .collect()
}

#[test]
fn scenarios_run_in_parallel_are_reported_in_the_order_given() {
    let scenarios = many();
    let mut args: Vec<&str> = scenarios.iter().map(String::as_str).collect();
    args.extend(["--jobs", "4"]);
    let output = awl_test(&args);
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{printed}");
    let reported: Vec<&str> = printed
        .lines()
        .filter_map(|line| line.strip_prefix("PASS "))
        .map(|line| line.split("  ").next().unwrap())
        .collect();
    assert_eq!(reported, scenarios);
    assert!(printed.ends_with(&format!("{} passed, 0 failed\n", scenarios.len())));
}

#[test]
fn junit_xml_has_a_testcase_per_scenario_with_its_failure_or_error() {
    let folder = common::scratch("test-command", "junit");
    let broken = folder.join("broken.toml");
    std::fs::write(
        folder.join("broken.awl"),
        "OB 1\n      A  I 0.0\n      XYZ Q 4.0\n      BE\n",
    )
    .unwrap();
    std::fs::write(
        &broken,
        "program = \"broken.awl\"\n[expect]\n\"Q 4.0\" = 1\n",
    )
    .unwrap();
    let output = awl_test(&[
        "programs/fig5_2.toml",
        "tests/scenarios/failing.toml",
        broken.to_str().unwrap(),
        "--format",
        "junit",
    ]);
    assert_eq!(output.status.code(), Some(4));
    let xml = String::from_utf8(output.stdout).unwrap();
    let document = roxmltree::Document::parse(&xml).expect("well-formed XML");
    let suite = document
        .descendants()
        .find(|node| node.has_tag_name("testsuite"))
        .expect("a test suite");
    assert_eq!(suite.attribute("tests"), Some("3"));
    assert_eq!(suite.attribute("failures"), Some("1"));
    assert_eq!(suite.attribute("errors"), Some("1"));
    let cases: Vec<_> = suite
        .children()
        .filter(|node| node.has_tag_name("testcase"))
        .collect();
    assert_eq!(cases[0].attribute("name"), Some("programs/fig5_2.toml"));
    assert!(cases[0].children().all(|node| !node.is_element()));
    let failure = cases[1]
        .children()
        .find(|node| node.has_tag_name("failure"))
        .unwrap();
    assert_eq!(
        failure.attribute("message"),
        Some("Q 4.0 expected 1, got 0")
    );
    let error = cases[2]
        .children()
        .find(|node| node.has_tag_name("error"))
        .unwrap();
    assert_eq!(error.attribute("message"), Some("the program has errors"));
    assert!(error.text().unwrap_or("").contains("XYZ"), "{xml}");
    // Stdout holds the XML alone; the diagnostics go to stderr.
    assert!(String::from_utf8_lossy(&output.stderr).contains("XYZ"));
}

#[test]
fn jobs_must_be_one_or_more() {
    let output = awl_test(&["programs/fig5_2.toml", "--jobs", "0"]);
    assert_eq!(output.status.code(), Some(2));
}
