//! `plcrun draw` and the `--svg` / `--svg-chart` outputs of a run, through
//! the real binary; and the pictures of docs/sfc.md, which this test draws
//! again and compares byte for byte (`PLCRUN_BLESS=1` rewrites them).

use crate::support::cli;

use cli::{plcrun, plcrun_ok};
use roxmltree::Document;

fn classed<'a, 'i>(doc: &'a Document<'i>, class: &str) -> Vec<roxmltree::Node<'a, 'i>> {
    doc.descendants()
        .filter(|n| {
            n.attribute("class")
                .is_some_and(|c| c.split(' ').any(|k| k == class))
        })
        .collect()
}

fn temp_path(name: &str) -> String {
    cli::temp_file(name, "")
}

#[test]
fn draw_prints_or_writes_the_chart() {
    let printed = plcrun_ok(&["draw", "programs/chariot.sfc"]);
    let doc = Document::parse(&printed).expect("SVG on standard output");
    assert_eq!(classed(&doc, "step").len(), 4);
    assert_eq!(classed(&doc, "transition").len(), 4);
    let out = temp_path("chart.svg");
    let (code, stdout, _) = plcrun(&["draw", "programs/graf1_sfc.sfc", "-o", &out]);
    assert_eq!((code, stdout.as_str()), (0, ""));
    let written = std::fs::read_to_string(&out).unwrap();
    let doc = Document::parse(&written).unwrap();
    assert_eq!(classed(&doc, "step").len(), 5);
    assert_eq!(classed(&doc, "initial").len(), 1);
}

#[test]
fn draw_refuses_what_it_cannot_draw() {
    let (code, _, err) = plcrun(&["draw", "programs/comparator.st"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("no PROGRAM or FUNCTION_BLOCK has a chart"),
        "{err}"
    );
    let (code, _, err) = plcrun(&["draw", "programs/chariot.sfc", "--program", "nope"]);
    assert_eq!(code, 2);
    assert!(err.contains("no POU named `nope`"), "{err}");
    let bad = cli::temp_file(
        "bad.sfc",
        "PROGRAM p\nINITIAL_STEP A : END_STEP\nTRANSITION FROM A TO Z := TRUE; END_TRANSITION\nEND_PROGRAM\n",
    );
    let (code, out, err) = plcrun(&["draw", &bad]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    assert!(err.contains("error"), "{err}");
}

/// The `data-*` attribute `name` of every element of class `class`.
fn data_of(doc: &Document, class: &str, name: &str) -> Vec<String> {
    classed(doc, class)
        .iter()
        .filter_map(|n| n.attribute(name).map(str::to_string))
        .collect()
}

#[test]
fn draw_draws_ld_rungs_with_their_symbols() {
    let svg = plcrun_ok(&["draw", "tests/plcopen/drawn_rungs.xml"]);
    let doc = Document::parse(&svg).expect("well-formed SVG");
    // One symbol per contact and coil, with the letter its kind shows.
    let mut contacts = data_of(&doc, "contact", "data-symbol");
    contacts.sort();
    assert_eq!(contacts, ["", "", "", "", "/", "N", "P"]);
    let mut coils = data_of(&doc, "coil", "data-symbol");
    coils.sort();
    assert_eq!(coils, ["", "", "/", "N", "P", "R", "S"]);
    assert_eq!(classed(&doc, "rail").len(), 2);
    assert_eq!(classed(&doc, "comment").len(), 1);
    assert_eq!(data_of(&doc, "block", "data-type"), ["TON"]);
    // Every contact and coil names its variable, every wire is a polyline.
    let names: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("name"))
        .filter_map(|n| n.text())
        .collect();
    for v in [
        "start", "stop", "run", "jog", "alarm", "idle", "pulse", "fell", "done",
    ] {
        assert!(names.contains(&v), "{v} in {names:?}");
    }
    assert!(classed(&doc, "wire").len() >= 18);
    // The same input gives the same bytes.
    assert_eq!(svg, plcrun_ok(&["draw", "tests/plcopen/drawn_rungs.xml"]));
}

#[test]
fn draw_draws_an_fbd_network_with_blocks_variables_and_flow_control() {
    let svg = plcrun_ok(&[
        "draw",
        "tests/plcopen/drawn_network.xml",
        "--program",
        "network",
    ]);
    let doc = Document::parse(&svg).expect("well-formed SVG");
    assert_eq!(data_of(&doc, "block", "data-type"), ["AND", "TON", "ADD"]);
    let instances: Vec<&str> = classed(&doc, "instance")
        .iter()
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(instances, ["t1"]);
    // A text for each variable, a circle for each negation.
    let expressions: Vec<&str> = classed(&doc, "expression")
        .iter()
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(
        expressions,
        [
            "a", "b", "q", "T#1s", "done", "n", "1", "count", "total", "n > 100", "n < 0", "TRUE",
            "late"
        ]
    );
    assert_eq!(classed(&doc, "negation").len(), 2);
    for class in [
        "connector",
        "continuation",
        "jump",
        "label",
        "return",
        "comment",
    ] {
        assert_eq!(classed(&doc, class).len(), 1, "{class}");
    }
    let pins: Vec<&str> = classed(&doc, "pin")
        .iter()
        .filter_map(|n| n.text())
        .collect();
    assert!(pins.contains(&"PT") && pins.contains(&"ET"), "{pins:?}");
}

#[test]
fn draw_says_what_it_cannot_draw_in_a_plcopen_project() {
    let (code, _, err) = plcrun(&["draw", "tests/plcopen/comparator.xml"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("and no POU an FBD or LD body"), "{err}");
    let (code, _, err) = plcrun(&[
        "draw",
        "tests/plcopen/openplc_project.xml",
        "--pou",
        "Counter",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("the body of `Counter` is neither a chart (SFC) nor an FBD or LD network"),
        "{err}"
    );
}

#[test]
fn a_run_writes_a_timing_diagram_and_the_chart_at_a_cycle() {
    let timing = temp_path("timing.svg");
    let chart = temp_path("chart.svg");
    let printed = plcrun_ok(&[
        "programs/chariot.sfc",
        "--cycles",
        "120",
        "--stimulus",
        "programs/chariot.csv",
        "--trace",
        "Dcy,KMAV,ATT.X,ATT.T",
        "--svg",
        &timing,
        "--svg-chart",
        &chart,
        "--svg-chart-cycle",
        "50",
    ]);
    // The trace is printed as without the pictures.
    assert_eq!(printed.lines().count(), 121);
    let text = std::fs::read_to_string(&timing).unwrap();
    let doc = Document::parse(&text).unwrap();
    let names: Vec<&str> = classed(&doc, "signal")
        .iter()
        .map(|s| s.attribute("data-name").unwrap())
        .collect();
    assert_eq!(names, ["Dcy", "KMAV", "ATT.X", "ATT.T"]);
    let text = std::fs::read_to_string(&chart).unwrap();
    let doc = Document::parse(&text).unwrap();
    let active: Vec<&str> = classed(&doc, "active")
        .iter()
        .map(|s| s.attribute("data-name").unwrap())
        .collect();
    assert_eq!(active, ["AV"], "cycle 50: the trolley runs to B");
    // Without --svg-chart-cycle: the last cycle run (119: waiting at B).
    plcrun_ok(&[
        "programs/chariot.sfc",
        "--cycles",
        "120",
        "--stimulus",
        "programs/chariot.csv",
        "--svg-chart",
        &chart,
    ]);
    let text = std::fs::read_to_string(&chart).unwrap();
    assert!(text.contains(r#"class="step active" data-name="ATT""#));
}

#[test]
fn a_chart_cycle_after_the_run_is_an_error() {
    let chart = temp_path("chart.svg");
    let (code, _, err) = plcrun(&[
        "programs/chariot.sfc",
        "--cycles",
        "10",
        "--svg-chart",
        &chart,
        "--svg-chart-cycle",
        "10",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("the run ended before cycle 10"), "{err}");
    let (code, _, err) = plcrun(&[
        "programs/chariot.sfc",
        "--cycles",
        "3",
        "--svg-chart",
        &chart,
        "--svg-chart-cycle",
        "18446744073709551615",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("the run ended before cycle 18446744073709551615"),
        "{err}"
    );
    let (code, _, err) = plcrun(&[
        "programs/comparator.st",
        "--cycles",
        "1",
        "--svg-chart",
        &chart,
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--svg-chart: no PROGRAM"), "{err}");
}

/// The pictures of docs/sfc.md: (file under docs/images/, arguments that
/// draw it into `OUT`).
const DOC_IMAGES: &[(&str, &[&str])] = &[
    (
        "chariot_chart.svg",
        &["draw", "programs/chariot.sfc", "-o", "OUT"],
    ),
    (
        "chariot_timing.svg",
        &[
            "programs/chariot.sfc",
            "--cycles",
            "60320",
            "--stimulus",
            "programs/chariot.csv",
            "--trace",
            "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,AR.X,KMAV,KMAR,VOM",
            "--format",
            "csv",
            "--changes-only",
            "--svg",
            "OUT",
        ],
    ),
    (
        "chariot_start.svg",
        &[
            "programs/chariot.sfc",
            "--cycles",
            "130",
            "--stimulus",
            "programs/chariot.csv",
            "--trace",
            "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,KMAV,VOM,ATT.T",
            "--svg",
            "OUT",
        ],
    ),
    (
        "ld_rungs.svg",
        &["draw", "tests/plcopen/drawn_rungs.xml", "-o", "OUT"],
    ),
    (
        "fbd_network.svg",
        &[
            "draw",
            "tests/plcopen/drawn_network.xml",
            "--pou",
            "Network",
            "-o",
            "OUT",
        ],
    ),
    (
        "chariot_chart_cycle_50.svg",
        &[
            "programs/chariot.sfc",
            "--cycles",
            "51",
            "--stimulus",
            "programs/chariot.csv",
            "--svg-chart",
            "OUT",
            "--svg-chart-cycle",
            "50",
        ],
    ),
];

#[test]
fn the_pictures_of_the_docs_are_up_to_date() {
    let bless = std::env::var_os("PLCRUN_BLESS").is_some();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/images");
    let mut stale = Vec::new();
    for (name, args) in DOC_IMAGES {
        let out = temp_path(name);
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "OUT" { out.as_str() } else { a })
            .collect();
        plcrun_ok(&args);
        let drawn = std::fs::read_to_string(&out).unwrap();
        Document::parse(&drawn).unwrap();
        let path = dir.join(name);
        if bless {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &drawn).unwrap();
        } else if std::fs::read_to_string(&path).ok().as_deref() != Some(drawn.as_str()) {
            stale.push(*name);
        }
    }
    assert!(
        stale.is_empty(),
        "docs/images/{stale:?} differ from what plcrun draws now; run PLCRUN_BLESS=1 cargo test --test suite draw_cli::"
    );
}
