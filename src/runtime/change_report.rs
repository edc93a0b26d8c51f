//! What an online change did ([`ChangeReport`]) and why one was refused
//! ([`OnlineChangeError`]).

use super::engine::{CompileError, RuntimeFault};
use super::session::StimulusBindError;
use super::var_error::VarError;
use std::fmt;

/// A variable whose type changed across an online change: it starts again
/// from its new initial value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Retyped {
    /// Its path (`Main.count`, `Glob`).
    pub path: String,
    /// The type it had.
    pub old_type: String,
    /// The type it has now.
    pub new_type: String,
}

/// What [`crate::Plc::online_change`] did with each variable, by path.
///
/// A path is listed at the highest level where one outcome holds for all
/// of it: a timer instance that kept its whole state is `kept` as
/// `Main.t`, not pin by pin; a user FB instance whose FUNCTION_BLOCK gained
/// a variable lists its members one by one.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ChangeReport {
    /// Carried over with their values (and, for FB instances, their hidden
    /// state: a running timer keeps timing, an edge detector its memory).
    pub kept: Vec<String>,
    /// New: they start from their initial values.
    pub initialised: Vec<String>,
    /// Gone from the new version: their values are dropped.
    pub dropped: Vec<String>,
    /// Same path, another type: re-initialised.
    pub retyped: Vec<Retyped>,
    /// Instances whose SFC chart changed shape (steps, transitions or
    /// actions): the chart starts again at its initial steps.
    pub charts_restarted: Vec<String>,
    /// Instances of a function block whose declaration changed: copied
    /// into the new layout, with `FB_exit(bInCopyCode := TRUE)` called on
    /// the old instance before and `FB_reinit` on the new one after, where
    /// the block has them (docs/semantics.md §24). Their variables are
    /// also listed above.
    pub copied: Vec<String>,
}

impl ChangeReport {
    /// True when nothing but kept variables is listed: the new version
    /// took over the whole state.
    pub fn is_seamless(&self) -> bool {
        self.initialised.is_empty()
            && self.dropped.is_empty()
            && self.retyped.is_empty()
            && self.charts_restarted.is_empty()
    }
}

impl fmt::Display for ChangeReport {
    /// One line per path: `kept Main.t`, `initialised Main.extra`,
    /// `dropped Main.old`, `retyped Main.x (INT -> REAL)`, `chart restarted Main`,
    /// `copied Main.axis`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for p in &self.kept {
            writeln!(f, "kept {p}")?;
        }
        for p in &self.initialised {
            writeln!(f, "initialised {p}")?;
        }
        for p in &self.dropped {
            writeln!(f, "dropped {p}")?;
        }
        for r in &self.retyped {
            writeln!(f, "retyped {} ({} -> {})", r.path, r.old_type, r.new_type)?;
        }
        for p in &self.charts_restarted {
            writeln!(f, "chart restarted {p}")?;
        }
        for p in &self.copied {
            writeln!(f, "copied {p}")?;
        }
        Ok(())
    }
}

/// Why an online change was refused (the running program is left exactly
/// as it was), or, for [`OnlineChangeError::Fault`], stopped the PLC.
#[derive(Debug, Clone)]
pub enum OnlineChangeError {
    /// The new sources do not compile.
    Compile(Box<CompileError>),
    /// The new version's tasks differ from the running ones (names,
    /// intervals, priorities or SINGLE triggers): the schedule and the
    /// clock's tick cannot change under a running PLC.
    TasksChanged {
        /// The running tasks, as `name(interval ns, priority)`.
        old: Vec<String>,
        /// The new version's tasks, in the same form.
        new: Vec<String>,
    },
    /// The new version's base tick (cycle time) differs from the running one.
    CycleTimeChanged {
        /// Running base tick, in nanoseconds.
        old: i64,
        /// New base tick, in nanoseconds.
        new: i64,
    },
    /// `FB_exit` on a copied instance of the running version, or
    /// `FB_reinit` on one of the new version, faulted: the PLC is stopped
    /// with this fault (after `FB_exit`, the running version; after
    /// `FB_reinit`, the new one, which took over).
    Fault(Box<RuntimeFault>),
    /// A forced variable is gone from the new version, or its forced value
    /// does not fit its new type: a force is never dropped silently (it may
    /// hold a machine in a safe state); unforce it first.
    ForceDoesNotFit {
        /// The forced variable's path.
        path: String,
        /// Why it does not fit.
        error: Box<VarError>,
    },
}

impl fmt::Display for OnlineChangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OnlineChangeError::Compile(e) => {
                write!(
                    f,
                    "online change refused: the new version does not compile\n{e}"
                )
            }
            OnlineChangeError::TasksChanged { old, new } => write!(
                f,
                "online change refused: the tasks changed (running: [{}], new: [{}]); \
                 restart the PLC to change its tasks",
                old.join(", "),
                new.join(", ")
            ),
            OnlineChangeError::CycleTimeChanged { old, new } => write!(
                f,
                "online change refused: the cycle time changed ({old} ns -> {new} ns); \
                 restart the PLC to change it"
            ),
            OnlineChangeError::ForceDoesNotFit { path, error } => write!(
                f,
                "online change refused: the forced variable `{path}` does not fit the new \
                 version ({error}); unforce it first"
            ),
            OnlineChangeError::Fault(fault) => write!(
                f,
                "online change stopped the PLC: FB_exit or FB_reinit of a copied instance faulted\n{fault}"
            ),
        }
    }
}

impl std::error::Error for OnlineChangeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            OnlineChangeError::Compile(e) => Some(e.as_ref()),
            OnlineChangeError::ForceDoesNotFit { error, .. } => Some(error.as_ref()),
            _ => None,
        }
    }
}

impl From<CompileError> for OnlineChangeError {
    fn from(e: CompileError) -> Self {
        OnlineChangeError::Compile(Box::new(e))
    }
}

/// Why [`crate::Session::online_change`] was refused. The session and its
/// program are left exactly as they were.
#[derive(Debug, Clone)]
pub enum SessionChangeError {
    /// The PLC refused the change.
    Change(OnlineChangeError),
    /// A traced name does not name a value of the new version.
    Trace(VarError),
    /// A stimulus column or cell does not fit the new version.
    Stimulus(StimulusBindError),
}

impl fmt::Display for SessionChangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SessionChangeError::Change(e) => e.fmt(f),
            SessionChangeError::Trace(e) => {
                write!(f, "online change refused: traced variable: {e}")
            }
            SessionChangeError::Stimulus(e) => write!(f, "online change refused: stimulus: {e}"),
        }
    }
}

impl std::error::Error for SessionChangeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SessionChangeError::Change(e) => Some(e),
            SessionChangeError::Trace(e) => Some(e),
            SessionChangeError::Stimulus(e) => Some(e),
        }
    }
}

impl From<OnlineChangeError> for SessionChangeError {
    fn from(e: OnlineChangeError) -> Self {
        SessionChangeError::Change(e)
    }
}
