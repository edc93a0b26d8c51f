//! `plcrun check --map`: the located variables of a compiled program and
//! their addresses, incomplete addresses (`AT %I*`) with the address each
//! got.

use crate::ir::image::{Image, RootVar};

/// One line per located variable (`%IX1.0  MAIN.bStart : BOOL`), by area
/// and address.
pub(crate) fn address_map(image: &Image) -> String {
    let mut rows: Vec<(String, &RootVar)> = image
        .globals
        .iter()
        // A located variable is also reachable by its address's name.
        .filter(|r| !r.name.starts_with('%'))
        .filter_map(|r| r.location.clone().map(|l| (l, r)))
        .collect();
    let key = |l: &str| match crate::address::parse(l) {
        Ok(a) => (
            a.area.index(),
            a.index * 8 + usize::from(a.bit),
            a.width.index(),
        ),
        Err(_) => (usize::MAX, 0, 0),
    };
    rows.sort_by_key(|(l, r)| (key(l), r.name.clone()));
    let width = rows.iter().map(|(l, _)| l.len()).max().unwrap_or(0);
    let mut out = String::new();
    for (l, r) in rows {
        out.push_str(&format!(
            "{l:<width$}  {} : {}\n",
            r.name,
            image.types.name(r.ty)
        ));
    }
    out
}
