//! `plcrun export --plcopen` of PLCopen projects with FBD and LD bodies
//! (issue #29, point 3): read, exported and read again, every graphical
//! body is the same diagram (elements, localIds, positions, sizes, pins,
//! modifiers, connections and their routes) and the project runs the
//! same; charts (with FBD/LD actions, transitions and wired conditions)
//! and textual POUs of the same file and of other files go along.

use crate::support::{cli, graphic};

use graphic::*;
use plcrun::syntax::plcopen::diagram::{
    ActionTarget, BodyModel, ConditionKind, Diagram, ElementKind, GraphicalPou, Language, PouBody,
    graphical_pous, project_pous,
};
use plcrun::syntax::plcopen::network::{Edge, Storage};
use plcrun::{ExportError, SourceMap, export_plcopen};

/// The test projects with graphical bodies (our own).
const GRAPHICAL: [&str; 4] = [
    "tests/plcopen/fbd_elements.xml",
    "tests/plcopen/ld_elements.xml",
    "tests/plcopen/drawn_rungs.xml",
    "tests/plcopen/drawn_network.xml",
];

/// A chart with a wired condition, FBD actions and transitions, an inline
/// LD action, divergences, convergences and a jump.
const CHART: &str = "tests/plcopen/drawn_chart.xml";

/// The export of the files given as (name, text).
fn export(files: &[(&str, &str)]) -> Result<String, ExportError> {
    let mut sources = SourceMap::new();
    for (name, text) in files {
        sources.add(*name, *text);
    }
    export_plcopen(&sources)
}

/// The graphical POUs of a project, as (name, diagram).
fn diagrams(xml: &str) -> Vec<(String, Diagram)> {
    graphical_pous(xml)
        .expect("readable")
        .into_iter()
        .map(|GraphicalPou { name, diagram, .. }| (name, diagram))
        .collect()
}

/// Every POU body of a project as read, as (name, body).
fn bodies(xml: &str) -> Vec<(String, PouBody)> {
    project_pous(xml)
        .expect("readable")
        .into_iter()
        .map(|p| (p.name, p.body))
        .collect()
}

#[test]
fn every_graphical_body_is_the_same_diagram_after_export() {
    let more = [
        CHART,
        "tests/plcopen/chariot.xml",
        "tests/plcopen/openplc_project.xml",
    ];
    for path in GRAPHICAL.into_iter().chain(more) {
        let original = repo_text(path);
        let exported = export(&[(path, &original)]).unwrap_or_else(|e| panic!("{path}: {e}"));
        let before = bodies(&original);
        assert!(!before.is_empty(), "{path}");
        assert_eq!(before, bodies(&exported), "{path}");
        // Exporting the export gives the same bytes: nothing drifts.
        let again = export(&[("again.xml", &exported)]).expect("export of the export");
        assert_eq!(exported, again, "{path}");
    }
}

#[test]
fn the_test_projects_hold_every_element_kind_and_modifier() {
    let all: Vec<Diagram> = GRAPHICAL
        .iter()
        .flat_map(|p| diagrams(&repo_text(p)))
        .map(|(_, d)| d)
        .collect();
    let elements: Vec<_> = all.iter().flat_map(|d| &d.elements).collect();
    let mut tags: Vec<&str> = elements.iter().map(|e| e.kind.tag()).collect();
    tags.sort_unstable();
    tags.dedup();
    assert_eq!(
        tags,
        [
            "block",
            "coil",
            "comment",
            "connector",
            "contact",
            "continuation",
            "inOutVariable",
            "inVariable",
            "jump",
            "label",
            "leftPowerRail",
            "outVariable",
            "return",
            "rightPowerRail",
        ]
    );
    let has = |f: &dyn Fn(&plcrun::syntax::plcopen::diagram::DiagramElement) -> bool| {
        elements.iter().any(|e| f(e))
    };
    for (kind, what) in [
        (ElementKind::Contact, "contact"),
        (ElementKind::Coil, "coil"),
    ] {
        let of = |e: &&&plcrun::syntax::plcopen::diagram::DiagramElement| e.kind == kind;
        let modifiers: Vec<_> = elements.iter().filter(of).map(|e| e.modifiers).collect();
        assert!(modifiers.iter().any(|m| m.negated), "negated {what}");
        assert!(modifiers.iter().any(|m| m.edge == Edge::Rising), "{what} P");
        assert!(
            modifiers.iter().any(|m| m.edge == Edge::Falling),
            "{what} N"
        );
    }
    assert!(has(
        &|e| e.kind == ElementKind::Coil && e.modifiers.storage == Storage::Set
    ));
    assert!(has(
        &|e| e.kind == ElementKind::Coil && e.modifiers.storage == Storage::Reset
    ));
    assert!(has(&|e| e.pins.iter().any(|p| p.modifiers.negated)));
    assert!(has(&|e| e
        .pins
        .iter()
        .any(|p| p.modifiers.edge != Edge::None)));
    assert!(has(&|e| matches!(
        &e.kind,
        ElementKind::Block {
            instance: Some(_),
            ..
        }
    )));
    assert!(has(&|e| e.order.is_some() && e.size.is_some()));
    assert!(has(&|e| e
        .inputs
        .iter()
        .any(|i| i.connections.iter().any(|c| c.route.len() >= 2))));
    assert!(all.iter().any(|d| d.language == Language::Fbd));
    assert!(all.iter().any(|d| d.language == Language::Ld));
}

#[test]
fn an_exported_project_runs_the_same_and_compiles_to_the_same_code() {
    let runs = [
        (
            GRAPHICAL[0],
            "a,b,c",
            "n,k",
            "q_and,q_nor,q_cv,q_t,q_mux,q_sum,q_skip,q_after",
        ),
        (
            GRAPHICAL[1],
            "start,stop,s1,s2,s3",
            "",
            "motor,lamp,dark,pulse,fell,latched,cnt,timed",
        ),
        (
            GRAPHICAL[2],
            "start,stop,jog",
            "",
            "run,idle,alarm,pulse,fell,done",
        ),
        (GRAPHICAL[3], "a,b", "n", "q,done,late,total"),
        (
            CHART,
            "go,abort",
            "",
            "n,lamp,busy,S0.X,S1.X,S2.X,S3.X,S4.X",
        ),
    ];
    for (path, bools, ints, outputs) in runs {
        let original = repo_text(path);
        let exported = export(&[(path, &original)]).expect("export");
        let split =
            |s: &'static str| -> Vec<&str> { s.split(',').filter(|n| !n.is_empty()).collect() };
        let stimulus = random_stimulus(&split(bools), &split(ints), 80, 4242);
        let files = |xml: &str| vec![(path.to_string(), xml.to_string())];
        let request = TraceRequest {
            cycles: 80,
            stimulus: Some(&stimulus),
            trace: Some(outputs),
            changes_only: false,
        };
        assert_same(
            &csv_trace(&files(&original), &request),
            &csv_trace(&files(&exported), &request),
            path,
        );
        let out = cli::temp_file("exported.xml", &exported);
        assert_eq!(
            cli::plcrun_ok(&["check", "--dump-ir", path]),
            cli::plcrun_ok(&["check", "--dump-ir", &out]),
            "{path}"
        );
    }
}

#[test]
fn a_mixed_project_exports_its_textual_and_graphical_pous() {
    let graphical = repo_text(GRAPHICAL[3]);
    let comparator = repo_text("tests/plcopen/comparator.xml");
    let st = "FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR\n  Twice := x * 2; (* kept *)\nEND_FUNCTION\n";
    let xml = export(&[
        ("net.xml", &graphical),
        ("cmp.xml", &comparator),
        ("twice.st", st),
    ])
    .expect("export");
    assert_eq!(diagrams(&xml), diagrams(&graphical));
    assert!(xml.contains("Twice := x * 2; (* kept *)"), "{xml}");
    let doc = roxmltree::Document::parse(&xml).expect("well-formed");
    let pous: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("pou"))
        .filter_map(|n| n.attribute("name"))
        .collect();
    assert!(
        pous.contains(&"Network") && pous.contains(&"Twice"),
        "{pous:?}"
    );
    // The hidden variables of the lowering are not declarations.
    assert!(!xml.contains("name=\"_T"), "{xml}");
    // The textual POUs of the PLCopen file run as before.
    let exported = export(&[("cmp.xml", &comparator)]).expect("export");
    let out = cli::temp_file("cmp.xml", &exported);
    assert_eq!(
        cli::plcrun_ok(&["check", "--dump-ir", "tests/plcopen/comparator.xml"]),
        cli::plcrun_ok(&["check", "--dump-ir", &out]),
    );
}

#[test]
fn an_openplc_project_keeps_its_addressing_after_export() {
    use plcrun::syntax::plcopen::origin::written_by_matiec_tools;
    // `%QX0.0` and `%QW0` are separate under `openplc` addressing, the
    // same bytes under `iec`: the export must keep the convention.
    let original = repo_text("tests/plcopen/openplc_project.xml");
    assert!(written_by_matiec_tools(&original));
    let exported = export(&[("tank.xml", &original)]).expect("export");
    assert!(
        written_by_matiec_tools(&exported),
        "the export keeps the mark"
    );
    let textual =
        export(&[("twin.st", &repo_text("tests/plcopen/openplc_project.st"))]).expect("export");
    assert!(
        !written_by_matiec_tools(&textual),
        "textual sources have none"
    );
    let out = cli::temp_file("tank.xml", &exported);
    let (_, _, before) = cli::plcrun(&["check", "tests/plcopen/openplc_project.xml"]);
    let (_, _, after) = cli::plcrun(&["check", &out]);
    let warnings = |e: &str| e.lines().filter(|l| l.starts_with("warning")).count();
    assert_eq!(warnings(&before), warnings(&after), "{before}\n{after}");
}

#[test]
fn entities_in_values_and_bodies_are_written_once_escaped() {
    let text = "<?xml version=\"1.0\"?>\n<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\" xmlns:xhtml=\"http://www.w3.org/1999/xhtml\"><types><dataTypes/><pous>\
        <pou name=\"P\" pouType=\"program\"><interface><outputVars>\
        <variable name=\"s\"><type><string/></type><initialValue><simpleValue value=\"&apos;a&lt;b&apos;\"/></initialValue></variable>\
        <variable name=\"q\"><type><BOOL/></type></variable></outputVars></interface>\
        <body><ST><xhtml:p>q := s = 'a&lt;b' AND 1 &lt; 2;</xhtml:p></ST></body></pou>\
        </pous></types><instances><configurations/></instances></project>";
    let exported = export(&[("e.xml", text)]).expect("export");
    assert!(exported.contains("value=\"'a&lt;b'\""), "{exported}");
    assert_eq!(bodies(text), bodies(&exported));
    let request = TraceRequest {
        cycles: 1,
        stimulus: None,
        trace: Some("q,s"),
        changes_only: false,
    };
    let trace = csv_trace(&[("e.xml", exported.as_str())], &request);
    assert!(trace.ends_with(",TRUE,'a<b'\n"), "{trace}");
}

#[test]
fn a_chart_keeps_its_graphical_actions_transitions_and_conditions() {
    let original = repo_text(CHART);
    let Some((_, PouBody::Chart(chart))) = bodies(&original).into_iter().next() else {
        panic!("a chart");
    };
    let kinds: Vec<&str> = chart.chart.elements.iter().map(|e| e.kind.tag()).collect();
    for tag in [
        "step",
        "transition",
        "selectionDivergence",
        "selectionConvergence",
        "simultaneousDivergence",
        "simultaneousConvergence",
        "jumpStep",
        "actionBlock",
        "leftPowerRail",
        "contact",
        "comment",
    ] {
        assert!(kinds.contains(&tag), "{tag} in {kinds:?}");
    }
    let conditions: Vec<&ConditionKind> = chart
        .chart
        .elements
        .iter()
        .filter_map(|e| match &e.kind {
            ElementKind::Transition { condition, .. } => Some(&condition.kind),
            _ => None,
        })
        .collect();
    assert!(
        conditions
            .iter()
            .any(|c| matches!(c, ConditionKind::Wired(_)))
    );
    assert!(
        conditions
            .iter()
            .any(|c| matches!(c, ConditionKind::Reference(_)))
    );
    let graphical = |b: &Option<BodyModel>| matches!(b, Some(BodyModel::Diagram(_)));
    assert!(chart.actions.iter().any(|a| graphical(&a.body)));
    assert!(chart.transitions.iter().any(|t| graphical(&t.body)));
    let inline_ld = chart.chart.elements.iter().any(|e| match &e.kind {
        ElementKind::ActionBlock(list) => list.iter().any(|a| {
            matches!(&a.action, ActionTarget::Inline(BodyModel::Diagram(d)) if d.language == Language::Ld)
        }),
        _ => false,
    });
    assert!(inline_ld);
    let exported = export(&[(CHART, &original)]).expect("export");
    assert_eq!(bodies(&original), bodies(&exported));
}

/// Measures the round trip on a folder of third-party projects (not in the
/// repository): `PLCRUN_ROUND_TRIP_DIR=DIR cargo test --test suite
/// plcopen_export_graphic:: -- --ignored --nocapture`.
#[test]
#[ignore = "needs PLCRUN_ROUND_TRIP_DIR"]
fn third_party_projects_round_trip() {
    let Some(dir) = std::env::var_os("PLCRUN_ROUND_TRIP_DIR") else {
        return;
    };
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .expect("a folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "xml"))
        .collect();
    paths.sort();
    let (mut same, mut networks, mut files) = (0, 0, 0);
    let (mut same_bodies, mut all_bodies, mut same_code) = (0, 0, 0);
    for path in &paths {
        let text = std::fs::read_to_string(path).expect("text");
        let Ok(before) = graphical_pous(&text) else {
            println!("{}: unreadable", path.display());
            continue;
        };
        files += 1;
        networks += before.len();
        let all = project_pous(&text).unwrap_or_default();
        all_bodies += all.len();
        match export(&[("in.xml", &text)]) {
            Ok(xml) => {
                let after_all = project_pous(&xml).unwrap_or_default();
                same_bodies += all
                    .iter()
                    .filter(|b| {
                        after_all
                            .iter()
                            .any(|a| a.name == b.name && a.body == b.body)
                    })
                    .count();
                let after = diagrams(&xml);
                let kept = before
                    .iter()
                    .filter(|b| after.iter().any(|(n, d)| *n == b.name && *d == b.diagram))
                    .count();
                same += kept;
                let out = cli::temp_file("exported.xml", &xml);
                let code = same_compilation(&path.to_string_lossy(), &out);
                same_code += usize::from(code);
                println!(
                    "{}: {kept}/{} networks the same, {} compilation",
                    path.display(),
                    before.len(),
                    if code { "the same" } else { "a different" }
                );
            }
            Err(e) => println!("{}: not exported: {e}", path.display()),
        }
    }
    println!("{same} of {networks} FBD/LD bodies in {files} files round trip to the same network");
    println!("{same_bodies} of {all_bodies} POU bodies (any language) are read back the same");
    println!("{same_code} of {files} files compile to the same code or the same diagnostics");
}

/// True when `plcrun check --dump-ir` gives the same exit status, code and
/// diagnostics (their headlines, without places) for the two files.
fn same_compilation(a: &str, b: &str) -> bool {
    let run = |path: &str| {
        let (status, out, err) = cli::plcrun(&["check", "--dump-ir", path]);
        let mut heads: Vec<String> = err
            .lines()
            .filter(|l| l.starts_with("error") || l.starts_with("warning"))
            .map(str::to_string)
            .collect();
        heads.sort();
        (status, out, heads)
    };
    run(a) == run(b)
}
