//! Edition-3 object orientation, lowered onto the existing FB machinery.
//!
//! * [`lower`] rewrites the syntax tree before the declaration phase: a
//!   child FB's variables are its parent's (flattened, parent first) followed
//!   by its own, so the child's instance layout starts with the parent's; each
//!   method's variables become hidden variables of the FB (named
//!   `Origin__Method__var`, which no identifier can spell); each interface
//!   becomes a two-slot structure type (instance address, type id) and a
//!   signature structure that gives its parameters their types.
//! * Every method *version* an FB has (its own, the inherited ones, the
//!   parents' versions reachable through `SUPER^`, the parents' bodies for
//!   `SUPER^()`) is compiled as its own code block of that FB, running on
//!   the instance like the FB's body, with its own temporaries
//!   ([`methods`]). Code is compiled per concrete FB, so a call of `M` on
//!   `THIS^` inside inherited code reaches the override without any lookup.
//! * Calls ([`calls`]): `inst.M(...)` stores the arguments into the hidden
//!   input variables and calls the method's block (`CallFb`); a call
//!   through an interface compares the value's type id with each
//!   implementing FB's id and calls that FB's version (`CallFbInd`); no
//!   match (an unassigned interface) is fault R080.
//! * Interface values ([`itf_values`]) go wherever a structure goes
//!   (arguments, results, array elements), an interface receives one of an
//!   interface extending it; `?=` ([`assign_attempt`]) tries the other
//!   way at run time.

mod assign_attempt;
pub(super) mod calls;
pub(super) mod class;
mod itf_values;
pub(super) mod lower;
mod method_scope;
mod method_vars;
pub(super) mod methods;
pub(super) mod model;
pub(super) mod property;
mod reentry;
mod this_call;
pub(super) mod this_pointer;
pub(super) mod var_access;

pub(super) use model::OopInfo;
