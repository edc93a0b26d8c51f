//! The messages of TwinCAT's ADS logger functions (`ADSLOGSTR`,
//! `ADSLOGDINT`, `ADSLOGLREAL` of Tc2_System). plcrun's TwinCAT library
//! keeps each message in the program's `PLCRUN_ADS_LOG` ring, and the host
//! reads the new ones between cycles: `plcrun run` prints them, an
//! embedder shows or records them as it likes.

use super::engine::Plc;

/// The global ring the TwinCAT library writes (twincat_library.st).
const RING: &str = "PLCRUN_ADS_LOG";
/// Messages the ring holds: message k is `aMessages[k MOD RING_LEN]`.
const RING_LEN: u64 = 16;

/// ADS log message kinds, bits of `msgCtrlMask` (Tc2_System; a hint is
/// 0x01).
const WARN: u32 = 0x02;
const ERROR: u32 = 0x04;

/// One message of the ADS logger.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AdsMessage {
    /// Its number in the run, from 0.
    pub index: u64,
    /// The `msgCtrlMask` it was logged with (`ADSLOG_MSGTYPE_*` bits).
    pub mask: u32,
    /// The message, placeholder replaced.
    pub text: String,
}

impl AdsMessage {
    /// `"error"`, `"warning"` or `"hint"`: the most severe kind its mask
    /// names (a mask naming none counts as a hint, as TwinCAT shows it).
    pub fn kind(&self) -> &'static str {
        if self.mask & ERROR != 0 {
            "error"
        } else if self.mask & WARN != 0 {
            "warning"
        } else {
            "hint"
        }
    }
}

/// What [`AdsLog::read_new`] found since the previous read.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct AdsLogNews {
    /// The new messages, oldest first.
    pub messages: Vec<AdsMessage>,
    /// Messages logged since the previous read that the ring no longer
    /// held (more than 16 between two reads).
    pub lost: u64,
}

/// Reads a PLC's ADS log messages as they come.
///
/// ```no_run
/// # fn show(plc: &plcrun::Plc) {
/// let mut log = plcrun::AdsLog::new();
/// for m in log.read_new(plc).messages {
///     eprintln!("{}: {}", m.kind(), m.text);
/// }
/// # }
/// ```
#[derive(Debug, Clone, Default)]
pub struct AdsLog {
    next: u64,
}

impl AdsLog {
    /// A reader that has seen no message yet.
    pub fn new() -> AdsLog {
        AdsLog::default()
    }

    /// True when `plc`'s program has the ADS log: it is built from TwinCAT
    /// files that call one of the logger functions.
    pub fn present(plc: &Plc) -> bool {
        plc.read(&format!("{RING}.nMessages")).is_ok()
    }

    /// The messages logged since the previous call (all of them at the
    /// first), and how many of those the ring had already dropped. Nothing
    /// for a program without the ADS log.
    pub fn read_new(&mut self, plc: &Plc) -> AdsLogNews {
        let Ok(count) = plc.read(&format!("{RING}.nMessages")) else {
            return AdsLogNews::default();
        };
        let count = count.as_i64().unwrap_or(0).max(0) as u64;
        // A PLC reset (or another program) starts its count again.
        if count < self.next {
            self.next = 0;
        }
        let first = self.next.max(count.saturating_sub(RING_LEN));
        let lost = first - self.next;
        let messages = (first..count)
            .map(|index| {
                let at = format!("{RING}.aMessages[{}]", index % RING_LEN);
                let mask = plc
                    .read(&format!("{at}.nMask"))
                    .ok()
                    .and_then(|v| v.as_i64())
                    .unwrap_or(0) as u32;
                let text = plc
                    .read(&format!("{at}.sText"))
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default();
                AdsMessage { index, mask, text }
            })
            .collect();
        self.next = count;
        AdsLogNews { messages, lost }
    }
}
