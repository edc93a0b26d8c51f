//! Layout of POU instances in the declaration phase: every variable gets
//! its storage (frame slot, absolute address or VAR_IN_OUT pointer), and
//! the POU its code block and instance type.

use super::decl_consts::init_const;
use super::declare::{Declarer, normalize_address};
use super::model::{ConstInit, LayoutState, Storage, VarInfo};
use crate::ir::type_table::{
    Member, MemberKind, Retention, TypeDef, TypeId, TypeKind, TypeTable, open_array_layout,
};
use crate::source::Span;
use crate::syntax::ast::{Ident, Item, Pou, PouKind, Retain, VarBlock, VarDecl, VarKind};
use indexmap::IndexMap;

fn member_kind(k: VarKind) -> MemberKind {
    match k {
        // VAR_INST outside a METHOD was refused (E434).
        VarKind::Local | VarKind::Global | VarKind::Inst | VarKind::Stat => MemberKind::Local,
        VarKind::Input => MemberKind::Input,
        VarKind::Output => MemberKind::Output,
        VarKind::InOut => MemberKind::InOut,
        VarKind::External => MemberKind::External,
        VarKind::Temp => MemberKind::Temp,
    }
}

/// The retention a block's qualifier gives its variables.
pub(super) fn retention(block: &VarBlock) -> Retention {
    match block.retain {
        None => Retention::Inherit,
        Some(Retain::Retain) => Retention::Retain,
        Some(Retain::NonRetain) => Retention::NonRetain,
        Some(Retain::Persistent) => Retention::Persistent,
    }
}

/// A POU's frame while its declarations are laid out.
#[derive(Default)]
struct Frame {
    /// Variables by case-folded name, in declaration order.
    vars: IndexMap<String, VarInfo>,
    /// Keys of the call interface, in order.
    params: Vec<String>,
    /// Next free slot.
    offset: u32,
    /// Members of the instance type.
    members: Vec<Member>,
    /// Variables of the blocks laid out so far whose initial value an FB's
    /// or PROGRAM's later static variable may read (`nVal : INT :=
    /// LowerLimit;` with `LowerLimit` an input): what they hold when the
    /// instance starts.
    initialised: Vec<String>,
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
                let from = self.layout_path.iter().position(|&q| q == p).unwrap_or(0);
                let mut ring: Vec<&str> = self.layout_path[from..]
                    .iter()
                    .map(|&q| self.model.pous[q].name.as_str())
                    .collect();
                ring.push(&self.model.pous[p].name);
                let message = format!(
                    "`{}` contains an instance of itself (directly or through another block: {})",
                    self.model.pous[p].name,
                    ring.join(" contains ")
                );
                self.diags.error("E204", span, message);
                return;
            }
            LayoutState::Pending => {}
        }
        self.pou_state[p] = LayoutState::InProgress;
        let (u, i) = self.model.pous[p].ast;
        let Item::Pou(pou) = &self.units[u].items[i] else {
            return;
        };
        self.layout_path.push(p);
        let mut frame = Frame::default();
        if pou.kind == PouKind::Function {
            self.layout_result(p, pou, &mut frame);
        }
        for block in blocks_in_layout_order(&pou.var_blocks) {
            self.layout_block(pou, block, &mut frame);
        }
        if let crate::syntax::ast::Body::Sfc(elems) = &pou.body {
            self.layout_chart(
                pou,
                elems,
                &mut frame.vars,
                &mut frame.members,
                &mut frame.offset,
            );
        }
        self.finish_layout(p, pou, frame);
        self.layout_path.pop();
        self.pou_state[p] = LayoutState::Done;
    }

    /// A function's result: a variable named as the function, at slot 0.
    fn layout_result(&mut self, p: usize, pou: &Pou, frame: &mut Frame) {
        let ret = match &pou.return_type {
            Some(t) => self.resolve_type(t, None),
            None => TypeTable::void(),
        };
        if ret == TypeTable::void() {
            return;
        }
        // A refused result type still gives the function its result
        // variable (of the error type), so calls and the body check on.
        // A function may return a function block instance, as CODESYS
        // allows (a copy of it); not a program, and not a block whose own
        // code calls this function (its size is not known yet).
        let ret = match self.types.get(ret).kind {
            TypeKind::Pou { program: true, .. } => {
                self.diags.error(
                    "E209",
                    pou.name.span,
                    "a function cannot return a program instance",
                );
                TypeTable::error()
            }
            TypeKind::Pou { .. } if self.being_emitted(ret) => {
                self.diags.error(
                    "E204",
                    pou.name.span,
                    "this function returns a function block whose own code calls it, so its size is not known yet (a cycle plcrun cannot lay out)",
                );
                TypeTable::error()
            }
            _ => ret,
        };
        self.model.pous[p].ret = ret;
        frame.vars.insert(
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
            },
        );
        frame.offset = self.types.size(ret);
    }

    /// The declarations of one VAR... END_VAR block.
    fn layout_block(&mut self, pou: &Pou, block: &VarBlock, frame: &mut Frame) {
        self.check_retain(pou, block);
        if block.kind == VarKind::Inst {
            self.diags.error(
                "E434",
                block.span,
                format!(
                    "VAR_INST is allowed in a METHOD only: `{}` keeps its VAR variables from call to call, declare them there",
                    pou.name.name
                ),
            );
            return;
        }
        if block.kind == VarKind::Global {
            self.diags.error(
                "E209",
                block.span,
                "VAR_GLOBAL is only allowed in a CONFIGURATION, a RESOURCE or at top level",
            );
            return;
        }
        // A CONSTANT block's declarations in dependency order (E121 for a
        // cycle); any other block's as written.
        let (order, cycles) = super::const_order::dependency_order(block);
        for cycle in cycles {
            self.report_constant_cycle(block, &cycle);
        }
        // The names an initial value may read (decl_consts.rs, same_block);
        // not in parameter blocks, whose values come from the caller.
        let reads_earlier = !matches!(
            block.kind,
            VarKind::Input | VarKind::InOut | VarKind::External
        );
        // Variables of an FB's or PROGRAM's earlier blocks start with their
        // declared initial values, which its later static variables may
        // read; a FUNCTION's inputs and any VAR_TEMP change at each call.
        let instance = matches!(pou.kind, PouKind::FunctionBlock | PouKind::Program);
        let mut earlier = if instance && reads_earlier && block.kind != VarKind::Temp {
            frame.initialised.clone()
        } else {
            Vec::new()
        };
        let starts_set = instance
            && !block.constant
            && matches!(
                block.kind,
                VarKind::Input | VarKind::Output | VarKind::Local
            );
        for decl in order.iter().map(|&d| &block.decls[d]) {
            let computed = self.layout_decl(pou, block, decl, frame, &earlier);
            let names = decl.names.iter().map(|n| n.key());
            // A value computed at each call is no value a later initial
            // value could fold.
            if reads_earlier && !computed {
                earlier.extend(names.clone());
            }
            if starts_set {
                frame.initialised.extend(names);
            }
        }
    }

    /// One declaration (`a, b : T := init`): its type checked against the
    /// POU kind, then each name laid out. True when its initial value is
    /// computed by the body at each call (computed_inits.rs).
    fn layout_decl(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
        frame: &mut Frame,
        earlier: &[String],
    ) -> bool {
        let ty = self.decl_type(pou, block, decl, frame);
        if ty == TypeTable::void() {
            return false;
        }
        // `REF(x)` / `ADR(x)`: evaluated by the body (ref_inits.rs).
        let by_reference = self.defer_reference_init(pou, block, decl, ty, &mut frame.offset);
        let computed =
            !by_reference && self.defer_computed_init(pou, block, decl, ty, &frame.vars, earlier);
        let by_body = by_reference || computed;
        let init = decl.init.as_ref().filter(|_| !by_body).and_then(|i| {
            let mut consts = self.consts();
            consts.same_block = earlier;
            consts.resolve_init(i, ty, Some(&frame.vars))
        });
        let edge = self.edge_input_ok(pou, block, decl, ty);
        for name in &decl.names {
            let key = name.key();
            if frame.vars.contains_key(&key) {
                self.diags.error(
                    "E202",
                    name.span,
                    format!("`{}` is declared twice in `{}`", name.name, pou.name.name),
                );
                continue;
            }
            let Some((storage, location)) = self.var_storage(pou, block, decl, name, ty, frame)
            else {
                continue;
            };
            // An edge input: the body reads two hidden slots (edge_inputs.rs).
            let (storage, raw) = match storage {
                Storage::Frame(o) if edge => {
                    let seen = frame.offset;
                    frame.offset = self.grow(frame.offset, 2, name.span);
                    (Storage::Frame(seen), Some(o))
                }
                _ => (storage, None),
            };
            if let (Storage::Abs(a), Some(_), Retention::Retain | Retention::Persistent) =
                (storage, &decl.location, retention(block))
            {
                let persistent = retention(block) == Retention::Persistent;
                (self.model.retained_located).push((name.name.clone(), a, ty, persistent));
            }
            let var = self.declared_var(block, name, ty, storage, location, &init);
            if matches!(
                block.kind,
                VarKind::Input | VarKind::Output | VarKind::InOut
            ) {
                frame.params.push(key.clone());
            }
            if let Storage::Frame(o) | Storage::Ref(o) = storage {
                frame.members.push(Member {
                    name: name.name.clone(),
                    ty,
                    offset: raw.unwrap_or(o),
                    kind: var.kind,
                    constant: block.constant,
                    retain: retention(block),
                });
            }
            frame.vars.insert(key, var);
        }
        computed
    }

    /// The type of declaration `decl`: a VAR_IN_OUT of the block being
    /// laid out gets the id reserved for it (self_ref_types.rs); after
    /// E209 for an instance the POU cannot hold (a PROGRAM anywhere) or
    /// E204 for an instance of a block whose body is being emitted (its
    /// size is not final: the block's code calls this POU), the error
    /// type. The names are still declared with the error type, so a
    /// refused parameter keeps its place in the interface: calls bind
    /// their arguments as written and the body finds the name, with no
    /// error of their own.
    fn decl_type(&mut self, pou: &Pou, block: &VarBlock, decl: &VarDecl, frame: &Frame) -> TypeId {
        // A VAR_IN_OUT is a pointer slot: it may name the block being laid out.
        let own = match (&decl.ty, block.kind) {
            (crate::syntax::ast::TypeSpec::Named(id), VarKind::InOut) => {
                self.own_fb_type(&id.key())
            }
            _ => None,
        };
        let ty = own
            .or_else(|| self.open_array_param(block.kind, &decl.ty, Some(&frame.vars)))
            .or_else(|| self.any_param(pou, block, decl))
            .unwrap_or_else(|| self.resolve_type(&decl.ty, Some(&frame.vars)));
        let tkind = &self.types.get(ty).kind;
        let is_fb = matches!(tkind, TypeKind::NativeFb(_) | TypeKind::Pou { .. });
        let (code, why) = if matches!(tkind, TypeKind::Pou { program: true, .. }) {
            ("E209", "a PROGRAM cannot be instantiated inside a POU")
        } else if is_fb && block.kind != VarKind::InOut && self.being_emitted(ty) {
            (
                "E204",
                "this block's own code calls the POU declared here, so its size is not known yet (a cycle plcrun cannot lay out)",
            )
        } else {
            return ty;
        };
        self.diags.error(code, decl.ty.span(), why);
        TypeTable::error()
    }

    /// True when `ty` is the instance type of a block whose body is being
    /// emitted: its size (which counts its body's temporaries) is not
    /// final yet.
    fn being_emitted(&self, ty: TypeId) -> bool {
        self.model
            .pous
            .iter()
            .position(|q| q.ty == ty)
            .is_some_and(|q| self.emit_state[q] == LayoutState::InProgress)
    }

    /// E210: RETAIN or PERSISTENT where a value cannot outlive a call
    /// (VAR_TEMP, VAR_IN_OUT, VAR_EXTERNAL, a FUNCTION's variables) or
    /// cannot change (CONSTANT).
    fn check_retain(&mut self, pou: &Pou, block: &VarBlock) {
        if !matches!(retention(block), Retention::Retain | Retention::Persistent) {
            return;
        }
        let why = match block.kind {
            VarKind::Temp => Some("VAR_TEMP is reset at every call"),
            VarKind::InOut => Some("a VAR_IN_OUT refers to the caller's variable"),
            VarKind::External => {
                Some("a VAR_EXTERNAL refers to a global: declare the global RETAIN")
            }
            _ if pou.kind == PouKind::Function => {
                Some("a FUNCTION's variables do not outlive a call")
            }
            _ if block.constant => Some("a CONSTANT never changes"),
            _ => None,
        };
        if let Some(why) = why {
            self.diags.error(
                "E210",
                block.span,
                format!("RETAIN and PERSISTENT cannot apply here: {why}"),
            );
        }
    }

    /// Where variable `name` lives: a located address, the global of a
    /// VAR_EXTERNAL, a pointer slot (VAR_IN_OUT) or frame slots.
    fn var_storage(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
        name: &Ident,
        ty: TypeId,
        frame: &mut Frame,
    ) -> Option<(Storage, Option<String>)> {
        if let Some(a) = decl.location.as_ref().filter(|a| a.fields.is_empty()) {
            // `AT %I*`: an instance variable, completed per instance by VAR_CONFIG.
            let location = self.incomplete_address(pou, block, a, ty)?;
            let s = Storage::Frame(frame.offset);
            frame.offset = self.grow(frame.offset, self.types.size(ty), name.span);
            return Some((s, Some(location)));
        }
        if let Some(a) = &decl.location {
            if pou.kind != PouKind::Program {
                self.diags.error(
                    "E207",
                    a.span,
                    "located variables (AT %...) are only allowed in PROGRAMs and globals",
                );
                return None;
            }
            let addr = self.out.located_slot(&self.types, self.diags, a, ty)?;
            return Some((Storage::Abs(addr), Some(normalize_address(a))));
        }
        match block.kind {
            VarKind::External => self.external_storage(block, name, ty),
            // One copy for every instance and call: absolute memory,
            // initialised once by the linker.
            VarKind::Stat => {
                let size = self.types.size(ty).max(1);
                Some((Storage::Abs(self.out.alloc_abs(self.diags, size)), None))
            }
            VarKind::InOut => {
                let s = Storage::Ref(frame.offset);
                // An `ARRAY[*]` also holds the argument's bounds.
                frame.offset += match self.types.get(ty).kind {
                    TypeKind::OpenArray { rank, .. } => open_array_layout::size(rank),
                    _ => 1,
                };
                Some((s, None))
            }
            _ => {
                let s = Storage::Frame(frame.offset);
                frame.offset = self.grow(frame.offset, self.types.size(ty), name.span);
                Some((s, None))
            }
        }
    }

    /// The global a VAR_EXTERNAL refers to, checked for type and CONSTANT.
    fn external_storage(
        &mut self,
        block: &VarBlock,
        name: &Ident,
        ty: TypeId,
    ) -> Option<(Storage, Option<String>)> {
        let Some(g) = self.model.globals.get(&name.key()) else {
            self.diags.error(
                "E201",
                name.span,
                format!("no VAR_GLOBAL named `{}` for this VAR_EXTERNAL", name.name),
            );
            return None;
        };
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
        Some((g.storage, g.location.clone()))
    }

    /// The variable as the model records it; a CONSTANT needs a constant
    /// initial value (a VAR_EXTERNAL CONSTANT takes the global's).
    fn declared_var(
        &mut self,
        block: &VarBlock,
        name: &Ident,
        ty: TypeId,
        storage: Storage,
        location: Option<String>,
        init: &Option<ConstInit>,
    ) -> VarInfo {
        // A VAR_INPUT CONSTANT (CODESYS) is set by the caller: its initial
        // value is only a default, so it is never folded; the body still
        // may not write it.
        let input = matches!(block.kind, VarKind::Input | VarKind::InOut);
        if block.constant && input {
            let what = match block.kind {
                VarKind::Input => {
                    "VAR_INPUT CONSTANT is a CODESYS extension (an input the body may not write)"
                }
                _ => {
                    "VAR_IN_OUT CONSTANT is a CODESYS extension (an in-out the body may not write, connected to any variable)"
                }
            };
            self.diags
                .warning("W353", name.span, format!("`{}`: {what}", name.name));
        }
        let value = if block.constant && !input {
            init.as_ref().and_then(init_const)
        } else {
            None
        };
        if block.constant
            && !input
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
            self.model
                .globals
                .get(&name.key())
                .and_then(|g| g.value.clone())
        } else {
            value
        };
        VarInfo {
            name: name.name.clone(),
            ty,
            kind: member_kind(block.kind),
            storage,
            constant: block.constant,
            value,
            init: init.clone(),
            location,
        }
    }

    /// Gives the laid-out POU its code block and instance type.
    fn finish_layout(&mut self, p: usize, pou: &Pou, frame: Frame) {
        let code = crate::ir::op::CodeIdx::new(self.out.codes.len() as u32);
        self.out.codes.push(crate::ir::image::CodeBlock {
            name: pou.name.name.clone(),
            kind: match pou.kind {
                PouKind::Program => crate::ir::image::CodeKind::Program,
                PouKind::FunctionBlock => crate::ir::image::CodeKind::FunctionBlock,
                PouKind::Function => crate::ir::image::CodeKind::Function,
            },
            ops: Vec::new(),
            spans: Vec::new(),
            entry_init: Vec::new(),
            entry_strings: Vec::new(),
            frame: 0,
            frame_size: frame.offset,
            handlers: Vec::new(),
        });
        let ty = self.place_pou_type(
            p,
            TypeDef {
                name: pou.name.name.clone(),
                kind: TypeKind::Pou {
                    code,
                    members: frame.members,
                    program: pou.kind == PouKind::Program,
                },
                size: frame.offset,
            },
        );
        let info = &mut self.model.pous[p];
        info.vars = frame.vars;
        info.params = frame.params;
        info.code = code;
        info.vars_size = frame.offset;
        info.ty = ty;
    }
}

/// The POU's variable blocks in the order they are laid out: as written,
/// except that when an array or string is declared before a local
/// `VAR CONSTANT` block, or an initial value reads a constant of a later
/// block, the constant blocks come first so that their names can size it
/// or give the value (CODESYS accepts a constant declared further down).
fn blocks_in_layout_order(blocks: &[VarBlock]) -> Vec<&VarBlock> {
    let local_constant = |b: &VarBlock| b.constant && b.kind == VarKind::Local;
    let sized = |b: &VarBlock| {
        b.decls.iter().any(|d| {
            matches!(
                d.ty,
                crate::syntax::ast::TypeSpec::Array { .. }
                    | crate::syntax::ast::TypeSpec::String { .. }
            )
        })
    };
    let sized_first = blocks
        .iter()
        .position(|b| !local_constant(b) && sized(b))
        .is_some_and(|first| blocks[first..].iter().any(local_constant));
    // An initial value reading a constant declared in a later block
    // (`nState : INT := IDLE;` before `VAR CONSTANT IDLE : INT := 0;`),
    // which CODESYS accepts: the constants are laid out first there too.
    let read_early = blocks.iter().enumerate().any(|(i, b)| {
        if local_constant(b) {
            return false;
        }
        let reads = super::const_order::names_read(b);
        blocks[i + 1..]
            .iter()
            .filter(|c| local_constant(c))
            .flat_map(|c| c.decls.iter().flat_map(|d| &d.names))
            .any(|n| reads.contains(&n.key()))
    });
    let hoist = sized_first || read_early;
    if !hoist {
        return blocks.iter().collect();
    }
    let (constants, rest): (Vec<&VarBlock>, Vec<&VarBlock>) =
        blocks.iter().partition(|b| local_constant(b));
    constants.into_iter().chain(rest).collect()
}
