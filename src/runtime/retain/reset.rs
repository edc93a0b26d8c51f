//! The warm reset: every variable back to its initial value, except the
//! retained ones, which keep theirs.

use super::layout::RetainLayout;
use crate::runtime::engine::Plc;
use crate::runtime::process_image::ProcessImage;

impl Plc {
    /// Warm reset: re-initialises every variable, FB instance and chart
    /// from the compiled initial values and restarts the task schedule,
    /// then puts the retained values (RETAIN and PERSISTENT) back, as a
    /// PLC does on a warm restart. As with [`Plc::reset_cold`], the cycle
    /// number and the virtual clock restart at 0 and a fault is cleared; a
    /// retained timer goes on from the time it had run.
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
        layout.take(&self.machine, self.cycle(), self.time(), &mut kept);
        self.reinitialise();
        // Timers' start instants move to the restarted clock.
        let now = self.time();
        layout.put(&kept, &mut self.machine, now, None);
        // Retained located variables: the image shows their kept values.
        self.io = ProcessImage::new(&self.image, &self.machine.mem, self.io.addressing());
        self.start(false);
    }
}
