//! Forcing: variables held at a value whatever the program, the stimulus
//! or the host writes, as a PLC's debug surface does.
//!
//! A forced variable takes its forced value at once, at the start of every
//! cycle (after the inputs are latched, before any program runs) and again
//! after each program runs, so that the program reads the forced value, the
//! trace and the process image show it, and a forced output keeps it
//! whatever the program wrote. Host writes ([`Plc::write`], [`Plc::set`],
//! [`Plc::soft_write`]) to a forced variable are soft writes: accepted, but
//! the force wins; the last one is what the variable takes when it is
//! unforced. Without such a write, unforcing leaves the forced value in
//! place until the program or the host writes the variable (as CODESYS
//! does when a force is released).
//!
//! Variables are forced by their slot: `%IX0.1` and the name declared at
//! it are the same forced variable. Any single value reachable by path can
//! be forced (inputs, outputs, locals, located variables, array elements,
//! structure fields, FB instance variables) except those the program cannot
//! write either: CONSTANTs and SFC step and action flags.
//!
//! ```
//! use plcrun::{Options, Plc};
//!
//! let src = "PROGRAM P VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM";
//! let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! plc.force("n", "100")?;
//! plc.run_cycle()?;
//! assert_eq!(plc.read("n")?.to_literal(), "100"); // the program wrote 101
//! plc.unforce("n")?;
//! plc.run_cycle()?;
//! assert_eq!(plc.read("n")?.to_literal(), "101");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::engine::Plc;
use super::names::VarRef;
use super::plc_value::Value;
use super::var_error::VarError;

/// One forced variable.
#[derive(Debug, Clone)]
struct Forced {
    /// The variable, as first named when forced.
    r: VarRef,
    /// Its forced value.
    value: Value,
    /// The last host write while forced: the value it takes when unforced.
    under: Option<Value>,
}

/// The forced variables of a PLC.
#[derive(Debug, Clone, Default)]
pub(crate) struct Forces {
    list: Vec<Forced>,
}

impl Forces {
    /// The same forces resolved in `plc` (a new version of the program,
    /// for an online change), or the path of the first one that no longer
    /// fits, with why.
    pub(crate) fn rebind(&self, plc: &Plc) -> Result<Forces, (String, VarError)> {
        let mut list = Vec::with_capacity(self.list.len());
        for f in &self.list {
            let fail = |e| (f.r.name.clone(), e);
            let r = plc.resolve(&f.r.name).map_err(fail)?;
            plc.writable(&r).map_err(fail)?;
            let value = plc.parse_value(&r, &f.value.to_literal()).map_err(fail)?;
            let under = match &f.under {
                Some(u) => Some(plc.parse_value(&r, &u.to_literal()).map_err(fail)?),
                None => None,
            };
            list.push(Forced { r, value, under });
        }
        Ok(Forces { list })
    }

    /// True when nothing is forced (then nothing is applied per cycle).
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Whether the variable `r` is forced.
    pub(crate) fn is_forced(&self, r: &VarRef) -> bool {
        self.list.iter().any(|f| f.r.same_place(r))
    }

    /// When the variable `r` is forced, remembers `v` as the value under
    /// the force and returns true (the write must not reach the slot).
    pub(crate) fn hold_under(&mut self, r: &VarRef, v: &Value) -> bool {
        match self.list.iter_mut().find(|f| f.r.same_place(r)) {
            Some(f) => {
                f.under = Some(v.clone());
                true
            }
            None => false,
        }
    }
}

/// A forced variable as [`Plc::forces`] lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct Force {
    /// The path it was forced by (as given to [`Plc::force`], trimmed).
    pub path: String,
    /// The forced value.
    pub value: Value,
}

impl Plc {
    /// Forces variable `name` to the IEC literal `literal` (see the
    /// section "Forcing" of docs/runtime.md). Forcing a forced
    /// variable again replaces its value. An unknown name, a literal that
    /// does not fit the variable's type ([`VarError::ValueDoesNotFit`],
    /// naming both) and a variable the program cannot write
    /// ([`VarError::ReadOnly`]) are refused.
    pub fn force(&mut self, name: &str, literal: &str) -> Result<(), VarError> {
        let r = self.resolve(name)?;
        self.writable(&r)?;
        let value = self.parse_value(&r, literal).map_err(|e| match e {
            VarError::BadValue {
                literal,
                ty,
                problem,
            } => VarError::ValueDoesNotFit {
                path: r.name.clone(),
                literal,
                ty,
                problem: Box::new(problem),
            },
            other => other,
        })?;
        self.force_value(&r, &value)
    }

    /// Forces a resolved variable to `value` (of its type, as
    /// [`Plc::set`] requires).
    pub fn force_value(&mut self, r: &VarRef, value: &Value) -> Result<(), VarError> {
        self.owned(r)?;
        self.writable(r)?;
        self.check_fits(r, value)?;
        // A soft write made under an earlier force still applies on unforce.
        let under = match self.forces.list.iter().position(|f| f.r.same_place(r)) {
            Some(i) => self.forces.list.remove(i).under,
            None => None,
        };
        self.store(r, value);
        self.forces.list.push(Forced {
            r: r.clone(),
            value: value.clone(),
            under,
        });
        Ok(())
    }

    /// Releases the force on variable `name`; true when it was forced.
    /// The variable keeps its forced value unless it was soft-written
    /// while forced (then it takes the last value written).
    pub fn unforce(&mut self, name: &str) -> Result<bool, VarError> {
        let r = self.resolve(name)?;
        Ok(self.unforce_ref(&r))
    }

    /// Releases the force on a resolved variable; true when it was forced.
    pub fn unforce_ref(&mut self, r: &VarRef) -> bool {
        if r.owner != self.id {
            return false;
        }
        let Some(i) = self.forces.list.iter().position(|f| f.r.same_place(r)) else {
            return false;
        };
        let f = self.forces.list.remove(i);
        if let Some(v) = &f.under {
            self.store(&f.r, v);
        }
        true
    }

    /// Releases every force (each as [`Self::unforce`] does).
    pub fn unforce_all(&mut self) {
        for f in std::mem::take(&mut self.forces.list) {
            if let Some(v) = &f.under {
                self.store(&f.r, v);
            }
        }
    }

    /// The forced variables, in the order they were forced.
    pub fn forces(&self) -> Vec<Force> {
        self.forces
            .list
            .iter()
            .map(|f| Force {
                path: f.r.name.clone(),
                value: f.value.clone(),
            })
            .collect()
    }

    /// Whether the variable `r` is forced (under any of its names).
    pub fn is_forced(&self, r: &VarRef) -> bool {
        r.owner == self.id && self.forces.is_forced(r)
    }

    /// Writes variable `name` from an IEC literal as a soft write: a force
    /// on it overrides the write (which the variable takes when unforced).
    /// Host writes are all soft writes: this is [`Plc::write`] under the
    /// name debug surfaces give it.
    pub fn soft_write(&mut self, name: &str, literal: &str) -> Result<(), VarError> {
        self.write(name, literal)
    }

    /// Puts every forced variable at its forced value.
    pub(super) fn apply_forces(&mut self) {
        let list = std::mem::take(&mut self.forces.list);
        for f in &list {
            self.store(&f.r, &f.value);
        }
        self.forces.list = list;
    }
}
