//! Step tables: how a Sequential Function Chart is represented in the image.
//!
//! A chart body lowers to one [`Chart`] plus ordinary code blocks (one per
//! transition condition that is not a constant or a plain BOOL variable, one
//! per action body). The POU's own code block starts with `Op::Sfc`, which
//! runs evolution and action control from the table, then continues with the
//! plain statements of the body. All run-time state lives in the instance
//! memory, at offsets recorded here (relative to the instance base), so
//! every FB instance has its own chart state.
//!
//! Hidden state of one instance (see [`header`]): a header, the list of
//! active steps (sorted by step index), the list of live actions (sorted by
//! action index), one evaluation cache slot per transition, one scratch
//! slot per step, and one [`action_layout`] record per action.

/// Offsets inside the chart header.
pub mod header {
    /// Non-zero once the initial steps have been activated.
    pub const STARTED: u32 = 0;
    /// Call counter, used to stamp per-call caches.
    pub const EPOCH: u32 = 1;
    /// Number of active steps.
    pub const N_ACTIVE: u32 = 2;
    /// Number of live actions.
    pub const N_LIVE: u32 = 3;
    /// Where condition code blocks leave their result.
    pub const COND: u32 = 4;
    /// Header size in slots.
    pub const SIZE: u32 = 5;
}

/// Slot layout of an action's control record. `Q` and `A` are visible as
/// `name.Q` / `name.A`; the rest is hidden state of ACTION_CONTROL.
pub mod action_layout {
    /// Output Q of the action control.
    pub const Q: u32 = 0;
    /// Activity: TRUE while the body runs (including the final scan).
    pub const A: u32 = 1;
    /// Epoch of the call in which `INPUTS` was last accumulated.
    pub const IN_EPOCH: u32 = 2;
    /// Qualifier inputs of the current call (bit set of [`super::Qualifier`]).
    pub const INPUTS: u32 = 3;
    /// Qualifier inputs of the previous processing (for edges).
    pub const PREV: u32 = 4;
    /// Stored flag of S.
    pub const S_SET: u32 = 5;
    /// Stored flag of SD and the clock when it was set.
    pub const SD_SET: u32 = 6;
    /// Clock at which SD was stored.
    pub const SD_AT: u32 = 7;
    /// Duration in effect when SD was stored.
    pub const SD_T: u32 = 8;
    /// Stored flag of DS.
    pub const DS_SET: u32 = 9;
    /// Clock at which DS rose.
    pub const DS_AT: u32 = 10;
    /// Stored flag of SL.
    pub const SL_SET: u32 = 11;
    /// Clock at which SL was stored.
    pub const SL_AT: u32 = 12;
    /// Duration in effect when SL was stored.
    pub const SL_T: u32 = 13;
    /// Clock at which L rose.
    pub const L_AT: u32 = 14;
    /// Clock at which D rose.
    pub const D_AT: u32 = 15;
    /// Durations of L, D, DS in the current call (filled with the inputs).
    pub const DUR_L: u32 = 16;
    /// Duration of D in the current call.
    pub const DUR_D: u32 = 17;
    /// Duration of DS in the current call.
    pub const DUR_DS: u32 = 18;
    /// Duration of SD in the current call.
    pub const DUR_SD: u32 = 19;
    /// Duration of SL in the current call.
    pub const DUR_SL: u32 = 20;
    /// Record size in slots.
    pub const SIZE: u32 = 21;
}

/// An action qualifier (IEC 61131-3 table 45).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Qualifier {
    /// Non-stored.
    N,
    /// Reset (overriding).
    R,
    /// Set (stored).
    S,
    /// Time limited.
    L,
    /// Time delayed.
    D,
    /// Pulse.
    P,
    /// Pulse on the falling edge.
    P0,
    /// Pulse on the rising edge.
    P1,
    /// Stored and time delayed.
    SD,
    /// Delayed and stored.
    DS,
    /// Stored and time limited.
    SL,
}

impl Qualifier {
    /// The qualifier named `s` (upper case), if any.
    pub fn parse(s: &str) -> Option<Qualifier> {
        Some(match s {
            "N" => Qualifier::N,
            "R" => Qualifier::R,
            "S" => Qualifier::S,
            "L" => Qualifier::L,
            "D" => Qualifier::D,
            "P" => Qualifier::P,
            "P0" => Qualifier::P0,
            "P1" => Qualifier::P1,
            "SD" => Qualifier::SD,
            "DS" => Qualifier::DS,
            "SL" => Qualifier::SL,
            _ => return None,
        })
    }

    /// True for the qualifiers that need a duration.
    pub fn timed(self) -> bool {
        matches!(
            self,
            Qualifier::L | Qualifier::D | Qualifier::SD | Qualifier::DS | Qualifier::SL
        )
    }

    /// Its bit in an input set.
    pub fn bit(self) -> u64 {
        1 << (self as u32)
    }
}

/// Where a duration comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Duration {
    /// No duration (untimed qualifier).
    None,
    /// A constant, in nanoseconds.
    Const(i64),
    /// A TIME variable in the instance frame.
    Frame(u32),
    /// A TIME variable at an absolute address.
    Abs(u32),
}

/// One action association of a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Association {
    /// Index into [`Chart::actions`].
    pub action: u32,
    /// Qualifier.
    pub qualifier: Qualifier,
    /// Its duration.
    pub duration: Duration,
}

/// A step.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Name as declared.
    pub name: String,
    /// Offset of its step record (`ir::type_table::step_layout`).
    pub rec: u32,
    /// Offset of its per-call scratch slot (the transition that wins it).
    pub scratch: u32,
    /// Outgoing transitions, first to be tried first (priority, then text).
    pub out: Vec<u32>,
    /// Action associations in textual order.
    pub assocs: Vec<Association>,
}

/// How a transition condition is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Condition {
    /// Known at compile time.
    Const(bool),
    /// A BOOL in the instance frame.
    Frame(u32),
    /// A code block that leaves the BOOL in the header's `COND` slot.
    Code(crate::ir::op::CodeIdx),
}

/// A transition.
#[derive(Debug, Clone, PartialEq)]
pub struct Transition {
    /// Preceding steps.
    pub from: Vec<u32>,
    /// Following steps.
    pub to: Vec<u32>,
    /// Its condition.
    pub cond: Condition,
}

/// What an action does with its output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActionKind {
    /// Runs a code block (while Q, plus the final scan).
    Body(crate::ir::op::CodeIdx),
    /// Copies Q into a BOOL in the instance frame.
    Frame(u32),
    /// Copies Q into a BOOL at an absolute address.
    Abs(u32),
}

/// An action.
#[derive(Debug, Clone, PartialEq)]
pub struct Action {
    /// Name as declared.
    pub name: String,
    /// Offset of its control record ([`action_layout`]).
    pub rec: u32,
    /// What it drives.
    pub kind: ActionKind,
}

/// The step table of one chart body.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// POU name (for messages).
    pub name: String,
    /// Offset of the header ([`header`]).
    pub header: u32,
    /// Offset of the active list (`steps.len()` slots).
    pub active: u32,
    /// Offset of the live action list (`actions.len()` slots).
    pub live: u32,
    /// Offset of the transition cache (`transitions.len()` slots).
    pub cache: u32,
    /// Initial steps.
    pub initial: Vec<u32>,
    /// Steps, in declaration order.
    pub steps: Vec<Step>,
    /// Transitions, in declaration order.
    pub transitions: Vec<Transition>,
    /// Actions, in execution order.
    pub actions: Vec<Action>,
    /// Which standard's evolution rules the chart follows.
    pub evolution: Evolution,
    /// Forcing orders of partial grafcets held by its steps (IEC 60848
    /// evolution only; empty otherwise).
    pub forcings: Vec<Forcing>,
}

/// The evolution rules a chart follows, chosen at compile time for every
/// chart of the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evolution {
    /// IEC 61131-3 SFC: one evolution per call (`vm::chart`).
    #[default]
    Sfc,
    /// IEC 60848 GRAFCET: evolution iterated to a stable situation, stored
    /// actions on activation events (`vm::grafcet`).
    Grafcet,
}

/// Where a forced FUNCTION_BLOCK instance (a partial grafcet) lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InstanceAt {
    /// In the forcing POU's frame, at this offset.
    Frame(u32),
    /// At this absolute address (a global instance).
    Abs(u32),
}

/// What a forcing order imposes on its partial grafcet.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ForcingOrder {
    /// `F/G:{...}`: exactly these steps (indexes into the target's steps,
    /// sorted, no duplicates; empty for the empty situation).
    Situation(Vec<u32>),
    /// `F/G:{*}`: the current situation (the grafcet is frozen).
    Freeze,
}

/// A forcing order `F/G:{...}` associated with a step: while that step is
/// active in a stable situation, the partial grafcet `G` (an FB instance
/// whose body is a chart) is held in the order's situation and does not
/// evolve.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Forcing {
    /// The step of this chart that holds the order.
    pub step: u32,
    /// The forced instance.
    pub instance: InstanceAt,
    /// Offset of the forced chart's header, relative to the instance.
    pub header: u32,
    /// Offsets of the forced chart's step records, relative to the
    /// instance, in its step order.
    pub steps: Vec<u32>,
    /// The order.
    pub order: ForcingOrder,
}

/// Bits of the header's `STARTED` slot under IEC 60848 evolution.
pub mod started {
    /// The initial situation has been set.
    pub const RUNNING: u64 = 1;
    /// A forcing order holds the chart in its situation for its next call.
    pub const FORCED: u64 = 2;
    /// A forcing order imposed a situation since the chart's last call:
    /// further orders add their steps (a step forced active by one order
    /// and inactive by another is active).
    pub const IMPOSED: u64 = 4;
}
