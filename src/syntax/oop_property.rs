//! `PROPERTY` in function blocks, classes and interfaces (CODESYS 3 /
//! TwinCAT 3; not part of IEC 61131-3 edition 3):
//!
//! ```text
//! PROPERTY PUBLIC Speed : REAL
//!     GET  Speed := rpm * 0.1;  END_GET
//!     SET  rpm := Speed * 10.0; END_SET
//! END_PROPERTY
//! ```
//!
//! A property is its accessors, and the accessors are methods: GET is a
//! method `Speed.GET : REAL` whose result is written through the name
//! `Speed`, SET a method `Speed.SET` with one input named `Speed`. The
//! names hold a dot, which no identifier can spell, so they never clash
//! with a user's method. [`expand`] puts them in place of the property,
//! and the method machinery (overriding, FINAL, ABSTRACT, access checks,
//! interfaces, dispatch) then applies to them unchanged; reads and writes
//! of `inst.Speed` become calls of them in `src/sema/oop/property.rs`.
//!
//! `GET` and `SET` stay names everywhere else: the lexer makes identifiers
//! of them and [`accessor_words`] turns only the ones that open an
//! accessor into keywords.

use crate::source::Span;
use crate::syntax::ast::{Body, Ident, TypeSpec, VarBlock, VarDecl, VarKind};
use crate::syntax::construct::State;
use crate::syntax::lexer::Spanned;
use crate::syntax::oop::{Method, Modifier, Modifiers};
use crate::syntax::token::{Kw, Tok};

/// Suffix of the GET accessor's method name.
const GET: &str = ".GET";
/// Suffix of the SET accessor's method name.
const SET: &str = ".SET";

/// The method name of property `name`'s GET (`get`) or SET accessor.
pub fn accessor_name(name: &str, get: bool) -> String {
    format!("{name}{}", if get { GET } else { SET })
}

/// The property a method name is an accessor of, and whether it is GET.
pub fn property_of(method: &str) -> Option<(&str, bool)> {
    let upper = method
        .len()
        .checked_sub(4)
        .and_then(|at| method.get(at..))?;
    let base = &method[..method.len() - 4];
    if upper.eq_ignore_ascii_case(GET) {
        Some((base, true))
    } else if upper.eq_ignore_ascii_case(SET) {
        Some((base, false))
    } else {
        None
    }
}

/// One `GET ... END_GET` or `SET ... END_SET` as parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct Accessor {
    /// True for GET.
    pub get: bool,
    /// Modifiers written after `GET`/`SET` (they win over the property's).
    pub mods: Modifiers,
    /// Its own variable sections.
    pub var_blocks: Vec<VarBlock>,
    /// Its statements.
    pub body: Body,
    /// Span from `GET`/`SET` to `END_GET`/`END_SET`.
    pub span: Span,
}

/// An accessor.
pub fn accessor(
    st: &State,
    get: bool,
    mods: Vec<Modifier>,
    var_blocks: Vec<VarBlock>,
    body: Body,
    l: usize,
    r: usize,
) -> Accessor {
    Accessor {
        get,
        mods: Modifiers::from_words(&mods),
        var_blocks,
        body,
        span: st.span(l, r),
    }
}

/// A property, as a [`Method`] holding its accessors (see [`expand`]).
/// Two GETs or two SETs are E923.
#[allow(clippy::too_many_arguments)]
pub fn property(
    st: &State,
    mods: Vec<Modifier>,
    name: Ident,
    ty: TypeSpec,
    accessors: Vec<Accessor>,
    l: usize,
    r: usize,
) -> Method {
    let mods = Modifiers::from_words(&mods);
    let span = st.span(l, r);
    let mut methods: Vec<Method> = Vec::new();
    for a in accessors {
        if methods
            .iter()
            .any(|m| property_of(&m.name.name).is_some_and(|(_, g)| g == a.get))
        {
            st.error(
                "E923",
                a.span,
                format!(
                    "property `{}` has two {} accessors",
                    name.name,
                    if a.get { "GET" } else { "SET" }
                ),
            );
            continue;
        }
        methods.push(accessor_method(&name, &ty, mods, a));
    }
    Method {
        name,
        mods,
        return_type: Some(ty),
        var_blocks: Vec::new(),
        body: Body::St(Vec::new()),
        span,
        property: Some(methods),
        call_after_init: false,
        no_check: false,
    }
}

/// The method an accessor is.
fn accessor_method(name: &Ident, ty: &TypeSpec, prop: Modifiers, a: Accessor) -> Method {
    let mods = Modifiers {
        access: a.mods.access.or(prop.access),
        is_abstract: prop.is_abstract || a.mods.is_abstract,
        is_final: prop.is_final || a.mods.is_final,
    };
    let mut var_blocks = Vec::new();
    if !a.get {
        var_blocks.push(value_input(name, ty, a.span));
    }
    var_blocks.extend(a.var_blocks);
    Method {
        name: Ident {
            name: accessor_name(&name.name, a.get),
            span: name.span,
        },
        mods,
        return_type: a.get.then(|| ty.clone()),
        var_blocks,
        body: a.body,
        span: a.span,
        property: None,
        call_after_init: false,
        no_check: false,
    }
}

/// `VAR_INPUT name : ty; END_VAR`: the value a SET accessor receives.
fn value_input(name: &Ident, ty: &TypeSpec, span: Span) -> VarBlock {
    VarBlock {
        kind: VarKind::Input,
        constant: false,
        retain: None,
        decls: vec![VarDecl {
            names: vec![name.clone()],
            location: None,
            ty: ty.clone(),
            init: None,
            span: name.span,
            edge: None,
            init_args: None,
        }],
        span,
    }
}

/// Replaces each property by its accessors. In an interface
/// (`prototypes`) a property written without accessors declares both; in
/// an FB or class it has no code to run (E923).
pub fn expand(st: &State, methods: Vec<Method>, prototypes: bool) -> Vec<Method> {
    let mut out = Vec::with_capacity(methods.len());
    for mut m in methods {
        let Some(accessors) = m.property.take() else {
            out.push(m);
            continue;
        };
        if !accessors.is_empty() {
            out.extend(accessors);
            continue;
        }
        if !prototypes {
            st.error(
                "E923",
                m.name.span,
                format!(
                    "property `{}` has neither GET nor SET: give it at least one accessor",
                    m.name.name
                ),
            );
            continue;
        }
        let ty = m
            .return_type
            .clone()
            .unwrap_or(TypeSpec::Named(m.name.clone()));
        for get in [true, false] {
            let a = Accessor {
                get,
                mods: Modifiers::default(),
                var_blocks: Vec::new(),
                body: Body::St(Vec::new()),
                span: m.span,
            };
            out.push(accessor_method(&m.name, &ty, m.mods, a));
        }
    }
    out
}

/// Turns the `GET`/`SET` identifiers that open an accessor into keywords:
/// those inside `PROPERTY ... END_PROPERTY`, outside any accessor, and not
/// the property's own name.
pub fn accessor_words(mut tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut in_property = false;
    let mut in_accessor = false;
    let mut prev: Option<Tok> = None;
    for t in tokens.iter_mut() {
        match &t.1 {
            Tok::Eol => continue,
            Tok::Kw(Kw::Property) => (in_property, in_accessor) = (true, false),
            Tok::Kw(
                Kw::EndProperty
                | Kw::EndFunctionBlock
                | Kw::EndClass
                | Kw::EndInterface
                | Kw::Method
                | Kw::Program
                | Kw::Function
                | Kw::FunctionBlock,
            ) => (in_property, in_accessor) = (false, false),
            Tok::Kw(Kw::EndGet | Kw::EndSet) => in_accessor = false,
            Tok::Ident(w) if in_property && !in_accessor && !after_header_word(prev.as_ref()) => {
                let kw = if w.eq_ignore_ascii_case("GET") {
                    Some(Kw::Get)
                } else if w.eq_ignore_ascii_case("SET") {
                    Some(Kw::Set)
                } else {
                    None
                };
                if let Some(kw) = kw {
                    t.1 = Tok::Kw(kw);
                    in_accessor = true;
                }
            }
            _ => {}
        }
        prev = Some(t.1.clone());
    }
    tokens
}

/// True after a word that a name follows in a property's header (the
/// property may be called `Get`).
fn after_header_word(prev: Option<&Tok>) -> bool {
    matches!(
        prev,
        Some(
            Tok::Kw(
                Kw::Property
                    | Kw::Public
                    | Kw::Private
                    | Kw::Protected
                    | Kw::Internal
                    | Kw::Abstract
                    | Kw::Final
            ) | Tok::Colon
        )
    )
}
