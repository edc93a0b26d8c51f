//! The OPC UA server's Write handling without a network, for the fuzz
//! targets (fuzz/src/targets.rs): bytes are decoded by `async-opcua`'s own
//! decoder as a WriteRequest, each WriteValue is checked as the server
//! checks a client's, and what is accepted is applied to a PLC as the
//! scan side applies it.

use super::glob::Globs;
use super::model::Model;
use super::node_manager::checked_write;
use super::published::Published;
use super::server::Shared;
use super::stats::Counters;
use super::types::variant;
use crate::runtime::engine::{Options, Plc};
use async_opcua::server::node_manager::ParsedWriteValue;
use async_opcua::types::{
    Array, AttributeId, BinaryDecodable, BinaryEncodable, ContextOwned, DataValue, NodeId,
    NumericRange, Variant, WriteRequest, WriteValue,
};
use std::sync::atomic::AtomicU16;

/// The namespace index the PLC's nodes get here.
const NAMESPACE: u16 = 2;

/// A program with a variable of every kind the server maps: integers,
/// reals, bit strings, durations, dates, strings, an enumeration, a
/// subrange, arrays, a structure, a block instance, a constant.
const PROGRAM: &str = "
TYPE Mode : (Off, Manual, Auto); END_TYPE
TYPE Point : STRUCT x : REAL; y : REAL; END_STRUCT END_TYPE
PROGRAM Main
VAR
    b : BOOL; si : SINT; i : INT; di : DINT; li : LINT;
    usi : USINT; ui : UINT; udi : UDINT; uli : ULINT;
    r : REAL; lr : LREAL; bt : BYTE; w : WORD; dw : DWORD; lw : LWORD;
    t : TIME; lt : LTIME; d : DATE; tod : TOD; dt : DT;
    s : STRING[8]; ws : WSTRING[8];
    mode : Mode; pct : INT (0..100);
    a : ARRAY[1..4] OF INT; m : ARRAY[0..1, 0..2] OF BOOL;
    p : Point; tmr : TON;
END_VAR
VAR CONSTANT k : INT := 3; END_VAR
tmr(IN := b, PT := t);
END_PROGRAM
";

/// A PLC and the server's view of it, to feed WriteRequests to.
pub struct WriteFuzz {
    plc: Plc,
    shared: Shared,
}

impl Default for WriteFuzz {
    fn default() -> Self {
        WriteFuzz::new()
    }
}

impl WriteFuzz {
    /// Compiles the program and builds the address space over it.
    pub fn new() -> WriteFuzz {
        let plc = Plc::compile_files(&[("main.st", PROGRAM)], &Options::default())
            .expect("the fuzzing program compiles");
        let model = Model::build(&plc, &Globs::new(&[]));
        let shared = Shared {
            published: Published::new(model.leaves.len()),
            model,
            wake: tokio::sync::Notify::new(),
            counters: Counters::default(),
            namespace: AtomicU16::new(NAMESPACE),
            cycle_ms: 10.0,
        };
        WriteFuzz { plc, shared }
    }

    /// Seeds: one encoded WriteRequest per served variable (a value of its
    /// type; arrays whole and one element by index range), and one that
    /// writes them all.
    pub fn seeds(&self) -> Vec<(String, Vec<u8>)> {
        let model = &self.shared.model;
        let mut writes = Vec::new();
        for (node, n) in model.nodes.iter().enumerate() {
            let Some(leaves) = model.leaves_of(node) else {
                continue;
            };
            let values: Vec<Variant> = leaves
                .iter()
                .map(|&l| variant(&model.leaves[l].kind, 1, "ab"))
                .collect();
            let id = NodeId::new(NAMESPACE, n.id.clone());
            let whole = match values.as_slice() {
                [one] if leaves.len() == 1 && !n.id.ends_with(']') => one.clone(),
                _ => match Array::new(
                    values[0]
                        .scalar_type_id()
                        .unwrap_or(async_opcua::types::VariantScalarTypeId::Int16),
                    values.clone(),
                ) {
                    Ok(a) => Variant::Array(Box::new(a)),
                    Err(_) => continue,
                },
            };
            writes.push((
                n.id.clone(),
                write_value(id.clone(), NumericRange::None, whole),
            ));
            if values.len() > 1 {
                let range = NumericRange::Index(1);
                writes.push((
                    format!("{}[1]", n.id),
                    write_value(id, range, values[1].clone()),
                ));
            }
        }
        let mut seeds: Vec<(String, Vec<u8>)> = writes
            .iter()
            .map(|(name, w)| (format!("write_{name}"), encode(vec![w.clone()])))
            .collect();
        seeds.push((
            "write_all".into(),
            encode(writes.into_iter().map(|(_, w)| w).collect()),
        ));
        seeds
    }

    /// Decodes `bytes` as a WriteRequest and applies each accepted write
    /// to the PLC, then runs a cycle. Returns the writes accepted; panics
    /// if a write the server would accept is refused by the PLC.
    pub fn feed(&mut self, bytes: &[u8]) -> usize {
        let context = ContextOwned::default();
        let Ok(request) = WriteRequest::decode(&mut &bytes[..], &context.context()) else {
            return 0;
        };
        let mut accepted = 0;
        for write in request.nodes_to_write.into_iter().flatten() {
            let Ok(parsed) = ParsedWriteValue::parse(write) else {
                continue;
            };
            let Ok(batch) = checked_write(&self.shared, &parsed, false) else {
                continue;
            };
            for (leaf, value) in &batch {
                let var = &self.shared.model.leaves[*leaf].var;
                if let Err(e) = self.plc.set(var, value) {
                    panic!("a write the server accepts is refused: {var:?} := {value:?}: {e}");
                }
            }
            accepted += 1;
        }
        let _ = self.plc.run_cycle();
        accepted
    }
}

fn write_value(node_id: NodeId, index_range: NumericRange, value: Variant) -> WriteValue {
    WriteValue {
        node_id,
        attribute_id: AttributeId::Value as u32,
        index_range,
        value: DataValue::value_only(value),
    }
}

/// A WriteRequest of `writes`, as a client puts it on the wire.
fn encode(writes: Vec<WriteValue>) -> Vec<u8> {
    let request = WriteRequest {
        request_header: Default::default(),
        nodes_to_write: Some(writes),
    };
    let context = ContextOwned::default();
    let mut bytes = Vec::new();
    request
        .encode(&mut bytes, &context.context())
        .expect("a request of served values encodes");
    bytes
}
