//! Assembles the lowered routines into one PROGRAM `OB1`: the memory areas
//! as BYTE arrays, the timer and counter arrays, each routine's logic stack
//! and control variable, the scan prologue (virtual clock, SM0.0 always 1,
//! SM0.1 first scan, SM0.4/SM0.5 clocks, SM0.6 scan clock), and the
//! timer/counter support functions when used.

use super::build::At;
use super::lower::{Lowering, Routine, STACK};
use super::operands::{Area, TIMERS};
use super::support::SUPPORT_ST;
use crate::diagnostics::Diagnostics;
use crate::source::{FileId, Span};
use crate::syntax::ast::{
    BinaryOp, Body, CompilationUnit, Initializer, Item, Pou, PouKind, Stmt, TypeSpec, VarBlock,
    VarDecl, VarKind,
};
use std::collections::HashMap;

/// Long enough never to end: the clock the S7-200 timers read.
const CLOCK_SPAN_NANOS: i64 = 100_000 * 86_400 * 1_000_000_000;

/// `name : ARRAY[0..hi] OF elem` or `name : elem`.
fn decl(at: At, name: &str, elem: &str, hi: Option<u32>, init: Option<bool>) -> VarDecl {
    let named = TypeSpec::Named(at.ident(elem));
    let ty = match hi {
        Some(hi) => TypeSpec::Array {
            ranges: vec![(at.int(0), at.int(i64::from(hi)))],
            elem: Box::new(named),
            span: at.0,
        },
        None => named,
    };
    VarDecl {
        names: vec![at.ident(name)],
        location: None,
        ty,
        init: init.map(|b| Initializer::Expr(at.boolean(b))),
        span: at.0,
        edge: None,
        init_args: None,
    }
}

/// The declarations of OB1.
fn declarations(at: At, l: &Lowering<'_>) -> Vec<VarDecl> {
    let mut d = Vec::new();
    for area in Area::ALL {
        d.push(decl(at, area.image(), "BYTE", Some(area.size() - 1), None));
    }
    let last = TIMERS - 1;
    for (name, ty) in [
        ("S7_T", "INT"),
        ("S7_TB", "BOOL"),
        ("S7_TRUN", "BOOL"),
        ("S7_TREM", "LINT"),
        ("S7_TLAST", "LINT"),
        ("S7_C", "INT"),
        ("S7_CB", "BOOL"),
        ("S7_CPU", "BOOL"),
        ("S7_CPD", "BOOL"),
    ] {
        d.push(decl(at, name, ty, Some(last), None));
    }
    d.push(decl(
        at,
        "S7_QUSED",
        "BOOL",
        Some(l.q_max.unwrap_or(0)),
        None,
    ));
    if l.edges > 0 {
        d.push(decl(at, "S7_E", "BOOL", Some(l.edges - 1), None));
    }
    d.push(decl(at, "S7_CLOCK", "TON", None, None));
    d.push(decl(at, "S7_NOW", "LINT", None, None));
    d.push(decl(at, "S7_FIRST", "BOOL", None, Some(true)));
    d.push(decl(at, "S7_W", "WORD", None, None));
    d.push(decl(at, "S7_D", "DWORD", None, None));
    d.push(decl(at, "S7_X", "BOOL", None, None));
    for tag in &l.tags {
        for i in 0..STACK {
            d.push(decl(at, &format!("S7_{tag}_S{i}"), "BOOL", None, None));
        }
    }
    for tag in &l.jumps {
        d.push(decl(at, &format!("S7_{tag}_J"), "INT", None, None));
    }
    d
}

/// What runs before OB1's first instruction in every scan.
fn prologue(at: At) -> Vec<Stmt> {
    let sm0 = |bit: u8| at.bit(at.index(Area::Sm.image(), 0), bit);
    let now = || at.name("S7_NOW");
    let half = |period: i64| {
        at.bin(
            BinaryOp::Ge,
            at.bin(BinaryOp::Mod, now(), at.typed("LINT", period)),
            at.typed("LINT", period / 2),
        )
    };
    let mut out = vec![
        at.call_stmt(
            "S7_CLOCK",
            vec![
                ("IN", at.boolean(true)),
                ("PT", at.duration(CLOCK_SPAN_NANOS)),
            ],
        ),
        at.assign(
            now(),
            at.call("TIME_TO_LINT", vec![at.member(at.name("S7_CLOCK"), "ET")]),
        ),
        at.assign(sm0(0), at.boolean(true)),
        at.assign(sm0(1), at.name("S7_FIRST")),
        at.assign(at.name("S7_FIRST"), at.boolean(false)),
        at.assign(sm0(4), half(60_000)),
        at.assign(sm0(5), half(1_000)),
        at.assign(sm0(6), at.not(sm0(6))),
    ];
    for i in 0..STACK {
        out.push(at.assign(at.name(&format!("S7_OB1_S{i}")), at.boolean(false)));
    }
    out
}

/// The compilation unit of an S7-200 file.
pub(super) fn build(
    file: FileId,
    text: &str,
    routines: &[Routine],
    diags: &mut Diagnostics,
) -> CompilationUnit {
    let whole = Span::new(file, 0, text.len());
    let at = At(routines.first().map_or(whole, |r| r.span));
    let sbrs: HashMap<u32, &Routine> = routines
        .iter()
        .filter_map(|r| r.number.map(|n| (n, r)))
        .collect();
    let main = routines.iter().find(|r| r.number.is_none());
    let mut lowering = Lowering::new(sbrs, diags);
    let mut body = prologue(at);
    if let Some(main) = main {
        body.extend(lowering.main(main));
    }
    lowering.uncalled();
    if !lowering.tags.iter().any(|t| t == "OB1") {
        lowering.tags.push("OB1".to_string());
    }
    let vars = VarBlock {
        kind: VarKind::Local,
        constant: false,
        retain: None,
        decls: declarations(at, &lowering),
        span: at.0,
    };
    let uses_support = lowering.uses_timers || lowering.uses_counters;
    let mut items = vec![Item::Pou(Pou {
        kind: PouKind::Program,
        name: at.ident("OB1"),
        return_type: None,
        var_blocks: vec![vars],
        body: Body::St(body),
        span: whole,
        oop: None,
        no_check: false,
    })];
    if uses_support {
        let support = crate::syntax::parse(file, SUPPORT_ST, diags);
        items.extend(support.items);
    }
    CompilationUnit { items }
}
