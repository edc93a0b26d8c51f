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
