//! What the lowering pass tells the body builders about methods,
//! inheritance and interfaces (read-only after the declaration phase).

use crate::ir::op::CodeIdx;
use crate::source::Span;
use crate::syntax::ast::{Body, Ident};
use crate::syntax::oop::Modifiers;
use indexmap::IndexMap;
use std::collections::HashMap;

/// The name of the version of a parent's body that `SUPER^()` calls.
pub(crate) const BODY: &str = "__BODY";

/// Field of an interface value holding the instance's absolute address.
pub(crate) const ADDR_FIELD: &str = "__ADDR";
/// Field of an interface value holding the instance's type id (0: none).
pub(crate) const TID_FIELD: &str = "__TID";

/// Everything object-oriented in the program.
#[derive(Debug, Default, Clone)]
pub(crate) struct OopInfo {
    /// FBs with methods, a parent or interfaces, and their ancestors, by
    /// case-folded name.
    pub fbs: HashMap<String, FbOop>,
    /// Interfaces by case-folded name.
    pub interfaces: HashMap<String, ItfInfo>,
    /// Classes (FBs without a body) by case-folded name.
    pub classes: std::collections::HashSet<String>,
    /// Variables with an access specifier: FB key -> variable key ->
    /// (key of the FB that declares it, its access).
    pub var_access: HashMap<String, HashMap<String, (String, crate::syntax::oop::Access)>>,
}

impl OopInfo {
    /// True when the program uses no object orientation at all.
    pub(crate) fn is_empty(&self) -> bool {
        self.fbs.is_empty() && self.interfaces.is_empty()
    }
}

/// One FB's methods and ancestry.
#[derive(Debug, Clone)]
pub(crate) struct FbOop {
    /// Name as declared.
    pub name: String,
    /// Type id stored in interface values (from 1).
    pub tid: u32,
    /// The parent's key.
    pub parent: Option<String>,
    /// Declared ABSTRACT.
    pub is_abstract: bool,
    /// Every method version compiled for this FB.
    pub versions: Vec<Version>,
    /// The version a call of each method name runs (most derived).
    pub dispatch: IndexMap<String, usize>,
    /// Interfaces implemented, with inherited and extended ones.
    pub interfaces: Vec<String>,
    /// Code block of each version (parallel to `versions`).
    pub codes: Vec<CodeIdx>,
}

impl FbOop {
    /// The version of method `key` declared in `origin`, if this FB has it.
    pub(crate) fn version_of(&self, origin: &str, key: &str) -> Option<usize> {
        self.versions
            .iter()
            .position(|v| v.origin == origin && v.name.key() == key)
    }
}

/// One parameter of a method (input or output, in declaration order).
#[derive(Debug, Clone)]
pub(crate) struct ParamSig {
    /// Name as declared.
    pub name: String,
    /// True for VAR_INPUT, false for VAR_OUTPUT.
    pub input: bool,
    /// Key of the hidden variable (or signature field) holding it.
    pub hidden: String,
    /// VAR_IN_OUT (then `input` is true too): the hidden variable holds the
    /// address of the caller's variable.
    pub in_out: bool,
}

/// A method's signature as text, for override and implementation checks:
/// `(name key, section, type)` per parameter, and the result type.
pub(crate) type Signature = (Vec<(String, bool, String)>, String);

/// One method (or parent body) compiled for an FB.
#[derive(Debug, Clone)]
pub(crate) struct Version {
    /// Key of the FB that declared it.
    pub origin: String,
    /// Its name ([`BODY`] for a parent's body).
    pub name: Ident,
    /// Its modifiers.
    pub mods: Modifiers,
    /// Inputs and outputs.
    pub params: Vec<ParamSig>,
    /// Key of the hidden result variable.
    pub ret: Option<String>,
    /// User key -> hidden key of every variable of the method.
    pub locals: HashMap<String, String>,
    /// Hidden keys reset at every call (all but the inputs).
    pub resets: Vec<String>,
    /// The statements.
    pub body: Body,
    /// The declaration.
    pub span: Span,
    /// For checks.
    pub sig: Signature,
    /// Key of the hidden BOOL that is TRUE while the method runs on the
    /// instance, when a cycle of calls through interfaces may reach it
    /// again (`reentry.rs`).
    pub guard: Option<String>,
    /// Declared after `{attribute 'no_check'}` (a METHOD), or the body of
    /// a block so declared: calls no implicit check.
    pub no_check: bool,
}

/// An interface.
#[derive(Debug, Clone)]
pub(crate) struct ItfInfo {
    /// Name as declared.
    pub name: String,
    /// Its methods (with the extended interfaces' ones).
    pub methods: IndexMap<String, ItfMethod>,
    /// Key of the structure type whose fields type the parameters.
    pub sig_type: String,
    /// Keys of this interface and of every interface it extends, directly
    /// or not (a value of this interface may be assigned to any of them).
    pub ancestors: Vec<String>,
}

/// One method prototype of an interface.
#[derive(Debug, Clone)]
pub(crate) struct ItfMethod {
    /// Name as declared.
    pub name: Ident,
    /// Inputs and outputs (`hidden` names a field of the signature type).
    pub params: Vec<ParamSig>,
    /// Field of the signature type typing the result.
    pub ret: Option<String>,
    /// For checks.
    pub sig: Signature,
}
