//! Preparing the thread that runs a PLC on the wall clock: scheduling
//! policy and priority, CPU affinity, locked and pre-faulted memory, and
//! the kernel's timer slack.
//!
//! [`RealTimeSetup::apply`] works on the calling thread, so it is applied
//! by the thread that runs the cycles: [`crate::TaskRunner`] does it when
//! a real-time run starts, and a host driving `Plc::run_cycle` from its
//! own loop (the C ABI's `plc_rt_setup`) calls it once on that thread.
//!
//! What each setting does, on Linux:
//! - `priority`: `SCHED_FIFO` at that priority (1–99), so the cycle
//!   preempts every ordinary thread. Needs root, `CAP_SYS_NICE` or an
//!   `RLIMIT_RTPRIO` (`ulimit -r`) at least as high; refused otherwise
//!   with [`RealTimeError::PriorityNotPermitted`].
//! - `cpu`: the thread runs on that CPU only (`sched_setaffinity`); pair it
//!   with `isolcpus=` on the kernel command line to keep the core free.
//! - `lock_memory`: `mlockall(MCL_CURRENT | MCL_FUTURE)`, then the stack
//!   the cycle will use is touched once, so that no page fault happens
//!   during a cycle. The PLC's memory was written when it was created, so
//!   it is already present and now stays so. Locking needs `CAP_IPC_LOCK`
//!   or a large enough `RLIMIT_MEMLOCK` (`ulimit -l`); when refused, the
//!   run goes on and [`RealTimeReport::memory_lock`] says why.
//! - `keep_cpu_awake`: `/dev/cpu_dma_latency` is held at 0 µs for as long
//!   as the [`RealTimeReport`] lives, so idle CPUs poll instead of entering
//!   sleep states whose exit takes tens of microseconds (on a virtual
//!   machine: instead of handing the virtual CPU back to the host).
//!   cyclictest does the same by default. Needs root; when refused, the run
//!   goes on and [`RealTimeReport::cpu_awake`] says why.
//! - Always: the thread's timer slack is set to 1 ns (`PR_SET_TIMERSLACK`).
//!   Under the default policy the kernel otherwise lets a sleep end up to
//!   50 µs late to batch wake-ups; `SCHED_FIFO` threads have no slack.

use std::fmt;
use std::io;

/// How the thread running a PLC in real time is prepared (see the module
/// docs). The default changes nothing but the timer slack.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RealTimeSetup {
    /// `SCHED_FIFO` priority, 1 to 99; `None` keeps the current policy.
    pub priority: Option<u8>,
    /// The only CPU (0-based) the thread may run on; `None` keeps the
    /// current affinity.
    pub cpu: Option<usize>,
    /// Lock the process's memory and pre-fault the thread's stack.
    pub lock_memory: bool,
    /// Keep idle CPUs out of deep sleep states while the run lasts.
    pub keep_cpu_awake: bool,
}

/// What [`RealTimeSetup::apply`] did beside what it was sure to do. While
/// it lives it holds the CPU latency request (`keep_cpu_awake`); dropping
/// it, or [`RealTimeReport::release`], lets the CPUs sleep again.
#[derive(Debug)]
pub struct RealTimeReport {
    /// `Ok(true)` when memory was locked, `Ok(false)` when locking was not
    /// asked for, and the operating system's reason when it was refused
    /// (the run goes on, with page faults possible).
    pub memory_lock: Result<bool, io::Error>,
    /// The same for keeping the CPUs awake.
    pub cpu_awake: Result<bool, io::Error>,
    /// The open request; the kernel honours it until it is closed.
    latency_request: Option<std::fs::File>,
}

impl RealTimeReport {
    /// Ends the CPU latency request, keeping what the report says.
    pub fn release(&mut self) {
        self.latency_request = None;
    }
}

/// A setting [`RealTimeSetup::apply`] could not honour. Nothing after the
/// failing setting was applied.
#[derive(Debug)]
pub enum RealTimeError {
    /// The priority is outside 1..=99.
    PriorityOutOfRange(u8),
    /// The operating system refused `SCHED_FIFO` for this process.
    PriorityNotPermitted {
        /// The priority asked for.
        priority: u8,
    },
    /// The CPU does not exist or is not one this process may use.
    CpuNotAvailable {
        /// The CPU asked for.
        cpu: usize,
        /// How many CPUs the machine reports.
        online: usize,
    },
    /// This platform has no such setting (only Linux has them).
    Unsupported(&'static str),
    /// Any other refusal by the operating system.
    Os {
        /// The call that failed.
        call: &'static str,
        /// Its error.
        error: io::Error,
    },
}

impl fmt::Display for RealTimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RealTimeError::PriorityOutOfRange(p) => {
                write!(f, "real-time priority {p} is out of range (1 to 99)")
            }
            RealTimeError::PriorityNotPermitted { priority } => write!(
                f,
                "SCHED_FIFO priority {priority} is not permitted for this process: run it \
                 as root, give the binary CAP_SYS_NICE (setcap cap_sys_nice+ep), or raise \
                 its real-time priority limit (ulimit -r {priority})"
            ),
            RealTimeError::CpuNotAvailable { cpu, online } => write!(
                f,
                "CPU {cpu} is not available to this process ({online} CPUs online, numbered \
                 from 0)"
            ),
            RealTimeError::Unsupported(what) => {
                write!(f, "{what} is only supported on Linux")
            }
            RealTimeError::Os { call, error } => write!(f, "{call} failed: {error}"),
        }
    }
}

impl std::error::Error for RealTimeError {}

/// Stack touched in advance when memory is locked: deeper than any cycle
/// goes in practice (the executor recurses once per nested call, a few
/// hundred bytes each, and calls are bounded to 1 000 levels).
const PREFAULT_STACK_BYTES: usize = 512 * 1024;

impl RealTimeSetup {
    /// Whether anything beyond the timer slack is asked for.
    pub fn is_default(&self) -> bool {
        *self == RealTimeSetup::default()
    }

    /// Applies the setup to the calling thread (see the module docs):
    /// CPU first, then memory, then the priority, so that a refused
    /// priority leaves a thread that is pinned and locked but ordinary.
    pub fn apply(&self) -> Result<RealTimeReport, RealTimeError> {
        if let Some(p) = self.priority
            && !(1..=99).contains(&p)
        {
            return Err(RealTimeError::PriorityOutOfRange(p));
        }
        os::set_timer_slack();
        if let Some(cpu) = self.cpu {
            os::pin_to_cpu(cpu)?;
        }
        let memory_lock = if self.lock_memory {
            os::lock_memory().map(|()| {
                prefault_stack();
                true
            })
        } else {
            Ok(false)
        };
        let (cpu_awake, latency_request) = if self.keep_cpu_awake {
            match os::hold_cpu_latency_zero() {
                Ok(file) => (Ok(true), Some(file)),
                Err(e) => (Err(e), None),
            }
        } else {
            (Ok(false), None)
        };
        if let Some(priority) = self.priority {
            os::set_fifo(priority)?;
        }
        Ok(RealTimeReport {
            memory_lock,
            cpu_awake,
            latency_request,
        })
    }
}

/// Touches the next [`PREFAULT_STACK_BYTES`] of the stack so its pages are
/// present (and, once memory is locked, stay so).
#[inline(never)]
fn prefault_stack() {
    let mut pages = [0u8; PREFAULT_STACK_BYTES];
    // Written through black_box, so the writes are not optimised away.
    std::hint::black_box(&mut pages)
        .iter_mut()
        .step_by(4096)
        .for_each(|b| *b = 1);
    std::hint::black_box(&pages);
}

#[cfg(target_os = "linux")]
mod os {
    use super::RealTimeError;
    use std::io;

    pub(super) fn set_timer_slack() {
        // SAFETY: prctl with PR_SET_TIMERSLACK takes one integer argument
        // and touches no memory of ours. A failure leaves the default
        // slack, which only costs latency.
        unsafe { libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong, 0, 0, 0) };
    }

    pub(super) fn pin_to_cpu(cpu: usize) -> Result<(), RealTimeError> {
        // SAFETY: sysconf has no memory effects.
        let online = unsafe { libc::sysconf(libc::_SC_NPROCESSORS_ONLN) }.max(1) as usize;
        if cpu >= libc::CPU_SETSIZE as usize {
            return Err(RealTimeError::CpuNotAvailable { cpu, online });
        }
        // SAFETY: a zeroed cpu_set_t is an empty set; CPU_SET writes bit
        // `cpu` < CPU_SETSIZE inside it; sched_setaffinity reads the set
        // we pass with its size.
        let result = unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            libc::CPU_SET(cpu, &mut set);
            libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &set)
        };
        if result == 0 {
            return Ok(());
        }
        let error = io::Error::last_os_error();
        if error.raw_os_error() == Some(libc::EINVAL) {
            Err(RealTimeError::CpuNotAvailable { cpu, online })
        } else {
            Err(RealTimeError::Os {
                call: "sched_setaffinity",
                error,
            })
        }
    }

    pub(super) fn lock_memory() -> Result<(), io::Error> {
        // SAFETY: mlockall takes flags only.
        if unsafe { libc::mlockall(libc::MCL_CURRENT | libc::MCL_FUTURE) } == 0 {
            Ok(())
        } else {
            Err(io::Error::last_os_error())
        }
    }

    /// Opens `/dev/cpu_dma_latency` and asks for 0 µs; the request holds
    /// while the file stays open (the kernel's PM QoS interface).
    pub(super) fn hold_cpu_latency_zero() -> Result<std::fs::File, io::Error> {
        use std::io::Write;
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/cpu_dma_latency")?;
        file.write_all(&0i32.to_ne_bytes())?;
        Ok(file)
    }

    pub(super) fn set_fifo(priority: u8) -> Result<(), RealTimeError> {
        let param = libc::sched_param {
            sched_priority: i32::from(priority),
        };
        // SAFETY: `param` is a valid sched_param for the call's duration;
        // pid 0 is the calling thread.
        if unsafe { libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) } == 0 {
            return Ok(());
        }
        let error = io::Error::last_os_error();
        if error.raw_os_error() == Some(libc::EPERM) {
            Err(RealTimeError::PriorityNotPermitted { priority })
        } else {
            Err(RealTimeError::Os {
                call: "sched_setscheduler",
                error,
            })
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod os {
    use super::RealTimeError;
    use std::io;

    pub(super) fn set_timer_slack() {}

    pub(super) fn pin_to_cpu(_cpu: usize) -> Result<(), RealTimeError> {
        Err(RealTimeError::Unsupported("CPU affinity"))
    }

    pub(super) fn lock_memory() -> Result<(), io::Error> {
        Err(io::Error::new(
            io::ErrorKind::Unsupported,
            "memory locking is only supported on Linux",
        ))
    }

    pub(super) fn hold_cpu_latency_zero() -> Result<std::fs::File, io::Error> {
        Err(io::Error::new(
            io::ErrorKind::Unsupported,
            "CPU latency requests are only supported on Linux",
        ))
    }

    pub(super) fn set_fifo(_priority: u8) -> Result<(), RealTimeError> {
        Err(RealTimeError::Unsupported("SCHED_FIFO"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn priority_out_of_range_is_refused_before_anything_changes() {
        for p in [0, 100, 255] {
            let setup = RealTimeSetup {
                priority: Some(p),
                ..RealTimeSetup::default()
            };
            let err = setup.apply().unwrap_err();
            assert!(matches!(err, RealTimeError::PriorityOutOfRange(q) if q == p));
            assert!(err.to_string().contains("1 to 99"), "{err}");
        }
    }

    #[test]
    fn a_missing_cpu_is_named() {
        let setup = RealTimeSetup {
            cpu: Some(100_000),
            ..RealTimeSetup::default()
        };
        // Run on a thread of its own: a success would pin the test thread.
        let err = std::thread::spawn(move || setup.apply().unwrap_err())
            .join()
            .unwrap();
        assert!(
            err.to_string().starts_with("CPU 100000 is not available"),
            "{err}"
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn pinning_to_cpu_0_takes_effect() {
        let on = std::thread::spawn(|| {
            let setup = RealTimeSetup {
                cpu: Some(0),
                ..RealTimeSetup::default()
            };
            setup.apply().unwrap();
            // SAFETY: sched_getcpu has no memory effects.
            unsafe { libc::sched_getcpu() }
        })
        .join()
        .unwrap();
        assert_eq!(on, 0);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn the_cpu_latency_request_is_held_while_the_report_lives_or_refused() {
        let setup = RealTimeSetup {
            keep_cpu_awake: true,
            ..RealTimeSetup::default()
        };
        let mut report = setup.apply().unwrap();
        match &report.cpu_awake {
            Ok(held) => {
                assert!(held);
                assert!(report.latency_request.is_some());
            }
            Err(e) => {
                // Not root: the device is refused, and nothing is held.
                assert_eq!(e.kind(), io::ErrorKind::PermissionDenied, "{e}");
                assert!(report.latency_request.is_none());
            }
        }
        report.release();
        assert!(report.latency_request.is_none());
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn timer_slack_is_one_nanosecond_after_apply() {
        let slack = std::thread::spawn(|| {
            RealTimeSetup::default().apply().unwrap();
            // SAFETY: PR_GET_TIMERSLACK returns the value, no memory effects.
            unsafe { libc::prctl(libc::PR_GET_TIMERSLACK, 0, 0, 0, 0) }
        })
        .join()
        .unwrap();
        assert_eq!(slack, 1);
    }
}
