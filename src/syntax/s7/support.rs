//! The S7-200 timer and counter semantics, written once in Structured Text
//! and compiled with the program that uses them (docs/s7-200.md, "Timers"
//! and "Counters"). The state of timer `Tn` lives in the program's arrays
//! (`S7_T[n]` current value, `S7_TB[n]` bit, and hidden `S7_TRUN`,
//! `S7_TREM`, `S7_TLAST`), passed in-out, so that `R Tn`, `MOVW …, Tn` and
//! the trace see and change the same timer.

/// Timer resolution in milliseconds by number, as the S7-200 system manual
/// (table "Timer Numbers and Resolutions") gives it; `None` when the number
/// is not of that kind (TONR only on T0–T31 and T64–T95).
pub(super) fn resolution_ms(retentive: bool, n: u32) -> Option<i64> {
    let base = if n < 64 { n } else { n - 64 };
    if retentive {
        match base {
            0 => Some(1),
            1..=4 => Some(10),
            5..=31 => Some(100),
            _ => None,
        }
    } else {
        match base {
            32 => Some(1),
            33..=36 => Some(10),
            37..=191 => Some(100),
            _ => None,
        }
    }
}

/// `S7_TIMER` (KIND 0 = TON, 1 = TONR, 2 = TOF; times in milliseconds) and
/// `S7_COUNTER` (KIND 0 = CTU, 1 = CTD, 2 = CTUD).
pub(super) const SUPPORT_ST: &str = "
FUNCTION S7_TIMER
VAR_INPUT IN : BOOL; KIND : INT; PT : INT; RES : LINT; NOW : LINT; END_VAR
VAR_IN_OUT CV : INT; BIT : BOOL; RUN : BOOL; REM : LINT; LAST : LINT; END_VAR
VAR total : LINT; END_VAR
IF KIND = 2 THEN
    IF IN THEN
        BIT := TRUE; CV := 0; RUN := FALSE;
        RETURN;
    END_IF;
    IF NOT BIT THEN
        RUN := FALSE;
        RETURN;
    END_IF;
ELSIF NOT IN THEN
    RUN := FALSE;
    IF KIND = 0 THEN
        CV := 0; BIT := FALSE;
    END_IF;
    RETURN;
END_IF;
IF RUN THEN
    total := REM + (NOW - LAST);
    REM := total MOD RES;
    total := INT_TO_LINT(CV) + total / RES;
    IF total > 32767 THEN
        total := 32767;
    END_IF;
    IF KIND = 2 AND total > INT_TO_LINT(PT) AND CV <= PT THEN
        total := INT_TO_LINT(PT);
    END_IF;
    CV := LINT_TO_INT(total);
ELSE
    RUN := TRUE; REM := 0;
END_IF;
LAST := NOW;
IF KIND = 2 THEN
    IF CV >= PT THEN
        BIT := FALSE; RUN := FALSE;
    END_IF;
ELSE
    BIT := CV >= PT;
END_IF;
END_FUNCTION

FUNCTION S7_COUNTER
VAR_INPUT KIND : INT; CU : BOOL; CD : BOOL; RST : BOOL; PV : INT; END_VAR
VAR_IN_OUT CV : INT; BIT : BOOL; PCU : BOOL; PCD : BOOL; END_VAR
VAR up : BOOL; down : BOOL; END_VAR
up := CU AND NOT PCU;
down := CD AND NOT PCD;
PCU := CU;
PCD := CD;
IF KIND = 1 THEN
    IF RST THEN
        CV := PV; BIT := FALSE;
        RETURN;
    END_IF;
    IF down AND CV > 0 THEN
        CV := CV - 1;
    END_IF;
    BIT := CV = 0;
    RETURN;
END_IF;
IF RST THEN
    CV := 0; BIT := FALSE;
    RETURN;
END_IF;
IF up THEN
    IF CV < 32767 THEN
        CV := CV + 1;
    ELSIF KIND = 2 THEN
        CV := -32768;
    END_IF;
END_IF;
IF KIND = 2 AND down THEN
    IF CV > -32768 THEN
        CV := CV - 1;
    ELSE
        CV := 32767;
    END_IF;
END_IF;
BIT := CV >= PV;
END_FUNCTION
";

#[cfg(test)]
mod tests {
    use super::resolution_ms;

    #[test]
    fn resolutions_follow_the_system_manual() {
        assert_eq!(resolution_ms(true, 0), Some(1));
        assert_eq!(resolution_ms(true, 64), Some(1));
        assert_eq!(resolution_ms(true, 4), Some(10));
        assert_eq!(resolution_ms(true, 68), Some(10));
        assert_eq!(resolution_ms(true, 31), Some(100));
        assert_eq!(resolution_ms(true, 95), Some(100));
        assert_eq!(resolution_ms(true, 32), None);
        assert_eq!(resolution_ms(false, 32), Some(1));
        assert_eq!(resolution_ms(false, 96), Some(1));
        assert_eq!(resolution_ms(false, 36), Some(10));
        assert_eq!(resolution_ms(false, 100), Some(10));
        assert_eq!(resolution_ms(false, 37), Some(100));
        assert_eq!(resolution_ms(false, 255), Some(100));
        assert_eq!(resolution_ms(false, 5), None);
    }
}
