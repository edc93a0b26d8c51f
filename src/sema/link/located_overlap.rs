//! W204: located variables whose image bytes overlap under the chosen
//! addressing convention (`docs/diagnostics.md`). Usually the sign of a
//! program written for another convention: OpenPLC programs put coils at
//! `%QX0.0` and registers at `%QW0` in separate tables, which share a byte
//! under `iec`.

use super::Linker;
use crate::address::{self, Addressing, IoAddress};

/// The code of the warning.
pub(crate) const OVERLAP: &str = "W204";

impl Linker<'_> {
    /// One W204 per located address (in the order first written) that
    /// shares image bits with an address written before it, at the later
    /// one, naming the earlier.
    pub(super) fn warn_overlapping_addresses(&mut self, addressing: Addressing) {
        // Keys that do not parse (`%I*`) have no place in the image.
        let parsed: Vec<(usize, IoAddress)> = self
            .out
            .located
            .keys()
            .enumerate()
            .filter_map(|(i, k)| address::parse(k).ok().map(|a| (i, a)))
            .collect();
        let addresses: Vec<IoAddress> = parsed.iter().map(|&(_, a)| a).collect();
        for (later, earlier, count) in address::overlap::overlapping(&addresses, addressing) {
            let (a, b) = (addresses[later], addresses[earlier]);
            let Some(&span) = self.out.located_spans.get(parsed[later].0) else {
                continue;
            };
            let Ok(spot) = addressing.spot(&a) else {
                continue;
            };
            let more = match count {
                1 => String::new(),
                2 => " and 1 other address".to_string(),
                n => format!(" and {} other addresses", n - 1),
            };
            let last = spot.end() - 1;
            let bytes = if spot.byte == last {
                format!("byte {}", spot.byte)
            } else {
                format!("bytes {}..{last}", spot.byte)
            };
            let message = format!(
                "`{a}` ({bytes} of {} under {addressing} addressing) overlaps `{b}`{more}: \
                 writing one changes the other",
                spot.table
            );
            let note = match addressing {
                Addressing::Iec => {
                    "the program may have been written for `openplc` (OpenPLC, matiec), where \
                     %QX, %QW, %MW, %MD and %ML are separate tables numbered by their own size: \
                     run it with `--addressing openplc`"
                }
                Addressing::Byte => {
                    "under `byte` addressing every number is a byte offset (%QW1 is bytes 1..2, \
                     overlapping %QW0); a program that numbers words by word wants \
                     `--addressing iec` (CODESYS) or `--addressing openplc`"
                }
                Addressing::OpenPlc => "each size has its own table under `openplc`",
            };
            self.diags.push(
                crate::diagnostics::Diagnostic::warning(OVERLAP, span, message).with_note(note),
            );
        }
    }
}
