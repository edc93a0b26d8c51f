//! The PLCopen commands of the binary: `plcrun FILE.xml`, `plcrun check
//! FILE.xml` and `plcrun export --plcopen`, end to end.

use crate::support::cli;

use cli::{plcrun, plcrun_ok, temp_file};

#[test]
fn an_xml_project_runs_and_checks_like_a_textual_file() {
    let args = [
        "tests/plcopen/chariot.xml",
        "--cycles",
        "60320",
        "--stimulus",
        "programs/chariot.csv",
        "--trace",
        "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,AR.X,KMAV,KMAR,VOM",
        "--changes-only",
    ];
    let expected = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("programs/chariot.expected.csv"),
    )
    .expect("expected trace");
    assert_eq!(plcrun_ok(&args), expected);
    let (code, _, err) = plcrun(&["check", "tests/plcopen/openplc_project.xml"]);
    assert_eq!((code, err.as_str()), (0, "ok: 1 file checked\n"));
}

#[test]
fn export_writes_a_project_that_runs_identically() {
    let out = temp_file("chariot.xml", "");
    plcrun_ok(&["export", "--plcopen", "programs/chariot.sfc", "-o", &out]);
    let written = std::fs::read_to_string(&out).expect("the export was written");
    assert!(written.starts_with("<?xml"));
    let run = |file: &str| {
        plcrun_ok(&[
            file,
            "--cycles",
            "3000",
            "--stimulus",
            "programs/chariot.csv",
            "--changes-only",
        ])
    };
    assert_eq!(run(&out), run("programs/chariot.sfc"));
    let stdout = plcrun_ok(&["export", "--plcopen", "programs/chariot.sfc"]);
    assert_eq!(stdout, written);
}

#[test]
fn refusals_and_usage_errors_have_their_exit_statuses() {
    // (FBD bodies, refused here once, run since issue #29: a macro step is
    // the refusal now.)
    let refused = temp_file(
        "refused.xml",
        "<?xml version=\"1.0\"?>\n<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\">\n<types><dataTypes/><pous>\n<pou name=\"P\" pouType=\"program\"><body>\n<SFC><macroStep localId=\"1\" name=\"M\"/></SFC>\n</body></pou>\n</pous></types><instances><configurations/></instances></project>\n",
    );
    let (code, _, err) = plcrun(&["check", &refused]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("E807") && err.contains("refused.xml:5:6"),
        "{err}"
    );
    let (code, _, err) = plcrun(&["export", "programs/chariot.sfc"]);
    assert_eq!(code, 2, "--plcopen is required: {err}");
    // PLCopen input exports too (tests/plcopen_export_graphic.rs).
    let (code, out, err) = plcrun(&["export", "--plcopen", "tests/plcopen/chariot.xml"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("<SFC>"), "{out}");
}

/// The GRAFCET-mode programs (forcing orders are step associations) export
/// and run identically under `--grafcet`; `tests/plcopen.rs` round-trips
/// the others with default options.
#[test]
fn grafcet_mode_programs_round_trip_under_grafcet() {
    for (name, cycles, trace) in [
        ("grafcet_transient", "13", None),
        (
            "grafcet_forcing",
            "16",
            Some("S0.X,S1.X,S2.X,S3.X,G1.P0.X,G1.P1.X,G1.P2.X,motor,alarm"),
        ),
    ] {
        let source = format!("programs/{name}.sfc");
        let stimulus = format!("programs/{name}.csv");
        let out = temp_file(&format!("{name}.xml"), "");
        plcrun_ok(&["export", "--plcopen", &source, "-o", &out]);
        let run = |file: &str| {
            let mut args = vec![
                file,
                "--grafcet",
                "--cycles",
                cycles,
                "--stimulus",
                &stimulus,
            ];
            if let Some(t) = trace {
                args.extend(["--trace", t]);
            }
            plcrun_ok(&args)
        };
        assert_eq!(run(&out), run(&source), "{name}");
    }
}

/// S7-200 STL has no PLCopen body language: export refuses it by name.
#[test]
fn an_s7_200_program_is_not_exported() {
    let (code, out, err) = plcrun(&["export", "--plcopen", "programs/s7_table_example1.awl"]);
    assert_eq!((code, out.as_str()), (2, ""), "{err}");
    assert!(err.contains("S7-200 STL"), "{err}");
}
