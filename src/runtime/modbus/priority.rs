//! The server's threads give up a real-time scheduling policy they
//! inherited (`chrt -f 50 plcrun --realtime --modbus ...`), so that a busy
//! Modbus network never competes with the scan for the CPU: the scan keeps
//! the real-time priority, the server runs in what time is left.

/// Moves the calling thread to the normal time-sharing policy when it
/// runs under a real-time one; does nothing otherwise (nor where the
/// system refuses). A host's own server threads call it so that, under
/// `chrt -f 50 plcrun ...`, they leave the CPU to the scan; threads they
/// start inherit the normal policy.
#[cfg(target_os = "linux")]
pub fn leave_real_time() {
    // SAFETY: plain system calls on the calling thread (pid 0 names it on
    // Linux) with a parameter block that lives across the call.
    unsafe {
        let policy = libc::sched_getscheduler(0);
        if policy == libc::SCHED_FIFO || policy == libc::SCHED_RR {
            let normal = libc::sched_param { sched_priority: 0 };
            libc::sched_setscheduler(0, libc::SCHED_OTHER, &normal);
        }
    }
}

/// Elsewhere threads keep their priority.
#[cfg(not(target_os = "linux"))]
pub fn leave_real_time() {}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    #[test]
    fn a_normal_thread_stays_normal() {
        std::thread::spawn(|| {
            super::leave_real_time();
            // SAFETY: a plain query of the calling thread's policy.
            assert_eq!(unsafe { libc::sched_getscheduler(0) }, libc::SCHED_OTHER);
        })
        .join()
        .unwrap();
    }
}
