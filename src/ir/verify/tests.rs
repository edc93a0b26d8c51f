//! A real compiled image, corrupted in every way the executor's unchecked
//! accesses depend on: the verifier refuses each one, naming the problem.

use super::*;
use crate::ir::image::CodeBlock;
use crate::ir::op::{
    ArrayIdx, ChartIdx, CodeIdx, ConstIdx, Op, ScalarTypeIdx, ShortArrayIdx, ShortTarget, Slot,
    StrConstIdx, Target,
};
use crate::ir::operands::{Access, examples, for_each_slot};

/// A program with every kind of operand the verifier checks: frame slots,
/// runs (MUX, string functions), instances of user and native FBs, jumps,
/// fused loops, a two-word instruction, all the tables, a function frame,
/// a chart with condition and action blocks, two tasks (one SINGLE) and
/// program connections.
const SOURCE: &str = "
VAR_GLOBAL g : INT; trig : BOOL; gout : INT; END_VAR

FUNCTION Twice : INT
VAR_INPUT x : INT; END_VAR
Twice := x * 2;
END_FUNCTION

FUNCTION_BLOCK Bump
VAR_IN_OUT v : INT; END_VAR
v := v + 1;
END_FUNCTION_BLOCK

FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
total := total + x;
END_FUNCTION_BLOCK

PROGRAM Main
VAR_INPUT inp : INT; END_VAR
VAR_OUTPUT outp : INT; END_VAR
VAR
  a : ARRAY[0..9] OF INT;
  f : ARRAY[0..9] OF BOOL;
  i, j, n : INT;
  r, s : REAL;
  acc : Acc;
  bump : Bump;
  t : TON;
  txt : STRING;
  k : DINT := 123456789;
END_VAR
VAR_TEMP tmp : INT; END_VAR
j := 0;
WHILE j <= 9 DO a[j] := 1; j := j + 2; END_WHILE;
FOR i := 0 TO 9 DO IF f[i] THEN n := n + 1; END_IF; END_FOR;
n := a[n MOD 10];
r := r * s + r;
n := MUX(i MOD 3, 1, 2, 3);
txt := CONCAT(txt, 'x');
txt := INT_TO_STRING(n);
acc(x := Twice(inp));
t(IN := TRUE, PT := T#1s);
bump(v := g);
tmp := n;
outp := acc.total + g + DINT_TO_INT(k) + tmp;
END_PROGRAM

PROGRAM Seq
VAR go : BOOL; n : INT; lamp : BOOL; d : TIME := T#20ms; END_VAR
INITIAL_STEP S0 : lamp(N); END_STEP
STEP S1 : Count(N); lamp(D, d); END_STEP
ACTION Count : n := n + 1; END_ACTION
TRANSITION FROM S0 TO S1 := go AND n < 5; END_TRANSITION
TRANSITION FROM S1 TO S0 := n >= 3; END_TRANSITION
END_PROGRAM

CONFIGURATION Cfg
  RESOURCE Res ON PLC
    TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
    TASK Once (SINGLE := trig, PRIORITY := 0);
    PROGRAM m WITH Fast : Main(inp := g, outp => gout);
    PROGRAM q WITH Once : Seq;
  END_RESOURCE
END_CONFIGURATION
";

/// The compiled image, unsealed so that it can be corrupted.
fn image() -> Image {
    let plc = crate::Plc::compile_files(&[("v.st", SOURCE)], &crate::Options::default())
        .unwrap_or_else(|e| panic!("{e}"));
    plc.image().clone()
}

/// The problem the verifier reports for `image`.
fn refused(image: Image) -> Problem {
    match verify(image) {
        Ok(_) => panic!("a corrupted image was accepted"),
        Err(e) => e.problem,
    }
}

/// Every `(block, pc)` whose instruction `is` holds.
fn places(img: &Image, is: impl Fn(&Op) -> bool) -> Vec<(usize, usize)> {
    let mut found = Vec::new();
    for (ci, c) in img.codes.iter().enumerate() {
        for (pc, op) in c.ops.iter().enumerate() {
            if is(op) {
                found.push((ci, pc));
            }
        }
    }
    found
}

/// The first place of an instruction `is` (the test program has one).
fn place(img: &Image, is: impl Fn(&Op) -> bool) -> (usize, usize) {
    places(img, is)
        .first()
        .copied()
        .expect("the test program holds this instruction")
}

/// `img` with `change` applied to its instruction at `at`.
fn with_op(img: &Image, (ci, pc): (usize, usize), change: impl FnOnce(&mut Op)) -> Image {
    let mut bad = img.clone();
    change(&mut bad.codes[ci].ops[pc]);
    bad
}

#[test]
fn the_uncorrupted_image_is_accepted() {
    assert!(verify(image()).is_ok());
}

#[test]
fn the_program_holds_every_instruction_kind_the_tests_corrupt() {
    let img = image();
    for name in [
        "StoreStep",
        "ForScan",
        "MulAddF32",
        "Operand",
        "Mux",
        "StrCall",
        "StrConst",
        "ToStr",
        "LoadK",
        "LoadElem",
        "LoadAbs",
        "CallFb",
        "CallFn",
        "CallNative",
        "Sfc",
    ] {
        assert!(img.instruction_count(name).is_some_and(|n| n > 0), "{name}");
    }
}

#[test]
fn the_issue_example_a_move_far_outside_the_frame_is_refused() {
    let mut bad = image();
    let main = &mut bad.codes[0];
    main.ops.insert(
        0,
        Op::Mov {
            d: Slot::new(50_000_000),
            s: Slot::new(0),
        },
    );
    main.spans.insert(0, Default::default());
    assert_eq!(refused(bad), Problem::SlotOutsideFrame);
}

#[test]
fn every_slot_operand_of_every_instruction_outside_its_frame_is_refused() {
    let img = image();
    let mut corrupted = 0;
    for (ci, c) in img.codes.iter().enumerate() {
        for pc in 0..c.ops.len() {
            // Corrupt the j-th slot operand (of any slot role) alone.
            for j in 0.. {
                let mut bad = img.clone();
                let size = c.frame_size;
                let mut k = 0;
                crate::ir::operands::for_each_slot(&mut bad.codes[ci].ops[pc], &mut |s| {
                    if k == j {
                        *s = Slot::new(size);
                    }
                    k += 1;
                });
                if j >= k {
                    break;
                }
                let problem = refused(bad);
                let expected = [
                    Problem::SlotOutsideFrame,
                    Problem::RunOutsideFrame,
                    Problem::InstanceOutsideFrame,
                    // The index of a fused pair's partner no longer matches.
                    Problem::MissingPartner,
                ];
                assert!(expected.contains(&problem), "{:?}: {problem:?}", c.ops[pc]);
                corrupted += 1;
            }
        }
    }
    assert!(corrupted > 80, "{corrupted}");
}

#[test]
fn every_slot_role_of_every_listed_instruction_is_checked_against_the_frame() {
    // Independent of what the compiler emits: each instruction of the list,
    // in a block whose frame ends just below its first slot operand.
    let img = image();
    for op in examples() {
        let mut probe = op;
        let mut slots = Vec::new();
        for_each_slot(&mut probe, &mut |s| slots.push(*s));
        for s in slots {
            let block = CodeBlock {
                frame_size: s.get(),
                ..img.codes[0].clone()
            };
            let mut refused = false;
            let mut o = op;
            operands(&mut o, &mut |o| {
                let mine = matches!(
                    &o,
                    Operand::Slot(x, _) | Operand::Run(x, _) | Operand::Instance(x, _) if **x == s
                );
                if mine {
                    refused |= check_operand(&img, &block, o).is_err();
                }
            });
            assert!(refused, "{op:?} slot {s:?}");
        }
    }
}

#[test]
fn runs_reaching_past_the_frame_are_refused() {
    let img = image();
    let mux = place(&img, |o| matches!(o, Op::Mux { n, .. } if *n >= 2));
    let size = img.codes[mux.0].frame_size;
    let bad = with_op(&img, mux, |o| {
        if let Op::Mux { first, .. } = o {
            *first = Slot::new(size - 1);
        }
    });
    assert_eq!(refused(bad), Problem::RunOutsideFrame);
    let call = place(&img, |o| matches!(o, Op::StrCall { .. }));
    let size = img.codes[call.0].frame_size;
    let bad = with_op(&img, call, |o| {
        if let Op::StrCall { a, .. } = o {
            *a = Slot::new(size - 3);
        }
    });
    assert_eq!(refused(bad), Problem::RunOutsideFrame);
}

#[test]
fn jumps_outside_the_block_or_onto_an_operand_word_are_refused() {
    let img = image();
    let branches = places(&img, |o| {
        let mut o = *o;
        let mut any = false;
        operands(&mut o, &mut |x| {
            any |= matches!(x, Operand::Target(_) | Operand::ShortTarget(_))
        });
        any
    });
    assert!(branches.len() > 5);
    let word = place(&img, |o| matches!(o, Op::Operand { .. }));
    for at in branches {
        let len = img.codes[at.0].ops.len() as u32;
        let same_block_word = (word.0 == at.0).then_some(word.1 as u32);
        for target in [Some(len), Some(u16::MAX as u32), same_block_word]
            .into_iter()
            .flatten()
        {
            let bad = with_op(&img, at, |o| {
                let mut t32 = None;
                operands(o, &mut |x| match x {
                    Operand::Target(t) => t32 = Some(t),
                    Operand::ShortTarget(t) => *t = ShortTarget::new(target as u16),
                    _ => {}
                });
                if let Some(t) = t32 {
                    *t = Target::new(target);
                }
            });
            let problem = refused(bad);
            // A fused pair's target is also its partner's place.
            assert!(
                [Problem::BadTarget, Problem::MissingPartner].contains(&problem),
                "{problem:?}"
            );
        }
    }
    // The operand word's own block has a branch to corrupt onto it.
    assert!(img.codes[word.0].ops.iter().any(|o| {
        let mut o = *o;
        crate::ir::operands::target_mut(&mut o).is_some()
    }));
}

#[test]
fn a_block_without_ret_is_refused() {
    let mut bad = image();
    let last = bad.codes[0].ops.len() - 1;
    bad.codes[0].ops[last] = Op::Nop;
    assert_eq!(refused(bad), Problem::NoRet);
    let mut bad = image();
    bad.codes[1].ops.clear();
    bad.codes[1].spans.clear();
    assert_eq!(refused(bad), Problem::NoRet);
}

/// Which instruction to corrupt, how, and the problem expected.
type OpCase = (fn(&Op) -> bool, Box<dyn Fn(&mut Op)>, Problem);

/// How to corrupt a chart, and the problem expected.
type ChartCase = (Box<dyn Fn(&mut Chart)>, Problem);

#[test]
fn every_table_index_out_of_range_is_refused() {
    let img = image();
    let consts = ConstIdx::new(img.consts.len() as u32);
    let strs = StrConstIdx::new(img.str_consts.len() as u32);
    let arrays = img.arrays.len() as u32;
    let types = ScalarTypeIdx::new(img.scalar_types.len() as u8);
    let codes = CodeIdx::new(img.codes.len() as u32);
    let charts = ChartIdx::new(img.charts.len() as u32);
    let mem = img.memory.len() as u32;
    let cases: [OpCase; 9] = [
        (
            |o| matches!(o, Op::LoadK { .. }),
            Box::new(move |o| {
                if let Op::LoadK { k, .. } = o {
                    *k = consts
                }
            }),
            Problem::ConstOutOfRange,
        ),
        (
            |o| matches!(o, Op::StrConst { .. }),
            Box::new(move |o| {
                if let Op::StrConst { k, .. } = o {
                    *k = strs
                }
            }),
            Problem::StrConstOutOfRange,
        ),
        (
            |o| matches!(o, Op::LoadElem { .. }),
            Box::new(move |o| {
                if let Op::LoadElem { desc, .. } = o {
                    *desc = ArrayIdx::new(arrays)
                }
            }),
            Problem::ArrayOutOfRange,
        ),
        (
            |o| matches!(o, Op::ForScan { .. }),
            Box::new(move |o| {
                if let Op::ForScan { desc, .. } = o {
                    *desc = ShortArrayIdx::new(arrays as u16)
                }
            }),
            Problem::ArrayOutOfRange,
        ),
        (
            |o| matches!(o, Op::ToStr { .. }),
            Box::new(move |o| {
                if let Op::ToStr { ty, .. } = o {
                    *ty = types
                }
            }),
            Problem::ScalarTypeOutOfRange,
        ),
        (
            |o| matches!(o, Op::CallFb { .. }),
            Box::new(move |o| {
                if let Op::CallFb { code, .. } = o {
                    *code = codes
                }
            }),
            Problem::CodeOutOfRange,
        ),
        (
            |o| matches!(o, Op::CallFn { .. }),
            Box::new(move |o| {
                if let Op::CallFn { code } = o {
                    *code = codes
                }
            }),
            Problem::CodeOutOfRange,
        ),
        (
            |o| matches!(o, Op::Sfc { .. }),
            Box::new(move |o| {
                if let Op::Sfc { chart } = o {
                    *chart = charts
                }
            }),
            Problem::ChartOutOfRange,
        ),
        (
            |o| matches!(o, Op::LoadAbs { .. }),
            Box::new(move |o| {
                if let Op::LoadAbs { abs, .. } = o {
                    *abs = mem
                }
            }),
            Problem::AbsOutsideMemory,
        ),
    ];
    for (is, corrupt, problem) in cases {
        let at = place(&img, is);
        assert_eq!(refused(with_op(&img, at, corrupt)), problem);
    }
}

#[test]
fn an_array_reaching_past_the_frame_is_refused() {
    let img = image();
    let (ci, pc) = place(&img, |o| matches!(o, Op::LoadElem { .. }));
    let Op::LoadElem { desc, .. } = img.codes[ci].ops[pc] else {
        unreachable!()
    };
    let mut bad = img.clone();
    bad.arrays[desc.index()].offset = img.codes[ci].frame_size;
    assert_eq!(refused(bad), Problem::ArrayOutsideFrame);
    let mut bad = img.clone();
    bad.arrays[desc.index()].stride = 0;
    assert_eq!(refused(bad), Problem::ArrayOutsideFrame);
}

#[test]
fn callee_frames_too_big_or_of_the_wrong_kind_are_refused() {
    let img = image();
    let (ci, pc) = place(&img, |o| matches!(o, Op::CallFb { .. }));
    let Op::CallFb { code: fb, .. } = img.codes[ci].ops[pc] else {
        unreachable!()
    };
    let mut bad = img.clone();
    bad.codes[fb.index()].frame_size = img.codes[ci].frame_size;
    assert_eq!(refused(bad), Problem::InstanceOutsideFrame);
    let (fi, fpc) = place(&img, |o| matches!(o, Op::CallFn { .. }));
    let Op::CallFn { code: function } = img.codes[fi].ops[fpc] else {
        unreachable!()
    };
    // A function called as an FB, an FB called as a function.
    let bad = with_op(&img, (ci, pc), |o| {
        if let Op::CallFb { code, .. } = o {
            *code = function
        }
    });
    assert_eq!(refused(bad), Problem::WrongCalleeKind);
    let bad = with_op(&img, (fi, fpc), |o| *o = Op::CallFn { code: fb });
    assert_eq!(refused(bad), Problem::WrongCalleeKind);
    // A native instance running past the frame.
    let native = place(&img, |o| matches!(o, Op::CallNative { .. }));
    let size = img.codes[native.0].frame_size;
    let bad = with_op(&img, native, |o| {
        if let Op::CallNative { inst, .. } = o {
            *inst = Slot::new(size - 2)
        }
    });
    assert_eq!(refused(bad), Problem::InstanceOutsideFrame);
}

#[test]
fn a_two_word_instruction_without_its_word_is_refused() {
    let img = image();
    let (ci, pc) = place(&img, |o| matches!(o, Op::Operand { .. }));
    let bad = with_op(&img, (ci, pc), |o| *o = Op::Nop);
    assert_eq!(refused(bad), Problem::MissingOperandWord);
}

#[test]
fn a_fused_loop_without_its_partner_is_refused() {
    let img = image();
    let (ci, pc) = place(&img, |o| matches!(o, Op::StoreStep { .. }));
    let bad = with_op(&img, (ci, pc + 1), |o| *o = Op::Nop);
    assert_eq!(refused(bad), Problem::MissingPartner);
    let (ci, pc) = place(&img, |o| matches!(o, Op::ForScan { .. }));
    let Op::ForScan { t, .. } = img.codes[ci].ops[pc] else {
        unreachable!()
    };
    let bad = with_op(&img, (ci, t.index()), |o| *o = Op::Nop);
    assert_eq!(refused(bad), Problem::MissingPartner);
}

#[test]
fn frames_instances_connections_and_triggers_outside_memory_are_refused() {
    let img = image();
    let mem = img.memory.len() as u32;
    let function = img
        .codes
        .iter()
        .position(|c| c.kind == CodeKind::Function)
        .expect("a function");
    let mut bad = img.clone();
    bad.codes[function].frame = mem;
    assert_eq!(refused(bad), Problem::FunctionFrameOutsideMemory);
    let mut bad = img.clone();
    bad.programs[0].base = mem;
    assert_eq!(refused(bad), Problem::ProgramOutsideMemory);
    let mut bad = img.clone();
    assert!(!bad.programs[0].inputs.is_empty() && !bad.programs[0].outputs.is_empty());
    bad.programs[0].inputs[0].1 = mem;
    assert_eq!(refused(bad), Problem::ConnectionOutsideMemory);
    let mut bad = img.clone();
    bad.programs[0].outputs[0].0 = mem;
    assert_eq!(refused(bad), Problem::ConnectionOutsideMemory);
    let mut bad = img.clone();
    bad.programs[0].code = CodeIdx::new(img.codes.len() as u32);
    assert_eq!(refused(bad), Problem::ProgramCode);
    let mut bad = img.clone();
    bad.programs[0].code = CodeIdx::new(function as u32);
    assert_eq!(refused(bad), Problem::ProgramCode);
    let mut bad = img.clone();
    bad.programs[0].task = img.tasks.len();
    assert_eq!(refused(bad), Problem::ProgramTask);
    let mut bad = img.clone();
    let single = bad.tasks.iter_mut().find(|t| t.single.is_some());
    single.expect("a SINGLE task").single = Some(mem);
    assert_eq!(refused(bad), Problem::TriggerOutsideMemory);
}

#[test]
fn entry_resets_outside_the_frame_are_refused() {
    let img = image();
    let ci = img
        .codes
        .iter()
        .position(|c| !c.entry_init.is_empty())
        .expect("a block with entry resets");
    let mut bad = img.clone();
    bad.codes[ci].entry_init[0].0 = Slot::new(img.codes[ci].frame_size);
    assert_eq!(refused(bad), Problem::EntryResetOutsideFrame);
    let mut bad = img.clone();
    bad.codes[ci]
        .entry_strings
        .push((Slot::new(img.codes[ci].frame_size), StrConstIdx::new(0)));
    assert_eq!(refused(bad), Problem::EntryStringOutOfRange);
    let mut bad = img.clone();
    bad.codes[ci]
        .entry_strings
        .push((Slot::new(0), StrConstIdx::new(img.str_consts.len() as u32)));
    assert_eq!(refused(bad), Problem::EntryStringOutOfRange);
}

#[test]
fn inconsistent_chart_tables_are_refused() {
    use crate::ir::chart::{ActionKind, Condition};
    let img = image();
    let (ci, pc) = place(&img, |o| matches!(o, Op::Sfc { .. }));
    let Op::Sfc { chart } = img.codes[ci].ops[pc] else {
        unreachable!()
    };
    let size = img.codes[ci].frame_size;
    let fb = img
        .codes
        .iter()
        .position(|c| c.kind == CodeKind::FunctionBlock)
        .expect("an FB") as u32;
    let fb = CodeIdx::new(fb);
    let corruptions: Vec<ChartCase> = vec![
        (
            Box::new(|c| c.initial.push(c.steps.len() as u32)),
            Problem::ChartIndex,
        ),
        (
            Box::new(|c| c.steps[0].out.push(c.transitions.len() as u32)),
            Problem::ChartIndex,
        ),
        (
            Box::new(|c| c.transitions[0].to.push(c.steps.len() as u32)),
            Problem::ChartIndex,
        ),
        (
            Box::new(|c| {
                let n = c.actions.len() as u32;
                c.steps[0].assocs[0].action = n;
            }),
            Problem::ChartIndex,
        ),
        (
            Box::new(move |c| c.header = size),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.active = size - 1),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.cache = size - 1),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.steps[1].rec = size - 1),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.actions[0].rec = size - 1),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.transitions[0].cond = Condition::Frame(size)),
            Problem::ChartOutsideFrame,
        ),
        (
            Box::new(move |c| c.actions[0].kind = ActionKind::Body(fb)),
            Problem::WrongCalleeKind,
        ),
        (
            Box::new(move |c| c.transitions[0].cond = Condition::Code(CodeIdx::new(u32::MAX))),
            Problem::CodeOutOfRange,
        ),
    ];
    for (corrupt, problem) in corruptions {
        let mut bad = img.clone();
        corrupt(&mut bad.charts[chart.index()]);
        assert_eq!(refused(bad), problem);
    }
    // A condition block larger than the frame it runs on.
    let mut bad = img.clone();
    let Condition::Code(cond) = img.charts[chart.index()]
        .transitions
        .iter()
        .map(|t| t.cond)
        .find(|c| matches!(c, Condition::Code(_)))
        .expect("a condition block")
    else {
        unreachable!()
    };
    bad.codes[cond.index()].frame_size = size + 1;
    assert_eq!(refused(bad), Problem::ChartOutsideFrame);
}

#[test]
fn writes_come_from_the_roles() {
    // `Out` slots are results the emitter may retarget; `Def` and `InOut`
    // are written but not retargetable; `In` is not written.
    for mut op in examples() {
        let mut outs = 0;
        operands(&mut op, &mut |o| {
            if matches!(o, Operand::Slot(_, Access::Out)) {
                outs += 1;
            }
        });
        let w = crate::ir::operands::writes(&mut op);
        assert_eq!(w.result, outs == 1, "{op:?}");
    }
}

#[test]
fn a_host_body_index_out_of_range_is_refused() {
    let mut hosts = crate::HostBlocks::new();
    let sig = crate::HostSignature::block("Hb").output("q", crate::ElemType::Bool);
    let ok = |_: &mut crate::HostIo<'_>| -> crate::HostResult { Ok(()) };
    hosts.block(sig, move || ok).expect("a valid declaration");
    let options = crate::Options {
        hosts,
        ..crate::Options::default()
    };
    let src = "PROGRAM P VAR h : Hb; END_VAR h(); END_PROGRAM";
    let plc =
        crate::Plc::compile_files(&[("h.st", src)], &options).unwrap_or_else(|e| panic!("{e}"));
    let img = plc.image().clone();
    assert!(verify(img.clone()).is_ok());
    let at = place(&img, |o| matches!(o, Op::CallHost { .. }));
    let bad = with_op(&img, at, |o| {
        if let Op::CallHost { id } = o {
            *id = crate::ir::op::HostIdx::new(1)
        }
    });
    assert_eq!(refused(bad), Problem::HostOutOfRange);
    // An image that lost its host table is refused too.
    let mut bad = img;
    bad.hosts.clear();
    assert_eq!(refused(bad), Problem::HostOutOfRange);
}

#[test]
fn retained_values_outside_memory_or_with_another_string_are_refused() {
    use crate::ir::retained::RetainedStorage;
    let src = "PROGRAM P VAR RETAIN n : INT; s : STRING[4]; t : STRING[4]; END_VAR END_PROGRAM";
    let plc = crate::Plc::compile_files(&[("r.st", src)], &crate::Options::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let img = plc.image().clone();
    assert!(verify(img.clone()).is_ok());
    let mem = img.memory.len() as u32;
    let mut bad = img.clone();
    bad.retained[0].storage = RetainedStorage::Slot(mem);
    assert_eq!(refused(bad), Problem::RetainedOutsideMemory);
    let RetainedStorage::Text { slot, string } = img.retained[1].storage else {
        panic!("{:?}", img.retained[1]);
    };
    let mut bad = img.clone();
    bad.retained[1].storage = RetainedStorage::Text {
        slot,
        string: string + 1,
    };
    assert_eq!(refused(bad), Problem::RetainedOutsideMemory);
    let mut bad = img.clone();
    bad.retained[1].storage = RetainedStorage::Text { slot: mem, string };
    assert_eq!(refused(bad), Problem::RetainedOutsideMemory);
}
