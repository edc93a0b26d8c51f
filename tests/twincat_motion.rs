//! Tc2_MC2's motion blocks over plcrun's simulated NC axes
//! (docs/twincat.md, "Motion control"): an `AXIS_REF` moves under
//! `MC_Power`, `MC_MoveAbsolute`, `MC_MoveVelocity`, `MC_Halt`, `MC_Home`...
//! with the timing and the NC error codes TwinCAT programs test for.

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, pou};

/// P declaring `declarations` and running `body` every cycle (10 ms),
/// compiled as a TwinCAT project.
fn axis_program(declarations: &str, body: &str) -> plcrun::Plc {
    let main = pou(
        "P",
        &format!(
            "PROGRAM P\nVAR\n  ax : AXIS_REF;\n  power : MC_Power;\n  n : INT;\n{declarations}\nEND_VAR"
        ),
        &format!("n := n + 1;\n{body}\nax.ReadStatus();"),
        "",
    );
    compile_ok(&[("P.TcPOU", &main)])
}

#[test]
fn an_absolute_move_reaches_its_target_and_says_done() {
    let mut plc = axis_program(
        "  move : MC_MoveAbsolute;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         move(Axis := ax, Execute := n >= 3, Position := 10.0, Velocity := 100.0);",
    );
    run(&mut plc, 3);
    // The NC answers MC_Power the cycle after: the move started at once.
    assert_eq!(lit(&plc, "P.power.Status"), "TRUE");
    assert_eq!(lit(&plc, "P.move.Busy"), "TRUE");
    assert_eq!(
        lit(&plc, "P.ax.Status.MotionState"),
        "MC_AXISSTATE_DISCRETEMOTION"
    );
    run(&mut plc, 5);
    // 100 mm/s for 10 ms cycles: 1 mm per cycle.
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), "5.0");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActVelo"), "100.0");
    assert_eq!(lit(&plc, "P.move.Done"), "FALSE");
    run(&mut plc, 6);
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), "10.0");
    assert_eq!(lit(&plc, "P.move.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.move.Busy"), "FALSE");
    assert_eq!(lit(&plc, "P.ax.Status.InTargetPosition"), "TRUE");
    assert_eq!(
        lit(&plc, "P.ax.Status.MotionState"),
        "MC_AXISSTATE_STANDSTILL"
    );
}

#[test]
fn a_move_without_enable_is_an_nc_error_until_reset() {
    let mut plc = axis_program(
        "  move : MC_MoveAbsolute;\n  reset : MC_Reset;",
        "power(Axis := ax, Enable := n >= 5, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         move(Axis := ax, Execute := n >= 2, Position := 10.0, Velocity := 100.0);\n\
         reset(Axis := ax, Execute := n >= 4);",
    );
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.move.Error"), "TRUE");
    assert_eq!(lit(&plc, "P.move.ErrorID"), "16931");
    assert_eq!(lit(&plc, "P.ax.Status.ErrorId"), "16931");
    assert_eq!(
        lit(&plc, "P.ax.Status.MotionState"),
        "MC_AXISSTATE_ERRORSTOP"
    );
    // MC_Reset answers the call after Execute rose.
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.reset.Busy"), "TRUE");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.reset.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.Status.Error"), "FALSE");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), "0.0");
}

#[test]
fn soft_limits_written_by_parameter_refuse_a_target_beyond_them() {
    let mut plc = axis_program(
        "  limit : MC_WriteParameter;\n  enable : MC_WriteBoolParameter;\n  read : MC_ReadParameter;\n\
         \x20 move : MC_MoveAbsolute;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         limit(Axis := ax, Execute := TRUE, ParameterNumber := MC_AxisParameter.AxisMaxSoftPosLimit, Value := 5.0);\n\
         enable(Axis := ax, Execute := TRUE, ParameterNumber := MC_AxisParameter.AxisEnMaxSoftPosLimit, Value := TRUE);\n\
         read(Axis := ax, Enable := n >= 3, ParameterNumber := MC_AxisParameter.AxisMaxSoftPosLimit);\n\
         move(Axis := ax, Execute := n >= 5, Position := 10.0, Velocity := 100.0);",
    );
    run(&mut plc, 4);
    assert_eq!(lit(&plc, "P.limit.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.read.Valid"), "TRUE");
    assert_eq!(lit(&plc, "P.read.Value"), "5.0");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.move.Error"), "TRUE");
    assert_eq!(lit(&plc, "P.move.ErrorID"), "17240");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), "0.0");
}

#[test]
fn a_velocity_move_runs_until_a_halt_takes_over() {
    let mut plc = axis_program(
        "  velocity : MC_MoveVelocity;\n  halt : MC_Halt;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         velocity(Axis := ax, Execute := n >= 2, Velocity := 50.0, Acceleration := 2500.0,\n\
         \x20 Deceleration := 2500.0, Direction := MC_Negative_Direction);\n\
         halt(Axis := ax, Execute := n >= 12, Deceleration := 2500.0);",
    );
    run(&mut plc, 3);
    // 2 500 mm/s² reaches 50 mm/s in two 10 ms cycles.
    assert_eq!(lit(&plc, "P.velocity.InVelocity"), "FALSE");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.velocity.InVelocity"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActVelo"), "-50.0");
    assert_eq!(
        lit(&plc, "P.ax.Status.MotionState"),
        "MC_AXISSTATE_CONTINOUSMOTION"
    );
    run(&mut plc, 8);
    assert_eq!(lit(&plc, "P.velocity.CommandAborted"), "TRUE");
    assert_eq!(lit(&plc, "P.halt.Busy"), "TRUE");
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.halt.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActVelo"), "0.0");
    assert_eq!(lit(&plc, "P.ax.Status.HasBeenStopped"), "TRUE");
}

#[test]
fn homing_on_the_cam_sets_the_home_position_and_the_homed_flag() {
    let mut plc = axis_program(
        "  home : MC_Home;\n  cam : BOOL;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         cam := ax.NcToPlc.ActPos <= -0.5;\n\
         home(Axis := ax, Execute := n >= 2, Position := 100.0, HomingMode := MC_DefaultHoming,\n\
         \x20 bCalibrationCam := cam);",
    );
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.ax.Status.HomingBusy"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.Status.MotionState"), "MC_AXISSTATE_HOMING");
    assert_eq!(lit(&plc, "P.ax.Status.Homed"), "FALSE");
    run(&mut plc, 20);
    assert_eq!(lit(&plc, "P.home.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.Status.Homed"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), "100.0");
}

#[test]
fn every_axis_has_its_own_id_and_a_parameter_set() {
    let mut plc = axis_program(
        "  other : AXIS_REF;\n  read : MC_ReadParameterSet;\n  params : ST_AxisParameterSet;",
        "other.ReadStatus();\n\
         read(Axis := other, Execute := TRUE, Parameter := params);",
    );
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "P.other.NcToPlc.AxisId"), "1");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.AxisId"), "2");
    assert_eq!(lit(&plc, "P.read.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.params.AxisId"), "16#1");
    assert_eq!(lit(&plc, "P.params.fVeloMaximum"), "2000.0");
    assert_eq!(lit(&plc, "P.params.bCtrlEnablePosDiffControl"), "16#1");
}

#[test]
fn floor_of_tc2_math_rounds_down() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  a : LREAL;\n  b : LREAL;\n  c : LREAL;\nEND_VAR",
        "a := FLOOR(2.8);\nb := FLOOR(-2.8);\nc := FLOOR(3.0);",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.a"), "2.0");
    assert_eq!(lit(&plc, "P.b"), "-3.0");
    assert_eq!(lit(&plc, "P.c"), "3.0");
}

#[test]
fn a_reset_during_a_move_stops_the_axis_and_aborts_the_move() {
    let mut plc = axis_program(
        "  move : MC_MoveAbsolute;\n  reset : MC_Reset;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         move(Axis := ax, Execute := n >= 2, Position := 100.0, Velocity := 100.0);\n\
         reset(Axis := ax, Execute := n >= 6);",
    );
    run(&mut plc, 8);
    assert_eq!(lit(&plc, "P.reset.Done"), "TRUE");
    assert_eq!(lit(&plc, "P.move.CommandAborted"), "TRUE");
    assert_eq!(lit(&plc, "P.move.Busy"), "FALSE");
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActVelo"), "0.0");
    let stopped = lit(&plc, "P.ax.NcToPlc.ActPos");
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.ax.NcToPlc.ActPos"), stopped);
}

#[test]
fn an_error_written_to_the_nc_through_ads_stops_the_axis() {
    // lcls-twincat-motion's FB_CauseNCError: ADSWRITE to port 501, index
    // group 16#4200 + the drive id, offset 16#19.
    let mut plc = axis_program(
        "  drive : MC_ReadDriveAddress;\n  write : ADSWRITE;\n  code : UDINT := 16#4550;\n  reset : MC_Reset;",
        "power(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\n\
         drive(Axis := ax, Execute := TRUE);\n\
         write(PORT := 501, IDXGRP := 16#4200 + drive.DriveAddress.NcDriveId, IDXOFFS := 16#19,\n\
         \x20 LEN := SIZEOF(code), SRCADDR := ADR(code), WRITE := drive.Done);\n\
         reset(Axis := ax, Execute := n >= 6);",
    );
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.ax.Status.Error"), "FALSE");
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.write.ERR"), "FALSE");
    assert_eq!(lit(&plc, "P.ax.Status.Error"), "TRUE");
    assert_eq!(lit(&plc, "P.ax.Status.ErrorId"), "17744");
    assert_eq!(
        lit(&plc, "P.ax.Status.MotionState"),
        "MC_AXISSTATE_ERRORSTOP"
    );
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "P.ax.Status.Error"), "FALSE");
}
