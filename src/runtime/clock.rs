//! Where a PLC's clock comes from: the virtual clock (the default), the
//! monotonic wall clock, or the caller's.
//!
//! The clock gives the `now` a cycle runs at, which every timer (TON, TOF,
//! TP, SFC step times) of that cycle sees. The *schedule* — which task is
//! due at which base tick — does not depend on it: it always counts base
//! ticks. So a virtual run reads `now = tick × base tick` and is exactly
//! reproducible, while a real-time run reads the monotonic time since the
//! run started, and a host that simulates a plant faster or slower than
//! real time brings its own clock.
//!
//! ```
//! use plcrun::{Clock, Options, Plc};
//! use std::sync::Arc;
//! use std::sync::atomic::{AtomicI64, Ordering};
//!
//! let src = "PROGRAM P VAR_OUTPUT q : BOOL; END_VAR VAR t : TON; END_VAR
//!            t(IN := TRUE, PT := T#1s); q := t.Q; END_PROGRAM";
//! let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! // The host's own clock, in nanoseconds.
//! let host_ns = Arc::new(AtomicI64::new(0));
//! let reading = Arc::clone(&host_ns);
//! plc.set_clock(Clock::from_fn(move || reading.load(Ordering::Relaxed)));
//! plc.run_cycle()?; // TON starts timing at 0
//! host_ns.store(999_000_000, Ordering::Relaxed);
//! plc.run_cycle()?;
//! assert_eq!(plc.read("q")?.to_literal(), "FALSE");
//! host_ns.store(1_000_000_000, Ordering::Relaxed);
//! plc.run_cycle()?;
//! assert_eq!(plc.read("q")?.to_literal(), "TRUE");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt;
use std::sync::Arc;
use std::time::Instant;

/// The source of a PLC's `now` (see the module docs).
#[derive(Clone, Default)]
pub struct Clock {
    source: Source,
}

#[derive(Clone, Default)]
enum Source {
    /// `now` is the scheduled time of the tick.
    #[default]
    Virtual,
    /// Nanoseconds since `origin` on the monotonic clock.
    Monotonic(Instant),
    /// The caller's reading, in nanoseconds.
    Caller(Arc<dyn Fn() -> i64 + Send + Sync>),
}

impl Clock {
    /// The virtual clock: base tick `k` runs at `k × base tick`, however
    /// long it really takes (the default; runs are reproducible).
    pub fn virtual_time() -> Clock {
        Clock {
            source: Source::Virtual,
        }
    }

    /// The monotonic wall clock, counting from now.
    pub fn monotonic() -> Clock {
        Clock::monotonic_since(Instant::now())
    }

    /// The monotonic wall clock, counting from `origin` (an instant in
    /// the future reads as a negative time).
    pub fn monotonic_since(origin: Instant) -> Clock {
        Clock {
            source: Source::Monotonic(origin),
        }
    }

    /// The caller's clock: `read` returns the current time in nanoseconds.
    /// It should never go backwards (timers would then see a negative
    /// elapsed time and saturate at 0).
    pub fn from_fn(read: impl Fn() -> i64 + Send + Sync + 'static) -> Clock {
        Clock {
            source: Source::Caller(Arc::new(read)),
        }
    }

    /// True for the virtual clock.
    pub fn is_virtual(&self) -> bool {
        matches!(self.source, Source::Virtual)
    }

    /// The time, in nanoseconds, of a tick scheduled at `scheduled_ns`.
    #[inline]
    pub fn now(&self, scheduled_ns: i64) -> i64 {
        match &self.source {
            Source::Virtual => scheduled_ns,
            Source::Monotonic(origin) => {
                let now = Instant::now();
                match now.checked_duration_since(*origin) {
                    Some(d) => i64::try_from(d.as_nanos()).unwrap_or(i64::MAX),
                    None => {
                        let ahead = origin.duration_since(now).as_nanos();
                        -i64::try_from(ahead).unwrap_or(i64::MAX)
                    }
                }
            }
            Source::Caller(read) => read(),
        }
    }
}

impl fmt::Debug for Clock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.source {
            Source::Virtual => f.write_str("Clock::Virtual"),
            Source::Monotonic(origin) => write!(f, "Clock::Monotonic({origin:?})"),
            Source::Caller(_) => f.write_str("Clock::Caller"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn the_virtual_clock_is_the_schedule() {
        assert_eq!(Clock::default().now(42), 42);
        assert!(Clock::virtual_time().is_virtual());
    }

    #[test]
    fn the_monotonic_clock_counts_from_its_origin() {
        let origin = Instant::now();
        let clock = Clock::monotonic_since(origin);
        std::thread::sleep(Duration::from_millis(2));
        let now = clock.now(0);
        assert!(now >= 2_000_000, "{now}");
        assert!(!clock.is_virtual());
        let ahead = Clock::monotonic_since(origin + Duration::from_secs(60));
        assert!(ahead.now(0) < 0);
    }

    #[test]
    fn the_callers_clock_is_read_as_given() {
        assert_eq!(Clock::from_fn(|| 7).now(42), 7);
    }
}
