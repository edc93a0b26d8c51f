//! Signature help: inside a call's parentheses, the callee's parameters
//! and which one the cursor is on.

use super::Analysis;
use super::std_functions::std_function;
use super::symbol::{SymbolKind, VarSection};
use super::text_context;
use crate::source::FileId;

/// A callee's parameters, with the one being written.
#[derive(Debug, Clone, PartialEq)]
pub struct Signature {
    /// `TON(IN : BOOL, PT : TIME) => (Q : BOOL, ET : TIME)`.
    pub label: String,
    /// Its parameters in order: inputs, in-outs, then outputs.
    pub params: Vec<SignatureParam>,
    /// The parameter the cursor is on, if it can be told.
    pub active: Option<usize>,
    /// The callee's documentation comment or summary.
    pub documentation: Option<String>,
}

/// One parameter of a [`Signature`].
#[derive(Debug, Clone, PartialEq)]
pub struct SignatureParam {
    /// `IN : BOOL`.
    pub label: String,
    /// Its documentation comment.
    pub documentation: Option<String>,
}

impl Analysis {
    /// The signature of the call around byte `offset` of `file`.
    pub fn signature_help(&self, file: FileId, offset: u32) -> Option<Signature> {
        let site = text_context::call_site(self.text(file), offset as usize)?;
        let scope = self.scope_at(file, offset);
        let Some(owner) = self.callee_of(&scope, &site.callee) else {
            let name = &site.callee.last()?.name;
            let f = std_function(name)?;
            let params: Vec<SignatureParam> = f
                .inputs
                .iter()
                .map(|(n, t)| SignatureParam {
                    label: format!("{n} : {t}"),
                    documentation: None,
                })
                .collect();
            let by_name = site
                .named
                .as_ref()
                .and_then(|n| f.inputs.iter().position(|(p, _)| p.eq_ignore_ascii_case(n)));
            let last = params.len().saturating_sub(1);
            let active = by_name.or(Some(if f.extensible {
                site.argument.min(last)
            } else {
                site.argument
            }));
            return Some(Signature {
                label: f.signature(),
                params,
                active: active.filter(|&a| a <= last),
                documentation: Some(f.summary.to_string()),
            });
        };
        let mut members: Vec<_> = self
            .table
            .members(owner)
            .into_iter()
            .filter_map(|m| match self.symbol(m).kind {
                SymbolKind::Variable(v) | SymbolKind::StandardPin(v) if v.is_interface() => {
                    Some((m, v))
                }
                _ => None,
            })
            .collect();
        members.sort_by_key(|&(_, v)| match v {
            VarSection::Input => 0,
            VarSection::InOut => 1,
            _ => 2,
        });
        let params: Vec<SignatureParam> = members
            .iter()
            .map(|&(m, _)| {
                let s = self.symbol(m);
                SignatureParam {
                    label: format!("{} : {}", s.name, s.type_text.as_deref().unwrap_or("?")),
                    documentation: self.documentation(s),
                }
            })
            .collect();
        let active = match &site.named {
            Some(n) => members
                .iter()
                .position(|&(m, _)| self.symbol(m).name.eq_ignore_ascii_case(n)),
            None => (site.argument < params.len()).then_some(site.argument),
        };
        Some(Signature {
            label: self.declaration_line(owner),
            params,
            active,
            documentation: self.documentation(self.symbol(owner)),
        })
    }
}
