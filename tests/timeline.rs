//! The timeline picture: its marks stand for exactly the trace's events in the window, it
//! renders with a real SVG renderer, it stays small on a long run, and the README's Fig. 5.2
//! pictures are up to date.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use awl::runner::{self, RunOptions};
use awl::vm::cycle::RunLimit;

mod common;

/// A fresh path in the temporary directory.
fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("awl-timeline-{}-{name}", std::process::id()))
}

/// Runs `options` with a jsonl trace and a timeline; the SVG and the trace's lines.
fn picture_and_trace(name: &str, options: RunOptions) -> (String, Vec<serde_json::Value>) {
    let (svg_path, trace_path) = (temp(&format!("{name}.svg")), temp(&format!("{name}.jsonl")));
    let options = RunOptions {
        trace: Some(trace_path.clone()),
        timeline: Some(svg_path.clone()),
        ..options
    };
    let ran = runner::run(&options).unwrap_or_else(|_| panic!("{name} runs"));
    assert!(
        ran.warnings
            .iter()
            .all(|w| !w.to_string().contains("incomplete"))
    );
    let svg = std::fs::read_to_string(&svg_path).expect("the timeline was written");
    let trace = std::fs::read_to_string(&trace_path).expect("the trace was written");
    let _ = std::fs::remove_file(svg_path);
    let _ = std::fs::remove_file(trace_path);
    let events = trace
        .lines()
        .map(|line| serde_json::from_str(line).expect("a JSON line"))
        .collect();
    (svg, events)
}

/// The events a class of marks stands for, summed over the marks' `data-count`.
fn marks(svg: &str) -> BTreeMap<String, u64> {
    let document = roxmltree::Document::parse(svg).expect("the SVG parses as XML");
    let mut counts = BTreeMap::new();
    for node in document.descendants().filter(|node| node.is_element()) {
        if let (Some(class), Some(count)) = (node.attribute("class"), node.attribute("data-count"))
        {
            *counts.entry(class.to_string()).or_default() += count.parse::<u64>().unwrap();
        }
    }
    counts
}

/// The trace's events of each kind the picture marks.
fn trace_counts(events: &[serde_json::Value]) -> BTreeMap<String, u64> {
    let classes = [
        ("irq_request", "request"),
        ("irq_service", "service"),
        ("irq_lost", "lost"),
        ("irq_ignored", "ignored"),
        ("block_call", "block"),
    ];
    let mut counts = BTreeMap::new();
    for (ev, class) in classes {
        let n = events.iter().filter(|event| event["ev"] == ev).count() as u64;
        counts.insert(class.to_string(), n);
    }
    counts
}

fn compared(marks: &BTreeMap<String, u64>) -> BTreeMap<String, u64> {
    ["request", "service", "lost", "ignored", "block"]
        .into_iter()
        .map(|class| (class.to_string(), marks.get(class).copied().unwrap_or(0)))
        .collect()
}

#[test]
fn every_sample_s_picture_marks_exactly_the_trace_s_events() {
    for scenario in common::sample_scenarios() {
        let name = scenario.file_stem().unwrap().to_string_lossy().to_string();
        let (svg, events) = picture_and_trace(
            &name,
            RunOptions {
                scenario: Some(scenario.clone()),
                ..RunOptions::default()
            },
        );
        assert_eq!(
            compared(&marks(&svg)),
            trace_counts(&events),
            "{}",
            scenario.display()
        );
        for class in ["lane", "run", "tick", "data-cycle", "os-time"] {
            assert!(
                svg.contains(&format!("class=\"{class}\"")),
                "{name}: {class}"
            );
        }
    }
}

#[test]
fn a_window_shows_the_trace_s_events_in_it() {
    let (svg, events) = picture_and_trace(
        "window",
        RunOptions {
            scenario: Some("programs/priorities.toml".into()),
            from_ns: Some(20_000),
            to_ns: Some(60_000),
            ..RunOptions::default()
        },
    );
    assert!(events.iter().all(|event| {
        let t = event["t_ns"].as_u64().unwrap();
        (20_000..=60_000).contains(&t)
    }));
    assert!(
        trace_counts(&events)["request"] > 0,
        "the window holds requests"
    );
    assert_eq!(compared(&marks(&svg)), trace_counts(&events));
}

#[test]
fn a_stop_and_lost_and_ignored_requests_are_marked() {
    let (svg, _) = picture_and_trace(
        "stop",
        RunOptions {
            scenario: Some("programs/speed7_stop.toml".into()),
            ..RunOptions::default()
        },
    );
    assert!(svg.contains(r#"class="stop""#));
    assert!(svg.contains("STOP OB85"));
    let (svg, _) = picture_and_trace(
        "lost",
        RunOptions {
            scenario: Some("programs/speed7_lost.toml".into()),
            ..RunOptions::default()
        },
    );
    assert!(marks(&svg)["lost"] > 0);
}

fn render(svg: &str) -> resvg::tiny_skia::Pixmap {
    let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default())
        .expect("resvg reads the SVG");
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap
}

fn hex(colour: &str) -> [u8; 3] {
    let channel = |at: usize| u8::from_str_radix(&colour[at..at + 2], 16).unwrap();
    [channel(1), channel(3), channel(5)]
}

#[test]
fn the_picture_renders_with_its_lane_colours_where_the_lanes_run() {
    let (svg, _) = picture_and_trace(
        "render",
        RunOptions {
            scenario: Some("programs/nested.toml".into()),
            to_ns: Some(90_000),
            ..RunOptions::default()
        },
    );
    let pixmap = render(&svg);
    let pixels = pixmap.pixels();
    let coloured = pixels
        .iter()
        .filter(|p| p.alpha() > 0 && (p.red(), p.green(), p.blue()) != (255, 255, 255))
        .count();
    assert!(
        coloured * 20 > pixels.len(),
        "not blank: {coloured} of {} pixels drawn",
        pixels.len()
    );
    let document = roxmltree::Document::parse(&svg).unwrap();
    let number =
        |node: roxmltree::Node, name| node.attribute(name).unwrap().parse::<f64>().unwrap();
    let mut lanes_seen = std::collections::BTreeSet::new();
    for bar in document
        .descendants()
        .filter(|node| node.attribute("class") == Some("run"))
    {
        let (x, y, w) = (number(bar, "x"), number(bar, "y"), number(bar, "width"));
        if w < 24.0 {
            continue;
        }
        let fill = bar.attribute("fill").unwrap();
        // Above the bar's name, clear of the service mark at its start and the tick at its end.
        let pixel = pixmap
            .pixel((x + w - 6.0) as u32, (y + 2.5) as u32)
            .unwrap()
            .demultiply();
        let got = [pixel.red(), pixel.green(), pixel.blue()];
        let want = hex(fill);
        assert!(
            got.iter().zip(want).all(|(g, w)| g.abs_diff(w) <= 3),
            "the bar at x {x} is drawn in {got:?}, not its lane's {fill}"
        );
        lanes_seen.insert(fill.to_string());
    }
    assert!(
        lanes_seen.len() >= 3,
        "OB 1, OB 3 and OB 4 run in nested.toml: {lanes_seen:?}"
    );
}

#[test]
fn a_sixty_second_run_stays_small() {
    let path = temp("long.svg");
    let options = RunOptions {
        scenario: Some("programs/conveyor.toml".into()),
        limit: Some(RunLimit::Duration(60_000_000_000)),
        timeline: Some(path.clone()),
        ..RunOptions::default()
    };
    runner::run(&options).unwrap_or_else(|_| panic!("conveyor runs"));
    let svg = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(path);
    assert!(svg.len() < 5_000_000, "{} bytes", svg.len());
    roxmltree::Document::parse(&svg).expect("the SVG parses");
    let counts = marks(&svg);
    assert!(
        counts["tick"] > 100_000,
        "merged marks keep their counts: {counts:?}"
    );
}

/// The README's pictures: Fig. 5.2 with block points and with operation points.
#[test]
fn the_readme_pictures_are_up_to_date() {
    let pictures = [
        (
            "programs/fig5_2_interrupt.toml",
            "programs/timelines/fig5_2_block.svg",
        ),
        (
            "programs/fig5_2_operation.toml",
            "programs/timelines/fig5_2_operation.svg",
        ),
    ];
    let mut stale = Vec::new();
    for (scenario, picture) in pictures {
        let fresh = temp("readme.svg");
        let options = RunOptions {
            scenario: Some(scenario.into()),
            timeline: Some(fresh.clone()),
            to_ns: Some(110_000),
            ..RunOptions::default()
        };
        runner::run(&options).unwrap_or_else(|_| panic!("{scenario} runs"));
        let svg = std::fs::read_to_string(&fresh).unwrap();
        let _ = std::fs::remove_file(fresh);
        if std::fs::read_to_string(picture).ok().as_deref() != Some(svg.as_str()) {
            std::fs::create_dir_all(Path::new(picture).parent().unwrap()).unwrap();
            std::fs::write(picture, svg).unwrap();
            stale.push(picture);
        }
    }
    assert!(
        stale.is_empty(),
        "regenerated {stale:?}: they were stale; commit them"
    );
}
