//! The warm reset: every variable back to its initial value, except the
//! retained ones, which keep theirs.

use super::layout::RetainLayout;
use crate::runtime::engine::Plc;
use crate::runtime::scheduler::Scheduler;

impl Plc {
    /// Warm reset: re-initialises every variable, FB instance and chart
    /// from the compiled initial values and restarts the task schedule,
    /// then puts the retained values (RETAIN and PERSISTENT) back, as a
    /// PLC does on a warm restart. The clock and the cycle number go on.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = "PROGRAM P VAR RETAIN kept : INT; END_VAR VAR lost : INT; END_VAR
    ///            kept := kept + 1; lost := lost + 1; END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// for _ in 0..3 { plc.run_cycle()?; }
    /// plc.reset_warm();
    /// assert_eq!(plc.read_i64("kept")?, 3);
    /// assert_eq!(plc.read_i64("lost")?, 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reset_warm(&mut self) {
        let layout = RetainLayout::new(&self.image);
        let mut kept = layout.buffer();
        let now = self.time();
        layout.take(&self.machine, self.cycle(), now, &mut kept);
        self.reinitialise();
        layout.put(&kept, &mut self.machine, now, None);
    }

    /// Memory and strings back to the image's initial values, the
    /// schedule restarted (SINGLE triggers forgotten).
    pub(crate) fn reinitialise(&mut self) {
        self.machine.mem.copy_from_slice(&self.image.memory);
        for (s, init) in self.machine.strings.iter_mut().zip(&self.image.strings) {
            s.set(&init.init);
        }
        let tick = self.scheduler.base_tick();
        self.scheduler = Scheduler::new(&self.image.tasks, &self.image.programs, tick);
    }
}
