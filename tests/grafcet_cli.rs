//! `--grafcet` on the command line: `run` selects IEC 60848 evolution,
//! `check` accepts forcing orders with it and refuses them without, and an
//! unstable chart ends the run with R020 and exit status 3.

use crate::support::cli;

use cli::{plcrun, plcrun_ok, temp_file};

const TRACE: &str = "X0.X,X1.X,X2.X,pass,seen,count";

#[test]
fn grafcet_flag_changes_the_evolution_of_run() {
    let args = |grafcet: bool| {
        let mut a = vec![
            "programs/grafcet_transient.sfc",
            "--cycles",
            "3",
            "--stimulus",
            "programs/grafcet_transient.csv",
            "--trace",
            TRACE,
        ];
        if grafcet {
            a.push("--grafcet");
        }
        a
    };
    // Cycle 2: a and b rise together. SFC: X1 active, pass TRUE; GRAFCET:
    // X1 transient, X2 active, pass FALSE (seen and count act in both).
    let sfc = plcrun_ok(&args(false));
    assert_eq!(
        sfc.lines().nth(3),
        Some("2,T#20ms,FALSE,TRUE,FALSE,TRUE,TRUE,1")
    );
    let grafcet = plcrun_ok(&args(true));
    assert_eq!(
        grafcet.lines().nth(3),
        Some("2,T#20ms,FALSE,FALSE,TRUE,FALSE,TRUE,1")
    );
}

#[test]
fn check_accepts_forcing_orders_only_with_grafcet() {
    let (code, _, err) = plcrun(&["check", "programs/grafcet_forcing.sfc"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[E630]"), "{err}");
    let (code, _, err) = plcrun(&["check", "programs/grafcet_forcing.sfc", "--grafcet"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn an_unstable_chart_exits_with_status_3_and_r020() {
    let src = temp_file(
        "unstable.sfc",
        "PROGRAM U\nINITIAL_STEP A : END_STEP\nSTEP B : END_STEP\n\
         TRANSITION FROM A TO B := TRUE; END_TRANSITION\n\
         TRANSITION FROM B TO A := TRUE; END_TRANSITION\nEND_PROGRAM\n",
    );
    let (code, _, err) = plcrun(&[&src, "--cycles", "2", "--grafcet"]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("error[R020]"), "{err}");
    assert!(err.contains("A -> B") && err.contains("B -> A"), "{err}");
    // SFC evolution alternates A and B, one per cycle.
    let (code, _, err) = plcrun(&[&src, "--cycles", "2"]);
    assert_eq!(code, 0, "{err}");
}
