//! `VAR_CONFIG`: per-instance addresses and initial values, given by the
//! configuration for variables deep inside its program instances
//! (`Res.Prog.fb.x AT %QX1.0 : BOOL := TRUE;`), and the check that every
//! incomplete address (`AT %I*`) of a running instance was completed.
//!
//! A completed variable stays in its instance's memory; it becomes a
//! located root variable at that slot, so the process image exchanges it
//! like any `AT %QX1.0` variable.

use super::Linker;
use super::auto_address::Unplaced;
use crate::ir::image::{ProgramInstance, RootVar};
use crate::ir::type_table::{TypeId, TypeKind};
use crate::sema::declare::normalize_address;
use crate::sema::incomplete_address::{address_fits, address_leaves, is_incomplete};
use crate::sema::model::{Storage, VarInfo};
use crate::source::Span;
use crate::syntax::ast::{
    Area, ConfigInit, Configuration, Ident, Item, Resource, TypeSpec, VarDecl,
};
use std::collections::HashSet;

/// A VAR_CONFIG path that names nothing.
const UNKNOWN_PATH: &str = "E711";
/// A VAR_CONFIG type that is not the variable's.
const WRONG_TYPE: &str = "E712";
/// A VAR_CONFIG address that cannot complete the declaration.
const WRONG_ADDRESS: &str = "E713";
/// The same variable configured twice.
const TWICE: &str = "E714";

/// The variable a VAR_CONFIG path leads to.
struct Target {
    /// The path without the resource, as variables are named (`P.fb.x`).
    name: String,
    /// Its declaration.
    var: VarInfo,
    /// Its absolute slot.
    addr: u32,
}

impl Linker<'_> {
    /// Applies the running configuration's VAR_CONFIG to `instances` and
    /// gives every incomplete address left an address of its own after
    /// those of `known` and the configured ones (auto_address.rs); returns
    /// the completed and placed variables as located root variables.
    pub(super) fn apply_var_config(
        &mut self,
        running_config: bool,
        instances: &[ProgramInstance],
        known: &[RootVar],
        addressing: crate::address::Addressing,
    ) -> Vec<RootVar> {
        let units = self.units;
        let config = units
            .iter()
            .flat_map(|u| u.items.iter())
            .find_map(|i| match i {
                Item::Configuration(c) if running_config => Some(c),
                _ => None,
            });
        let mut completed = HashSet::new();
        let mut roots = Vec::new();
        if let Some(cfg) = config {
            for line in &cfg.var_config {
                let Some(target) = self.config_target(cfg, line, instances) else {
                    continue;
                };
                if let Some(root) = self.configure(line, &target, &mut completed) {
                    roots.push(root);
                }
            }
        }
        let mut unplaced = Vec::new();
        for inst in instances {
            if let Some(p) = self.model.pous.iter().position(|x| x.code == inst.code) {
                self.collect_uncompleted(p, inst.base, &inst.name, &completed, 0, &mut unplaced);
            }
        }
        let mut located: Vec<RootVar> = known.to_vec();
        located.extend(roots.iter().cloned());
        roots.extend(self.place_automatically(unplaced, &located, addressing));
        roots
    }

    /// Follows `line`'s path: resource (may be left out when there is one),
    /// program instance, FB instances, variable.
    fn config_target(
        &mut self,
        cfg: &Configuration,
        line: &ConfigInit,
        instances: &[ProgramInstance],
    ) -> Option<Target> {
        let model = self.model;
        let (res, rest) = self.config_resource(cfg, &line.path)?;
        // Subscripts by position in `rest` (none on the resource or the
        // program instance).
        let skipped = line.path.len() - rest.len();
        let subscripts = |i: usize| {
            line.subscripts
                .iter()
                .find(|(at, _)| *at == i + skipped)
                .map(|(_, ix)| ix.as_slice())
        };
        if let Some((at, ix)) = line.subscripts.iter().find(|(at, _)| *at <= skipped) {
            let span = ix.first().map_or(line.span, |e| e.span);
            let what = line.path.get(*at).map_or("", |i| i.name.as_str());
            self.diags.error(
                UNKNOWN_PATH,
                span,
                format!("`{what}` is a resource or program instance: it has no elements"),
            );
            return None;
        }
        let [prog, inner @ .., last] = rest else {
            let span = line.path.last().map_or(line.span, |i| i.span);
            self.diags.error(
                UNKNOWN_PATH,
                span,
                "a VAR_CONFIG path names a program instance and a variable inside it",
            );
            return None;
        };
        if let Some(e) = line.subscripts.first().and_then(|(_, ix)| ix.first()) {
            self.warn_config_elements(e.span);
        }
        let declared = res.programs.iter().any(|p| p.name.key() == prog.key());
        let inst = instances
            .iter()
            .find(|i| i.name.eq_ignore_ascii_case(&prog.name));
        let (Some(inst), true) = (inst, declared) else {
            self.diags.error(
                UNKNOWN_PATH,
                prog.span,
                format!(
                    "no program instance `{}` in RESOURCE `{}`",
                    prog.name, res.name.name
                ),
            );
            return None;
        };
        let mut p = model.pous.iter().position(|x| x.code == inst.code)?;
        let mut addr = inst.base;
        let mut name = inst.name.clone();
        for (i, seg) in inner.iter().enumerate() {
            let var = model.pous[p].vars.get(&seg.key());
            let mut seg_name = seg.name.clone();
            let var = match (var, subscripts(i + 1)) {
                (Some(v), Some(ix)) => {
                    let (off, ty, text) = self.config_element(v.ty, ix, &seg.name, seg.span)?;
                    seg_name = text;
                    match v.storage {
                        Storage::Frame(o) => Some((o + off, ty)),
                        _ => None,
                    }
                }
                (Some(v), None) => match v.storage {
                    Storage::Frame(o) => Some((o, v.ty)),
                    _ => None,
                },
                (None, _) => None,
            };
            let next = var.and_then(|(o, ty)| self.fb_pou(ty).map(|q| (o, q)));
            let Some((offset, q)) = next else {
                self.diags.error(
                    UNKNOWN_PATH,
                    seg.span,
                    format!(
                        "`{}` is not a function block instance in `{name}`",
                        seg.name
                    ),
                );
                return None;
            };
            addr += offset;
            p = q;
            name = format!("{name}.{seg_name}");
        }
        let var = model.pous[p].vars.get(&last.key());
        let Some((var, Storage::Frame(offset))) = var.map(|v| (v, v.storage)) else {
            self.diags.error(
                UNKNOWN_PATH,
                last.span,
                format!(
                    "no variable `{}` in `{name}` that VAR_CONFIG can configure",
                    last.name
                ),
            );
            return None;
        };
        let Some(ix) = subscripts(rest.len() - 1) else {
            return Some(Target {
                name: format!("{name}.{}", var.name),
                var: var.clone(),
                addr: addr + offset,
            });
        };
        let (off, ty, text) = self.config_element(var.ty, ix, &var.name, last.span)?;
        Some(Target {
            name: format!("{name}.{text}"),
            var: VarInfo { ty, ..var.clone() },
            addr: addr + offset + off,
        })
    }

    /// The resource a path starts with, and the rest of the path; with a
    /// single resource its name may be left out.
    fn config_resource<'c, 'p>(
        &mut self,
        cfg: &'c Configuration,
        path: &'p [Ident],
    ) -> Option<(&'c Resource, &'p [Ident])> {
        let first = path.first()?;
        if let Some(res) = cfg.resources.iter().find(|r| r.name.key() == first.key()) {
            return Some((res, &path[1..]));
        }
        match cfg.resources.as_slice() {
            [only] => Some((only, path)),
            _ => {
                self.diags.error(
                    UNKNOWN_PATH,
                    first.span,
                    format!(
                        "no RESOURCE `{}` in CONFIGURATION `{}`",
                        first.name, cfg.name.name
                    ),
                );
                None
            }
        }
    }

    /// The POU of a function block instance type.
    pub(super) fn fb_pou(&self, ty: TypeId) -> Option<usize> {
        match &self.types.get(ty).kind {
            TypeKind::Pou {
                code,
                program: false,
                ..
            } => self.model.pous.iter().position(|x| x.code == *code),
            _ => None,
        }
    }

    /// Checks one line against its target and applies it: the address
    /// completing the declaration, the initial value.
    fn configure(
        &mut self,
        line: &ConfigInit,
        target: &Target,
        completed: &mut HashSet<u32>,
    ) -> Option<RootVar> {
        let var = &target.var;
        if !self.same_type(&line.ty, var.ty) {
            self.diags.error(
                WRONG_TYPE,
                line.ty.span(),
                format!(
                    "`{}` is declared {}, not {}",
                    target.name,
                    self.types.name(var.ty),
                    type_text(&line.ty)
                ),
            );
            return None;
        }
        if !completed.insert(target.addr) {
            self.diags.error(
                TWICE,
                line.span,
                format!("`{}` is configured twice", target.name),
            );
            return None;
        }
        let location = match &line.location {
            Some(a) => Some(self.completing_address(a, target)?),
            None => None,
        };
        if location.is_none() {
            // Only an initial value: the variable is not completed by it.
            completed.remove(&target.addr);
        }
        if let Some(init) = &line.init {
            let init = self.consts().resolve_init(init, var.ty, None)?;
            self.instantiate(target.addr, var.ty, Some(&init));
        }
        Some(RootVar {
            name: target.name.clone(),
            ty: var.ty,
            addr: target.addr,
            kind: var.kind,
            location: Some(location?),
            constant: false,
        })
    }

    /// The normalised text of `a` when it completes `target`'s incomplete
    /// address (same area, a size that holds the type), else E713.
    fn completing_address(
        &mut self,
        a: &crate::syntax::ast::DirectAddress,
        target: &Target,
    ) -> Option<String> {
        let declared = target.var.location.as_deref().filter(|l| is_incomplete(l));
        let area = match a.area {
            Area::Input => "%I",
            Area::Output => "%Q",
            Area::Memory => "%M",
        };
        let problem = match declared {
            None => Some(format!(
                "`{}` has no incomplete address (AT %I*, %Q*, %M*) to complete",
                target.name
            )),
            Some(_) if a.fields.is_empty() => {
                Some("VAR_CONFIG must give a complete address".to_string())
            }
            Some(d) if !d.starts_with(area) => Some(format!(
                "`{}` is declared AT {d}: `{}` is in another area",
                target.name, a.text
            )),
            Some(d) if d.len() == 4 && !normalize_address(a).starts_with(&d[..3]) => Some(format!(
                "`{}` is declared AT {d}: `{}` has another size",
                target.name, a.text
            )),
            Some(_) if !address_fits(a.size, self.types.scalar(target.var.ty)) => Some(format!(
                "`{}` cannot hold a {}: the address size does not match the type",
                a.text,
                self.types.name(target.var.ty)
            )),
            Some(_) => None,
        };
        match problem {
            Some(m) => {
                self.diags.error(WRONG_ADDRESS, a.span, m);
                None
            }
            None => Some(normalize_address(a)),
        }
    }

    /// True when the type written in VAR_CONFIG is the variable's type
    /// (by name: elementary, STRING or a declared type).
    fn same_type(&self, written: &TypeSpec, ty: TypeId) -> bool {
        let declared = self.types.name(ty);
        match written {
            TypeSpec::Named(id) => id.name.eq_ignore_ascii_case(declared),
            TypeSpec::String {
                wide, len: None, ..
            } => declared.eq_ignore_ascii_case(if *wide { "WSTRING" } else { "STRING" }),
            _ => false,
        }
    }

    /// Collects into `out` every incomplete address in the instance of POU
    /// `p` at `base` (named `path`) and in the FB instances inside it that
    /// `completed` does not hold.
    pub(super) fn collect_uncompleted(
        &mut self,
        p: usize,
        base: u32,
        path: &str,
        completed: &HashSet<u32>,
        depth: usize,
        out: &mut Vec<Unplaced>,
    ) {
        // Instances nest as deep as types do; E122 bounds that elsewhere.
        if depth > 64 {
            return;
        }
        let model = self.model;
        for var in model.pous[p].vars.values() {
            let Storage::Frame(offset) = var.storage else {
                continue;
            };
            let here = format!("{path}.{}", var.name);
            if let Some(l) = var.location.as_ref().filter(|l| is_incomplete(l)) {
                // The variable, or each element or field of it.
                let span = self.address_span(p, &var.name);
                let leaves = address_leaves(self.types, var.ty).unwrap_or_default();
                for leaf in leaves {
                    let slot = base + offset + leaf.offset;
                    if !completed.contains(&slot) {
                        out.push(Unplaced {
                            name: format!("{here}{}", leaf.path),
                            ty: leaf.ty,
                            kind: var.kind,
                            slot,
                            declared: l.clone(),
                            span,
                        });
                    }
                }
                continue;
            }
            if self.array_elements(var.ty).is_some() {
                self.collect_uncompleted_elements(var, base + offset, &here, completed, depth, out);
                continue;
            }
            if let (None, Some(q)) = (&var.location, self.fb_pou(var.ty)) {
                self.collect_uncompleted(q, base + offset, &here, completed, depth + 1, out)
            }
        }
    }

    /// Where the address of variable `name` of POU `p` is written.
    pub(super) fn address_span(&self, p: usize, name: &str) -> Span {
        let (u, i) = self.model.pous[p].ast;
        let Some(Item::Pou(pou)) = self.units.get(u).and_then(|u| u.items.get(i)) else {
            return Span::default();
        };
        let decls = pou.var_blocks.iter().flat_map(|b| b.decls.iter());
        let named = |d: &&VarDecl| d.names.iter().any(|n| n.name.eq_ignore_ascii_case(name));
        decls
            .filter(named)
            .find_map(|d| d.location.as_ref().map(|a| a.span))
            .unwrap_or(pou.name.span)
    }
}

/// A type as written, for messages.
fn type_text(ty: &TypeSpec) -> String {
    match ty {
        TypeSpec::Named(id) => id.name.clone(),
        TypeSpec::String { wide: true, .. } => "WSTRING".into(),
        TypeSpec::String { .. } => "STRING".into(),
        _ => "a type other than the declared one".into(),
    }
}
