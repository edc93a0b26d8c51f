//! Choosing the addressing convention of a compiled PLC after the fact
//! ([`Plc::set_addressing`]), for hosts that cannot pass it in
//! [`crate::Options`] (the C ABI's `plc_set_addressing`).

use super::engine::Plc;
use super::process_image::ProcessImage;
use crate::address::Addressing;
use crate::diagnostics::Diagnostics;
use crate::driver::{self, CheckOptions};

/// The code of the overlap warning, judged again on a change.
const OVERLAP: &str = "W204";

impl Plc {
    /// How the process image numbers direct addresses (chosen by
    /// [`crate::Options::addressing`] or from the sources).
    pub fn addressing(&self) -> Addressing {
        self.io.addressing()
    }

    /// Lays the process image out again under `addressing`: every located
    /// variable keeps its value, and the image takes them at their new
    /// places (as after a reset); the next cycle exchanges through the new
    /// layout. The overlap warnings (W204) among [`Plc::warnings`] are
    /// judged again under the new convention. Nothing happens when
    /// `addressing` is the current one.
    ///
    /// ```
    /// use plcrun::{Addressing, Options, Plc};
    /// let src = "PROGRAM P VAR c AT %QX0.0 : BOOL; r AT %QW0 : INT; END_VAR
    ///            c := TRUE; r := 7; END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// assert_eq!(plc.warnings().iter().next().map(|d| d.code), Some("W204"));
    /// plc.set_addressing(Addressing::OpenPlc);
    /// assert!(plc.warnings().is_empty());
    /// plc.run_cycle()?;
    /// assert!(plc.process_image().read_bit("%QX0.0")?);
    /// assert_eq!(plc.process_image().read_word("%QW0")?, 7);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_addressing(&mut self, addressing: Addressing) {
        if addressing == self.io.addressing() {
            return;
        }
        self.io = ProcessImage::new(&self.image, &self.machine.mem, addressing);
        let report = driver::check(
            &self.sources,
            &CheckOptions {
                addressing: Some(addressing),
                ..CheckOptions::default()
            },
        );
        let mut warnings = Diagnostics::new();
        for d in self.warnings.iter().filter(|d| d.code != OVERLAP) {
            warnings.push(d.clone());
        }
        for d in report.diagnostics.iter().filter(|d| d.code == OVERLAP) {
            warnings.push(d.clone());
        }
        self.warnings = warnings;
    }
}
