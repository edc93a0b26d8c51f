//! Tc2_System's ADS logger (`ADSLOGSTR`, `ADSLOGDINT`, `ADSLOGLREAL`) in
//! every mode, not only under `plcrun test` (issue #25): the messages reach
//! an embedder through `plcrun::AdsLog` and `plcrun run`'s standard error.

use crate::support::{plc, twincat};

use plcrun::{AdsLog, AdsMessage};

/// A TwinCAT program `P` (variables `n`, `r`, `i`, `s`) running `body`.
fn program(body: &str) -> plcrun::Plc {
    let pou = twincat::pou(
        "P",
        "PROGRAM P\nVAR n : DINT; r : DINT; i : INT; s : STRING(255); END_VAR",
        body,
        "",
    );
    twincat::compile_ok(&[("P.TcPOU", &pou)])
}

fn texts(messages: &[AdsMessage]) -> Vec<(&'static str, &str)> {
    messages
        .iter()
        .map(|m| (m.kind(), m.text.as_str()))
        .collect()
}

#[test]
fn the_three_functions_format_their_argument_and_return_0() {
    let mut p = program(
        "n := n + 1;
         r := ADSLOGSTR(ADSLOG_MSGTYPE_HINT, 'valve %s open', 'V1');
         r := r + ADSLOGDINT(ADSLOG_MSGTYPE_WARN OR ADSLOG_MSGTYPE_LOG, 'cycle %d', n);
         r := r + ADSLOGLREAL(ADSLOG_MSGTYPE_ERROR, 'x = %f mm', 187.2030459);",
    );
    plc::run(&mut p, 1);
    let news = AdsLog::new().read_new(&p);
    // %f keeps six decimals, cut (not rounded) as TwinCAT writes it.
    assert_eq!(
        texts(&news.messages),
        [
            ("hint", "valve V1 open"),
            ("warning", "cycle 1"),
            ("error", "x = 187.203045 mm")
        ]
    );
    assert_eq!(news.messages[1].mask, 0x12);
    assert_eq!(news.lost, 0);
    assert_eq!(plc::lit(&p, "r"), "0");
}

#[test]
fn only_the_first_placeholder_is_replaced_and_a_message_is_cut_to_253_characters() {
    // s: 250 characters, then 5 more; the message keeps 253.
    let mut p = program(
        "ADSLOGSTR(ADSLOG_MSGTYPE_HINT, '%s and %s', 'a');
         ADSLOGSTR(ADSLOG_MSGTYPE_HINT, 'no placeholder', 'a');
         ADSLOGDINT(ADSLOG_MSGTYPE_HINT, '%s stays: %d', -5);
         s := '';
         FOR i := 1 TO 25 DO s := CONCAT(s, '0123456789'); END_FOR
         s := CONCAT(s, 'abcde');
         ADSLOGSTR(ADSLOG_MSGTYPE_HINT, '%s', s);",
    );
    plc::run(&mut p, 1);
    let news = AdsLog::new().read_new(&p);
    let t = texts(&news.messages);
    assert_eq!(t[0].1, "a and %s");
    assert_eq!(t[1].1, "no placeholder");
    assert_eq!(t[2].1, "%s stays: -5");
    assert_eq!(t[3].1, format!("{}abc", "0123456789".repeat(25)));
}

#[test]
fn a_reader_sees_each_message_once_and_counts_those_the_ring_dropped() {
    let mut p = program(
        "n := n + 1;
         ADSLOGDINT(ADSLOG_MSGTYPE_HINT, 'm%d', n);",
    );
    let mut log = AdsLog::new();
    plc::run(&mut p, 2);
    assert_eq!(
        texts(&log.read_new(&p).messages),
        [("hint", "m1"), ("hint", "m2")]
    );
    assert!(log.read_new(&p).messages.is_empty());
    // 20 messages more, read at once: the ring keeps the last 16.
    plc::run(&mut p, 20);
    let news = log.read_new(&p);
    assert_eq!(news.lost, 4);
    assert_eq!(news.messages.len(), 16);
    assert_eq!(news.messages[0].text, "m7");
    assert_eq!(news.messages[0].index, 6);
    assert_eq!(news.messages[15].text, "m22");
}

#[test]
fn a_program_without_the_logger_has_no_ads_log() {
    let p = program("n := n + 1;");
    assert!(!AdsLog::present(&p));
    assert!(AdsLog::new().read_new(&p).messages.is_empty());
}

#[cfg(feature = "cli")]
#[test]
fn plcrun_run_prints_the_messages_of_each_cycle_on_standard_error() {
    use crate::support::cli;
    let pou = twincat::pou(
        "MAIN",
        "PROGRAM MAIN\nVAR n : DINT; END_VAR",
        "n := n + 1;
         IF n = 2 THEN ADSLOGDINT(ADSLOG_MSGTYPE_WARN, 'n reached %d', n); END_IF",
        "",
    );
    let file = cli::temp_file("MAIN.TcPOU", pou);
    let (code, out, err) = cli::plcrun(&[&file, "--cycles", "3", "--trace", "n"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("ADS log, cycle 1, warning: n reached 2"),
        "{err}"
    );
    assert_eq!(err.matches("ADS log").count(), 1, "{err}");
    assert_eq!(out.lines().count(), 4, "{out}");
}
