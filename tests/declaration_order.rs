//! POUs may be declared in any order: a function block declared after the
//! block that holds an instance of it may call a function declared after
//! both (the OSCAT BASIC export is ordered this way: FT_AVG holds a DELAY,
//! whose body calls INC1, declared further down).

use crate::support::plc;

use plc::{compile, lit, run};

const LATE_FUNCTION: &str = "
PROGRAM main
  VAR outer : OUTER; r : INT; END_VAR
  outer(x := 21);
  r := outer.y;
END_PROGRAM
FUNCTION_BLOCK OUTER
  VAR_INPUT x : INT; END_VAR
  VAR_OUTPUT y : INT; END_VAR
  VAR inner : INNER; END_VAR
  inner(x := x);
  y := inner.y;
END_FUNCTION_BLOCK
FUNCTION_BLOCK INNER
  VAR_INPUT x : INT; END_VAR
  VAR_OUTPUT y : INT; END_VAR
  y := TWICE(x);
END_FUNCTION_BLOCK
FUNCTION TWICE : INT
  VAR_INPUT v : INT; END_VAR
  TWICE := v * 2;
END_FUNCTION
";

#[test]
fn a_block_laid_out_early_calls_a_function_declared_after_it() {
    let mut plc = compile(LATE_FUNCTION);
    run(&mut plc, 1);
    // 21 passed down two blocks and doubled by the function
    assert_eq!(lit(&plc, "r"), "42");
}

/// A global FB instance first in its list, whose body uses globals the
/// list declares after it (TcUnit's GVL_TcUnit does so), and a pointer to
/// an FB before the globals its body writes: both load and run.
#[test]
fn a_global_instance_uses_the_globals_declared_after_it() {
    let src = "
VAR_GLOBAL
  runner : FB_Runner;
  suites : ARRAY[1..3] OF POINTER TO FB_Suite;
  count : INT;
  ticks : DINT;
END_VAR
FUNCTION_BLOCK FB_Suite
  VAR registered : BOOL; END_VAR
  IF NOT registered THEN
    count := count + 1;
    suites[count] := THIS;
    registered := TRUE;
  END_IF
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Runner
  ticks := ticks + count;
END_FUNCTION_BLOCK
PROGRAM main
  VAR a, b : FB_Suite; END_VAR
  a(); b();
  runner();
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "count"), "2");
    assert_eq!(lit(&plc, "ticks"), "4");
}

/// A global instance whose block's code names another global instance of
/// its list declared after it (TcUnit's runner reads
/// `GVL_TcUnit.GetCpuCounter`, declared 12 lines later), by its list's
/// name or bare, from its own body, a method, or an instance it holds:
/// the named instances are declared first, every list keeps the rest of
/// its order, and each body sees the others' values.
#[test]
fn a_global_instance_names_instances_declared_after_it() {
    let src = "
VAR_GLOBAL
  runner : FB_Runner;
  seen : DINT;
  counter : FB_Counter;
END_VAR
VAR_GLOBAL
  watcher : FB_Watcher;
  clock : FB_Counter;
END_VAR
FUNCTION_BLOCK FB_Counter
  VAR_OUTPUT n : DINT; END_VAR
  n := n + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Probe
  VAR_OUTPUT v : DINT; END_VAR
  v := clock.n * 100;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Runner
  VAR probe : FB_Probe; END_VAR
  METHOD Late : DINT
    Late := watcher.w;
  END_METHOD
  GVL_Main.counter();
  probe();
  seen := GVL_Main.counter.n + probe.v + Late();
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Watcher
  VAR_OUTPUT w : DINT; END_VAR
  w := w + 1000;
END_FUNCTION_BLOCK
PROGRAM main
  clock();
  watcher();
  runner();
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 2);
    // counter 2 + clock 2 * 100 + watcher 2 * 1000
    assert_eq!(lit(&plc, "seen"), "2202");
}

/// A pointer to a block declared before an instance that block's code
/// names (TcUnit's `CurrentTestSuiteBeingCalled : POINTER TO
/// FB_TestSuite` comes before `AdsMessageQueue`, which the suite's
/// assertion formatter writes to): the named instance is declared first.
#[test]
fn a_pointer_to_a_block_comes_after_the_instances_its_code_names() {
    let src = "
VAR_GLOBAL
  current : POINTER TO FB_Suite;
  queue : FB_Queue;
END_VAR
FUNCTION_BLOCK FB_Queue
  VAR_OUTPUT n : DINT; END_VAR
  METHOD Push
    n := n + 1;
  END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Formatter
  GVL_Main.queue.Push();
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Suite
  VAR fmt : FB_Formatter; END_VAR
  fmt();
END_FUNCTION_BLOCK
PROGRAM main
  VAR s : FB_Suite; END_VAR
  current := ADR(s);
  current^();
END_PROGRAM";
    let mut plc = compile(src);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "queue.n"), "3");
}
