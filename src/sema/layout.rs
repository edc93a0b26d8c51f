//! Layout of POU instances in the declaration phase: every variable gets
//! its storage (frame slot, absolute address or VAR_IN_OUT pointer), and
//! the POU its code block and instance type.

use super::decl_consts::init_const;
use super::declare::{Declarer, normalize_address};
use super::model::{LayoutState, Storage, VarInfo};
use crate::ir::types::{Member, MemberKind, TypeDef, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Item, PouKind, VarKind};
use indexmap::IndexMap;

fn member_kind(k: VarKind) -> MemberKind {
    match k {
        VarKind::Local | VarKind::Global => MemberKind::Local,
        VarKind::Input => MemberKind::Input,
        VarKind::Output => MemberKind::Output,
        VarKind::InOut => MemberKind::InOut,
        VarKind::External => MemberKind::External,
        VarKind::Temp => MemberKind::Temp,
    }
}

impl Declarer<'_> {
    /// `offset + size`, reporting E206 (once per call site) when an
    /// instance or structure would exceed [`super::MAX_FRAME_SLOTS`].
    pub(super) fn grow(&mut self, offset: u32, size: u32, span: Span) -> u32 {
        match offset.checked_add(size) {
            Some(end) if end <= super::MAX_FRAME_SLOTS => end,
            _ => {
                self.diags.error(
                    "E206",
                    span,
                    format!(
                        "this declaration makes the POU or structure larger than {} Mi slots",
                        super::MAX_FRAME_SLOTS >> 20
                    ),
                );
                offset
            }
        }
    }

    /// Lays out the variables of POU `p` (idempotent).
    pub(super) fn layout_pou(&mut self, p: usize) {
        match self.pou_state[p] {
            LayoutState::Done => return,
            LayoutState::InProgress => {
                let span = self.model.pous[p].span;
                self.diags.error(
                    "E204",
                    span,
                    format!(
                        "`{}` contains an instance of itself (directly or through another block)",
                        self.model.pous[p].name
                    ),
                );
                return;
            }
            LayoutState::Pending => {}
        }
        self.pou_state[p] = LayoutState::InProgress;
        let (u, i) = self.model.pous[p].ast;
        let Item::Pou(pou) = &self.units[u].items[i] else {
            return;
        };
        let kind = pou.kind;
        let mut vars: IndexMap<String, VarInfo> = IndexMap::new();
        let mut params = Vec::new();
        let mut offset = 0u32;
        let mut members = Vec::new();
        if kind == PouKind::Function {
            let ret = match &pou.return_type {
                Some(t) => self.resolve_type(t, None),
                None => TypeTable::void(),
            };
            self.model.pous[p].ret = ret;
            if ret != TypeTable::void() {
                if !self.types.get(ret).kind.is_value_type() {
                    self.diags.error(
                        "E209",
                        pou.name.span,
                        "a function cannot return a function block instance",
                    );
                }
                vars.insert(
                    pou.name.key(),
                    VarInfo {
                        name: pou.name.name.clone(),
                        ty: ret,
                        kind: MemberKind::Output,
                        storage: Storage::Frame(0),
                        constant: false,
                        value: None,
                        init: None,
                        location: None,
                        span: pou.name.span,
                    },
                );
                offset = self.types.size(ret);
            }
        }
        for block in &pou.var_blocks {
            if block.retain == Some(crate::syntax::ast::Retain::Retain) {
                self.diags.warning(
                    "W203",
                    block.span,
                    "RETAIN is accepted but has no effect: plcrun starts every run from the declared initial values",
                );
            }
            if block.kind == VarKind::Global {
                self.diags.error(
                    "E209",
                    block.span,
                    "VAR_GLOBAL is only allowed in a CONFIGURATION, a RESOURCE or at top level",
                );
                continue;
            }
            for decl in &block.decls {
                let ty = self.resolve_type(&decl.ty, Some(&vars));
                let tkind = self.types.get(ty).kind.clone();
                let is_fb = matches!(tkind, TypeKind::NativeFb(_) | TypeKind::Pou { .. });
                if matches!(tkind, TypeKind::Pou { program: true, .. }) {
                    self.diags.error(
                        "E209",
                        decl.ty.span(),
                        "a PROGRAM cannot be instantiated inside a POU",
                    );
                    continue;
                }
                if is_fb && kind == PouKind::Function && block.kind != VarKind::InOut {
                    self.diags.error(
                        "E209",
                        decl.ty.span(),
                        "a FUNCTION cannot hold function block instances (they have state)",
                    );
                    continue;
                }
                if ty == TypeTable::void() {
                    continue;
                }
                let init = decl
                    .init
                    .as_ref()
                    .and_then(|i| self.consts().resolve_init(i, ty, Some(&vars)));
                for name in &decl.names {
                    let key = name.key();
                    if vars.contains_key(&key) {
                        self.diags.error(
                            "E202",
                            name.span,
                            format!("`{}` is declared twice in `{}`", name.name, pou.name.name),
                        );
                        continue;
                    }
                    let mkind = member_kind(block.kind);
                    let (storage, location) = if let Some(a) = &decl.location {
                        if kind != PouKind::Program {
                            self.diags.error(
                                "E207",
                                a.span,
                                "located variables (AT %...) are only allowed in PROGRAMs and globals",
                            );
                            continue;
                        }
                        match self.out.located_slot(&self.types, self.diags, a, ty) {
                            Some(addr) => (Storage::Abs(addr), Some(normalize_address(a))),
                            None => continue,
                        }
                    } else if block.kind == VarKind::External {
                        match self.model.globals.get(&key) {
                            Some(g) => {
                                if g.ty != ty && ty != TypeTable::error() {
                                    self.diags.error(
                                        "E301",
                                        name.span,
                                        format!(
                                            "VAR_EXTERNAL `{}` is declared {} but the global is {}",
                                            name.name,
                                            self.types.name(ty),
                                            self.types.name(g.ty)
                                        ),
                                    );
                                }
                                if g.constant && !block.constant {
                                    self.diags.error(
                                        "E401",
                                        name.span,
                                        format!(
                                            "global `{}` is CONSTANT: declare it in VAR_EXTERNAL CONSTANT",
                                            name.name
                                        ),
                                    );
                                }
                                (g.storage, g.location.clone())
                            }
                            None => {
                                self.diags.error(
                                    "E201",
                                    name.span,
                                    format!(
                                        "no VAR_GLOBAL named `{}` for this VAR_EXTERNAL",
                                        name.name
                                    ),
                                );
                                continue;
                            }
                        }
                    } else if block.kind == VarKind::InOut {
                        let s = Storage::Ref(offset);
                        offset += 1;
                        (s, None)
                    } else {
                        let s = Storage::Frame(offset);
                        offset = self.grow(offset, self.types.size(ty), name.span);
                        (s, None)
                    };
                    let value = if block.constant {
                        init.as_ref().and_then(init_const)
                    } else {
                        None
                    };
                    if block.constant
                        && value.is_none()
                        && block.kind != VarKind::External
                        && !self.is_aggregate(ty)
                    {
                        self.diags.error(
                            "E205",
                            name.span,
                            format!("constant `{}` needs a constant initial value", name.name),
                        );
                    }
                    let value = if block.kind == VarKind::External {
                        self.model.globals.get(&key).and_then(|g| g.value.clone())
                    } else {
                        value
                    };
                    if matches!(
                        block.kind,
                        VarKind::Input | VarKind::Output | VarKind::InOut
                    ) {
                        params.push(key.clone());
                    }
                    if let Storage::Frame(o) | Storage::Ref(o) = storage {
                        members.push(Member {
                            name: name.name.clone(),
                            ty,
                            offset: o,
                            kind: mkind,
                            constant: block.constant,
                        });
                    }
                    vars.insert(
                        key,
                        VarInfo {
                            name: name.name.clone(),
                            ty,
                            kind: mkind,
                            storage,
                            constant: block.constant,
                            value,
                            init: init.clone(),
                            location,
                            span: name.span,
                        },
                    );
                }
            }
        }
        if let crate::syntax::ast::Body::Sfc(elems) = &pou.body {
            self.layout_chart(pou, elems, &mut vars, &mut members, &mut offset);
        }
        let code = self.out.codes.len() as u32;
        self.out.codes.push(crate::ir::image::CodeBlock {
            name: pou.name.name.clone(),
            kind: match kind {
                PouKind::Program => crate::ir::image::CodeKind::Program,
                PouKind::FunctionBlock => crate::ir::image::CodeKind::FunctionBlock,
                PouKind::Function => crate::ir::image::CodeKind::Function,
            },
            ops: Vec::new(),
            spans: Vec::new(),
            entry_init: Vec::new(),
            entry_strings: Vec::new(),
            frame: 0,
            frame_size: offset,
        });
        let ty = self.types.add(TypeDef {
            name: pou.name.name.clone(),
            kind: TypeKind::Pou {
                code,
                members,
                program: kind == PouKind::Program,
            },
            size: offset,
        });
        let info = &mut self.model.pous[p];
        info.vars = vars;
        info.params = params;
        info.code = code;
        info.vars_size = offset;
        info.ty = ty;
        self.pou_state[p] = LayoutState::Done;
    }
}
