//! Small verified images through the executor: the unchecked frame
//! accesses stay inside the frame, and every address computed at run time
//! (pointer slots, instance addresses, copy ranges) is checked, also when
//! it is near the top of the address space. These are the tests to run
//! under Miri where the toolchain has it (docs/adr/0004).

use super::{FaultKind, Machine};
use crate::ir::image::{CodeBlock, CodeKind, Image, ProgramInstance, Task};
use crate::ir::op::{CodeIdx, NativeFb, Op, Slot};
use crate::ir::type_table::{TypeId, TypeTable};
use crate::ir::verify::{VerifiedImage, verify};

const MEMORY: usize = 16;

/// The program's code block and the FB's.
const PROGRAM: CodeIdx = CodeIdx::new(0);
const FB: CodeIdx = CodeIdx::new(1);
/// The four slots of the program's frame.
const S0: Slot = Slot::new(0);
const S1: Slot = Slot::new(1);
const S2: Slot = Slot::new(2);
const S3: Slot = Slot::new(3);

fn block(kind: CodeKind, ops: Vec<Op>, frame_size: u32) -> CodeBlock {
    CodeBlock {
        name: "t".into(),
        kind,
        spans: vec![Default::default(); ops.len()],
        ops,
        entry_init: Vec::new(),
        entry_strings: Vec::new(),
        frame: 0,
        frame_size,
        handlers: Vec::new(),
    }
}

/// A program of `ops` on a 4-slot frame at address 0, plus an FB body of
/// three slots (code 1) that counts its calls in its first slot.
fn program(ops: Vec<Op>) -> VerifiedImage {
    let fb = vec![
        Op::AddSI {
            d: S0,
            a: S0,
            imm: 1,
            shift: 0,
        },
        Op::Ret,
    ];
    let image = Image {
        codes: vec![
            block(CodeKind::Program, ops, 4),
            block(CodeKind::FunctionBlock, fb, 3),
        ],
        consts: Vec::new(),
        str_consts: Vec::new(),
        arrays: Vec::new(),
        memory: vec![0; MEMORY],
        strings: Vec::new(),
        types: TypeTable::new(),
        scalar_types: Vec::new(),
        byte_layouts: Vec::new(),
        globals: Vec::new(),
        programs: vec![ProgramInstance {
            name: "p".into(),
            type_name: "P".into(),
            code: PROGRAM,
            base: 0,
            ty: TypeId(0),
            task: 0,
            inputs: Vec::new(),
            outputs: Vec::new(),
        }],
        tasks: vec![Task {
            name: "t".into(),
            interval: 1,
            priority: 0,
            single: None,
        }],
        charts: Vec::new(),
        hosts: Vec::new(),
        retained: Vec::new(),
        start: Vec::new(),
        exit: Vec::new(),
        copy_calls: Vec::new(),
        names: Default::default(),
    };
    verify(image).expect("a valid image")
}

/// Runs the program once with slots 0 and 1 preset; the fault kind, if any.
fn run(image: &VerifiedImage, slot0: u64, slot1: u64) -> (Result<(), FaultKind>, Machine) {
    let mut m = Machine::new(image);
    m.mem[0] = slot0;
    m.mem[1] = slot1;
    let r = m.run(image, PROGRAM, 0).map_err(|f| f.kind);
    (r, m)
}

#[test]
fn copies_run_inside_memory_and_fault_outside_it() {
    let img = program(vec![Op::MemCopy { d: S0, s: S1, n: 4 }, Op::Ret]);
    let mut m = Machine::new(&img);
    m.mem[0] = 8;
    m.mem[1] = 4;
    m.mem[4..8].copy_from_slice(&[1, 2, 3, 4]);
    assert_eq!(m.run(&img, PROGRAM, 0), Ok(()));
    assert_eq!(m.mem[8..12], [1, 2, 3, 4]);
    for (to, from) in [(13, 0), (0, 13), (u64::MAX - 1, 0), (0, u64::MAX - 1)] {
        assert_eq!(
            run(&img, to, from).0,
            Err(FaultKind::BadAddress),
            "{to} {from}"
        );
    }
}

#[test]
fn native_instances_behind_pointers_are_checked() {
    let img = program(vec![
        Op::CallNativeInd {
            fb: NativeFb::RTrig,
            p: S0,
        },
        Op::Ret,
    ]);
    // R_TRIG at 8: CLK = 1 gives Q = 1.
    let mut m = Machine::new(&img);
    m.mem[0] = 8;
    m.mem[8] = 1;
    assert_eq!(m.run(&img, PROGRAM, 0), Ok(()));
    assert_eq!(m.mem[9], 1);
    for p in [14, MEMORY as u64, u64::MAX - 1] {
        assert_eq!(run(&img, p, 0).0, Err(FaultKind::BadAddress), "{p}");
    }
}

#[test]
fn fb_instances_behind_pointers_are_checked() {
    let img = program(vec![Op::CallFbInd { code: FB, p: S0 }, Op::Ret]);
    let (r, m) = run(&img, 13, 0);
    assert_eq!(r, Ok(()));
    assert_eq!(m.mem[13], 1);
    for p in [14, u64::MAX - 1, u64::MAX] {
        assert_eq!(run(&img, p, 0).0, Err(FaultKind::BadAddress), "{p}");
    }
}

#[test]
fn loads_and_stores_through_pointers_are_checked() {
    let img = program(vec![
        Op::LoadInd {
            d: S2,
            p: S0,
            off: 1,
        },
        Op::StoreInd {
            p: S1,
            off: 0,
            s: S2,
        },
        Op::Ret,
    ]);
    let mut m = Machine::new(&img);
    m.mem[0] = 10;
    m.mem[1] = 12;
    m.mem[11] = 42;
    assert_eq!(m.run(&img, PROGRAM, 0), Ok(()));
    assert_eq!(m.mem[12], 42);
    for (p, q) in [(15, 12), (10, 16), (u64::MAX - 1, 12)] {
        assert_eq!(run(&img, p, q).0, Err(FaultKind::BadAddress), "{p} {q}");
    }
}

#[test]
fn a_frame_outside_memory_faults_instead_of_running() {
    let img = program(vec![Op::Mov { d: S3, s: S0 }, Op::Ret]);
    let mut m = Machine::new(&img);
    for base in [13, u32::MAX] {
        let fault = m.run(&img, PROGRAM, base).expect_err("outside memory");
        assert_eq!(fault.kind, FaultKind::BadAddress);
    }
    assert_eq!(m.run(&img, PROGRAM, 12), Ok(()));
}

#[test]
fn a_two_word_instruction_reads_its_operand_word() {
    let img = program(vec![
        Op::MulAddF64 {
            d: S3,
            a: S0,
            b: S1,
        },
        Op::Operand { s: S2 },
        Op::Ret,
    ]);
    let mut m = Machine::new(&img);
    m.mem[..3].copy_from_slice(&[2.0f64.to_bits(), 3.0f64.to_bits(), 0.5f64.to_bits()]);
    assert_eq!(m.run(&img, PROGRAM, 0), Ok(()));
    assert_eq!(f64::from_bits(m.mem[3]), 6.5);
}
