//! A link of a TwinCAT solution's I/O configuration from one of a PLC's
//! `AT %Q*` outputs to one of its `AT %I*` inputs (read by the driver from
//! the `.tsproj`, applied by the TcUnit runner between cycles).

/// One link from a PLC output to a PLC input, by the variables' paths as
/// the PLC names them (`PRG_Test.fbTest.fbPump.i_iTemp`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IoLink {
    /// The `AT %I*` variable that takes the value.
    pub input: String,
    /// The `AT %Q*` variable whose value it takes.
    pub output: String,
}
