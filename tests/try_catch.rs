//! `__TRY ... __CATCH(exc) ... __FINALLY ... __ENDTRY` (CODESYS V3,
//! TwinCAT 3): a runtime fault in the guarded statements, or in a call
//! made there, runs the `__CATCH` statements with the exception code in
//! the variable, then the `__FINALLY` ones, and the cycle goes on; the
//! watchdog is never caught; the native tier leaves such blocks to the
//! interpreter and gives the same results.

use crate::support::plc::{compile, error_codes, first_fault, lit, program, run};
use plcrun::{Engine, Options, Plc};

const DECLS: &str = "
    exc : __SYSTEM.ExceptionCode;
    d, q : INT;
    tries, catches, finals, after : INT;
    a : ARRAY[1..3] OF INT;
    i : INT := 5;";

/// A program whose guarded division faults when `d` is 0.
fn dividing() -> String {
    program(
        "",
        DECLS,
        "__TRY
            tries := tries + 1;
            q := 100 / d;
            tries := tries + 10;
        __CATCH(exc)
            catches := catches + 1;
        __FINALLY
            finals := finals + 1;
        __ENDTRY
        after := after + 1;",
    )
}

#[test]
fn a_fault_in_the_guarded_statements_runs_catch_then_finally_and_the_cycle_goes_on() {
    let mut plc = compile(&dividing());
    run(&mut plc, 2);
    // The statements after the faulting one are skipped, every time.
    assert_eq!(lit(&plc, "tries"), "2");
    assert_eq!(lit(&plc, "catches"), "2");
    assert_eq!(lit(&plc, "finals"), "2");
    assert_eq!(lit(&plc, "after"), "2");
    assert_eq!(lit(&plc, "exc"), "RTSEXCPT_DIVIDEBYZERO");
    // Without a fault: no CATCH, FINALLY still.
    plc.write("d", "4").unwrap();
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "q"), "25");
    assert_eq!(lit(&plc, "tries"), "13");
    assert_eq!(lit(&plc, "catches"), "2");
    assert_eq!(lit(&plc, "finals"), "3");
}

#[test]
fn a_fault_in_a_called_block_unwinds_to_the_try_and_the_code_is_compared_by_name() {
    let src = program(
        "FUNCTION Pick : INT
        VAR_INPUT k : INT; END_VAR
        VAR t : ARRAY[1..3] OF INT := [10, 20, 30]; END_VAR
        Pick := t[k];
        END_FUNCTION
        FUNCTION_BLOCK Reader
        VAR_INPUT k : INT; END_VAR
        VAR_OUTPUT v : INT; END_VAR
        v := Pick(k);
        END_FUNCTION_BLOCK",
        "exc : __SYSTEM.ExceptionCode; r : Reader; bounds, v : INT; k : INT := 2;",
        "__TRY
            r(k := k);
            v := r.v;
        __CATCH(exc)
            IF exc = __SYSTEM.ExceptionCode.RTSEXCPT_ARRAYBOUNDS THEN
                bounds := bounds + 1;
            END_IF
        __ENDTRY
        k := k + 1;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 3);
    // k = 2, 3 read; k = 4 faults two calls down.
    assert_eq!(lit(&plc, "v"), "30");
    assert_eq!(lit(&plc, "bounds"), "1");
}

#[test]
fn regions_nest_and_a_fault_in_a_catch_goes_to_the_enclosing_try() {
    let src = program(
        "",
        "inner, outer : __SYSTEM.ExceptionCode; d : INT; a : ARRAY[0..1] OF INT; i : INT := 7;
         seen_inner, seen_outer : INT;",
        "__TRY
            __TRY
                a[0] := 1 / d;
            __CATCH(inner)
                seen_inner := seen_inner + 1;
                a[i] := 1;
            __ENDTRY
        __CATCH(outer)
            seen_outer := seen_outer + 1;
        __ENDTRY",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "seen_inner"), "1");
    assert_eq!(lit(&plc, "inner"), "RTSEXCPT_DIVIDEBYZERO");
    assert_eq!(lit(&plc, "seen_outer"), "1");
    assert_eq!(lit(&plc, "outer"), "RTSEXCPT_ARRAYBOUNDS");
}

#[test]
fn a_fault_outside_any_try_still_stops_the_plc_at_its_line() {
    let src = program(
        "",
        "exc : UDINT; d : INT; q : INT;",
        "__TRY
            q := 1;
        __CATCH(exc)
            q := 2;
        __ENDTRY
        q := 10 / d;",
    );
    let fault = first_fault(&src);
    assert_eq!(fault.code(), "R001");
    assert!(fault.to_string().contains(":11:"), "{fault}");
}

#[test]
fn the_watchdog_is_not_caught() {
    let src = program(
        "",
        "exc : __SYSTEM.ExceptionCode; n : DINT; caught : BOOL;",
        "__TRY
            WHILE TRUE DO n := n + 1; END_WHILE
        __CATCH(exc)
            caught := TRUE;
        __ENDTRY",
    );
    let options = Options {
        watchdog: Some(std::time::Duration::from_millis(50)),
        ..Options::default()
    };
    let mut plc = Plc::compile_files(&[("t.st", src.as_str())], &options).unwrap();
    let fault = plc.run_cycle().expect_err("the loop never ends");
    assert_eq!(fault.code(), "R008", "{fault}");
    assert_eq!(lit(&plc, "caught"), "FALSE");
}

#[test]
fn both_engines_give_the_same_values_and_the_guarded_block_stays_interpreted() {
    let src = dividing();
    let mut values = Vec::new();
    for engine in [Engine::Interp, Engine::Native] {
        let options = Options {
            engine,
            ..Options::default()
        };
        let mut plc = Plc::compile_files(&[("t.st", src.as_str())], &options).unwrap();
        run(&mut plc, 3);
        values.push(
            ["tries", "catches", "finals", "after", "exc"]
                .map(|n| lit(&plc, n))
                .join(","),
        );
        if engine == Engine::Native
            && let Some(report) = plc.native_report()
        {
            assert!(
                report
                    .fell_back
                    .iter()
                    .any(|f| f.block == "P" && f.reason.contains("__TRY")),
                "{:?}",
                report.fell_back
            );
        }
    }
    assert_eq!(values[0], values[1]);
}

#[test]
fn the_catch_variable_must_hold_an_exception_code_and_catch_is_required() {
    let bad_type = program(
        "",
        "exc : INT; q : INT;",
        "__TRY q := 1; __CATCH(exc) q := 2; __ENDTRY",
    );
    assert_eq!(error_codes(&[("t.st", &bad_type)])[0].0, "E413");
    let no_catch = program("", "q : INT;", "__TRY q := 1; __FINALLY q := 2; __ENDTRY");
    assert_eq!(error_codes(&[("t.st", &no_catch)])[0].0, "E112");
    let undeclared = program("", "q : INT;", "__TRY q := 1; __CATCH(e) q := 2; __ENDTRY");
    assert_eq!(error_codes(&[("t.st", &undeclared)])[0].0, "E201");
}

/// A function that raises the exception it is given when `go` is TRUE.
const RAISER: &str = "FUNCTION Raiser : BOOL
VAR_INPUT go : BOOL; code : UDINT; END_VAR
IF go THEN F_RaiseException(code); END_IF
Raiser := TRUE;
END_FUNCTION";

#[test]
fn f_raiseexception_is_caught_with_its_code_even_two_calls_down() {
    // Cycle 2 raises ARRAYBOUNDS in place, cycle 3 16#1234 inside Raiser:
    // each skips the statements after it and reaches the __CATCH.
    let src = program(
        RAISER,
        "exc : __SYSTEM.ExceptionCode; code : UDINT; n, done, caught : INT;",
        "n := n + 1;
        __TRY
            IF n = 2 THEN F_RaiseException(__SYSTEM.ExceptionCode.RTSEXCPT_ARRAYBOUNDS); END_IF
            Raiser(go := n = 3, code := 16#1234);
            done := done + 1;
        __CATCH(exc)
            caught := caught + 1;
            code := exc;
        __ENDTRY",
    );
    let mut plc = compile(&src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "exc"), "RTSEXCPT_ARRAYBOUNDS");
    assert_eq!(lit(&plc, "code"), "257");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "code"), "4660");
    assert_eq!(lit(&plc, "caught"), "2");
    assert_eq!(lit(&plc, "done"), "2");
}

#[test]
fn an_uncaught_f_raiseexception_stops_the_plc_at_the_call_on_both_engines() {
    let src = program(
        "",
        "n : INT;",
        "n := n + 1;
        IF n = 3 THEN
            F_RaiseException(ExceptionCode := __SYSTEM.ExceptionCode.RTSEXCPT_DIVIDEBYZERO);
        END_IF",
    );
    for engine in [Engine::Interp, Engine::Native] {
        let options = Options {
            engine,
            ..Options::default()
        };
        let mut plc = Plc::compile_files(&[("t.st", src.as_str())], &options).unwrap();
        run(&mut plc, 2);
        let fault = plc.run_cycle().expect_err("cycle 3 raises");
        assert_eq!(fault.code(), "R082", "{fault}");
        let text = fault.to_string();
        assert!(text.contains("t.st:8:13"), "{text}");
        assert!(text.contains("RTSEXCPT_DIVIDEBYZERO (16#102)"), "{text}");
        assert_eq!(lit(&plc, "n"), "3");
    }
}

#[test]
fn f_raiseexception_takes_one_code_and_returns_nothing() {
    let two = program("", "q : INT;", "F_RaiseException(1, 2);");
    assert_eq!(error_codes(&[("t.st", &two)])[0].0, "E251");
    let text = program("", "q : INT;", "F_RaiseException('x');");
    assert_eq!(error_codes(&[("t.st", &text)])[0].0, "E301");
    let value = program("", "b : BOOL;", "b := F_RaiseException(1);");
    assert_eq!(error_codes(&[("t.st", &value)])[0].0, "E415");
}

#[test]
fn return_exit_and_continue_leaving_a_try_run_its_finally_first() {
    // RETURN from the guarded statements and from the catch; EXIT and
    // CONTINUE of a loop around the try; EXIT of a loop inside the try
    // (which leaves no try: no finally there).
    let src = program(
        "FUNCTION_BLOCK Early
        VAR_INPUT fail : BOOL; END_VAR
        VAR_OUTPUT finals, tail : INT; END_VAR
        VAR exc : __SYSTEM.ExceptionCode; z : INT; k : INT; END_VAR
        __TRY
            IF fail THEN k := 1 / z; END_IF;
            FOR k := 1 TO 3 DO
                IF k = 2 THEN EXIT; END_IF;
            END_FOR;
            RETURN;
        __CATCH(exc)
            RETURN;
        __FINALLY
            finals := finals + 1;
        __ENDTRY
        tail := tail + 1;
        END_FUNCTION_BLOCK",
        "e : Early; n, loop_finals, body_runs : INT; exc : __SYSTEM.ExceptionCode;",
        "e(fail := FALSE);
        e(fail := TRUE);
        FOR n := 1 TO 4 DO
            __TRY
                body_runs := body_runs + 1;
                IF n = 2 THEN CONTINUE; END_IF;
                IF n = 3 THEN EXIT; END_IF;
            __CATCH(exc)
                ;
            __FINALLY
                loop_finals := loop_finals + 1;
            __ENDTRY
        END_FOR;",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "e.finals"), "2");
    assert_eq!(lit(&plc, "e.tail"), "0");
    // n = 1 ends normally, 2 continues, 3 exits: three finally runs.
    assert_eq!(lit(&plc, "body_runs"), "3");
    assert_eq!(lit(&plc, "loop_finals"), "3");
}

#[test]
fn nested_finally_parts_run_innermost_first_and_a_fault_in_one_goes_outward() {
    let src = program(
        "",
        "inner, outer : __SYSTEM.ExceptionCode; order : DINT; d : INT; x : INT;
         caught_outer : INT;",
        "__TRY
            __TRY
                IF order = 0 THEN
                    order := 1;
                    RETURN;
                END_IF;
            __CATCH(inner)
                order := -1;
            __FINALLY
                order := order * 10 + 2;
                x := 1 / d;
            __ENDTRY
        __CATCH(outer)
            caught_outer := caught_outer + 1;
        __FINALLY
            order := order * 10 + 3;
        __ENDTRY",
    );
    let mut plc = compile(&src);
    let inner_before = lit(&plc, "inner");
    run(&mut plc, 1);
    // The inner finally ran (1 -> 12), faulted in its division: not the
    // inner try's to catch, the outer one's; then the outer finally
    // (12 -> 123), and the RETURN's jump was never reached.
    assert_eq!(lit(&plc, "caught_outer"), "1");
    assert_eq!(lit(&plc, "outer"), "RTSEXCPT_DIVIDEBYZERO");
    assert_eq!(lit(&plc, "inner"), inner_before);
    assert_eq!(lit(&plc, "order"), "123");
}

#[test]
fn an_error_in_a_finally_part_is_reported_once_however_often_it_is_copied() {
    let src = program(
        "",
        "exc : __SYSTEM.ExceptionCode; n : INT;",
        "FOR n := 1 TO 3 DO
            __TRY
                IF n = 1 THEN CONTINUE; END_IF;
                IF n = 2 THEN EXIT; END_IF;
                RETURN;
            __CATCH(exc)
                RETURN;
            __FINALLY
                n := undeclared_thing;
            __ENDTRY
        END_FOR;",
    );
    let codes = error_codes(&[("p.st", &src)]);
    assert_eq!(codes.len(), 1, "{codes:?}");
}

#[test]
fn a_fault_in_a_finally_copy_skips_a_try_without_finally_between() {
    // RETURN inside C, a __TRY without __FINALLY, inside B, whose
    // __FINALLY faults: the copy of B's part run before the RETURN is not
    // C's to catch (nor B's), but A's, around B.
    let src = program(
        "",
        "a_exc, b_exc, c_exc : __SYSTEM.ExceptionCode; d, x : INT;
         caught_a, caught_b, caught_c, finals : INT;",
        "__TRY
            __TRY
                __TRY
                    RETURN;
                __CATCH(c_exc)
                    caught_c := caught_c + 1;
                __ENDTRY
            __CATCH(b_exc)
                caught_b := caught_b + 1;
            __FINALLY
                finals := finals + 1;
                x := 1 / d;
            __ENDTRY
        __CATCH(a_exc)
            caught_a := caught_a + 1;
        __ENDTRY",
    );
    let mut plc = compile(&src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "finals"), "1");
    assert_eq!(lit(&plc, "caught_c"), "0");
    assert_eq!(lit(&plc, "caught_b"), "0");
    assert_eq!(lit(&plc, "caught_a"), "1");
    assert_eq!(lit(&plc, "a_exc"), "RTSEXCPT_DIVIDEBYZERO");
}
