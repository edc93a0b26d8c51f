//! One Modbus TCP request and its response, decoded and encoded by
//! `rmodbus`, served from the published tables and the write queue.
//!
//! `rmodbus` 0.13 decodes the fields and builds the responses; this file
//! adds the checks it leaves to its caller, so that no request reaches it
//! in a shape it would mis-read: quantity 0, a byte count that does not
//! match the quantity or the frame's length, a frame longer or shorter
//! than its function needs (exception 03, as the protocol asks for a
//! quantity or a length it cannot serve), and addresses past the tables
//! (exception 02). It also lifts `rmodbus`' cap of 250 on the MBAP length
//! field to the protocol's 254 (the length of a full 123-register or
//! 1968-coil write).

use super::exchange::{ClientWrite, MAX_WRITE_BYTES};
use super::mapping::ModbusTable;
use super::server::Shared;
use super::stats::bump;
use rmodbus::server::{ModbusFrame, Read, Write};
use rmodbus::{ErrorKind, ModbusProto};
use std::sync::mpsc::{SyncSender, TrySendError};

/// The largest Modbus TCP frame: the 7-byte MBAP header (with the unit
/// identifier) and a PDU of at most 253 bytes.
pub(crate) const MAX_FRAME: usize = 260;
/// The MBAP header, unit identifier included.
pub(crate) const HEADER: usize = 7;
/// The largest MBAP length `rmodbus` 0.13 accepts.
const RMODBUS_MAX_LENGTH: u16 = 250;

/// Exception codes the server answers with.
const ILLEGAL_FUNCTION: u8 = 0x01;
const ILLEGAL_DATA_VALUE: u8 = 0x03;

/// Answers the complete frame `frame` (header and PDU, its length field
/// already checked against its size) into `out`.
pub(crate) fn respond(
    frame: &[u8],
    shared: &Shared,
    writes: &SyncSender<ClientWrite>,
    out: &mut Vec<u8>,
) {
    bump(&shared.counters.requests);
    let function = frame[HEADER];
    let Some(table) = table_of(function) else {
        exception(frame, ILLEGAL_FUNCTION, out);
        bump(&shared.counters.exceptions);
        return;
    };
    if !well_formed(&frame[HEADER..]) {
        exception(frame, ILLEGAL_DATA_VALUE, out);
        bump(&shared.counters.exceptions);
        return;
    }
    let mut buf = [0u8; MAX_FRAME];
    let buf = &mut buf[..frame.len()];
    buf.copy_from_slice(frame);
    let length = u16::from_be_bytes([buf[4], buf[5]]);
    buf[4..6].copy_from_slice(&length.min(RMODBUS_MAX_LENGTH).to_be_bytes());
    let unit = frame[HEADER - 1];
    let mut request =
        ModbusFrame::new(unit, buf, ModbusProto::TcpUdp, out).with_broadcast_units(&[]);
    if request.parse().is_err() {
        // Cannot happen after `well_formed`; answered all the same.
        exception(frame, ILLEGAL_DATA_VALUE, out);
        bump(&shared.counters.exceptions);
        return;
    }
    if request.error.is_none() && request.processing_required {
        if !table.contains(request.reg, request.count) {
            let _ = request.set_modbus_error_if_unset(&ErrorKind::IllegalDataAddress);
        } else if request.readonly {
            serve_read(&mut request, table, shared);
        } else {
            queue_write(&mut request, table, shared, writes);
        }
    }
    if request.error.is_some() {
        bump(&shared.counters.exceptions);
    }
    if request.finalize_response().is_err() {
        exception(frame, ILLEGAL_DATA_VALUE, out);
    }
}

/// The table a function code works on (`None`: a function this server
/// does not implement).
fn table_of(function: u8) -> Option<ModbusTable> {
    match function {
        1 | 5 | 15 => Some(ModbusTable::Coils),
        2 => Some(ModbusTable::DiscreteInputs),
        3 | 6 | 16 => Some(ModbusTable::HoldingRegisters),
        4 => Some(ModbusTable::InputRegisters),
        _ => None,
    }
}

/// True when the PDU `pdu` (function code first) has the length its
/// function needs, a quantity within the protocol's limits and, for the
/// multiple writes, a byte count that matches both.
fn well_formed(pdu: &[u8]) -> bool {
    let quantity = |pdu: &[u8]| u16::from_be_bytes([pdu[3], pdu[4]]);
    match pdu[0] {
        1..=6 if pdu.len() != 5 => false,
        1 | 2 => (1..=2000).contains(&quantity(pdu)),
        3 | 4 => (1..=125).contains(&quantity(pdu)),
        5 | 6 => true,
        15 | 16 if pdu.len() < 6 => false,
        function @ (15 | 16) => {
            let q = quantity(pdu);
            let (limit, bytes) = if function == 15 {
                (1968, q.div_ceil(8))
            } else {
                (123, q.saturating_mul(2))
            };
            let count = usize::from(pdu[5]);
            (1..=limit).contains(&q) && usize::from(bytes) == count && pdu.len() == 6 + count
        }
        _ => false,
    }
}

/// Fills a read response from the published tables.
fn serve_read(request: &mut ModbusFrame<'_, Vec<u8>>, table: ModbusTable, shared: &Shared) {
    match request.get_external_read() {
        Ok(Read::Bits(r)) => shared
            .published
            .read(|t| t.read_bits(table, r.address, r.count, r.buf)),
        Ok(Read::Words(r)) => shared
            .published
            .read(|t| t.read_words(table, r.address, r.count, r.buf)),
        Err(e) => {
            let _ = request.set_modbus_error_if_unset(&e);
            return;
        }
    }
    let _ = request.process_external_read(Ok(()));
}

/// Queues a write for the next cycle boundary; a full queue answers
/// exception 06 (server busy), a stopped scan side exception 04.
fn queue_write(
    request: &mut ModbusFrame<'_, Vec<u8>>,
    table: ModbusTable,
    shared: &Shared,
    writes: &SyncSender<ClientWrite>,
) {
    let write = match request.get_external_write() {
        Ok(Write::Bits(w)) => client_write(table, w.address, w.count, w.data),
        Ok(Write::Words(w)) => client_write(table, w.address, w.count, w.data),
        Err(e) => {
            let _ = request.set_modbus_error_if_unset(&e);
            return;
        }
    };
    let result = match writes.try_send(write) {
        Ok(()) => {
            bump(&shared.counters.writes_queued);
            Ok(())
        }
        Err(TrySendError::Full(_)) => {
            bump(&shared.counters.writes_refused_busy);
            Err(ErrorKind::SlaveDeviceBusy)
        }
        Err(TrySendError::Disconnected(_)) => Err(ErrorKind::SlaveDeviceFailure),
    };
    let _ = request.process_external_write(result);
}

fn client_write(table: ModbusTable, start: u16, count: u16, data: &[u8]) -> ClientWrite {
    let mut write = ClientWrite {
        table,
        start,
        count,
        data: [0; MAX_WRITE_BYTES],
    };
    let n = data.len().min(MAX_WRITE_BYTES);
    write.data[..n].copy_from_slice(&data[..n]);
    write
}

/// An exception response to `frame`: its transaction identifier, protocol
/// 0, length 3, its unit, the function with the high bit set, `code`.
fn exception(frame: &[u8], code: u8, out: &mut Vec<u8>) {
    out.clear();
    out.extend_from_slice(&frame[..4]);
    out.extend_from_slice(&3u16.to_be_bytes());
    out.extend_from_slice(&[frame[HEADER - 1], frame[HEADER] | 0x80, code]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes() {
        assert!(well_formed(&[3, 0, 0, 0, 125]));
        assert!(!well_formed(&[3, 0, 0, 0, 126]));
        assert!(!well_formed(&[3, 0, 0, 0, 0]));
        assert!(!well_formed(&[3, 0, 0, 0]));
        assert!(!well_formed(&[3, 0, 0, 0, 1, 9]));
        assert!(well_formed(&[1, 0, 0, 0x07, 0xD0]));
        assert!(!well_formed(&[1, 0, 0, 0x07, 0xD1]));
        assert!(well_formed(&[15, 0, 0, 0, 9, 2, 0xFF, 1]));
        assert!(!well_formed(&[15, 0, 0, 0, 9, 1, 0xFF]));
        assert!(!well_formed(&[15, 0, 0, 0, 9, 2, 0xFF]));
        assert!(well_formed(&[16, 0, 0, 0, 1, 2, 0, 1]));
        assert!(!well_formed(&[16, 0, 0, 0, 1, 4, 0, 1, 0, 0]));
        assert!(!well_formed(&[16, 0, 0, 0, 124, 248]));
        assert!(!well_formed(&[16, 0, 0]));
    }
}
