//! Edition-3 object orientation in the syntax tree: methods, inheritance,
//! interfaces and their modifiers. The parser attaches a [`PouOop`] to a
//! FUNCTION_BLOCK that uses any of them and makes an [`Interface`] item of
//! each `INTERFACE ... END_INTERFACE`; `src/sema/oop/` lowers both.

use crate::source::Span;
use crate::syntax::ast::{Body, Ident, TypeSpec, VarBlock};

/// Who may call a method (edition 3 access specifiers).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// `PUBLIC` (the default): everyone.
    Public,
    /// `PRIVATE`: the declaring FB only.
    Private,
    /// `PROTECTED`: the declaring FB and the FBs that extend it.
    Protected,
    /// `INTERNAL`: the same namespace; without namespaces, everyone.
    Internal,
}

/// One modifier word before a method or FB name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Modifier {
    /// An access specifier.
    Access(Access),
    /// `ABSTRACT`.
    Abstract,
    /// `FINAL`.
    Final,
}

/// The modifiers of a method or FB, folded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Modifiers {
    /// The access specifier written, if any.
    pub access: Option<Access>,
    /// `ABSTRACT` was written.
    pub is_abstract: bool,
    /// `FINAL` was written.
    pub is_final: bool,
}

impl Modifiers {
    /// Folds modifier words in source order (a later access word wins).
    pub fn from_words(words: &[Modifier]) -> Modifiers {
        let mut m = Modifiers::default();
        for w in words {
            match w {
                Modifier::Access(a) => m.access = Some(*a),
                Modifier::Abstract => m.is_abstract = true,
                Modifier::Final => m.is_final = true,
            }
        }
        m
    }

    /// The access that applies (PUBLIC when none is written).
    pub fn access(&self) -> Access {
        self.access.unwrap_or(Access::Public)
    }
}

/// `METHOD [modifiers] name [: type] ... END_METHOD`, in an FB or (as a
/// prototype without a body) in an interface.
#[derive(Debug, Clone, PartialEq)]
pub struct Method {
    /// The method's name.
    pub name: Ident,
    /// Modifiers written before the name.
    pub mods: Modifiers,
    /// The result type, if any.
    pub return_type: Option<TypeSpec>,
    /// Its own variable sections.
    pub var_blocks: Vec<VarBlock>,
    /// Its statements.
    pub body: Body,
    /// Span from `METHOD` to `END_METHOD`.
    pub span: Span,
    /// For a `PROPERTY`: its GET and SET accessors as methods (replaced by
    /// them in the FB or interface, see [`crate::syntax::oop_property`]).
    pub property: Option<Vec<Method>>,
    /// Declared after `{attribute 'call_after_init'}`: called on every
    /// instance right after its `FB_init` (`src/sema/instance_calls/`).
    pub call_after_init: bool,
    /// Declared after `{attribute 'no_check'}`: its code calls no implicit
    /// check (`src/sema/implicit_checks.rs`).
    pub no_check: bool,
}

/// What a FUNCTION_BLOCK declares beyond edition 2.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PouOop {
    /// Modifiers of the FB itself (`ABSTRACT`, `FINAL`).
    pub mods: Modifiers,
    /// `EXTENDS parent`.
    pub extends: Option<Ident>,
    /// `IMPLEMENTS i1, i2`.
    pub implements: Vec<Ident>,
    /// Methods in source order.
    pub methods: Vec<Method>,
    /// Declared `CLASS ... END_CLASS` (an FB without a body).
    pub is_class: bool,
    /// Variable sections with an access specifier (`VAR PRIVATE`): the
    /// section's span and its access.
    pub var_access: Vec<(Span, Access)>,
}

/// `INTERFACE name [EXTENDS i, ...] METHOD ... END_METHOD ... END_INTERFACE`.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// The interface's name.
    pub name: Ident,
    /// Interfaces it extends.
    pub extends: Vec<Ident>,
    /// Method prototypes.
    pub methods: Vec<Method>,
    /// Span from `INTERFACE` to `END_INTERFACE`.
    pub span: Span,
}

// ------------------------------------------------------------------ building

use crate::syntax::ast::{Expr, ExprKind, Pou, PouKind};
use crate::syntax::construct::State;

/// The name of the `THIS^` root in the tree (no identifier can spell it).
pub const THIS: &str = "THIS^";
/// The name of the `SUPER^` root in the tree.
pub const SUPER: &str = "SUPER^";

/// An FB with edition-3 parts.
#[allow(clippy::too_many_arguments)]
pub fn fb(
    st: &State,
    mods: Vec<Modifier>,
    name: Ident,
    extends: Option<Ident>,
    implements: Option<Vec<Ident>>,
    var_blocks: Vec<VarBlock>,
    methods: Vec<Method>,
    body: Body,
    l: usize,
    r: usize,
) -> Pou {
    let mut pou = crate::syntax::construct::pou(
        st,
        PouKind::FunctionBlock,
        name,
        None,
        var_blocks,
        body,
        l,
        r,
    );
    pou.oop = Some(Box::new(PouOop {
        mods: Modifiers::from_words(&mods),
        extends,
        implements: implements.unwrap_or_default(),
        methods: crate::syntax::oop_property::expand(st, methods, false),
        ..PouOop::default()
    }));
    pou
}

/// A method (or an interface's method prototype).
#[allow(clippy::too_many_arguments)]
pub fn method(
    st: &State,
    mods: Vec<Modifier>,
    name: Ident,
    return_type: Option<TypeSpec>,
    var_blocks: Vec<VarBlock>,
    body: Body,
    l: usize,
    r: usize,
) -> Method {
    Method {
        name,
        mods: Modifiers::from_words(&mods),
        return_type,
        var_blocks,
        body,
        span: st.span(l, r),
        property: None,
        call_after_init: crate::syntax::qualified_only::before_type(
            st.text(),
            l,
            crate::syntax::qualified_only::is_call_after_init,
        ),
        no_check: crate::syntax::qualified_only::before_type(
            st.text(),
            l,
            crate::syntax::qualified_only::is_no_check,
        ),
    }
}

/// An interface.
pub fn interface(
    st: &State,
    name: Ident,
    extends: Vec<Ident>,
    methods: Vec<Method>,
    l: usize,
    r: usize,
) -> Interface {
    Interface {
        name,
        extends,
        methods: crate::syntax::oop_property::expand(st, methods, true),
        span: st.span(l, r),
    }
}

/// A METHOD outside any FUNCTION_BLOCK (E110: plcrun has no CLASS or
/// separate method objects).
pub fn stray_method(st: &State, m: &Method) {
    if m.property.is_some() {
        st.error(
            "E110",
            m.span,
            format!(
                "a PROPERTY outside a FUNCTION_BLOCK, PROGRAM, CLASS or INTERFACE is not supported by plcrun: declare `{}` in one",
                m.name.name
            ),
        );
        return;
    }
    st.error(
        "E110",
        m.span,
        format!(
            "a METHOD outside a FUNCTION_BLOCK or PROGRAM is not supported by plcrun: declare `{}` between the POU's variables and its body",
            m.name.name
        ),
    );
}

/// `THIS^` or `SUPER^` as an expression.
pub fn root(st: &State, which: &str, l: usize, r: usize) -> Expr {
    let span = st.span(l, r);
    Expr {
        kind: ExprKind::Name(Ident {
            name: which.to_string(),
            span,
        }),
        span,
    }
}
