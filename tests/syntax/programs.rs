//! Real programs: the benchmark programs, ALG01 (Moeller IL) and CHARIOT (SFC).

use super::common::*;
use plcrun::syntax::ast::*;
use rstest::rstest;

#[rstest]
#[case::bench_a(include_str!("../../benches/programs/bench_a_bool_logic.st"))]
#[case::bench_b(include_str!("../../benches/programs/bench_b_int_sieve.st"))]
#[case::bench_c_array(include_str!("../../benches/programs/bench_c_fb_array.st"))]
#[case::bench_c_unrolled(include_str!("../../benches/programs/bench_c_fb_unrolled.st"))]
#[case::bench_d(include_str!("../../benches/programs/bench_d_real_math.st"))]
fn bench_programs_parse(#[case] src: &str) {
    let unit = parse_ok(src);
    let p = pou(&unit);
    assert_eq!(p.name.name, "bench");
    assert_eq!(p.var_blocks[0].decls[0].names[0].name, "checksum");
    assert!(matches!(&p.body, Body::St(s) if !s.is_empty()));
}

#[test]
fn alg01_parses_as_il() {
    let unit = parse_ok(include_str!("../../programs/alg01.il"));
    let p = pou(&unit);
    assert_eq!(p.name.name, "ALG01");
    assert_eq!(p.var_blocks[0].decls.len(), 18);
    let Body::Il(lines) = &p.body else {
        panic!("IL body expected")
    };
    assert_eq!(lines.len(), 51);
    let calls = lines
        .iter()
        .filter(|l| {
            matches!(
                l.instr.as_ref().map(|i| &i.kind),
                Some(IlInstrKind::Call { outputs, .. }) if outputs.len() == 2
            )
        })
        .count();
    assert_eq!(calls, 2);
}

#[test]
fn chariot_parses_as_sfc() {
    let unit = parse_ok(include_str!("../../programs/chariot.sfc"));
    let Body::Sfc(elems) = &pou(&unit).body else {
        panic!("SFC body expected")
    };
    let steps = elems
        .iter()
        .filter(|e| matches!(e, SfcElement::Step(_)))
        .count();
    let transitions = elems
        .iter()
        .filter(|e| matches!(e, SfcElement::Transition(_)))
        .count();
    let statements = elems
        .iter()
        .filter(|e| matches!(e, SfcElement::Statement(_)))
        .count();
    assert_eq!((steps, transitions, statements), (4, 4, 1));
    let SfcElement::Step(av) = &elems[2] else {
        panic!("{:?}", elems[2])
    };
    assert_eq!(av.actions[0].action.name, "KMAV");
    assert_eq!(av.actions[0].indicators[0].name, "fcB");
}
