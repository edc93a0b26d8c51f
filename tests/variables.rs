//! The variable listing for HMIs (`Plc::variables`) and chart step states
//! (`Plc::chart_states`, `Plc::active_steps`).

use plcrun::{ChartState, Direction, ElemType, Options, Plc, VarShape};

const SRC: &str = "
TYPE Color : (Red, Green); END_TYPE
FUNCTION_BLOCK Blinker
VAR_INPUT enable : BOOL; END_VAR
VAR_OUTPUT shown : BOOL; END_VAR
INITIAL_STEP Dark : END_STEP
TRANSITION FROM Dark TO Bright := enable; END_TRANSITION
STEP Bright : END_STEP
TRANSITION FROM Bright TO Dark := NOT enable; END_TRANSITION
END_FUNCTION_BLOCK
PROGRAM P
VAR_INPUT go AT %IX0.1 : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR
    arr : ARRAY[1..2] OF REAL;
    c : Color;
    name : STRING[12];
    t : TON;
    b : Blinker;
END_VAR
VAR CONSTANT limit : INT := 3; END_VAR
b(enable := go);
n := n + 1;
END_PROGRAM
";

fn plc() -> Plc {
    Plc::compile_files(&[("p.st", SRC)], &Options::default()).unwrap()
}

#[test]
fn every_single_value_is_listed_with_its_type_section_address_and_writability() {
    let vars = plc().variables();
    let find = |p: &str| {
        vars.iter()
            .find(|v| v.path == p)
            .unwrap_or_else(|| panic!("{p} not listed in {vars:#?}"))
    };
    let go = find("go");
    assert_eq!(go.direction, Direction::Input);
    assert_eq!(go.address.as_deref(), Some("%IX0.1"));
    assert!(go.writable);
    assert_eq!(find("n").shape, VarShape::Elementary(ElemType::Int));
    assert_eq!(find("arr[2]").type_name, "REAL");
    assert_eq!(
        find("c").shape,
        VarShape::Enum {
            values: vec!["Red".into(), "Green".into()]
        }
    );
    assert_eq!(
        find("name").shape,
        VarShape::String {
            wide: false,
            max: 12
        }
    );
    assert_eq!(find("t.ET").direction, Direction::Output);
    assert_eq!(find("t.PT").direction, Direction::Input);
    assert_eq!(find("b.shown").direction, Direction::Output);
    let x = find("b.Bright.X");
    assert_eq!(x.direction, Direction::Step);
    assert!(!x.writable);
    assert!(!find("limit").writable);
    assert_eq!(find("limit").direction, Direction::Local);
    // The located input is listed once, by its name.
    assert!(!vars.iter().any(|v| v.path.starts_with('%')));
    // Every listed path reads.
    let plc = plc();
    for v in &vars {
        plc.read(&v.path)
            .unwrap_or_else(|e| panic!("{}: {e}", v.path));
    }
}

#[test]
fn chart_states_name_the_active_steps_of_each_chart() {
    let mut plc = plc();
    plc.run_cycle().unwrap();
    assert_eq!(
        plc.chart_states(),
        vec![ChartState {
            path: "P.b".into(),
            pou: "Blinker".into(),
            active: vec!["Dark".into()]
        }]
    );
    plc.write("go", "TRUE").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.active_steps("P.b"), Some(vec!["Bright".to_string()]));
    assert_eq!(plc.active_steps("P"), None);
}

#[test]
fn the_chariot_starts_in_init() {
    let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/programs/chariot.sfc"))
        .unwrap();
    let mut plc = Plc::compile_files(&[("chariot.sfc", &src)], &Options::default()).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.active_steps("CHARIOT"), Some(vec!["INIT".to_string()]));
    plc.write("Dcy", "TRUE").unwrap();
    plc.write("FcA", "TRUE").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.active_steps("CHARIOT"), Some(vec!["AV".to_string()]));
}
