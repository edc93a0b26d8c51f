//! The calls at unloading: for each instance a declaration declares, its
//! `FB_exit`, then its members' exit (the reverse of the start's order).

use super::EXIT;
use super::build::{all_elements, call_stmt, input, member, members_call, name};
use super::index::Index;
use crate::syntax::ast::{Body, Stmt, VarDecl};
use crate::syntax::oop::{Method, SUPER};

/// The exit of the instances `d` declares (none when their block needs
/// nothing at exit).
pub(super) fn exit_of(index: &Index, d: &VarDecl, loops: &mut usize) -> Vec<Stmt> {
    let Some((key, dims)) = index.block_type(&d.ty) else {
        return Vec::new();
    };
    let fb_exit = index.method_of(&key, EXIT).is_some();
    let tree = index.has_tree(&key, EXIT);
    if !fb_exit && !tree {
        return Vec::new();
    }
    let span = d.span;
    all_elements(d, &dims, loops, |target| {
        let mut out = Vec::new();
        if fb_exit {
            let flag = vec![input(EXIT.flag, name(EXIT.flag, span))];
            out.push(call_stmt(
                member(target.clone(), EXIT.method, span),
                flag,
                span,
            ));
        }
        if tree {
            out.push(members_call(target, EXIT, span));
        }
        out
    })
}

/// Makes a derived block's `FB_exit` call its ancestor's last (TwinCAT
/// runs the derived block's first, then its parent's).
pub(super) fn append_parent_exit(own: &mut Method) {
    let span = own.name.span;
    let flag = vec![input(EXIT.flag, name(EXIT.flag, span))];
    let call = call_stmt(member(name(SUPER, span), EXIT.method, span), flag, span);
    if let Body::St(stmts) = &mut own.body {
        stmts.push(call);
    }
}
