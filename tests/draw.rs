//! Pictures (issue #14, point 3) through the library: chart drawings and
//! timing diagrams are parsed back with an XML parser and checked for what
//! they must show, rendered to PNG with resvg (a real renderer, with text)
//! to prove they are valid SVG, and drawn twice to prove they are
//! deterministic.

use crate::support::library;

use library::repo_text;
use plcrun::{
    ChartPicture, CheckOptions, Options, Plc, Session, SourceMap, TimingDiagram, parse_stimulus,
};
use roxmltree::{Document, Node};

fn has_class(n: &Node, class: &str) -> bool {
    n.attribute("class")
        .is_some_and(|c| c.split(' ').any(|k| k == class))
}

fn with_class<'a, 'i>(doc: &'a Document<'i>, class: &str) -> Vec<Node<'a, 'i>> {
    doc.descendants()
        .filter(|n| n.is_element() && has_class(n, class))
        .collect()
}

/// The text of every `<text>` under `n` with class `class`.
fn texts(n: Node, class: &str) -> Vec<String> {
    n.descendants()
        .filter(|t| t.has_tag_name("text") && has_class(t, class))
        .map(|t| t.text().unwrap_or("").to_string())
        .collect()
}

fn sources(files: &[&str]) -> SourceMap {
    let mut map = SourceMap::new();
    for f in files {
        map.add(*f, repo_text(f));
    }
    map
}

fn compile(src: &str) -> Plc {
    Plc::compile_files(&[("test.sfc", src)], &Options::default()).expect("compiles")
}

/// Renders `svg` with resvg (system fonts loaded, so text is drawn) and
/// returns the pixels; also writes a PNG into `PLCRUN_DRAW_PNG_DIR` when
/// that variable is set (to look at the pictures).
fn render(svg: &str, name: &str) -> Vec<u8> {
    let mut options = resvg::usvg::Options::default();
    options.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg, &options).expect("resvg parses the SVG");
    let size = tree.size().to_int_size();
    assert!(size.width() > 50 && size.height() > 50, "{size:?}");
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).expect("a pixmap of that size");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    if let Ok(dir) = std::env::var("PLCRUN_DRAW_PNG_DIR") {
        let path = std::path::Path::new(&dir).join(format!("{name}.png"));
        pixmap.save_png(path).expect("PNG written");
    }
    pixmap.data().to_vec()
}

const CHARIOT_CONDITIONS: [&str; 4] = ["dcy & fcA", "fcB", "ATT.T >= tX3", "fcA"];

#[test]
fn chariot_chart_has_every_step_transition_and_action() {
    let picture = ChartPicture::from_sources(&sources(&["programs/chariot.sfc"]), None).unwrap();
    let svg = picture.to_svg();
    let doc = Document::parse(&svg).expect("well-formed XML");
    let steps = with_class(&doc, "step");
    let names: Vec<&str> = steps
        .iter()
        .map(|s| s.attribute("data-name").unwrap())
        .collect();
    assert_eq!(names, ["INIT", "AV", "ATT", "AR"]);
    for s in &steps {
        assert_eq!(texts(*s, "name"), [s.attribute("data-name").unwrap()]);
    }
    // INIT is the initial step: double frame.
    let init = &steps[0];
    assert!(has_class(init, "initial"));
    assert_eq!(
        init.children().filter(|c| c.has_tag_name("rect")).count(),
        2
    );
    assert_eq!(
        steps[1]
            .children()
            .filter(|c| c.has_tag_name("rect"))
            .count(),
        1
    );
    let transitions = with_class(&doc, "transition");
    let conditions: Vec<Vec<String>> = transitions.iter().map(|t| texts(*t, "condition")).collect();
    assert_eq!(conditions, CHARIOT_CONDITIONS.map(|c| vec![c.to_string()]));
    let links: Vec<(&str, &str)> = transitions
        .iter()
        .map(|t| {
            (
                t.attribute("data-from").unwrap(),
                t.attribute("data-to").unwrap(),
            )
        })
        .collect();
    assert_eq!(
        links,
        [("INIT", "AV"), ("AV", "ATT"), ("ATT", "AR"), ("AR", "INIT")]
    );
    // Action blocks: qualifier, action, indicator, beside their step.
    let av = texts(steps[1], "qualifier");
    assert_eq!(av, ["N"]);
    assert_eq!(texts(steps[1], "action-name"), ["KMAV"]);
    assert_eq!(texts(steps[1], "indicator"), ["fcB"]);
    assert_eq!(texts(steps[3], "action-name"), ["KMAR"]);
    // The loop back to INIT is one routed edge with an arrow.
    let loops = with_class(&doc, "loop");
    assert_eq!(loops.len(), 1);
    assert_eq!(
        loops[0]
            .descendants()
            .filter(|n| has_class(n, "arrow"))
            .count(),
        1
    );
}

#[test]
fn every_chart_of_the_programs_directory_draws() {
    let mut drawn = 0;
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/programs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "sfc") {
            continue;
        }
        let rel = format!("programs/{}", path.file_name().unwrap().to_string_lossy());
        let map = sources(&[&rel]);
        // The GRAFCET examples hold forcing orders, accepted in that mode.
        let options = CheckOptions {
            grafcet: rel.starts_with("programs/grafcet_"),
            ..CheckOptions::default()
        };
        let report = plcrun::check(&map, &options);
        assert!(report.is_ok(), "{rel} checks");
        // A file with several charts (a program and its chart FBs) draws
        // each of them by name.
        let pictures = match ChartPicture::from_sources(&map, None) {
            Ok(p) => vec![p],
            Err(plcrun::DrawError::SeveralCharts(names)) => names
                .iter()
                .map(|n| ChartPicture::from_sources(&map, Some(n)).unwrap())
                .collect(),
            Err(e) => panic!("{rel}: {e}"),
        };
        for picture in pictures {
            let model = picture.model();
            let svg = picture.to_svg();
            let doc = Document::parse(&svg).unwrap_or_else(|e| panic!("{rel}: {e}"));
            let steps = with_class(&doc, "step");
            assert_eq!(steps.len(), model.steps.len(), "{rel}");
            for (node, step) in steps.iter().zip(&model.steps) {
                assert_eq!(node.attribute("data-name"), Some(step.name.as_str()));
                assert_eq!(
                    has_class(node, "initial"),
                    step.initial,
                    "{rel} {}",
                    step.name
                );
                let quals = texts(*node, "qualifier");
                let want: Vec<String> = step
                    .actions
                    .iter()
                    .map(|a| match &a.duration {
                        Some(d) => format!("{} {d}", a.qualifier),
                        None => a.qualifier.clone(),
                    })
                    .collect();
                assert_eq!(quals, want, "{rel} {}", step.name);
            }
            let transitions = with_class(&doc, "transition");
            assert_eq!(transitions.len(), model.transitions.len(), "{rel}");
            for (node, t) in transitions.iter().zip(&model.transitions) {
                assert_eq!(
                    texts(*node, "condition").join(" "),
                    t.condition.join(" "),
                    "{rel}"
                );
                assert!(!t.condition.is_empty());
            }
            render(&svg, &path.file_stem().unwrap().to_string_lossy());
            drawn += 1;
        }
    }
    // alg01, chariot, graf1_sfc, transfer_station, grafcet_transient, and
    // grafcet_forcing's supervisor and partial grafcet.
    assert_eq!(drawn, 7, "charts of programs/*.sfc");
}

const BRANCHES: &str = "
PROGRAM branches
VAR go, left, both, done : BOOL; lamp, horn : BOOL; t : TIME := T#2s; END_VAR
INITIAL_STEP Start : END_STEP
STEP A : lamp(L, T#5s); END_STEP
STEP B : horn(D, t, done); END_STEP
STEP C : Count(P1); END_STEP
STEP D : lamp(S); END_STEP
STEP E : lamp(R); END_STEP
TRANSITION FROM Start TO A := go AND left; END_TRANSITION
TRANSITION FROM Start TO (B, C) := go AND NOT left; END_TRANSITION
TRANSITION FROM (B, C) TO D := both; END_TRANSITION
TRANSITION FROM A TO D := done; END_TRANSITION
TRANSITION back (PRIORITY := 1) FROM D TO E :
    LD done
    AND go
END_TRANSITION
TRANSITION FROM E TO Start := TRUE; END_TRANSITION
ACTION Count : END_ACTION
END_PROGRAM
";

#[test]
fn divergences_convergences_qualifiers_and_il_conditions() {
    let plc = compile(BRANCHES);
    let picture = ChartPicture::of_program(&plc).unwrap();
    let svg = picture.to_svg();
    let doc = Document::parse(&svg).unwrap();
    // Start → A or (B, C): a selection divergence under Start; (B, C): a
    // simultaneous divergence and convergence; D: a selection convergence.
    let selection = with_class(&doc, "selection");
    let simultaneous = with_class(&doc, "simultaneous");
    assert_eq!(selection.len(), 2, "divergence at Start, convergence at D");
    assert_eq!(
        simultaneous.len(),
        2,
        "divergence into B, C and convergence out of them"
    );
    for s in &simultaneous {
        assert_eq!(s.children().filter(|c| c.has_tag_name("line")).count(), 2);
    }
    let step = |name: &str| {
        with_class(&doc, "step")
            .into_iter()
            .find(|s| s.attribute("data-name") == Some(name))
            .unwrap()
    };
    assert_eq!(texts(step("A"), "qualifier"), ["L T#5s"]);
    assert_eq!(texts(step("B"), "qualifier"), ["D t"]);
    assert_eq!(texts(step("B"), "indicator"), ["done"]);
    assert_eq!(texts(step("C"), "qualifier"), ["P1"]);
    assert_eq!(texts(step("D"), "qualifier"), ["S"]);
    assert_eq!(texts(step("E"), "qualifier"), ["R"]);
    let back = with_class(&doc, "transition")
        .into_iter()
        .find(|t| t.attribute("data-name") == Some("back"))
        .unwrap();
    assert_eq!(texts(back, "label"), ["back (PRIORITY := 1)"]);
    assert_eq!(texts(back, "condition"), ["LD done", "AND go"]);
    assert_eq!(with_class(&doc, "loop").len(), 1);
    render(&svg, "branches");
}

#[test]
fn active_steps_are_marked_at_the_chosen_cycle() {
    let plc = Plc::compile(sources(&["programs/chariot.sfc"]), &Options::default()).unwrap();
    let mut session = Session::new(plc);
    session
        .bind_stimulus(parse_stimulus(&repo_text("programs/chariot.csv")).unwrap())
        .unwrap();
    let picture = ChartPicture::of_program(session.plc()).unwrap();
    let active_at = |session: &Session| {
        let svg = picture.to_svg_active(&picture.active_in(session.plc()));
        let doc = Document::parse(&svg).unwrap();
        let on: Vec<String> = with_class(&doc, "active")
            .iter()
            .map(|n| n.attribute("data-name").unwrap().to_string())
            .collect();
        let tokens = with_class(&doc, "token").len();
        (on, tokens, svg)
    };
    for _ in 0..5 {
        session.step().unwrap();
    }
    assert_eq!(active_at(&session).0, ["INIT"], "cycles 0-4: INIT");
    session.step().unwrap(); // cycle 5: Dcy, INIT → AV
    let (on, tokens, svg) = active_at(&session);
    assert_eq!((on, tokens), (vec!["AV".to_string()], 1));
    render(&svg, "chariot_active");
    let doc = Document::parse(&svg).unwrap();
    let av = with_class(&doc, "active")[0];
    let fill = av.children().find(|c| c.has_tag_name("rect")).unwrap();
    assert_ne!(fill.attribute("fill"), Some("white"));
}

const WAVES: &str = "
PROGRAM waves
VAR_OUTPUT q : BOOL; n : INT; word : STRING; END_VAR
q := NOT q;
n := n + 1;
IF n MOD 4 = 0 THEN word := 'four'; ELSE word := 'other'; END_IF;
END_PROGRAM
";

/// x of the tick labelled `label` on the time axis.
fn tick_x(doc: &Document, label: &str) -> f64 {
    let tick = with_class(doc, "tick")
        .into_iter()
        .find(|t| t.attribute("data-time") == Some(label))
        .unwrap_or_else(|| panic!("a tick at {label}"));
    let line = tick.children().find(|c| c.has_tag_name("line")).unwrap();
    line.attribute("x1").unwrap().parse().unwrap()
}

fn points(n: Node) -> Vec<(f64, f64)> {
    n.attribute("points")
        .unwrap()
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

fn run_waves(cycles: u64) -> (Plc, TimingDiagram) {
    let mut plc = compile(WAVES);
    let mut diagram = TimingDiagram::for_plc(&plc, &["q", "n", "word"]).unwrap();
    for _ in 0..cycles {
        plc.run_cycle().unwrap();
        diagram.record(&plc);
    }
    diagram.set_end(plc.time());
    (plc, diagram)
}

#[test]
fn timing_diagram_rows_and_transitions_at_the_right_time() {
    let (_, diagram) = run_waves(10);
    let svg = diagram.to_svg();
    let doc = Document::parse(&svg).unwrap();
    let signals = with_class(&doc, "signal");
    let names: Vec<&str> = signals
        .iter()
        .map(|s| s.attribute("data-name").unwrap())
        .collect();
    assert_eq!(names, ["q", "n", "word"]);
    assert!(has_class(&signals[0], "logic"));
    assert!(has_class(&signals[1], "number"));
    assert!(has_class(&signals[2], "label"));
    for s in &signals {
        assert_eq!(texts(*s, "name"), [s.attribute("data-name").unwrap()]);
    }
    // 10 cycles of 10 ms: the axis runs from 0 to 100 ms.
    let x0 = tick_x(&doc, "0s");
    let x20 = tick_x(&doc, "20ms");
    let per_ms = (x20 - x0) / 20.0;
    // q toggles every cycle: its wave has a vertical edge at every 10 ms
    // from 10 ms to 90 ms (cycle k runs at k × 10 ms).
    let wave = signals[0]
        .descendants()
        .find(|n| has_class(n, "wave"))
        .unwrap();
    let pts = points(wave);
    let edges: Vec<f64> = pts
        .windows(2)
        .filter(|w| w[0].0 == w[1].0 && w[0].1 != w[1].1)
        .map(|w| w[0].0)
        .collect();
    let want: Vec<f64> = (1..10).map(|k| x0 + per_ms * 10.0 * k as f64).collect();
    assert_eq!(edges.len(), want.len(), "{edges:?}");
    for (got, want) in edges.iter().zip(&want) {
        assert!((got - want).abs() < 0.02, "edge at {got}, expected {want}");
    }
    // q is TRUE in cycle 0 (NOT FALSE): the first level is the high one.
    assert!(pts[0].1 < pts[2].1);
    // n counts 1..10, each value written at its change.
    let values = texts(signals[1], "value");
    let want: Vec<String> = (1..=10).map(|v| v.to_string()).collect();
    assert_eq!(values, want);
    // The string: a labelled segment per change ('other' x3, 'four', ...).
    assert_eq!(
        texts(signals[2], "value"),
        ["'other'", "'four'", "'other'", "'four'", "'other'"]
    );
    assert_eq!(
        signals[2]
            .descendants()
            .filter(|n| has_class(n, "segment"))
            .count(),
        5
    );
    render(&svg, "waves");
}

#[test]
fn forced_values_are_marked() {
    let mut plc = compile(WAVES);
    plc.force("q", "TRUE").unwrap();
    let mut diagram = TimingDiagram::for_plc(&plc, &["q", "n"]).unwrap();
    for _ in 0..4 {
        plc.run_cycle().unwrap();
        diagram.record(&plc);
    }
    plc.unforce("q").unwrap();
    for _ in 0..4 {
        plc.run_cycle().unwrap();
        diagram.record(&plc);
    }
    let svg = diagram.to_svg();
    let doc = Document::parse(&svg).unwrap();
    let signals = with_class(&doc, "signal");
    let forced = |s: &Node| s.descendants().filter(|n| has_class(n, "forced")).count();
    assert_eq!(forced(&signals[0]), 1, "one forced span of q");
    assert_eq!(forced(&signals[1]), 0);
    assert!(svg.contains("forced value"), "the legend");
}

#[test]
fn long_runs_stop_recording_with_a_note() {
    let (plc, diagram) = run_waves(45_000);
    // q changes every cycle, n too, word 2 times in 4: 100 000 changes are
    // reached before cycle 45 000.
    let stopped = diagram.stopped_at().expect("the limit was reached");
    assert!(stopped < plc.cycle());
    assert!(diagram.changes() <= plcrun::MAX_CHANGES);
    let svg = diagram.to_svg();
    assert!(svg.contains(&format!("recording stopped at cycle {stopped}")));
    Document::parse(&svg).unwrap();
}

#[test]
fn pictures_are_deterministic() {
    let map = sources(&["programs/transfer_station.sfc"]);
    let a = ChartPicture::from_sources(&map, None).unwrap().to_svg();
    let b = ChartPicture::from_sources(&sources(&["programs/transfer_station.sfc"]), None)
        .unwrap()
        .to_svg();
    assert_eq!(a, b);
    assert_eq!(run_waves(25).1.to_svg(), run_waves(25).1.to_svg());
}

#[test]
fn rendering_draws_the_text() {
    // The same picture without its text renders differently: the labels
    // are really drawn, with a real font.
    let svg = ChartPicture::from_sources(&sources(&["programs/chariot.sfc"]), None)
        .unwrap()
        .to_svg();
    let doc = Document::parse(&svg).unwrap();
    let mut bare = svg.clone();
    for t in doc.descendants().filter(|n| n.has_tag_name("text")) {
        let range = t.range();
        bare = bare.replacen(&svg[range], "", 1);
    }
    assert!(!bare.contains("<text"));
    let with_text = render(&svg, "chariot");
    let without = render(&bare, "chariot_bare");
    assert_eq!(with_text.len(), without.len());
    let differing = with_text
        .chunks(4)
        .zip(without.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(differing > 500, "text pixels: {differing}");
}

#[test]
fn choosing_the_chart() {
    let two = format!("{BRANCHES}\n{}", repo_text("programs/chariot.sfc"));
    let mut map = SourceMap::new();
    map.add("two.sfc", two);
    let err = ChartPicture::from_sources(&map, None).unwrap_err();
    assert_eq!(
        err,
        plcrun::DrawError::SeveralCharts(vec!["branches".into(), "CHARIOT".into()])
    );
    assert!(err.to_string().contains("--program"));
    let chariot = ChartPicture::from_sources(&map, Some("chariot")).unwrap();
    assert_eq!(chariot.model().pou, "CHARIOT");
    assert_eq!(
        ChartPicture::from_sources(&map, Some("nothing")).unwrap_err(),
        plcrun::DrawError::NoSuchPou("nothing".into())
    );
    let mut st = SourceMap::new();
    st.add("p.st", "PROGRAM p VAR x : INT; END_VAR x := 1; END_PROGRAM");
    assert_eq!(
        ChartPicture::from_sources(&st, Some("P")).unwrap_err(),
        plcrun::DrawError::NotAChart("P".into())
    );
    assert_eq!(
        ChartPicture::from_sources(&st, None).unwrap_err(),
        plcrun::DrawError::NoChart
    );
}

#[test]
fn the_pictures_of_the_docs_render() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/images");
    let mut rendered = 0;
    for entry in std::fs::read_dir(&dir).expect("docs/images") {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "svg") {
            let svg = std::fs::read_to_string(&path).unwrap();
            Document::parse(&svg).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            render(&svg, &path.file_stem().unwrap().to_string_lossy());
            rendered += 1;
        }
    }
    assert_eq!(
        rendered, 6,
        "the pictures of docs/sfc.md and docs/plcopen.md"
    );
}

#[test]
fn reals_that_are_not_numbers_stay_inside_their_row() {
    let src = "PROGRAM r VAR_OUTPUT x : REAL; END_VAR
        IF x = 0.0 THEN x := 1.0; ELSIF x = 1.0 THEN x := 0.0 / 0.0; ELSE x := 0.0; END_IF;
        END_PROGRAM";
    let mut plc = Plc::compile_files(&[("r.st", src)], &Options::default()).unwrap();
    let mut diagram = TimingDiagram::for_plc(&plc, &["x"]).unwrap();
    for _ in 0..6 {
        plc.run_cycle().unwrap();
        diagram.record(&plc);
    }
    let svg = diagram.to_svg();
    let doc = Document::parse(&svg).unwrap();
    let signal = with_class(&doc, "signal")[0];
    assert!(has_class(&signal, "number"));
    assert!(
        texts(signal, "value").iter().any(|v| v.contains("NaN")),
        "{svg}"
    );
    let wave = signal.descendants().find(|n| has_class(n, "wave")).unwrap();
    let ys: Vec<f64> = points(wave).iter().map(|p| p.1).collect();
    let lo = ys.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(lo > 30.0, "every point inside the row: {ys:?}");
}

#[test]
fn enumerations_are_labelled_segments() {
    let src = "TYPE Light : (Red, Amber, Green); END_TYPE
        PROGRAM lights VAR_OUTPUT l : Light; END_VAR
        CASE l OF Red: l := Green; Green: l := Amber; Amber: l := Red; END_CASE;
        END_PROGRAM";
    let mut plc = Plc::compile_files(&[("l.st", src)], &Options::default()).unwrap();
    let mut diagram = TimingDiagram::for_plc(&plc, &["l"]).unwrap();
    for _ in 0..6 {
        plc.run_cycle().unwrap();
        diagram.record(&plc);
    }
    diagram.set_end(plc.time());
    let svg = diagram.to_svg();
    let doc = Document::parse(&svg).unwrap();
    let signal = with_class(&doc, "signal")[0];
    assert!(has_class(&signal, "label"));
    assert_eq!(
        texts(signal, "value"),
        ["Green", "Amber", "Red", "Green", "Amber", "Red"]
    );
    assert_eq!(
        signal
            .descendants()
            .filter(|n| has_class(n, "segment"))
            .count(),
        6
    );
}

/// The PLCopen test projects with FBD and LD bodies.
const NETWORKS: [&str; 4] = [
    "tests/plcopen/drawn_rungs.xml",
    "tests/plcopen/drawn_network.xml",
    "tests/plcopen/fbd_elements.xml",
    "tests/plcopen/ld_elements.xml",
];

#[test]
fn every_element_of_a_network_is_drawn_once_and_the_picture_renders() {
    for path in NETWORKS {
        let picture = plcrun::NetworkPicture::from_sources(&sources(&[path]), None).unwrap();
        let svg = picture.to_svg();
        assert_eq!(svg, picture.to_svg(), "{path}: deterministic");
        let doc = Document::parse(&svg).unwrap();
        for pou in picture.pous() {
            let mut drawn: Vec<&str> = doc
                .descendants()
                .filter(|n| {
                    n.ancestors()
                        .any(|a| a.attribute("data-pou") == Some(&pou.name))
                })
                .filter_map(|n| n.attribute("data-id"))
                .collect();
            drawn.sort_unstable();
            let mut ids: Vec<&str> = pou.diagram.elements.iter().map(|e| e.id.as_str()).collect();
            ids.sort_unstable();
            assert_eq!(drawn, ids, "{path}: {}", pou.name);
        }
        let name = path.rsplit('/').next().unwrap().replace(".xml", "");
        render(&svg, &name);
    }
}

#[test]
fn draw_sources_draws_the_chart_or_the_networks_and_says_why_not() {
    use plcrun::{DrawError, draw_sources};
    let chart = draw_sources(&sources(&["programs/chariot.sfc"]), None).unwrap();
    assert!(chart.contains("class=\"step"), "a chart");
    let rungs = draw_sources(&sources(&[NETWORKS[0]]), None).unwrap();
    assert!(rungs.contains("class=\"network ld\""), "the rungs");
    let both = sources(&[NETWORKS[0], NETWORKS[1]]);
    let all = draw_sources(&both, None).unwrap();
    assert_eq!(all.matches("class=\"network ").count(), 2);
    let one = draw_sources(&both, Some("network")).unwrap();
    assert_eq!(one.matches("class=\"network fbd\"").count(), 1);
    assert_eq!(
        draw_sources(&both, Some("nope")).unwrap_err(),
        DrawError::NoSuchPou("nope".into())
    );
    let textual = sources(&["tests/plcopen/comparator.xml"]);
    assert_eq!(
        draw_sources(&textual, Some("COMPA")).unwrap_err(),
        DrawError::NotDrawable("COMPA".into())
    );
    assert_eq!(
        draw_sources(&textual, None).unwrap_err(),
        DrawError::NothingToDraw
    );
}
