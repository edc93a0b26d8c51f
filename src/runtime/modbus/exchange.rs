//! The scan side of a Modbus server: between two cycles, publish the image
//! the cycle left for the clients to read, and apply the writes they
//! queued, so that the next cycle latches them.
//!
//! Everything here is bounded and non-blocking: one copy of the tables
//! (a few kilobytes), at most the queue's capacity of writes, and a
//! `try_write` on the buffer the clients are not reading.

use super::mapping::{ModbusTable, Tables, for_each_byte_write};
use super::server::Shared;
use super::stats::bump;
use crate::address::ImageTable;
use crate::runtime::engine::Plc;
use crate::runtime::session::Session;
use std::sync::Arc;
use std::sync::mpsc::Receiver;

/// The most data bytes one write request carries (123 registers, 1968
/// coils).
pub(crate) const MAX_WRITE_BYTES: usize = 246;

/// A client write waiting for the next cycle boundary (already checked:
/// its addresses exist).
#[derive(Debug, Clone)]
pub(crate) struct ClientWrite {
    pub(crate) table: ModbusTable,
    pub(crate) start: u16,
    pub(crate) count: u16,
    pub(crate) data: [u8; MAX_WRITE_BYTES],
}

/// What one [`ModbusExchange::exchange`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExchangeReport {
    /// True when the image was published to the clients (false: a client
    /// was still reading the buffer; the next exchange publishes).
    pub published: bool,
    /// Client writes applied to the image.
    pub writes_applied: usize,
}

/// The scan side of a [`crate::ModbusServer`]: call
/// [`exchange`](Self::exchange) between cycles (see the module docs of
/// `docs/modbus.md`, "Consistency").
pub struct ModbusExchange {
    pub(crate) shared: Arc<Shared>,
    pub(crate) writes: Receiver<ClientWrite>,
    /// The tables as the scan side last saw them, with the writes to
    /// addresses past the program's areas.
    pub(crate) shadow: Tables,
    /// At most this many writes per exchange (the queue's capacity).
    pub(crate) per_exchange: usize,
}

impl std::fmt::Debug for ModbusExchange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ModbusExchange")
            .field("per_exchange", &self.per_exchange)
            .finish_non_exhaustive()
    }
}

impl ModbusExchange {
    /// Between two cycles: publishes `plc`'s process image (the cycle just
    /// completed) for the clients to read, then applies the writes they
    /// queued since the last exchange to the image; the next cycle latches
    /// them (forced variables keep their forced values). Never blocks.
    pub fn exchange(&mut self, plc: &mut Plc) -> ExchangeReport {
        let image = plc.process_image_mut();
        let addressing = image.addressing();
        if self.shadow.addressing() != addressing {
            // The first exchange with a PLC of another convention.
            self.shadow = Tables::new(addressing);
        }
        for table in ImageTable::all() {
            let from = image.table_bytes(table);
            let to = self.shadow.table_mut(table);
            let n = from.len().min(to.len());
            to[..n].copy_from_slice(&from[..n]);
        }
        let published = self.shared.published.try_publish(&self.shadow);
        bump(if published {
            &self.shared.counters.publishes
        } else {
            &self.shared.counters.publishes_deferred
        });
        let mut applied = 0;
        while applied < self.per_exchange {
            let Ok(write) = self.writes.try_recv() else {
                break;
            };
            let shadow = &mut self.shadow;
            for_each_byte_write(
                addressing,
                write.table,
                write.start,
                write.count,
                &write.data,
                |table, byte, mask, bits| {
                    let put = |b: &mut u8| *b = (*b & !mask) | (bits & mask);
                    put(&mut shadow.table_mut(table)[byte]);
                    if let Some(b) = image.table_bytes_mut(table).get_mut(byte) {
                        put(b);
                    }
                },
            );
            applied += 1;
        }
        if applied > 0 {
            self.shared
                .counters
                .writes_applied
                .fetch_add(applied as u64, std::sync::atomic::Ordering::Relaxed);
        }
        ExchangeReport {
            published,
            writes_applied: applied,
        }
    }

    /// The exchange as a [`crate::TaskRunner::set_between_ticks`] hook
    /// (call [`exchange`](Self::exchange) once before the run, so that
    /// clients read the initial image until the first tick ends).
    pub fn into_between_ticks(mut self) -> impl FnMut(&mut Session) + Send + 'static {
        move |session: &mut Session| {
            self.exchange(session.plc_mut());
        }
    }
}
