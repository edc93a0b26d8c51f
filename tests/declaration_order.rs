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
