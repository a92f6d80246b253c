// The playground page: editors, the examples menu, runs, the debugger and live mode. Every
// answer comes from awl's WebAssembly module (JSON in, JSON out); this script only shows it.
// Runs and debugger sessions go to a worker (web/worker.js), so the page never freezes.
// web/common.js comes before it.

const LINE_HEIGHT = 18;
const MS = 1e6;

function escapeHtml(text) {
  return text.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
}

function span(kind, text) {
  return kind ? `<span class="t-${kind}">${escapeHtml(text)}</span>` : escapeHtml(text);
}

// ---------------------------------------------------------------------------------------------
// Colouring. STL words come from awl's own tables (both mnemonic sets), TOML by its few forms.

function wordSets(words) {
  const set = (list) => new Set(list.map((word) => word.toUpperCase()));
  return {
    operations: set(words.operations),
    areas: set(words.areas),
    constants: set(words.constants),
    blocks: set(words.blocks),
    keywords: set(words.keywords),
    step7: {
      operations: set(words.step7.operations),
      areas: set(words.step7.areas),
      keywords: set(words.step7.keywords),
      lineWords: set(words.step7.line_words),
      blocks: set(words.blocks.concat(["FC", "FB", "SFC", "SFB", "UDT"])),
    },
  };
}

/** Whether `text` is STEP 7: a line opens with a word only a STEP 7 source writes. */
function isStep7(step7, text) {
  return text.split("\n").some((line) => {
    const first = /^\s*([A-Za-z_]+)/.exec(line);
    const upper = first ? first[1].toUpperCase() : "";
    return step7.lineWords.has(upper) || upper.startsWith("END_");
  });
}

/** Where a `;` or `//` comment starts outside quotes, or -1. */
function commentStart(line, markers) {
  let quoted = false;
  for (let i = 0; i < line.length; i++) {
    if (line[i] === "'") quoted = !quoted;
    if (!quoted && markers.some((marker) => line.startsWith(marker, i))) return i;
  }
  return -1;
}

const STL_TOKEN = /((?:!=|><|>=|<=|>|<|[+-])F\b|=(?=\s|$))|('[^']*'?)|(=[A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*)|(-[A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*)|([A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*)|([+-]?[0-9][\w.]*)|(\s+)|(.)/gi;

/** A word's colour by its place: a label, before the operation (a block header such as
 *  `PB 3`, or the operation), or in the operand (`PB` of `JU PB 3`, `KF`, `I`). */
function stlWordKind(words, upper, place) {
  if (place === "label") return words.keywords.has(upper) ? "keyword" : "label";
  if (words.blocks.has(upper)) return "block";
  if (place === "operation") {
    if (words.operations.has(upper)) return "op";
    return words.keywords.has(upper) ? "keyword" : "";
  }
  if (words.constants.has(upper)) return "const";
  return words.areas.has(upper) ? "area" : "";
}

function colourStl(words, line) {
  const at = commentStart(line, [";", "//"]);
  const code = at < 0 ? line : line.slice(0, at);
  const comment = at < 0 ? "" : line.slice(at);
  let html = "";
  let operationSeen = false;
  let afterBlock = false;
  let first = true;
  const labelled = /^\s*[A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*\s*:/.test(code);
  for (const match of code.matchAll(STL_TOKEN)) {
    const [text, sign, quoted, jump, symbol, word, number, space] = match;
    let kind = "";
    if (sign) kind = operationSeen ? "symbol" : "op";
    else if (quoted) kind = "string";
    else if (jump) kind = "jump";
    else if (symbol) kind = "symbol";
    else if (number) kind = afterBlock ? "block" : "number";
    else if (word) {
      const place = first && labelled ? "label" : operationSeen ? "operand" : "operation";
      kind = stlWordKind(words, word.toUpperCase(), place);
    }
    if (kind === "op") operationSeen = true;
    if (!space) {
      afterBlock = kind === "block" && Boolean(word);
      first = false;
    }
    html += span(kind, text);
  }
  return html + span("comment", comment);
}

const STEP7_TOKEN = /(\/\/.*)|("[^"]*"?)|('[^']*'?)|(#[A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*)|((?:[A-Za-z0-9]+#)+[\w.:+-]*|[+-]?[0-9][\w.]*)|([A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*\(?)|(\s+)|(.)/g;

/** A STEP 7 line: `;` ends a statement, `//` starts a comment, `"symbol"` and `#local` are
 *  names, `S5T#2S` and `W#16#FF` constants. */
function colourStep7(step7, line) {
  let html = "";
  let operationSeen = false;
  let first = true;
  const labelled = /^\s*[A-Za-z_\u00C0-\u00FF][\w\u00C0-\u00FF]*\s*:(?!=)/.test(line);
  for (const match of line.matchAll(STEP7_TOKEN)) {
    const [text, comment, symbol, quoted, local, constant, word, space] = match;
    let kind = "";
    if (comment) kind = "comment";
    else if (symbol || local) kind = "symbol";
    else if (quoted) kind = "string";
    else if (constant) kind = "number";
    else if (word) {
      const upper = word.toUpperCase();
      if (step7.keywords.has(upper) || upper.startsWith("END_")) kind = "keyword";
      else if (first && labelled) kind = "label";
      else if (step7.blocks.has(upper)) kind = "block";
      else if (!operationSeen && step7.operations.has(upper)) kind = "op";
      else if (operationSeen && step7.areas.has(upper)) kind = "area";
    }
    if (kind === "op") operationSeen = true;
    if (text === ";") operationSeen = false;
    if (!space) first = false;
    html += span(kind, text);
  }
  return html;
}

const TOML_TOKEN = /("(?:[^"\\]|\\.)*"?|'[^']*'?)|(#.*)|(^\s*\[\[?[^\]]*\]\]?)|(^\s*[\w".\- ]+?(?=\s*=))|([+-]?[0-9][\w.:+-]*)|(true|false)|(\s+)|(.)/g;

function colourToml(line) {
  let html = "";
  for (const match of line.matchAll(TOML_TOKEN)) {
    const [text, string, comment, section, key, number, boolean] = match;
    const kind = string ? "string" : comment ? "comment" : section ? "section" : key ? "key"
      : number || boolean ? "number" : "";
    html += span(kind, text);
  }
  return html;
}

// ---------------------------------------------------------------------------------------------
// An editor: a textarea over its coloured copy, line numbers beside it.

class Editor {
  constructor(root, colour) {
    this.textarea = root.querySelector("textarea");
    this.colours = root.querySelector(".colours");
    this.gutter = root.querySelector(".gutter");
    this.colour = colour;
    this.marks = new Map();
    this.breakpoints = null;
    this.onEdit = () => {};
    this.onGutter = () => {};
    this.beforeRender = () => {};
    this.textarea.addEventListener("input", () => {
      this.marks.clear();
      this.render();
      this.onEdit();
    });
    this.textarea.addEventListener("scroll", () => this.follow());
    this.gutter.addEventListener("click", (event) => {
      const line = Number(event.target.dataset.line);
      if (line) this.onGutter(line);
    });
  }

  get text() {
    return this.textarea.value;
  }

  set text(text) {
    this.textarea.value = text;
    this.marks.clear();
    this.render();
  }

  lines() {
    return this.textarea.value.split("\n");
  }

  /** Marks a line (`error`, `warning`, `paused`, `stopped`); a later mark of a line wins. */
  mark(line, kind) {
    this.marks.set(line, kind);
  }

  unmark(kind) {
    for (const [line, marked] of this.marks) if (marked === kind) this.marks.delete(line);
  }

  render() {
    this.beforeRender(this.textarea.value);
    const lines = this.lines();
    const mark = (n) => (this.marks.has(n) ? " " + this.marks.get(n) : "");
    this.colours.innerHTML = lines
      .map((line, i) => `<span class="line${mark(i + 1)}">${this.colour(line) || " "}</span>`)
      .join("") + '<span class="line"> </span>'.repeat(2);
    this.gutter.innerHTML = lines
      .map((_, i) => {
        const n = i + 1;
        const breakpoint = this.breakpoints && this.breakpoints.has(n) ? " breakpoint" : "";
        return `<div data-line="${n}" class="${mark(n).trim()}${breakpoint}">${n}</div>`;
      })
      .join("") + "<div></div>".repeat(2);
    this.follow();
  }

  follow() {
    this.colours.scrollTop = this.textarea.scrollTop;
    this.colours.scrollLeft = this.textarea.scrollLeft;
    this.gutter.scrollTop = this.textarea.scrollTop;
  }

  /** Selects line `line` and scrolls it into the middle of the editor. */
  jumpTo(line) {
    const lines = this.lines();
    const n = Math.min(Math.max(line, 1), lines.length);
    const start = lines.slice(0, n - 1).reduce((sum, text) => sum + text.length + 1, 0);
    this.textarea.focus({ preventScroll: true });
    this.textarea.setSelectionRange(start, start + lines[n - 1].length);
    this.reveal(n);
  }

  reveal(line) {
    const top = (line - 1) * LINE_HEIGHT - this.textarea.clientHeight / 3;
    this.textarea.scrollTop = Math.max(0, top);
    this.follow();
  }
}

// ---------------------------------------------------------------------------------------------
// The examples, the request and the results.

let awl = null;
let catalogue = null;
let program = null;
let scenario = null;
const current = { example: "", programName: "program.awl", scenarioName: "" };
const debugging = { commands: [] };

function directoryOf(name) {
  const slash = name.lastIndexOf("/");
  return slash < 0 ? "" : name.slice(0, slash + 1);
}

function stemOf(name) {
  return name.slice(directoryOf(name).length).replace(/\.[^.]*$/, "");
}

/** The programs a scenario names (`program = ["a.awl", …]`), as file names. */
function programsOf(scenarioName, text) {
  const list = /^\s*program\s*=\s*\[([^\]]*)\]/m.exec(text) || /^\s*program\s*=\s*("[^"]*")/m.exec(text);
  if (!list) return [];
  const names = [...list[1].matchAll(/"([^"]*)"/g)].map((found) => found[1]);
  return names.map((name) => directoryOf(scenarioName) + name);
}

function exampleFiles() {
  return Object.keys(catalogue.files);
}

/** The examples menu: per program, the program alone and each scenario that runs it. */
function fillExamples() {
  const select = $("examples");
  const files = exampleFiles();
  const scenariosOf = new Map();
  for (const name of files.filter((file) => file.endsWith(".toml"))) {
    const first = programsOf(name, catalogue.files[name])[0];
    if (!scenariosOf.has(first)) scenariosOf.set(first, []);
    scenariosOf.get(first).push(name);
  }
  for (const name of files.filter((file) => file.endsWith(".awl"))) {
    const group = document.createElement("optgroup");
    group.label = name;
    for (const scenarioName of scenariosOf.get(name) || []) {
      group.append(new Option(`${stemOf(scenarioName)} — scenario ${scenarioName}`, scenarioName));
    }
    group.append(new Option(`${stemOf(name)} — the program alone`, name));
    select.append(group);
  }
}

/** The example a fragment's `example=NAME` means: a file of that name (`fig5_2.awl`, as the
 *  page writes it), else the scenario of that stem, else the program. */
function exampleNamed(stem) {
  const files = exampleFiles();
  if (files.includes(stem)) return stem;
  const of = (extension) => files.find((file) => file === stem + extension || stemOf(file) === stem && file.endsWith(extension));
  return of(".toml") || of(".awl") || null;
}

function loadExample(name) {
  leaveDebug();
  stopLive();
  stopRun();
  current.example = name;
  if (name.endsWith(".toml")) {
    current.scenarioName = name;
    current.programName = programsOf(name, catalogue.files[name])[0] || "program.awl";
    scenario.text = catalogue.files[name];
  } else {
    current.scenarioName = "";
    current.programName = name;
    scenario.text = "";
  }
  program.text = catalogue.files[current.programName] || "";
  program.breakpoints.clear();
  program.render();
  $("examples").value = name;
  showNames();
}

function loadShared(params) {
  leaveDebug();
  stopLive();
  stopRun();
  current.example = "";
  current.programName = params.get("pname") || "program.awl";
  current.scenarioName = params.get("sname") || "";
  program.text = params.get("program") || "";
  scenario.text = params.get("scenario") || "";
  $("examples").value = "";
  showNames();
}

function showNames() {
  $("program-name").textContent = current.programName;
  $("scenario-name").textContent = scenario.text.trim() ? scenarioName() : "";
}

function scenarioName() {
  return current.scenarioName || directoryOf(current.programName) + "scenario.toml";
}

function request() {
  const files = Object.assign({}, catalogue.files);
  files[current.programName] = program.text;
  const hasScenario = scenario.text.trim() !== "";
  if (hasScenario) files[scenarioName()] = scenario.text;
  return {
    files,
    program: current.programName,
    scenario: hasScenario ? scenarioName() : null,
    cpu: $("cpu").value,
    mode: $("mode").value,
    points: $("points").value,
  };
}

function editorOf(file) {
  if (file === current.programName) return program;
  if (scenario.text.trim() && file === scenarioName()) return scenario;
  return null;
}

function placeText(at) {
  return at ? `${at.file}:${at.line}` : "";
}

function showDiagnostics(diagnostics) {
  const list = $("diagnostics");
  list.replaceChildren();
  for (const diagnostic of diagnostics) {
    const item = document.createElement("li");
    item.className = diagnostic.severity;
    const head = document.createElement("div");
    const place = document.createElement("span");
    place.className = "place";
    place.textContent = placeText(diagnostic.at);
    const message = document.createElement("strong");
    message.textContent = `${diagnostic.severity}: ${diagnostic.message}`;
    const code = document.createElement("span");
    code.className = "code-name";
    code.textContent = diagnostic.code || "";
    head.append(place, message, code);
    item.append(head);
    if (diagnostic.help) {
      const help = document.createElement("div");
      help.className = "help";
      help.textContent = `help: ${diagnostic.help}`;
      item.append(help);
    }
    const details = document.createElement("details");
    const summary = document.createElement("summary");
    summary.textContent = "as awl prints it";
    const rendered = document.createElement("pre");
    rendered.textContent = diagnostic.rendered;
    details.append(summary, rendered);
    item.append(details);
    const editor = diagnostic.at && editorOf(diagnostic.at.file);
    if (editor) {
      editor.mark(diagnostic.at.line, diagnostic.severity === "error" ? "error" : "warning");
      item.title = "click to go to the line";
      item.addEventListener("click", (event) => {
        if (!event.target.closest("details")) editor.jumpTo(diagnostic.at.line);
      });
    }
    list.append(item);
  }
}

function showOutcome(outcome) {
  for (const editor of [program, scenario]) {
    for (const kind of ["error", "warning", "stopped"]) editor.unmark(kind);
  }
  $("summary").textContent = outcome.summary;
  showDiagnostics(outcome.diagnostics);
  $("stop-box").hidden = !outcome.stop;
  $("stop").textContent = outcome.stop || "";
  if (outcome.stop_at) {
    const editor = editorOf(outcome.stop_at.file);
    if (editor) {
      editor.mark(outcome.stop_at.line, "stopped");
      editor.reveal(outcome.stop_at.line);
    }
  }
  $("timeline").innerHTML = outcome.timeline || "";
  $("state").textContent = outcome.state || "";
  $("watch-box").hidden = !outcome.watch;
  $("watch").textContent = outcome.watch || "";
  program.render();
  scenario.render();
}

function status(text) {
  $("status").textContent = text;
}

// ---------------------------------------------------------------------------------------------
// The worker: one job at a time. Its progress fills the status line; Stop (or Esc) ends the
// worker at once, and a new one, made from the module already compiled, waits for the next job.

const runner = { module: null, source: "", worker: null, job: null, jobs: 0 };
/** What the last button started, for the self-test to wait on. */
let lastAction = Promise.resolve();

/** The worker's script: the glue and web/worker.js, both in this page, as a Blob URL (a worker
 *  from a file would not load from file://). */
function workerSource() {
  const text = $("awl-glue").textContent + "\n" + $("awl-worker").textContent;
  return URL.createObjectURL(new Blob([text], { type: "text/javascript" }));
}

function newWorker() {
  const worker = new Worker(runner.source);
  worker.onmessage = (event) => heard(event.data);
  worker.onerror = (event) => {
    document.body.setAttribute("data-error", String(event.message));
    status(`the run failed: ${event.message}`);
    endJob();
  };
  worker.postMessage({ module: runner.module });
  return worker;
}

/** Hands the worker a job; the answer (parsed), or null if it was stopped. A job started while
 *  another runs stops that one. */
function ask(job) {
  stopRun();
  job.id = ++runner.jobs;
  job.progress = null;
  job.done = new Promise((resolve) => {
    job.resolve = resolve;
  });
  runner.job = job;
  runner.worker.postMessage({ id: job.id, kind: job.kind, request: job.request, commands: job.commands });
  $("stop-run").hidden = false;
  status("running…");
  return job.done;
}

function heard(message) {
  const job = runner.job;
  if (!job || message.id !== job.id) return;
  if (message.progress) {
    job.progress = message.progress;
    status(`running: ${progressText(job.progress)} — Stop (Esc) ends it`);
    return;
  }
  runner.job = null;
  $("stop-run").hidden = true;
  job.resolve(JSON.parse(message.answer));
}

function progressText(progress) {
  const ms = (progress.clockNs / MS).toLocaleString("en", { minimumFractionDigits: 1, maximumFractionDigits: 1 });
  return `${ms} ms simulated, cycle ${progress.cycle.toLocaleString("en")}`;
}

/** Ends the running job (its worker with it); it answers null. */
function endJob() {
  const job = runner.job;
  if (!job) return null;
  runner.worker.terminate();
  runner.worker = newWorker();
  runner.job = null;
  $("stop-run").hidden = true;
  job.resolve(null);
  return job;
}

function stopRun() {
  const job = endJob();
  if (!job) return;
  const where = job.progress ? ` at ${progressText(job.progress)}` : "";
  if (job.kind === "debug") {
    status(`stopped${where}: the debugger is where it was`);
    return;
  }
  status(`stopped${where}`);
  showOutcome({ summary: `not finished: stopped${where}\n`, diagnostics: [] });
}

async function run() {
  leaveDebug();
  const started = performance.now();
  const outcome = await ask({ kind: "run", request: JSON.stringify(request()) });
  if (!outcome) return null;
  showOutcome(outcome);
  status(`${outcome.ran ? "ran" : "not run"} in ${Math.round(performance.now() - started)} ms`);
  keepInAddress();
  return outcome;
}

// ---------------------------------------------------------------------------------------------
// The address: `#example=NAME` or the program and scenario themselves, and the selectors.

function keepInAddress() {
  const params = new URLSearchParams();
  const unchanged = current.example
    && program.text === (catalogue.files[current.programName] || "")
    && scenario.text === (current.scenarioName ? catalogue.files[current.scenarioName] : "");
  if (unchanged) {
    params.set("example", current.example);
  } else {
    params.set("pname", current.programName);
    params.set("program", program.text);
    if (scenario.text.trim()) {
      params.set("sname", scenarioName());
      params.set("scenario", scenario.text);
    }
  }
  for (const selector of ["cpu", "mode", "points"]) {
    if ($(selector).value) params.set(selector, $(selector).value);
  }
  const address = "#" + params.toString();
  try {
    history.replaceState(null, "", address);
  } catch (error) {
    location.replace(address);
  }
}

function share() {
  keepInAddress();
  const done = () => status("the address now holds this program and scenario: copy it to share");
  if (navigator.clipboard && window.isSecureContext) {
    navigator.clipboard.writeText(location.href).then(
      () => status("link copied: it holds this program and scenario"),
      done,
    );
  } else {
    done();
  }
}

function applyAddress() {
  const params = new URLSearchParams(location.hash.slice(1));
  for (const selector of ["cpu", "mode", "points"]) $(selector).value = params.get(selector) || "";
  if (params.has("samples")) return runSamples();
  if (params.has("selftest")) return selfTest();
  if (params.has("example")) {
    const name = exampleNamed(params.get("example"));
    if (!name) {
      status(`no example named ${params.get("example")}`);
      $("summary").textContent = `not run: no example named ${params.get("example")}\n`;
      return ready();
    }
    loadExample(name);
  } else if (params.has("program")) {
    loadShared(params);
  } else {
    loadExample(exampleNamed("fig5_2_interrupt"));
    return run().then(ready);
  }
  if (params.has("live")) startLive();
  if (params.has("run")) return run().then(ready);
  ready();
}

function ready() {
  document.body.setAttribute("data-ready", "yes");
}

/** `#samples`: runs every sample scenario; what `awl run` would print (the watch table, then
 *  the summary) as JSON for a test to compare. */
async function runSamples() {
  const summaries = {};
  for (const name of exampleFiles().filter((file) => file.endsWith(".toml"))) {
    loadExample(name);
    const outcome = await run();
    summaries[name] = (outcome.watch || "") + outcome.summary;
  }
  $("samples").textContent = JSON.stringify(summaries);
  ready();
}

/** `#selftest`: uses the step controls and live mode as a person would; the verdict goes into
 *  the body's data-selftest for a headless browser to read. */
async function selfTest() {
  const failures = [];
  const expect = (what, ok) => {
    if (!ok) failures.push(what);
  };
  const click = (id) => {
    $(id).click();
    return lastAction;
  };
  loadExample("fig5_2_interrupt.toml");
  await click("step");
  await click("step");
  expect("two steps pause", /^paused before fig5_2_interrupt\.awl:\d+$/.test($("paused").textContent));
  program.gutter.querySelector('[data-line="21"]').click();
  expect("the gutter sets a breakpoint", program.gutter.querySelector(".breakpoint") !== null);
  await click("continue");
  expect("continue stops at the breakpoint", $("paused").textContent === "paused before fig5_2_interrupt.awl:21");
  expect("the paused line is marked", program.colours.querySelector(".line.paused") !== null);
  program.gutter.querySelector('[data-line="21"]').click();
  await click("continue");
  expect("the run ends", $("paused").textContent === "the run has ended");
  expect("the summary follows", $("summary").textContent.includes("OB 3: requested 1, serviced 1"));

  loadExample("press_en.toml");
  $("live").click();
  const lamp = () => $("outputs").querySelector('[data-operand="Q 4.0"] .lamp');
  expect("a lamp per output", lamp() !== null && !lamp().classList.contains("on"));
  for (const operand of ["I 0.0", "I 0.1"]) {
    $("inputs").querySelector(`[data-operand="${operand}"] .switch`).click();
  }
  liveRun.run.advance(20 * MS, windowNs());
  showLive(JSON.parse(liveRun.run.view(windowNs())));
  expect("switches light the lamp", lamp().classList.contains("on"));
  expect("the live timeline", $("live-timeline").querySelector("svg") !== null);
  stopLive();

  loadExample("fig5_2_interrupt.toml");
  $("live").click();
  $("interrupts").querySelector("button").click();
  liveRun.run.advance(2 * MS, windowNs());
  showLive(JSON.parse(liveRun.run.view(windowNs())));
  expect("a requested OB is serviced", $("live-timeline").innerHTML.includes("OB 3 serviced"));
  stopLive();
  document.body.setAttribute("data-selftest", failures.length ? failures.join("; ") : "passed");
  ready();
}

// ---------------------------------------------------------------------------------------------
// The debugger: the commands so far run again from the start for each new one (runs are
// deterministic), breakpoints from the gutter first.

function blockAt(line) {
  const lines = program.lines();
  const words = catalogue.words.blocks.join("|");
  const header = new RegExp(`^\\s*(${words})\\s*(\\d+)\\b`, "i");
  for (let n = line; n >= 1; n--) {
    const found = header.exec(lines[n - 1]);
    if (found) return `${found[1].toUpperCase()} ${found[2]}`;
  }
  return null;
}

function breakpointCommands() {
  return [...program.breakpoints]
    .sort((a, b) => a - b)
    .map((line) => [line, blockAt(line)])
    .filter(([, block]) => block)
    .map(([line, block]) => `break ${block} line ${line}`);
}

async function debugWith(command) {
  const given = debugging.commands.concat(command);
  const commands = breakpointCommands().concat(given).join("\n") + "\n";
  const result = await ask({ kind: "debug", request: JSON.stringify(request()), commands });
  // A command stopped before it ended is forgotten: the debugger stays where it was.
  if (!result) return;
  debugging.commands = given;
  status("");
  $("debug-box").hidden = false;
  $("debug").textContent = result.transcript;
  $("debug").scrollTop = $("debug").scrollHeight;
  program.unmark("paused");
  if (result.outcome) {
    showOutcome(result.outcome);
    debugging.commands = [];
    $("paused").textContent = result.outcome.ran ? "the run has ended" : "the program cannot run";
    return;
  }
  $("state").textContent = result.state || "";
  const at = result.paused_at;
  if (at) {
    $("paused").textContent = `paused before ${placeText(at)}`;
    const editor = editorOf(at.file);
    if (editor) {
      editor.mark(at.line, "paused");
      editor.reveal(at.line);
    }
  }
  program.render();
}

function leaveDebug() {
  debugging.commands = [];
  $("paused").textContent = "";
  $("debug-box").hidden = true;
  if (program) {
    program.unmark("paused");
    program.render();
  }
}

function toggleBreakpoint(line) {
  if (program.breakpoints.has(line)) program.breakpoints.delete(line);
  else program.breakpoints.add(line);
  program.render();
  const block = blockAt(line);
  status(block ? `breakpoints: ${breakpointCommands().join(", ") || "none"}` : `line ${line} is in no block`);
}

// ---------------------------------------------------------------------------------------------
// Live mode: the run paced against the wall clock, a trainer case of switches and lamps.

const liveRun = { run: null, timer: 0, wall: 0, paused: false, built: false };

function speed() {
  return Number($("speed").value);
}

/** The timeline shows the last second of wall time at this speed, from 10 ms to 2 s. */
function windowNs() {
  return Math.min(2000, Math.max(10, 1000 * speed())) * MS;
}

function startLive() {
  stopLive();
  leaveDebug();
  const started = new awl.LiveRun(JSON.stringify(request()));
  const refusal = started.refusal();
  if (refusal) {
    started.free();
    showOutcome(JSON.parse(refusal));
    status("live mode needs a program that runs");
    return;
  }
  liveRun.run = started;
  liveRun.built = false;
  liveRun.paused = false;
  $("pause").textContent = "pause";
  $("live-panel").hidden = false;
  liveRun.wall = performance.now();
  liveRun.timer = setInterval(liveTick, 100);
  liveTick();
}

function stopLive() {
  if (liveRun.timer) clearInterval(liveRun.timer);
  liveRun.timer = 0;
  if (liveRun.run) liveRun.run.free();
  liveRun.run = null;
  $("live-panel").hidden = true;
}

function liveTick() {
  const now = performance.now();
  // A hidden tab gets few ticks: at most half a second of wall time is made up at once.
  const elapsed = Math.min(now - liveRun.wall, 500);
  liveRun.wall = now;
  if (!liveRun.paused) liveRun.run.advance(elapsed * MS * speed(), windowNs());
  showLive(JSON.parse(liveRun.run.view(windowNs())));
}

function ioItem(bit, input) {
  const item = document.createElement("li");
  const name = document.createElement("span");
  name.className = "io-name";
  name.textContent = bit.name ? bit.name : bit.operand;
  if (bit.name) {
    const operand = document.createElement("small");
    operand.textContent = bit.operand;
    name.append(operand);
  }
  if (input) {
    const toggle = document.createElement("button");
    toggle.type = "button";
    toggle.className = "switch";
    toggle.title = `switch ${bit.operand}`;
    toggle.addEventListener("click", () => setInput(bit.operand, !toggle.classList.contains("on")));
    const push = document.createElement("button");
    push.type = "button";
    push.className = "push";
    push.title = `push button ${bit.operand}: on while held`;
    push.addEventListener("pointerdown", () => setInput(bit.operand, true));
    for (const release of ["pointerup", "pointerleave"]) {
      push.addEventListener(release, () => {
        if (push.classList.contains("on")) setInput(bit.operand, false);
      });
    }
    item.append(toggle, push, name);
  } else {
    const lamp = document.createElement("span");
    lamp.className = "lamp";
    item.append(lamp, name);
  }
  item.dataset.operand = bit.operand;
  return item;
}

function setInput(operand, on) {
  const refused = liveRun.run.set_input(operand, on);
  if (refused) status(refused);
  showLive(JSON.parse(liveRun.run.view(windowNs())));
}

function requestOb(ob) {
  const pending = liveRun.run.request(ob);
  status(pending ? `OB ${ob} requested` : `OB ${ob} is not pending: the CPU ignores it now or it is pending already`);
}

function buildLive(view) {
  $("inputs").replaceChildren(...view.inputs.map((bit) => ioItem(bit, true)));
  $("outputs").replaceChildren(...view.outputs.map((bit) => ioItem(bit, false)));
  const buttons = view.interrupt_obs.map((ob) => {
    const button = document.createElement("button");
    button.type = "button";
    button.textContent = `request OB ${ob}`;
    button.addEventListener("click", () => requestOb(ob));
    return button;
  });
  $("interrupts").replaceChildren(...buttons);
  if (!view.inputs.length && !view.outputs.length) {
    $("inputs").textContent = "the program uses no input or output bits";
  }
  liveRun.built = true;
}

function showLive(view) {
  if (!liveRun.built) buildLive(view);
  for (const [list, bits, kind] of [["inputs", view.inputs, "button"], ["outputs", view.outputs, ".lamp"]]) {
    bits.forEach((bit, i) => {
      const item = $(list).children[i];
      if (!item) return;
      for (const element of item.querySelectorAll(kind === "button" ? "button" : kind)) {
        element.classList.toggle("on", bit.value);
      }
    });
  }
  $("live-clock").textContent = `${view.clock}   cycle ${view.cycles}   ${view.mode}`;
  $("live-timeline").innerHTML = view.timeline;
  $("live-stop").hidden = !view.stop;
  $("live-stop").textContent = view.stop || "";
  if (view.stop_at && !program.marks.has(view.stop_at.line)) {
    const editor = editorOf(view.stop_at.file);
    if (editor) {
      editor.mark(view.stop_at.line, "stopped");
      editor.render();
    }
  }
  if (view.stop && liveRun.timer) {
    clearInterval(liveRun.timer);
    liveRun.timer = 0;
  }
}

function togglePause() {
  liveRun.paused = !liveRun.paused;
  $("pause").textContent = liveRun.paused ? "go on" : "pause";
}

// ---------------------------------------------------------------------------------------------

/** The module's bytes: the page holds them gzipped (a third of their size), as base64. */
async function wasmBytes() {
  const binary = atob(AWL_WASM_GZIP_BASE64);
  const gzipped = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) gzipped[i] = binary.charCodeAt(i);
  const inflated = new Blob([gzipped]).stream().pipeThrough(new DecompressionStream("gzip"));
  return new Response(inflated).arrayBuffer();
}

function wire() {
  const words = wordSets(catalogue.words);
  let step7 = false;
  program = new Editor($("program-editor"), (line) =>
    step7 ? colourStep7(words.step7, line) : colourStl(words, line));
  program.beforeRender = (text) => {
    step7 = isStep7(words.step7, text);
  };
  program.breakpoints = new Set();
  program.onGutter = toggleBreakpoint;
  scenario = new Editor($("scenario-editor"), colourToml);
  for (const editor of [program, scenario]) {
    editor.onEdit = () => {
      leaveDebug();
      stopLive();
      showNames();
    };
    editor.textarea.addEventListener("keydown", (event) => {
      if (event.key === "Enter" && (event.ctrlKey || event.metaKey)) {
        event.preventDefault();
        lastAction = run();
      }
    });
  }
  for (const cpu of catalogue.cpus) {
    const option = new Option(cpu.name, cpu.name);
    option.title = cpu.title;
    $("cpu").append(option);
  }
  fillExamples();
  $("examples").addEventListener("change", () => {
    if ($("examples").value) loadExample($("examples").value);
    else loadShared(new URLSearchParams());
  });
  const act = (action) => () => {
    lastAction = action();
  };
  $("run").addEventListener("click", act(run));
  $("stop-run").addEventListener("click", stopRun);
  document.addEventListener("keydown", (event) => {
    if (event.key === "Escape" && runner.job) stopRun();
  });
  $("share").addEventListener("click", share);
  $("step").addEventListener("click", act(() => debugWith("step")));
  $("next").addEventListener("click", act(() => debugWith("next")));
  $("continue").addEventListener("click", act(() => debugWith("continue")));
  $("reset-debug").addEventListener("click", leaveDebug);
  $("live").addEventListener("click", startLive);
  $("live-close").addEventListener("click", stopLive);
  $("pause").addEventListener("click", togglePause);
}

// Compiled once; the page and each worker instantiate the same module.
async function start() {
  status("loading…");
  begin(await WebAssembly.compile(await wasmBytes()));
}

function begin(module) {
  wasm_bindgen.initSync({ module });
  awl = wasm_bindgen;
  runner.module = module;
  runner.source = workerSource();
  runner.worker = newWorker();
  catalogue = JSON.parse(awl.catalogue());
  wire();
  status("");
  applyAddress();
}

start().catch((error) => {
  status(`awl could not load in this browser: ${error}`);
  throw error;
});
