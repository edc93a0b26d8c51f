//! An axis of a TwinCAT solution's NC configuration and the PLC's
//! `AXIS_REF` its cyclic interface is linked to (read by the driver from
//! the `_Config` folder, applied by the TcUnit runner before the first
//! cycle: plcrun's simulated axis takes the axis' id, name and
//! parameters).

/// One configured NC axis linked to an `AXIS_REF`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NcAxis {
    /// The path of the `AXIS_REF` whose `NcToPlc` is linked to the axis,
    /// as the PLC names it (`PRG_TEST.fbTest.stMotionStage.Axis`).
    pub axis_ref: String,
    /// The axis' id in the NC.
    pub id: u32,
    /// Its name (its `.xti` file's name when it is named `__FILENAME__`).
    pub name: String,
    /// The parameters its `.xti` sets, as (field of `ST_AxisParameterSet`,
    /// IEC literal), in the order read.
    pub parameters: Vec<(String, String)>,
}
