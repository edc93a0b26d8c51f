//! Preparing the host's cycle thread for real time: a host that drives
//! `plc_run_cycle` from its own loop calls `plc_rt_setup` once on that
//! thread, with the settings `plcrun --rt-priority/--cpu` uses.

use crate::failure::Failure;
use crate::guard::guard;
use crate::status::{PLC_E_INVALID_ARGUMENT, PLC_E_NOT_PERMITTED};
use plcrun::{RealTimeError, RealTimeSetup};
use std::ffi::c_int;

/// Prepares the calling thread: `priority` 1-99 runs it under SCHED_FIFO
/// (0: keep the current policy), `cpu` >= 0 pins it to that CPU (-1: keep
/// the affinity), `lock_memory` locks the process's memory and pre-faults
/// the thread's stack; the timer slack is set to 1 ns in every case.
/// `PLC_E_NOT_PERMITTED` when the system refuses the priority or the
/// memory lock (`plc_last_error` says what to change), `PLC_E_INVALID_ARGUMENT`
/// for a priority over 99 or a CPU that is not available. Linux only:
/// elsewhere every setting but the defaults is `PLC_E_INVALID_ARGUMENT`.
#[unsafe(no_mangle)]
pub extern "C" fn plc_rt_setup(priority: c_int, cpu: c_int, lock_memory: bool) -> c_int {
    guard(|| {
        let priority = match priority {
            0 => None,
            1..=99 => Some(priority as u8),
            _ => {
                return Err(Failure::new(
                    PLC_E_INVALID_ARGUMENT,
                    format!("priority must be 0 (keep the policy) or 1 to 99, not {priority}"),
                ));
            }
        };
        let cpu = match cpu {
            -1 => None,
            k if k >= 0 => Some(k as usize),
            _ => {
                return Err(Failure::new(
                    PLC_E_INVALID_ARGUMENT,
                    format!("cpu must be -1 (keep the affinity) or a CPU number, not {cpu}"),
                ));
            }
        };
        let setup = RealTimeSetup {
            priority,
            cpu,
            lock_memory,
            // A request that outlives this call would need a handle to end
            // it; hosts that want it open /dev/cpu_dma_latency themselves.
            keep_cpu_awake: false,
        };
        let report = setup.apply().map_err(|e| {
            let code = match e {
                RealTimeError::PriorityNotPermitted { .. } => PLC_E_NOT_PERMITTED,
                _ => PLC_E_INVALID_ARGUMENT,
            };
            Failure::new(code, e.to_string())
        })?;
        match report.memory_lock {
            Err(why) => Err(Failure::new(
                PLC_E_NOT_PERMITTED,
                format!(
                    "memory could not be locked ({why}): run as root, give the program \
                     CAP_IPC_LOCK or raise `ulimit -l`; the other settings were applied"
                ),
            )),
            Ok(_) => Ok(()),
        }
    })
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use crate::status::PLC_OK;

    #[test]
    fn bad_arguments_are_refused_by_name() {
        assert_eq!(plc_rt_setup(100, -1, false), PLC_E_INVALID_ARGUMENT);
        assert_eq!(plc_rt_setup(-5, -1, false), PLC_E_INVALID_ARGUMENT);
        assert_eq!(plc_rt_setup(0, -2, false), PLC_E_INVALID_ARGUMENT);
        let status = std::thread::spawn(|| plc_rt_setup(0, 1_000_000, false))
            .join()
            .unwrap();
        assert_eq!(status, PLC_E_INVALID_ARGUMENT);
    }

    #[test]
    fn a_pinned_thread_runs_on_its_cpu() {
        let (status, on) = std::thread::spawn(|| {
            let status = plc_rt_setup(0, 0, false);
            // SAFETY: no memory effects.
            (status, unsafe { libc::sched_getcpu() })
        })
        .join()
        .unwrap();
        assert_eq!(status, PLC_OK);
        assert_eq!(on, 0);
    }

    #[test]
    fn fifo_is_granted_or_refused_with_not_permitted() {
        let (status, policy) = std::thread::spawn(|| {
            let status = plc_rt_setup(10, -1, false);
            // SAFETY: no memory effects.
            (status, unsafe { libc::sched_getscheduler(0) })
        })
        .join()
        .unwrap();
        if status == PLC_OK {
            assert_eq!(policy, libc::SCHED_FIFO);
        } else {
            assert_eq!(status, PLC_E_NOT_PERMITTED);
            assert_eq!(policy, libc::SCHED_OTHER);
        }
    }
}
