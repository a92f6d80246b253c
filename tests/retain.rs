//! Retentive memory (`--retain`) and snapshots (`--snapshot`, `--from`) with `awl run`: what a
//! restart keeps and clears, a cold start, the files that do not fit, and a run continued from
//! a snapshot ending as the uninterrupted one. The servers' side is in tests/retain_serve.rs.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

const COUNTER: &str = "tests/inputs/retain/counter.awl";
const DELAY: &str = "tests/inputs/retain/delay.awl";

fn folder(name: &str) -> PathBuf {
    common::scratch("retain", name)
}

fn awl(args: &[&str]) -> Output {
    common::awl_run(args)
}

fn text(output: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// The watch table's last row, by column name, after a run of `args`.
fn last_row(args: &[&str], columns: &str) -> (Vec<String>, String) {
    let mut all = args.to_vec();
    all.extend(["--watch", columns]);
    let output = awl(&all);
    let printed = text(&output);
    assert!(output.status.success(), "{printed}");
    let rows: Vec<&str> = printed
        .lines()
        .take_while(|line| !line.starts_with("longest") && !line.starts_with("response"))
        .collect();
    let last = rows.last().expect("a watch row");
    let values = last
        .split("  ")
        .map(str::trim)
        .filter(|cell| !cell.is_empty())
        .skip(2)
        .map(str::to_string)
        .collect();
    (values, printed)
}

#[test]
fn a_restart_keeps_the_retentive_memory_and_clears_the_rest() {
    let retain = folder("restart").join("memory.json");
    let file = retain.to_str().unwrap();
    let run = [COUNTER, "--cycles", "10", "--retain", file];
    let (first, printed) = last_row(&run, "DB1.count, MD 0, MD 100");
    assert_eq!(first, ["L#10", "L#10", "L#10"], "{printed}");
    assert!(
        printed.contains("retentive memory: a first start from the source's values, kept in"),
        "{printed}"
    );
    // The data block and MD 0 (MB 0–15) are retentive on the SPEED7; MD 100 is not.
    let (second, printed) = last_row(&run, "DB1.count, MD 0, MD 100");
    assert_eq!(second, ["L#20", "L#20", "L#10"], "{printed}");
    assert!(
        printed.contains("retentive memory: loaded from"),
        "{printed}"
    );
    // A cold start: the source's values, and the file written anew with them.
    let mut cold = run.to_vec();
    cold.push("--cold");
    let (third, printed) = last_row(&cold, "DB1.count, MD 0, MD 100");
    assert_eq!(third, ["L#10", "L#10", "L#10"], "{printed}");
    assert!(
        printed.contains("a cold start from the source's values"),
        "{printed}"
    );
    let (fourth, _) = last_row(&run, "DB1.count, MD 0, MD 100");
    assert_eq!(fourth, ["L#20", "L#20", "L#10"]);
}

#[test]
fn an_s5_cpu_keeps_its_first_half_of_flags_its_timers_and_its_data_blocks() {
    let retain = folder("s5").join("memory.json");
    let file = retain.to_str().unwrap();
    let run = [DELAY, "--for", "2s", "--retain", file];
    let columns = "Q 4.0, FW 10, FW 200, DB 5 DW 0";
    let (first, _) = last_row(&run, columns);
    assert_eq!(first, ["0", "KF +4420", "KF +4420", "KF +4420"]);
    // T 1 (of T 0–127) keeps the 3 s it has left: still running after two more seconds…
    let (second, _) = last_row(&run, columns);
    assert_eq!(second, ["0", "KF +8840", "KF +4420", "KF +8840"]);
    // …and run out one second into the third run, 5 s after it started.
    let (third, _) = last_row(&run, columns);
    assert_eq!(third, ["1", "KF +13260", "KF +4420", "KF +13260"]);
}

#[test]
fn the_scenario_sets_the_retentive_ranges() {
    let folder = folder("ranges");
    let scenario = folder.join("ranges.toml");
    std::fs::write(
        &scenario,
        format!(
            "program = \"{}\"\nrun = {{ cycles = 10 }}\n[retentive]\nflag_bytes = 104\ndata_blocks = false\n",
            Path::new(env!("CARGO_MANIFEST_DIR")).join(COUNTER).display()
        ),
    )
    .unwrap();
    let retain = folder.join("memory.json");
    let run = [
        "--scenario",
        scenario.to_str().unwrap(),
        "--retain",
        retain.to_str().unwrap(),
    ];
    last_row(&run, "MD 100");
    let (second, printed) = last_row(&run, "DB1.count, MD 0, MD 100");
    assert_eq!(second, ["L#10", "L#20", "L#20"], "{printed}");

    std::fs::write(
        &scenario,
        "program = \"x.awl\"\n[retentive]\nflag_bytes = 100000\nretain = 1\n",
    )
    .unwrap();
    let output = awl(&["--scenario", scenario.to_str().unwrap()]);
    let printed = text(&output);
    assert!(!output.status.success());
    assert!(printed.contains("[retentive]"), "{printed}");
}

/// Runs the counter with `file` as its retentive memory file; the run must fail with `code`.
fn refused(file: &Path, more: &[&str], code: &str) -> String {
    let mut args = vec![COUNTER, "--cycles", "3", "--retain", file.to_str().unwrap()];
    args.extend(more);
    let output = awl(&args);
    let printed = text(&output);
    assert!(!output.status.success(), "{printed}");
    assert!(printed.contains(code), "{printed}");
    assert!(printed.contains(&file.display().to_string()), "{printed}");
    printed
}

#[test]
fn a_damaged_or_foreign_file_is_an_error_and_left_as_it_is() {
    let folder = folder("damaged");
    let good = folder.join("good.json");
    assert!(
        awl(&[COUNTER, "--cycles", "3", "--retain", good.to_str().unwrap()])
            .status
            .success()
    );
    let written = std::fs::read_to_string(&good).unwrap();
    let cases = [
        (
            "cut.json",
            written[..written.len() / 2].to_string(),
            "awl::retain::damaged",
        ),
        (
            "changed.json",
            written.replacen("\"number\": 1", "\"number\": 2", 1),
            "awl::retain::damaged",
        ),
        ("text.json", "DB1 = 5\n".to_string(), "awl::retain::foreign"),
        (
            "version.json",
            written.replacen("\"version\": 1", "\"version\": 7", 1),
            "awl::retain::foreign",
        ),
    ];
    for (name, contents, code) in cases {
        let file = folder.join(name);
        std::fs::write(&file, &contents).unwrap();
        let printed = refused(&file, &[], code);
        assert!(printed.contains("--cold"), "{printed}");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), contents, "{name}");
    }
    assert!(refused(&folder.join("changed.json"), &[], "checksum").contains("does not match"));
    // A snapshot is not retentive memory, nor the other way round.
    let snapshot = folder.join("snapshot.json");
    let output = awl(&[
        COUNTER,
        "--cycles",
        "3",
        "--snapshot",
        snapshot.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", text(&output));
    refused(&snapshot, &[], "awl::retain::foreign");
    let output = awl(&[COUNTER, "--from", good.to_str().unwrap()]);
    assert!(
        text(&output).contains("awl::retain::foreign"),
        "{}",
        text(&output)
    );
    // `--cold` starts afresh and writes the file anew.
    let cut = folder.join("cut.json");
    let output = awl(&[
        COUNTER,
        "--cycles",
        "3",
        "--retain",
        cut.to_str().unwrap(),
        "--cold",
    ]);
    assert!(output.status.success(), "{}", text(&output));
    assert!(
        awl(&[COUNTER, "--cycles", "3", "--retain", cut.to_str().unwrap()])
            .status
            .success()
    );
}

#[test]
fn a_file_of_a_changed_program_is_out_of_date_unless_what_fits_is_asked_for() {
    let folder = folder("changed");
    let file = folder.join("memory.json");
    let path = file.to_str().unwrap();
    assert!(
        awl(&[COUNTER, "--cycles", "7", "--retain", path])
            .status
            .success()
    );
    let longer = "tests/inputs/retain/counter_longer_db.awl";
    let output = awl(&[longer, "--cycles", "3", "--retain", path]);
    let printed = text(&output);
    assert!(!output.status.success(), "{printed}");
    assert!(printed.contains("awl::retain::out_of_date"), "{printed}");
    assert!(
        printed.contains("DB 1 is 8 bytes long in the program, 6 in the file"),
        "{printed}"
    );
    assert!(printed.contains("--retain-what-fits"), "{printed}");
    let fits = [
        longer,
        "--cycles",
        "3",
        "--retain",
        path,
        "--retain-what-fits",
    ];
    let (values, printed) = last_row(&fits, "DB1.count, MD 0");
    assert_eq!(values, ["L#3", "L#10"], "{printed}");
    assert!(
        printed.contains("not loaded: DB 1 is 8 bytes long"),
        "{printed}"
    );
    // Another CPU's file.
    let s5 = folder.join("s5.json");
    let s5_path = s5.to_str().unwrap();
    assert!(
        awl(&[DELAY, "--cycles", "3", "--retain", s5_path])
            .status
            .success()
    );
    let output = awl(&[
        DELAY, "--cycles", "3", "--retain", s5_path, "--cpu", "s5-115u",
    ]);
    let printed = text(&output);
    assert!(
        printed.contains("written by the sinumerik-840c CPU"),
        "{printed}"
    );
}

#[test]
fn the_retain_flags_need_their_file() {
    for flags in [&["--cold"][..], &["--retain-every", "2s"]] {
        let mut args = vec![COUNTER];
        args.extend(flags);
        let output = awl(&args);
        assert_eq!(output.status.code(), Some(2), "{}", text(&output));
        assert!(
            text(&output).contains("--retain <FILE>"),
            "{}",
            text(&output)
        );
    }
    let output = awl(&[COUNTER, "--retain", "x.json", "--retain-every", "0"]);
    assert_eq!(output.status.code(), Some(2));
    let output = awl(&[COUNTER, "--retain", "/no/such/folder/memory.json"]);
    let printed = text(&output);
    assert!(printed.contains("awl::retain::write"), "{printed}");
}

/// The end state as JSON of `awl run ARGS --state-format json`.
fn end_state(args: &[&str]) -> String {
    let mut all = args.to_vec();
    all.extend(["--state-format", "json"]);
    let output = awl(&all);
    String::from_utf8_lossy(&output.stdout).into_owned()
}

#[test]
fn a_run_continued_from_a_snapshot_ends_as_the_uninterrupted_run() {
    let folder = folder("continued");
    let mut compared = 0;
    for scenario in common::sample_scenarios() {
        let scenario = scenario.to_str().unwrap();
        let whole = end_state(&["--scenario", scenario]);
        let snapshot = folder.join("snapshot.json");
        let at = "3ms";
        let taken = awl(&[
            "--scenario",
            scenario,
            "--snapshot",
            snapshot.to_str().unwrap(),
            "--snapshot-at",
            at,
        ]);
        // A run that went to STOP before the snapshot's time continues with a restart.
        if text(&taken).contains("mode at end: STOP") {
            continue;
        }
        let continued = end_state(&["--scenario", scenario, "--from", snapshot.to_str().unwrap()]);
        assert_eq!(continued, whole, "{scenario}");
        compared += 1;
    }
    assert!(compared >= 30, "only {compared} samples compared");
}

#[test]
fn from_takes_a_time_and_a_snapshot_once_each() {
    let folder = folder("from");
    let snapshot = folder.join("at.json");
    let path = snapshot.to_str().unwrap();
    assert!(
        awl(&[COUNTER, "--cycles", "5", "--snapshot", path])
            .status
            .success()
    );
    let output = awl(&[COUNTER, "--cycles", "9", "--from", path, "--from", path]);
    assert!(
        text(&output).contains("awl::cli::from_twice"),
        "{}",
        text(&output)
    );
    let output = awl(&[COUNTER, "--from", "10ms"]);
    assert!(text(&output).contains("awl::cli::window_needs_output"));
    let output = awl(&[COUNTER, "--from", "soon"]);
    assert!(
        text(&output).contains("neither a time"),
        "{}",
        text(&output)
    );
    let both = [
        COUNTER, "--cycles", "9", "--from", path, "--from", "0.3ms", "--trace", "-",
    ];
    let output = awl(&both);
    let printed = text(&output);
    assert!(output.status.success(), "{printed}");
    assert!(printed.contains("cycles: 9"), "{printed}");
}

/// The README's example is what the binary prints.
#[test]
fn the_readme_example_is_what_awl_prints() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let example = readme
        .split("```\n")
        .find(|block| block.starts_with("$ awl run tests/inputs/retain/counter.awl"))
        .expect("the README's retentive memory example");
    let folder = folder("readme");
    let mut printed = String::new();
    for line in example
        .lines()
        .filter(|line| line.starts_with("$ awl run "))
    {
        let args: Vec<&str> = line
            .trim_start_matches("$ awl run ")
            .split('"')
            .enumerate()
            .flat_map(|(at, part)| match at % 2 {
                0 => part.split_whitespace().collect::<Vec<_>>(),
                _ => vec![part],
            })
            .map(|arg| if arg == "memory.json" { "" } else { arg })
            .collect();
        let memory = folder.join("memory.json");
        let args: Vec<&str> = args
            .iter()
            .map(|arg| {
                if arg.is_empty() {
                    memory.to_str().unwrap()
                } else {
                    arg
                }
            })
            .collect();
        let output = awl(&args);
        printed.push_str(line);
        printed.push('\n');
        printed.push_str(&String::from_utf8_lossy(&output.stdout));
    }
    assert_eq!(printed, example);
}
