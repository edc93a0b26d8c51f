//! plcrun: an IEC 61131-3 runtime.
//!
//! Instruction List, Structured Text and textual SFC are parsed into one AST,
//! checked, lowered into one typed IR and executed by one interpreter under a
//! cyclic scheduler on a virtual clock.
//!
//! Embedding it as a soft-PLC core:
//!
//! ```
//! use plcrun::{Options, Plc};
//!
//! let source = "
//! PROGRAM Blink
//! VAR_INPUT start : BOOL; END_VAR
//! VAR_OUTPUT lamp : BOOL; END_VAR
//! VAR t : TON; END_VAR
//! t(IN := start AND NOT t.Q, PT := T#30ms);
//! lamp := start AND NOT t.Q;
//! END_PROGRAM
//! ";
//! let mut plc = Plc::compile_files(&[("blink.st", source)], &Options::default())?;
//! plc.write("start", "TRUE")?; // any variable, named as with --trace
//! let mut trace = String::new();
//! for _ in 0..5 {
//!     plc.run_cycle()?; // one 10 ms cycle on the virtual clock
//!     trace.push_str(&plc.read("lamp")?.to_literal());
//!     trace.push(' ');
//! }
//! // TON with PT = 30 ms: Q in the 4th call after IN rose, which drops IN.
//! assert_eq!(trace, "TRUE TRUE TRUE FALSE TRUE ");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

// The stages, in pipeline order. Only what the re-exports below name is
// the library's API; the stages themselves stay inside the crate.
pub mod address;
mod compare;
mod diagnostics;
mod draw;
mod driver;
mod elementary;
mod ide;
pub(crate) mod ir;
mod progress;
mod runtime;
mod sema;
mod source;
pub(crate) mod stdlib;
#[doc(hidden)]
pub mod syntax;
mod testing;
mod value;
pub(crate) mod vm;

pub use address::{
    AddressError, Addressing, Area, ImageSpot, ImageTable, IoAddress, IoLink, UnknownAddressing,
    Width,
};
pub use compare::{
    CompareError, CompareOptions, CompareReport, Difference, InputChange, InputKind, InputPlan,
    Mismatch, OutputDifference, Pair, PairedVar, Pairing, RandomStimulus, SeedsOutcome, Shrunk,
    Side, StimulusSource, parse_map, run_seeds, run_seeds_reporting,
};
pub use diagnostics::{Diagnostic, Diagnostics, STRICT_NOTE, Severity, is_compatibility_code};
pub use draw::{
    ActionLine, ChartModel, ChartPicture, DrawError, MAX_CHANGES, NetworkPicture, StepNode,
    TimingDiagram, TransitionNode, draw_chart, draw_sources,
};
pub use driver::{
    CheckOptions, CheckReport, LoadError, add_source_bytes, check, check_reporting, load_files,
    load_files_with, project_files, project_io_links, project_nc_axes, type_description_sources,
    with_library_projects,
};
pub use elementary::ElemType;
pub use ide::{
    Analysis, Completion, CompletionKind, Fold, Hover, LiveName, Occurrence, OutlineItem,
    RenameError, Shape, Signature, SignatureParam, StdFunction, Symbol, SymbolId, SymbolKind,
    TokenKind, TokenMark, VarSection, std_function, std_functions,
};
pub use progress::Progress;
pub use runtime::ads_log::{AdsLog, AdsLogNews, AdsMessage};
pub use runtime::change_report::{ChangeReport, OnlineChangeError, Retyped, SessionChangeError};
pub use runtime::clock::Clock;
pub use runtime::debug_lines::LineTable;
pub use runtime::debug_view::{Container, DebugVariable, Scope, StackFrame, StoppedPlc};
pub use runtime::debugger::{
    Breakpoint, BreakpointPlace, DebugControl, DebugFrontEnd, Resume, StopReason,
};
pub use runtime::engine::{CompileError, Options, Plc, RuntimeFault};
pub use runtime::fault_path::FaultFrame;
pub use runtime::forcing::Force;
pub use runtime::host_blocks::{
    HOST_SOURCE, HostBlocks, HostDeclError, HostIo, HostIoError, HostPin, HostResult,
    HostSignature, PinDir,
};
pub use runtime::life_cycle::PlcState;
pub use runtime::live_stimulus::{LiveStimulus, LiveStimulusError};
pub use runtime::modbus::priority::leave_real_time;
pub use runtime::modbus::{
    ExchangeReport, ImagePlace, ModbusConfig, ModbusError, ModbusExchange, ModbusServer,
    ModbusStats, ModbusTable, modbus_place,
};
pub use runtime::names::VarRef;
#[cfg(feature = "opcua")]
pub use runtime::opcua::{OpcUaConfig, OpcUaExchange, OpcUaServer, Users};
pub use vm::native::{Engine, NativeFallback, NativeReport, UnknownEngine};
#[cfg(feature = "opcua")]
pub mod opcua {
    //! The OPC UA server (cargo feature `opcua`, on by default): docs/opcua.md.
    pub use crate::runtime::opcua::*;
}
pub use runtime::plc_value::Value;
pub use runtime::process_image::ProcessImage;
pub use runtime::realtime::{BetweenTicksHook, RunOutcome, RunThread, TaskRunner};
pub use runtime::retain::saver::RetainSaver;
pub use runtime::retain::{
    Damage, RestoreMode, RestoreReport, RetainDiff, RetainError, RetainedVariable, TypeChange,
};
pub use runtime::rt_thread::{RealTimeError, RealTimeReport, RealTimeSetup};
pub use runtime::session::{
    CycleHook, Pacing, RunError, Session, StimulusBindError, StopHook, StopHookError,
};
pub use runtime::stimulus::{
    Stimulus, StimulusCursor, StimulusError, StimulusKey, StimulusRow, parse_stimulus,
};
pub use runtime::stop::StopHandle;
pub use runtime::task_stats::{
    Histogram, TaskHistograms, TaskStats, TaskStatsHandle, TimeStats, format_stats_table,
    histogram_bounds,
};
pub use runtime::tasks::{TaskInfo, TaskStepError};
pub use runtime::trace::{TraceCell, TraceFormat, TraceWriter, UnknownTraceFormat};
pub use runtime::trace_vcd::{VcdSignal, VcdTimescale};
pub use runtime::var_error::{PathProblem, ReadOnlyReason, ValueProblem, VarError};
pub use runtime::variables::{ChartState, Direction, VarInfo, VarShape};
pub use runtime::watchdog::{UnknownTask, WatchdogTrip};
pub use source::encoding::{Decoded, SourceEncoding, TextEncoding, UnknownEncoding, decode_source};
pub use source::{FileId, SourceFile, SourceMap, Span};
pub use syntax::plcopen::export::{ExportError, export_plcopen};
pub use testing::{
    AssertionFailure, TEST_PREFIX, TestCase, TestError, TestOptions, TestOutcome, TestReport,
    check_test_sources, run_tests, run_tests_reporting,
};
pub use value::literal::{LiteralError, format_duration, parse_time_literal};
pub use vm::{Fault, FaultKind, HostFailure, UnstableCycle};

/// Entry points for the fuzz targets (fuzz/): the network servers'
/// request paths without sockets. Not part of the API.
#[doc(hidden)]
pub mod fuzzing {
    pub use crate::runtime::modbus::fuzzing::serve_bytes as modbus_serve_bytes;
    #[cfg(feature = "opcua")]
    pub use crate::runtime::opcua::fuzzing::WriteFuzz as OpcUaWriteFuzz;
}

/// The examples of `docs/embedding.md`, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/embedding.md")]
pub struct EmbeddingGuide;
