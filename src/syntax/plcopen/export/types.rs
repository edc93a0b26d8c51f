//! Export of data types, variable declarations and initial values.

use super::writer::Writer;
use super::{ExportError, Exporter};
use crate::syntax::ast::{Initializer, TypeDecl, TypeSpec, VarDecl};

/// Type names that are TC6 elementary type elements, with the element
/// each is written as.
fn elementary(name: &str) -> Option<&'static str> {
    Some(match name.to_ascii_uppercase().as_str() {
        "BOOL" => "BOOL",
        "BYTE" => "BYTE",
        "WORD" => "WORD",
        "DWORD" => "DWORD",
        "LWORD" => "LWORD",
        "SINT" => "SINT",
        "INT" => "INT",
        "DINT" => "DINT",
        "LINT" => "LINT",
        "USINT" => "USINT",
        "UINT" => "UINT",
        "UDINT" => "UDINT",
        "ULINT" => "ULINT",
        "REAL" => "REAL",
        "LREAL" => "LREAL",
        "TIME" => "TIME",
        "DATE" => "DATE",
        "DT" | "DATE_AND_TIME" => "DT",
        "TOD" | "TIME_OF_DAY" => "TOD",
        "LTIME" => "LTIME",
        "LDATE" => "LDATE",
        "LTOD" | "LTIME_OF_DAY" => "LTOD",
        "LDT" | "LDATE_AND_TIME" => "LDT",
        "CHAR" => "CHAR",
        "WCHAR" => "WCHAR",
        _ => return None,
    })
}

impl Exporter<'_> {
    /// `<dataType name><baseType/><initialValue/></dataType>`.
    pub(super) fn data_type(&self, w: &mut Writer, d: &TypeDecl) -> Result<(), ExportError> {
        w.open("dataType", &[("name", &d.name.name)]);
        w.open("baseType", &[]);
        self.type_spec(w, &d.ty)?;
        w.close("baseType");
        if let Some(init) = &d.init {
            self.initial_value(w, init)?;
        }
        w.close("dataType");
        Ok(())
    }

    /// One type element.
    pub(super) fn type_spec(&self, w: &mut Writer, ty: &TypeSpec) -> Result<(), ExportError> {
        match ty {
            TypeSpec::Named(id) => match elementary(&id.name) {
                Some(el) => w.empty(el, &[]),
                None => w.empty("derived", &[("name", &id.name)]),
            },
            TypeSpec::String { wide, len, .. } => {
                let el = if *wide { "wstring" } else { "string" };
                match len {
                    Some(l) => w.empty(el, &[("length", &self.value_text(l.span))]),
                    None => w.empty(el, &[]),
                }
            }
            TypeSpec::Array { ranges, elem, .. } => {
                w.open("array", &[]);
                for (lo, hi) in ranges {
                    w.empty(
                        "dimension",
                        &[
                            ("lower", &self.value_text(lo.span)),
                            ("upper", &self.value_text(hi.span)),
                        ],
                    );
                }
                w.open("baseType", &[]);
                self.type_spec(w, elem)?;
                w.close("baseType");
                w.close("array");
            }
            TypeSpec::OpenArray { rank, elem, .. } => {
                // Read back by the importer as `ARRAY[*, ...]`.
                w.open("array", &[]);
                for _ in 0..*rank {
                    w.empty("dimension", &[("lower", "*"), ("upper", "*")]);
                }
                w.open("baseType", &[]);
                self.type_spec(w, elem)?;
                w.close("baseType");
                w.close("array");
            }
            TypeSpec::Subrange { base, lo, hi, .. } => {
                let unsigned = base.name.to_ascii_uppercase().starts_with('U');
                let el = if unsigned {
                    "subrangeUnsigned"
                } else {
                    "subrangeSigned"
                };
                w.open(el, &[]);
                w.empty(
                    "range",
                    &[
                        ("lower", &self.value_text(lo.span)),
                        ("upper", &self.value_text(hi.span)),
                    ],
                );
                w.open("baseType", &[]);
                self.type_spec(w, &TypeSpec::Named(base.clone()))?;
                w.close("baseType");
                w.close(el);
            }
            TypeSpec::Enum { base, values, .. } => {
                w.open("enum", &[]);
                w.open("values", &[]);
                for (name, value) in values {
                    match value {
                        Some(v) => w.empty(
                            "value",
                            &[("name", &name.name), ("value", &self.value_text(v.span))],
                        ),
                        None => w.empty("value", &[("name", &name.name)]),
                    }
                }
                w.close("values");
                if let Some(b) = base {
                    w.open("baseType", &[]);
                    self.type_spec(w, &TypeSpec::Named(b.clone()))?;
                    w.close("baseType");
                }
                w.close("enum");
            }
            TypeSpec::Struct {
                extends: Some(base),
                ..
            } => {
                // TC6 XML has no structure inheritance.
                return Err(self.refuse(
                    format!("a structure extending another (`EXTENDS {}`)", base.name),
                    base.span,
                ));
            }
            TypeSpec::Struct {
                union: true, span, ..
            } => {
                // TC6 XML has no union.
                return Err(self.refuse("a UNION".to_string(), *span));
            }
            TypeSpec::Struct { fields, .. } => {
                w.open("struct", &[]);
                for f in fields {
                    self.var_decl(w, f)?;
                }
                w.close("struct");
            }
            TypeSpec::Ref { target, .. } => {
                w.open("pointer", &[]);
                w.open("baseType", &[]);
                self.type_spec(w, target)?;
                w.close("baseType");
                w.close("pointer");
            }
        }
        Ok(())
    }

    /// `a, b AT %IX0.0 : T := v;` as one `<variable>` per name.
    pub(super) fn var_decl(&self, w: &mut Writer, decl: &VarDecl) -> Result<(), ExportError> {
        for name in &decl.names {
            let mut attrs = vec![("name", name.name.as_str())];
            if let Some(at) = &decl.location {
                attrs.push(("address", at.text.as_str()));
            }
            w.open("variable", &attrs);
            w.open("type", &[]);
            self.type_spec(w, &decl.ty)?;
            w.close("type");
            if let Some(init) = &decl.init {
                self.initial_value(w, init)?;
            }
            w.close("variable");
        }
        Ok(())
    }

    /// `<initialValue>`.
    fn initial_value(&self, w: &mut Writer, init: &Initializer) -> Result<(), ExportError> {
        w.open("initialValue", &[]);
        self.value(w, init)?;
        w.close("initialValue");
        Ok(())
    }

    /// `simpleValue`, `arrayValue` or `structValue`.
    fn value(&self, w: &mut Writer, init: &Initializer) -> Result<(), ExportError> {
        match init {
            Initializer::Expr(e) => w.empty("simpleValue", &[("value", &self.value_text(e.span))]),
            Initializer::Array(elems, _) => {
                w.open("arrayValue", &[]);
                for el in elems {
                    let Some(value) = &el.value else {
                        return Err(
                            self.refuse("an array initializer `n()` (default values)", el.span)
                        );
                    };
                    match &el.repeat {
                        Some(n) => {
                            w.open("value", &[("repetitionValue", &self.value_text(n.span))])
                        }
                        None => w.open("value", &[]),
                    }
                    self.value(w, value)?;
                    w.close("value");
                }
                w.close("arrayValue");
            }
            Initializer::Struct(members, _) => {
                w.open("structValue", &[]);
                for (name, value) in members {
                    w.open("value", &[("member", &name.name)]);
                    self.value(w, value)?;
                    w.close("value");
                }
                w.close("structValue");
            }
        }
        Ok(())
    }
}
