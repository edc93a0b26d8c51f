//! Textual SFC: steps, associations, transitions, actions.

use super::common::*;
use plcrun::syntax::ast::*;

fn chart(body: &str) -> Vec<SfcElement> {
    let unit = parse_ok(&format!("PROGRAM p\n{body}\nEND_PROGRAM"));
    match &pou(&unit).body {
        Body::Sfc(e) => e.clone(),
        other => panic!("expected SFC, got {other:?}"),
    }
}

fn assoc(a: &ActionAssociation) -> String {
    format!(
        "{}[{}|{}|{}]",
        a.action.name,
        a.qualifier.as_ref().map(|q| q.name.as_str()).unwrap_or("-"),
        a.duration.as_ref().map(sx).unwrap_or_default(),
        a.indicators
            .iter()
            .map(|i| i.name.as_str())
            .collect::<Vec<_>>()
            .join(",")
    )
}

#[test]
fn steps_and_associations() {
    let e = chart(
        "INITIAL_STEP s0 : A(N); B(L, T#10s); C(D, t#5s, ind); D(); E(N, ind2); F(SD, dly); G; K(fcB); END_STEP \
         STEP s1 : END_STEP",
    );
    let SfcElement::Step(s0) = &e[0] else {
        panic!()
    };
    assert!(s0.initial);
    let shown: Vec<String> = s0.actions.iter().map(assoc).collect();
    assert_eq!(
        shown,
        [
            "A[N||]",
            "B[L|T#10s|]",
            "C[D|T#5s|ind]",
            "D[-||]",
            "E[N||ind2]",
            "F[SD|dly|]",
            "G[-||]",
            "K[fcB||]"
        ]
    );
    let SfcElement::Step(s1) = &e[1] else {
        panic!()
    };
    assert!(!s1.initial && s1.actions.is_empty());
}

#[test]
fn all_qualifiers() {
    let e = chart(
        "STEP s : a(N); a(R); a(S); a(L, T#1s); a(D, T#1s); a(P); a(P0); a(P1); a(SD, T#1s); a(DS, T#1s); a(SL, T#1s); END_STEP",
    );
    let SfcElement::Step(s) = &e[0] else { panic!() };
    let q: Vec<&str> = s
        .actions
        .iter()
        .map(|a| a.qualifier.as_ref().unwrap().name.as_str())
        .collect();
    assert_eq!(
        q,
        ["N", "R", "S", "L", "D", "P", "P0", "P1", "SD", "DS", "SL"]
    );
}

#[test]
fn transitions() {
    let e = chart(
        "TRANSITION FROM a TO b := x AND y; END_TRANSITION \
         TRANSITION t2 (PRIORITY := 2) FROM (a, b) TO (c, d) := TRUE; END_TRANSITION \
         TRANSITION FROM c TO d :\n LD x\n AND y\nEND_TRANSITION \
         TRANSITION t4 FROM d TO a : LD x\n ANDN y\nEND_TRANSITION",
    );
    let ts: Vec<&Transition> = e
        .iter()
        .map(|x| match x {
            SfcElement::Transition(t) => t,
            _ => panic!(),
        })
        .collect();
    assert!(ts[0].name.is_none());
    assert!(matches!(&ts[0].condition, TransitionCondition::Expr(c) if sx(c) == "(AND x y)"));
    assert_eq!(ts[1].name.as_ref().unwrap().name, "t2");
    assert_eq!(sx(ts[1].priority.as_ref().unwrap()), "2");
    assert_eq!(ts[1].from.len(), 2);
    assert_eq!(ts[1].to.len(), 2);
    assert!(matches!(&ts[2].condition, TransitionCondition::Il(l) if l.len() == 2));
    assert_eq!(ts[3].name.as_ref().unwrap().name, "t4");
    assert!(matches!(&ts[3].condition, TransitionCondition::Il(l) if l.len() == 2));
}

#[test]
fn actions_and_plain_statements() {
    let e = chart(
        "INITIAL_STEP s0 : END_STEP\nv := x;\nACTION act : x := x + 1; IF x > 3 THEN x := 0; END_IF; END_ACTION\n\
         ACTION empty : END_ACTION",
    );
    assert!(matches!(&e[1], SfcElement::Statement(s) if matches!(s.kind, StmtKind::Assign { .. })));
    let SfcElement::Action(a) = &e[2] else {
        panic!()
    };
    assert_eq!(a.name.name, "act");
    assert!(matches!(&a.body, Body::St(s) if s.len() == 2));
    assert!(matches!(&e[3], SfcElement::Action(a) if a.body == Body::St(vec![])));
}

#[test]
fn function_block_with_chart() {
    let unit = parse_ok(
        "FUNCTION_BLOCK fb VAR_INPUT go : BOOL; END_VAR INITIAL_STEP s : END_STEP TRANSITION FROM s TO s := go; END_TRANSITION END_FUNCTION_BLOCK",
    );
    assert!(matches!(&pou(&unit).body, Body::Sfc(e) if e.len() == 2));
}
