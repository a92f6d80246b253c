//! The online page (`awl serve --http`) in a real browser: headless Chromium, driven through the
//! DevTools protocol, opens the page the binary serves, with a watch table and a status block
//! preloaded from its address, and is used as a person uses it — a value the program counts
//! changes live, modify and force act from the rows' buttons, a forced input beats a
//! python-snap7 write, program status shows the RLO, the timeline draws, STOP and the restarts
//! act from the buttons, a program's STOP shows its cause and report, a read-only serve greys
//! the controls — in both dialects, with no console error. Where Chromium is missing the tests
//! fail, saying how to install it; python-snap7 comes from the tests' own Python environment.

mod common;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use common::browser::{DevTools, Tab, chromium};
use common::serve::Serving;

/// Long enough for a debug build's CPU to answer a few refreshes of the page.
const WITHIN: Duration = Duration::from_secs(20);

/// A running `awl serve … --http 127.0.0.1:0 --s7 127.0.0.1:0` and the ports it printed.
struct Served {
    _serving: Serving,
    http: u16,
    s7: u16,
}

impl Served {
    fn start(args: &[&str]) -> Served {
        let args = [args, &["--http", "127.0.0.1:0", "--s7", "127.0.0.1:0"]].concat();
        let (serving, ports) =
            Serving::start(&args, &["Online page at ", "S7 server listening on "]);
        Served {
            _serving: serving,
            http: ports[0],
            s7: ports[1],
        }
    }

    /// The page's address with `query` (already encoded).
    fn page(&self, query: &str) -> String {
        format!("http://127.0.0.1:{}/{query}", self.http)
    }
}

/// Chromium with a profile of its own, in a temporary directory of its own.
fn browser(name: &str) -> (DevTools, PathBuf) {
    let dir = std::env::temp_dir().join(format!("awl-online-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let devtools = DevTools::start(&chromium(), &dir.join("profile"), "1400,1000");
    (devtools, dir)
}

/// `text` as a JavaScript string literal.
fn js(text: &str) -> String {
    json!(text).to_string()
}

/// The page, driven as a person drives it: through its elements.
struct Online<'a> {
    tab: Tab<'a>,
}

impl<'a> Online<'a> {
    /// Opens `url` and waits until the page has the CPU's first answer and the address's rows.
    fn open(devtools: &'a mut DevTools, url: &str) -> Online<'a> {
        let mut tab = devtools.open(url);
        tab.wait_for("document.body.dataset.ready === 'yes'", WITHIN);
        Online { tab }
    }

    fn eval(&mut self, expression: &str) -> Value {
        self.tab.eval(expression)
    }

    fn wait_for(&mut self, expression: &str) {
        self.tab.wait_for(expression, WITHIN);
    }

    /// The text of the first element `selector` matches ("" when none does).
    fn text(&mut self, selector: &str) -> String {
        let found = self.eval(&format!(
            "(document.querySelector({}) || {{ textContent: '' }}).textContent",
            js(selector)
        ));
        found.as_str().unwrap_or_default().to_string()
    }

    fn click(&mut self, selector: &str) {
        self.eval(&format!("document.querySelector({}).click()", js(selector)));
    }

    /// Waits until the element's text is `wanted`.
    fn wait_for_text(&mut self, selector: &str, wanted: &str) {
        let expression = format!(
            "(document.querySelector({}) || {{}}).textContent === {}",
            js(selector),
            js(wanted)
        );
        let deadline = Instant::now() + WITHIN;
        while self.eval(&expression) != json!(true) {
            assert!(
                Instant::now() < deadline,
                "{selector} is {:?}, not {wanted:?}",
                self.text(selector)
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Waits until the diagnostic buffer has an entry that says `text`.
    fn wait_for_diagnostic(&mut self, text: &str) {
        self.wait_for(&format!(
            "document.getElementById('diagnostics').textContent.includes({})",
            js(text)
        ));
    }

    /// Whether the element is disabled.
    fn disabled(&mut self, selector: &str) -> bool {
        self.eval(&format!(
            "document.querySelector({}).disabled",
            js(selector)
        )) == json!(true)
    }

    fn row(operand: &str) -> String {
        format!("#watch tr[data-operand={}]", js(operand))
    }

    /// The value the watch row of `operand` shows.
    fn value(&mut self, operand: &str) -> String {
        self.text(&format!("{} td.value", Online::row(operand)))
    }

    fn wait_for_value(&mut self, operand: &str, wanted: &str) {
        self.wait_for_text(&format!("{} td.value", Online::row(operand)), wanted);
    }

    /// Types `value` into the row's value field and presses the row's `button` (`modify`,
    /// `force`, `unforce`).
    fn press(&mut self, operand: &str, button: &str, value: &str) {
        let row = Online::row(operand);
        self.eval(&format!(
            "document.querySelector({}).value = {}",
            js(&format!("{row} .modify-value")),
            js(value)
        ));
        self.click(&format!("{row} .{button}"));
    }

    /// The refusal shown below the row of `operand`, once there is one.
    fn refusal(&mut self, operand: &str) -> String {
        let message = format!("{} + tr.message:not([hidden])", Online::row(operand));
        self.wait_for(&format!(
            "document.querySelector({}) !== null",
            js(&message)
        ));
        self.text(&message)
    }

    /// Adds a row as a person does: the operand typed into the field below the table.
    fn add(&mut self, operand: &str) {
        self.eval(&format!(
            "document.getElementById('add-operand').value = {}",
            js(operand)
        ));
        self.click("#add");
    }

    /// The watch rows' operands, in order.
    fn operands(&mut self) -> Vec<String> {
        let found = self.eval(
            "Array.from(document.querySelectorAll('#watch tr[data-operand]'), (row) => row.dataset.operand)",
        );
        serde_json::from_value(found).expect("a list of operands")
    }

    /// The formats the first row's select offers.
    fn formats(&mut self) -> Vec<String> {
        let found = self.eval(
            "Array.from(document.querySelectorAll('#watch tr[data-operand] select.format option'), (option) => option.value).filter(Boolean)",
        );
        serde_json::from_value(found).expect("a list of formats")
    }

    /// Waits until the row of `operand` shows a value that is neither the first placeholder
    /// nor `than`; that value.
    fn value_other_than(&mut self, operand: &str, than: &str) -> String {
        let deadline = Instant::now() + WITHIN;
        loop {
            let value = self.value(operand);
            if value != than && value != "…" && !value.is_empty() {
                return value;
            }
            assert!(
                Instant::now() < deadline,
                "{operand} stays {value:?} on the page"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// The problems the page had (console messages, uncaught exceptions, logged errors).
    fn problems(&self) -> Vec<String> {
        self.tab.problems().to_vec()
    }
}

/// The page the binary serves loads nothing from anywhere else.
fn assert_self_contained(online: &mut Online) {
    let html = online.eval("fetch('/').then((answer) => answer.text())");
    let html = html.as_str().expect("the page");
    for outside in [" src=", "@import", "url(", "http://", "https://"] {
        assert!(!html.contains(outside), "the page loads nothing: {outside}");
    }
}

/// Takes a screenshot of the page, for a person to look at, into cargo's directory for the
/// tests' files (target/tmp); checks that it is not blank.
fn screenshot(online: &mut Online, name: &str) {
    let png = online.tab.screenshot();
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).expect("a PNG screenshot");
    let drawn = pixmap
        .pixels()
        .iter()
        .filter(|pixel| (pixel.red(), pixel.green(), pixel.blue()) != (255, 255, 255))
        .count();
    assert!(
        drawn * 20 > pixmap.pixels().len(),
        "the screenshot is blank"
    );
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, &png).expect("the screenshot is written");
    println!("screenshot: {}", path.display());
}

/// Program status shows the block's lines with the RLO, one of them `statement`.
fn assert_status_shows_the_rlo(online: &mut Online, statement: &str) {
    online.wait_for(
        "Array.from(document.querySelectorAll('#status td.rlo'), (cell) => cell.textContent)
            .some((rlo) => rlo === '0' || rlo === '1')",
    );
    let lines = online.text("#status");
    assert!(lines.contains(statement), "{lines}");
}

/// The live timeline is the SVG the static timeline draws, OB 1's lane in it.
fn assert_timeline_draws(online: &mut Online) {
    online.wait_for("document.querySelector('#timeline svg') !== null");
    assert!(online.text("#timeline").contains("OB 1"));
}

/// Under the mouse the timeline holds still, to be read; it goes on once the mouse leaves.
fn timeline_holds_still_under_the_mouse(online: &mut Online) {
    let mouse = |event: &str| {
        format!("document.getElementById('timeline').dispatchEvent(new MouseEvent('{event}'))")
    };
    let drawn = "document.getElementById('timeline').innerHTML";
    online.eval(&mouse("mouseenter"));
    let held = online.eval(drawn);
    std::thread::sleep(Duration::from_secs(1));
    assert_eq!(online.eval(drawn), held, "the timeline held still");
    online.eval(&mouse("mouseleave"));
    online.wait_for(&format!("{drawn} !== {held}"));
}

/// No console message, uncaught exception or logged error, but for the answers of status
/// `refused` (a request refused on purpose: Chromium logs each such answer).
fn assert_no_problems(online: &Online, refused: Option<u16>) {
    let problems: Vec<String> = online
        .problems()
        .into_iter()
        .filter(|problem| {
            refused.is_none_or(|status| {
                !problem.contains(&format!("the server responded with a status of {status}"))
            })
        })
        .collect();
    assert!(problems.is_empty(), "{problems:?}");
}

/// Stop from the STOP button, then a restart from its button; the page follows each mode.
fn stop_and_restart(online: &mut Online, restart: &str) {
    assert!(online.disabled(restart), "a restart is greyed in RUN");
    online.click("#stop");
    online.wait_for_text("#mode", "STOP");
    online.wait_for("document.querySelector('#diagnostics li.mode') !== null");
    assert!(online.disabled("#stop"), "STOP is greyed in STOP");
    online.wait_for(&format!(
        "!document.querySelector({}).disabled",
        js(restart)
    ));
    online.click(restart);
    online.wait_for_text("#mode", "RUN");
}

/// Writes `value` into the input word `IW byte` as an HMI or a plant simulation does: with
/// python-snap7, to the S7 port.
fn snap7_writes_input_word(s7: u16, byte: u16, value: u16) {
    let script = "import sys, snap7\n\
        from snap7.type import Area\n\
        plc = snap7.client.Client()\n\
        plc.connect('127.0.0.1', 0, 2, tcp_port=int(sys.argv[1]))\n\
        plc.write_area(Area.PE, 0, int(sys.argv[2]), bytearray(int(sys.argv[3]).to_bytes(2, 'big')))\n";
    let output = common::python::command(&common::python::with("snap7"))
        .args(["-c", script])
        .args([s7.to_string(), byte.to_string(), value.to_string()])
        .output()
        .expect("python runs");
    assert!(
        output.status.success(),
        "python-snap7's write failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn a_step7_tank_is_watched_modified_forced_and_restarted_from_the_page() {
    let (mut devtools, dir) = browser("s7");
    let served = Served::start(&["--scenario", "programs/s7/tank_hmi_serve.toml"]);
    // The cycle count, the level the program copies from IW 0, the level sensor, the restarts
    // (as hex), the pump and the setpoint.
    let url = served.page(
        "?watch=DB1.DBD%206,DB1.DBW%202,IW%200,MW%2020%20HEX,Q%200.0,DB1.DBW%200&status=OB%201",
    );
    let mut online = Online::open(&mut devtools, &url);
    assert_self_contained(&mut online);
    online.wait_for_text("#mode", "RUN");
    let notation = online.text("#dialect");
    assert!(
        notation.contains("STEP 7") && notation.contains("English"),
        "{notation}"
    );
    assert_eq!(
        online.operands(),
        [
            "DB1.DBD 6",
            "DB1.DBW 2",
            "IW 0",
            "MW 20",
            "Q 0.0",
            "DB1.DBW 0"
        ]
    );
    let formats = online.formats();
    assert!(formats.contains(&"S5TIME".to_string()), "{formats:?}");
    assert!(!formats.contains(&"KT".to_string()), "{formats:?}");
    assert!(!formats.contains(&"KZ".to_string()), "{formats:?}");
    let chosen = online.eval(&format!(
        "document.querySelector({}).value",
        js(&format!("{} select", Online::row("MW 20")))
    ));
    assert_eq!(chosen, "HEX");

    // Live: the cycle count goes on between two looks.
    let first = online.value_other_than("DB1.DBD 6", "");
    assert!(first.starts_with("L#"), "{first}");
    online.value_other_than("DB1.DBD 6", &first);
    online.wait_for_value("MW 20", "W#16#0001");

    // Modify: the setpoint, once, at the next control point.
    online.wait_for_value("DB1.DBW 0", "500");
    online.press("DB1.DBW 0", "modify", "600");
    online.wait_for_value("DB1.DBW 0", "600");

    // Force: the level sensor held at 100 against python-snap7's write of 700; the banner shows
    // while it is forced.
    assert_eq!(
        online.eval("document.getElementById('forces-banner').hidden"),
        true
    );
    online.press("IW 0", "force", "100");
    online.wait_for("!document.getElementById('forces-banner').hidden");
    assert!(online.text("#forces-banner").contains("IW 0 = 100"));
    online.wait_for_value("IW 0", "100");
    online.wait_for_value("DB1.DBW 2", "100");
    snap7_writes_input_word(served.s7, 0, 700);
    // Many cycles and two refreshes of the page.
    std::thread::sleep(Duration::from_millis(600));
    assert_eq!(online.value("IW 0"), "100", "the force beat the write");
    assert_eq!(
        online.value("DB1.DBW 2"),
        "100",
        "the program read the force"
    );
    online.press("IW 0", "unforce", "");
    online.wait_for_value("DB1.DBW 2", "700");
    online.wait_for("document.getElementById('forces-banner').hidden");
    online.wait_for_diagnostic("IW 0 forced to 100");

    // A bit forced: the row is marked, its value is the force's, until all are unforced.
    online.press("Q 0.0", "force", "1");
    online.wait_for_value("Q 0.0", "1");
    online.wait_for(&format!(
        "document.querySelector({}).classList.contains('forced')",
        js(&Online::row("Q 0.0"))
    ));
    online.click("#unforce-all");
    online.wait_for("document.getElementById('forces-banner').hidden");
    online.wait_for_value("Q 0.0", "0");
    let only_io = format!(
        "document.querySelector({}) === null",
        js(&format!("{} .force", Online::row("MW 20")))
    );
    assert_eq!(
        online.eval(&only_io),
        true,
        "only inputs and outputs are forced"
    );

    assert_status_shows_the_rlo(&mut online, "DB1.DBW 2");
    assert!(online.text("#status thead").contains("RLO"));
    // The pump does not start, so the count of its starts is skipped: those lines are marked.
    online.wait_for(
        "Array.from(document.querySelectorAll('#status tr.not-executed'))
            .some((row) => row.textContent.includes('DB1.DBW 4'))",
    );
    assert_timeline_draws(&mut online);
    timeline_holds_still_under_the_mouse(&mut online);
    assert_no_problems(&online, None);
    screenshot(&mut online, "online-page-s7.png");

    // A refusal stands below its row, in the command line's words with its help; the other
    // rows go on.
    let before = online.value("DB1.DBD 6");
    online.add("XYZ 99");
    let refusal = online.refusal("XYZ 99");
    assert!(refusal.contains("not a STEP 7 operand"), "{refusal}");
    assert!(refusal.contains("help:"), "{refusal}");
    online.value_other_than("DB1.DBD 6", &before);
    online.click(&format!("{} .remove", Online::row("XYZ 99")));
    online.press("DB1.DBW 0", "modify", "abc");
    let refusal = online.refusal("DB1.DBW 0");
    assert!(refusal.contains("`abc` is no value"), "{refusal}");

    // STOP and warm restart from the buttons: OB 100 counts the restart.
    stop_and_restart(&mut online, "#warm");
    online.wait_for_value("MW 20", "W#16#0002");

    // Saved as the file `awl run --watch-file` reads, and loaded back.
    let saved = online.eval(
        "new Promise((resolve) => {
            HTMLAnchorElement.prototype.click = function () {
                fetch(this.href).then((answer) => answer.text()).then(resolve);
            };
            document.getElementById('save').click();
        })",
    );
    let saved = saved.as_str().expect("the saved table");
    assert!(saved.starts_with("// "), "{saved}");
    assert!(saved.contains("\nMW 20 HEX\n"), "{saved}");
    assert!(saved.contains("\nDB1.DBD 6\n"), "{saved}");
    the_command_line_reads(saved, &dir);
    load(
        &mut online,
        "// the pump and the restarts\nMW 20 DEC\n\nQ 0.0 // the pump\n",
    );
    assert_eq!(online.operands(), ["MW 20", "Q 0.0"]);
    online.wait_for_value("MW 20", "2");
    let address = online.eval("decodeURIComponent(location.search).replace(/\\+/g, ' ')");
    assert_eq!(address, "?watch=MW 20 DEC,Q 0.0&status=OB 1");

    assert_no_problems(&online, Some(400));
    drop(online);
    drop(devtools);
    let _ = std::fs::remove_dir_all(dir);
}

/// `awl run --watch-file` reads a table the page saved: a column for each row, in its format.
fn the_command_line_reads(saved: &str, dir: &Path) {
    let file = dir.join("saved.watch");
    std::fs::write(&file, saved).expect("the table is written");
    let ran = std::process::Command::new(env!("CARGO_BIN_EXE_awl"))
        .args([
            "run",
            "programs/s7/tank_hmi.awl",
            "--cycles",
            "2",
            "--watch-file",
        ])
        .arg(&file)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("awl runs");
    let stdout = String::from_utf8_lossy(&ran.stdout);
    assert!(
        ran.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    let header = stdout.lines().next().unwrap_or_default();
    assert!(header.contains("MW 20 HEX"), "{stdout}");
    assert!(header.contains("DB1.DBD 6"), "{stdout}");
}

/// Loads `table` as a person does, through the file field.
fn load(online: &mut Online, table: &str) {
    online.eval(&format!(
        "(() => {{
            const files = new DataTransfer();
            files.items.add(new File([{}], 'table.txt'));
            const input = document.getElementById('load');
            input.files = files.files;
            input.dispatchEvent(new Event('change'));
        }})()",
        js(table)
    ));
    let rows = table
        .lines()
        .filter_map(|line| line.split("//").next())
        .filter(|line| !line.trim().is_empty())
        .count();
    online.wait_for(&format!(
        "document.querySelectorAll('#watch tr[data-operand]').length === {rows}"
    ));
}

#[test]
fn a_step5_tank_on_an_s5_115u_is_shown_in_step_5_s_notation() {
    let (mut devtools, dir) = browser("s5");
    let served = Served::start(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    // The cycle count, the restarts as a count, the pump and the setpoint.
    let url =
        served.page("?watch=DB%201%20DW%203,FW%2020%20KZ,Q%200.0,DB%201%20DW%200&status=FB%201");
    let mut online = Online::open(&mut devtools, &url);
    online.wait_for_text("#mode", "RUN");
    let notation = online.text("#dialect");
    assert!(
        notation.contains("STEP 5") && notation.contains("English"),
        "{notation}"
    );
    let formats = online.formats();
    assert!(formats.contains(&"KT".to_string()), "{formats:?}");
    assert!(formats.contains(&"KZ".to_string()), "{formats:?}");
    assert!(!formats.contains(&"S5TIME".to_string()), "{formats:?}");

    let first = online.value_other_than("DB 1 DW 3", "");
    assert!(first.starts_with("KF +"), "{first}");
    online.value_other_than("DB 1 DW 3", &first);
    online.wait_for_value("FW 20", "KZ 001");
    online.press("DB 1 DW 0", "modify", "200");
    online.wait_for_value("DB 1 DW 0", "KF +200");
    online.press("Q 0.0", "force", "1");
    online.wait_for("!document.getElementById('forces-banner').hidden");
    online.wait_for_value("Q 0.0", "1");
    online.click("#unforce-all");
    online.wait_for("document.getElementById('forces-banner').hidden");

    assert_status_shows_the_rlo(&mut online, ":L    IW 0");
    assert_timeline_draws(&mut online);
    // A cold restart from the buttons loads the data blocks anew: the setpoint is the
    // program's again.
    stop_and_restart(&mut online, "#cold");
    online.wait_for_value("DB 1 DW 0", "KF +500");
    online.wait_for_diagnostic("cold restart");
    screenshot(&mut online, "online-page-s5.png");
    assert_no_problems(&online, None);
    drop(online);
    drop(devtools);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_read_only_serve_greys_every_control_that_changes_the_cpu() {
    let (mut devtools, dir) = browser("read-only");
    let served = Served::start(&["programs/s7/tank_hmi.awl", "--read-only"]);
    let mut online = Online::open(&mut devtools, &served.page("?watch=DB1.DBD%206,IW%200"));
    online.wait_for("!document.getElementById('read-only-note').hidden");
    let first = online.value_other_than("DB1.DBD 6", "");
    online.value_other_than("DB1.DBD 6", &first);
    for control in ["#stop", "#warm", "#cold", "#unforce-all"] {
        assert!(online.disabled(control), "{control} is greyed");
    }
    let enabled = online.eval(
        "Array.from(document.querySelectorAll('#watch .modify-value, #watch .modify, #watch .force, #watch .unforce'))
            .filter((control) => !control.disabled).length",
    );
    assert_eq!(enabled, 0, "modify and force are greyed");
    let changes = online.eval("document.querySelectorAll('#watch .changes').length");
    assert_eq!(
        changes,
        2 * 2 + 2,
        "two modify fields and buttons, one force and unforce"
    );
    // Rows added later are greyed too; reading goes on.
    online.add("MW 20");
    online.wait_for_value("MW 20", "1");
    assert!(online.disabled(&format!("{} .modify", Online::row("MW 20"))));
    online.click("#stop");
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(online.text("#mode"), "RUN");
    assert_no_problems(&online, None);
    drop(online);
    drop(devtools);
    let _ = std::fs::remove_dir_all(dir);
}

/// Counts its cycles in MW 0 and calls a block that is not loaded in the 50th: STOP.
const STOPS: &str = "ORGANIZATION_BLOCK OB 1
VAR_TEMP
  info : ARRAY [0..19] OF BYTE;
END_VAR
BEGIN
      L     MW 0;
      +     1;
      T     MW 0;
      L     MW 0;
      L     50;
      <I;
      BEC;
      CALL  FC 99;
END_ORGANIZATION_BLOCK
";

#[test]
fn a_program_s_stop_shows_its_cause_its_report_and_its_diagnostic_entry() {
    let (mut devtools, dir) = browser("stop");
    let program = dir.join("stops.awl");
    std::fs::write(&program, STOPS).expect("the program is written");
    let served = Served::start(&[program.to_str().expect("a UTF-8 path")]);
    let mut online = Online::open(&mut devtools, &served.page("?watch=MW%200"));
    online.wait_for_text("#mode", "STOP");
    online.wait_for("!document.getElementById('stop-box').hidden");
    assert_eq!(online.text("#stop-cause"), "STOP: LZF in OB 1, line 13");
    let report = online.text("#stop-report");
    assert!(report.contains("FC 99 is not loaded"), "{report}");
    online.wait_for("document.querySelector('#diagnostics li.stop') !== null");
    online.wait_for_value("MW 0", "50");
    assert!(online.disabled("#stop"));
    assert!(!online.disabled("#warm"));
    assert_no_problems(&online, None);
    drop(online);
    drop(devtools);
    let _ = std::fs::remove_dir_all(dir);
}
