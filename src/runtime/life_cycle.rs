//! A PLC's life cycle: running, stopped by a fault (faulted STOP), and
//! the resets that bring it back.
//!
//! After a runtime fault (an abort through a stop handle included) the PLC
//! keeps the fault and runs nothing more: [`Plc::run_cycle`] returns the
//! same fault again until a reset. A cold reset puts every variable back
//! to its initial value, as if the program had just been loaded.

use super::engine::{Plc, RuntimeFault};
use super::scheduler::Scheduler;
use crate::vm::{Fault, FaultKind};

/// Where a PLC stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlcState<'a> {
    /// Cycles run.
    Ready,
    /// Stopped by this fault: no cycle runs until a reset.
    Faulted(&'a RuntimeFault),
}

impl Plc {
    /// Whether cycles run, or which fault stopped them.
    ///
    /// ```
    /// use plcrun::{Options, Plc, PlcState};
    /// let src = "PROGRAM P VAR n, z : INT; END_VAR n := n + 1; n := n / z; END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// assert_eq!(plc.state(), PlcState::Ready);
    /// let fault = plc.run_cycle().unwrap_err();
    /// assert_eq!(plc.state(), PlcState::Faulted(&fault));
    /// assert_eq!(plc.run_cycle(), Err(fault)); // nothing runs
    /// assert_eq!(plc.read("n")?.to_literal(), "1");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state(&self) -> PlcState<'_> {
        match &self.faulted {
            Some(fault) => PlcState::Faulted(fault),
            None => PlcState::Ready,
        }
    }

    /// The fault that stopped the PLC, if it is stopped.
    pub fn fault(&self) -> Option<&RuntimeFault> {
        self.faulted.as_ref()
    }

    /// Cold reset: every variable back to its initial value (retained ones
    /// too), the cycle count and the clock back to 0, the fault and any stop
    /// or abort request withdrawn. The compiled program and the settings
    /// (watchdog limits) stay.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = "PROGRAM P VAR n : INT := 5; z : INT; END_VAR
    ///            n := n + 1; IF n > 6 THEN n := n / z; END_IF; END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// plc.run_cycle()?; // n = 6
    /// assert!(plc.run_cycle().is_err()); // n = 7: division by zero
    /// plc.reset_cold();
    /// assert_eq!(plc.read("n")?.to_literal(), "5");
    /// assert_eq!(plc.cycle(), 0);
    /// plc.run_cycle()?; // runs again
    /// assert_eq!(plc.read("n")?.to_literal(), "6");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reset_cold(&mut self) {
        self.reinitialise();
        self.start(true);
    }

    /// Runs the start calls (the `FB_init` methods of every instance, see
    /// docs/semantics.md §24) with `bInitRetains` = `init_retains`, then
    /// lets the process image show what they wrote. A fault in one stops
    /// the PLC as a fault in a cycle does.
    pub(crate) fn start(&mut self, init_retains: bool) {
        if self.image.start.is_empty() {
            return;
        }
        if self.run_instance_calls(false, init_retains).is_ok() {
            self.io = super::process_image::ProcessImage::new(
                &self.image,
                &self.machine.mem,
                self.io.addressing(),
            );
        }
    }

    /// Unloads the program as a controller does before it removes it: runs
    /// the `FB_exit` method of every instance that has one (with
    /// `bInCopyCode` FALSE), the program instances' from the last one, then
    /// the global lists' (docs/semantics.md §24). Call it once, after the
    /// last cycle; `plcrun` does before its last retain save, so that
    /// values `FB_exit` writes to RETAIN variables are kept. A fault in
    /// `FB_exit` stops the PLC and is returned; a stopped PLC runs nothing.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = "FUNCTION_BLOCK FB_Log VAR n : INT; END_VAR
    ///            METHOD FB_exit : BOOL VAR_INPUT bInCopyCode : BOOL; END_VAR
    ///            n := n + 100; END_METHOD
    ///            n := n + 1; END_FUNCTION_BLOCK
    ///            PROGRAM P VAR log : FB_Log; END_VAR log(); END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// plc.run_cycle()?;
    /// plc.unload()?;
    /// assert_eq!(plc.read("P.log.n")?.to_literal(), "101");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn unload(&mut self) -> Result<(), RuntimeFault> {
        if let Some(fault) = &self.faulted {
            return Err(fault.clone());
        }
        self.run_instance_calls(true, false)
    }

    /// Runs the start calls (`exit` false) or the exit calls with their
    /// flag set to `flag`; stops the PLC at a fault.
    fn run_instance_calls(&mut self, exit: bool, flag: bool) -> Result<(), RuntimeFault> {
        let n = if exit {
            self.image.exit.len()
        } else {
            self.image.start.len()
        };
        for k in 0..n {
            let call = if exit {
                self.image.exit[k]
            } else {
                self.image.start[k]
            };
            self.machine.mem[call.flag as usize] = u64::from(flag);
            if let Err(fault) = self.machine.run(&self.image, call.code, call.base) {
                return Err(self.fail(fault, call.base as usize));
            }
        }
        Ok(())
    }

    /// The part every reset shares: initial values everywhere, cycle 0,
    /// trigger memory of SINGLE tasks cleared, fault and stop requests
    /// withdrawn. A warm reset runs it, then restores the retained values.
    pub(crate) fn reinitialise(&mut self) {
        self.machine.reinitialise(&self.image);
        self.scheduler = Scheduler::new(
            &self.image.tasks,
            &self.image.programs,
            self.scheduler.base_tick(),
        );
        if let Some(info) = &mut self.task_info {
            info.reset(&self.image, &mut self.machine, self.scheduler.base_tick());
        }
        // The image follows the variables back to their initial values, so
        // that it does not publish or latch stale bits afterwards.
        self.io = super::process_image::ProcessImage::new(
            &self.image,
            &self.machine.mem,
            self.io.addressing(),
        );
        self.cycle = 0;
        self.faulted = None;
        self.stop.clear();
    }

    /// Records a fault raised by the executor in the program instance at
    /// `program_base`: locates it, adds the watchdog's account for a
    /// watchdog fault, and stops the PLC.
    #[cold]
    pub(super) fn fail(&mut self, fault: Fault, program_base: usize) -> RuntimeFault {
        // With a debugger: the stack as the fault left it (before `locate`
        // takes the calls it unwound through).
        let frames = self.debugger.is_some().then(|| {
            super::fault_path::fault_frames(
                self.image.image(),
                &self.machine.mem,
                (fault.code, fault.pc),
                self.machine.callers(),
                program_base,
            )
        });
        let mut located = self.locate(fault, program_base);
        if located.fault.kind == FaultKind::Watchdog {
            let tasks = &self.image.tasks;
            located.watchdog = self.watchdog.trip(|k| tasks[k].name.clone()).map(Box::new);
        }
        self.watchdog.leave();
        if let Some(frames) = frames {
            self.debug_fault(&located, frames);
        }
        self.faulted = Some(located.clone());
        located
    }
}
