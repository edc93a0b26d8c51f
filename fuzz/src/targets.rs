//! The bodies of the fuzz targets, one function per target. Each takes any
//! bytes and must return without panicking; the libFuzzer targets in
//! `fuzz_targets/` and the stable smoke test `tests/fuzz_smoke.rs` call
//! the same functions.

use plcrun::syntax::{lexer, plcopen, s7};
use plcrun::{CheckOptions, Diagnostics, FileId, Options, Plc, SourceMap};
use std::time::Duration;

/// The input as text, as `plcrun` reads a file (invalid UTF-8 replaced).
fn text(data: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(data)
}

/// The lexer (with literal decoding) on any text.
pub fn lex(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let tokens = lexer::lex(FileId(0), &text(data), &mut diags);
    std::hint::black_box(tokens);
}

/// The IEC text parser (ST, IL and SFC share it): lexer, IL line
/// handling, grammar and error recovery.
pub fn parse(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let unit = plcrun::syntax::parse(FileId(0), &text(data), &mut diags);
    std::hint::black_box(unit);
}

/// The PLCopen TC6 XML reader, from bytes.
pub fn plcopen(data: &[u8]) {
    let (unit, diags) = plcopen::parse_bytes(data);
    std::hint::black_box((unit, diags));
}

/// The S7-200 STL reader.
pub fn s7(data: &[u8]) {
    let mut diags = Diagnostics::new();
    let unit = s7::parse(FileId(0), &text(data), &mut diags);
    std::hint::black_box(unit);
}

/// The file name a whole-pipeline input is read as: the first byte picks
/// the front-end the way `plcrun` does from a file name, the rest is the
/// file.
fn named(data: &[u8]) -> (&'static str, &[u8]) {
    match data.split_first() {
        Some((b, rest)) => {
            let name = match b % 4 {
                0 => "fuzz.st",
                1 => "fuzz.il",
                2 => "fuzz.awl",
                _ => "fuzz.xml",
            };
            (name, rest)
        }
        None => ("fuzz.st", data),
    }
}

/// Parse and check (`plcrun check`): every declaration, every body, with
/// the IR built and verified when there is one runnable program, under a
/// 1 MiB data budget.
pub fn check(data: &[u8]) {
    let (name, body) = named(data);
    let mut sources = SourceMap::new();
    sources.add(name, text(body).into_owned());
    let options = CheckOptions {
        ir_listing: true,
        max_data_bytes: 1 << 20,
        ..CheckOptions::default()
    };
    let report = plcrun::check(&sources, &options);
    // Rendering walks every span back into the source.
    std::hint::black_box(report.diagnostics.render(&sources));
}

/// The whole pipeline: compile with a 1 MiB data budget, then run up to
/// three cycles under a 20 ms watchdog, reading every variable after each.
pub fn run(data: &[u8]) {
    let (name, body) = named(data);
    let mut sources = SourceMap::new();
    sources.add(name, text(body).into_owned());
    let options = Options {
        watchdog: Some(Duration::from_millis(20)),
        max_data_bytes: 1 << 20,
        ..Options::default()
    };
    let Ok(mut plc) = Plc::compile(sources, &options) else {
        return;
    };
    for _ in 0..3 {
        let result = plc.run_cycle();
        for v in plc.variables() {
            let _ = std::hint::black_box(plc.read(&v.path).map(|x| x.to_literal()));
        }
        if result.is_err() {
            break;
        }
    }
}

/// A generated, type-correct ST program run optimized and unoptimized,
/// compared cycle by cycle (see [`super::differential::check`]).
pub fn gen_diff(data: &[u8]) {
    let mut u = arbitrary::Unstructured::new(data);
    if let Ok(program) = super::st_gen::generate(&mut u) {
        super::differential::check(&program);
    }
}

/// A generated, type-correct IL program run optimized and unoptimized,
/// compared cycle by cycle (see [`super::il_gen`]).
pub fn gen_il_diff(data: &[u8]) {
    let mut u = arbitrary::Unstructured::new(data);
    if let Ok(program) = super::il_gen::generate(&mut u) {
        super::differential::check(&program);
    }
}

/// A generated program (ST when the first byte is even, IL otherwise) run
/// on the native tier and on the interpreter, compared cycle by cycle
/// (see [`super::differential::check_engines`]). Without the native tier
/// in the build both sides are the interpreter.
pub fn engines_agree(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let mut u = arbitrary::Unstructured::new(rest);
    let program = if pick % 2 == 0 {
        super::st_gen::generate(&mut u)
    } else {
        super::il_gen::generate(&mut u)
    };
    if let Ok(program) = program {
        super::differential::check_engines(&program);
    }
}

/// The Modbus TCP server's request path (frame reader and request
/// handler): any bytes as one client's stream. Every answer must be a
/// whole MBAP frame (protocol 0, a length of 2 to 254 that the answer
/// fills) answering a request of the stream.
pub fn modbus(data: &[u8]) {
    let (answers, _writes) = plcrun::fuzzing::modbus_serve_bytes(data);
    let mut rest = answers.as_slice();
    while !rest.is_empty() {
        assert!(rest.len() >= 8, "a truncated answer: {rest:?}");
        assert_eq!([rest[2], rest[3]], [0, 0], "protocol identifier");
        let length = usize::from(u16::from_be_bytes([rest[4], rest[5]]));
        assert!((2..=254).contains(&length), "MBAP length {length}");
        assert!(
            rest.len() >= 6 + length,
            "an answer shorter than its length"
        );
        let transaction = [rest[0], rest[1]];
        assert!(
            data.windows(2).any(|w| w == transaction),
            "an answer to a transaction nobody sent"
        );
        rest = &rest[6 + length..];
    }
}

/// One Modbus TCP request: transaction `t`, unit 1, the PDU `pdu`.
fn modbus_frame(t: u16, pdu: &[u8]) -> Vec<u8> {
    let mut frame = t.to_be_bytes().to_vec();
    frame.extend([0, 0]);
    frame.extend(((pdu.len() + 1) as u16).to_be_bytes());
    frame.push(1);
    frame.extend(pdu);
    frame
}

/// Seeds for [`modbus`]: a valid request of every function the server
/// serves (reads and writes of coils, inputs and registers, at the start,
/// middle and end of the tables), one of each error it answers, and a
/// stream of several requests back to back.
pub fn modbus_seeds() -> Vec<(String, Vec<u8>)> {
    let pdus: Vec<(&str, Vec<u8>)> = vec![
        ("read_coils", vec![0x01, 0, 0, 0, 16]),
        ("read_discrete_inputs", vec![0x02, 0, 8, 0, 8]),
        ("read_holding", vec![0x03, 0, 0, 0, 10]),
        ("read_holding_max", vec![0x03, 0, 0, 0, 125]),
        ("read_input_registers", vec![0x04, 0, 2, 0, 4]),
        ("write_single_coil", vec![0x05, 0, 3, 0xFF, 0]),
        ("write_single_register", vec![0x06, 0, 1, 0x12, 0x34]),
        ("write_coils", vec![0x0F, 0, 0, 0, 10, 2, 0xFF, 0x03]),
        ("write_registers", vec![0x10, 0, 0, 0, 2, 4, 0, 1, 0, 2]),
        ("memory_word", vec![0x03, 0x04, 0x00, 0, 2]),
        ("unknown_function", vec![0x2B, 0x0E, 1, 0]),
        ("quantity_zero", vec![0x03, 0, 0, 0, 0]),
        ("past_the_end", vec![0x03, 0xFF, 0xF0, 0, 125]),
        ("bad_byte_count", vec![0x10, 0, 0, 0, 2, 3, 0, 1, 0, 2]),
    ];
    let mut seeds: Vec<(String, Vec<u8>)> = pdus
        .iter()
        .enumerate()
        .map(|(i, (name, pdu))| (name.to_string(), modbus_frame(i as u16 + 1, pdu)))
        .collect();
    let stream: Vec<u8> = pdus
        .iter()
        .enumerate()
        .flat_map(|(i, (_, pdu))| modbus_frame(0x100 + i as u16, pdu))
        .collect();
    seeds.push(("stream".into(), stream));
    seeds
}

/// The OPC UA server's Write handling: any bytes decoded by async-opcua's
/// decoder as a WriteRequest, each write checked as the server checks a
/// client's and applied as the scan side applies it (a write the server
/// accepts must land), then a cycle.
#[cfg(feature = "opcua")]
pub fn opcua_write(data: &[u8]) {
    use std::cell::RefCell;
    thread_local! {
        static PLC: RefCell<plcrun::fuzzing::OpcUaWriteFuzz> =
            RefCell::new(plcrun::fuzzing::OpcUaWriteFuzz::new());
    }
    PLC.with(|plc| plc.borrow_mut().feed(data));
}

/// Seeds for [`opcua_write`]: a WriteRequest per served variable.
#[cfg(feature = "opcua")]
pub fn opcua_write_seeds() -> Vec<(String, Vec<u8>)> {
    plcrun::fuzzing::OpcUaWriteFuzz::new().seeds()
}
