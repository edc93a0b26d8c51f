//! The address space a PLC is served as, worked out from its variables
//! before the server starts: a folder per program instance and one for
//! the globals, an Object per FB instance or structure (nested as
//! declared), an array Variable per array of single values, a Variable per
//! other single value. Every Variable's NodeId is its path as `--trace`
//! names it (docs/opcua.md, "Address space").

use super::glob::Globs;
use super::types::Kind;
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;
use crate::runtime::variables::Direction;
use std::collections::HashMap;

/// One single value of the PLC that the server serves.
#[derive(Debug, Clone)]
pub(crate) struct Leaf {
    /// Its path (the trace's name).
    pub(crate) path: String,
    /// The handle the scan side reads and writes it through.
    pub(crate) var: VarRef,
    /// How it is served.
    pub(crate) kind: Kind,
    /// Whether clients may write it (not a CONSTANT nor an SFC flag).
    pub(crate) writable: bool,
}

/// What a node of the served tree is.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum NodeKind {
    /// A program instance's folder, or the globals' one.
    Folder,
    /// An FB instance, a structure, an element of an array of them.
    Object,
    /// A single value, or an array of them (`dims` set).
    Variable {
        /// Indexes into [`Model::leaves`], in the array's order.
        leaves: Vec<usize>,
        /// The array's dimensions; `None` for a scalar.
        dims: Option<Vec<u32>>,
    },
}

/// One node of the served tree.
#[derive(Debug, Clone)]
pub(crate) struct ModelNode {
    /// Its NodeId's string (`t1.ET`, `arr`, `Chariot` for a folder).
    pub(crate) id: String,
    /// Its browse name (the last part of the path).
    pub(crate) name: String,
    /// Its parent in [`Model::nodes`]; `None`: under the Objects folder.
    pub(crate) parent: Option<usize>,
    /// What it is.
    pub(crate) kind: NodeKind,
}

/// The served tree: nodes parents first, and the values they serve.
#[derive(Debug, Clone, Default)]
pub(crate) struct Model {
    /// The values, in the order [`Plc::variables`] lists them.
    pub(crate) leaves: Vec<Leaf>,
    /// The nodes; a parent comes before its children.
    pub(crate) nodes: Vec<ModelNode>,
    /// NodeId string to node.
    pub(crate) by_id: HashMap<String, usize>,
}

/// The name of the folder of the global variables.
pub(crate) const GLOBALS: &str = "Globals";

impl Model {
    /// The tree of `plc`'s variables that `expose` selects.
    pub(crate) fn build(plc: &Plc, expose: &Globs) -> Model {
        let mut model = Model::default();
        let programs: Vec<String> = plc.image.programs.iter().map(|p| p.name.clone()).collect();
        let qualified = programs.len() > 1;
        for info in plc.variables() {
            let array = array_name(&info.path);
            if !expose.matches(&info.path) && !array.is_some_and(|a| expose.matches(a)) {
                continue;
            }
            let Ok(var) = plc.resolve(&info.path) else {
                continue;
            };
            let Some(kind) = Kind::of(plc, &var) else {
                continue;
            };
            // Which folder, and the path's part inside it.
            let (folder, prefix, rest) = if info.direction == Direction::Global {
                (GLOBALS.to_string(), String::new(), info.path.clone())
            } else if qualified {
                match info.path.split_once('.') {
                    Some((p, rest)) => (p.to_string(), format!("{p}."), rest.to_string()),
                    None => (GLOBALS.to_string(), String::new(), info.path.clone()),
                }
            } else {
                let folder = programs.first().map_or(GLOBALS, String::as_str);
                (folder.to_string(), String::new(), info.path.clone())
            };
            let leaf = model.leaves.len();
            model.leaves.push(Leaf {
                writable: info.writable,
                path: info.path,
                var,
                kind,
            });
            let parent = model.folder(&folder);
            model.place(parent, &prefix, &rest, leaf);
        }
        for node in &mut model.nodes {
            if let NodeKind::Variable {
                leaves,
                dims: Some(dims),
            } = &mut node.kind
            {
                *dims = dimensions(&model.leaves, leaves);
            }
        }
        model
    }

    /// The folder node named `name` (made on first use).
    fn folder(&mut self, name: &str) -> usize {
        if let Some(&i) = self.by_id.get(name)
            && self.nodes[i].kind == NodeKind::Folder
        {
            return i;
        }
        // A folder's id never takes a variable's: a clash gets a `/`.
        let mut id = name.to_string();
        while self.by_id.contains_key(&id) {
            id.push('/');
        }
        self.push(ModelNode {
            id,
            name: name.to_string(),
            parent: None,
            kind: NodeKind::Folder,
        })
    }

    /// Adds a node and indexes its id.
    fn push(&mut self, node: ModelNode) -> usize {
        let i = self.nodes.len();
        self.by_id.insert(node.id.clone(), i);
        self.nodes.push(node);
        i
    }

    /// Places leaf `leaf`, whose path is `prefix` + `rest`, under `parent`:
    /// an Object per member step, then a Variable (or an array element).
    fn place(&mut self, mut parent: usize, prefix: &str, rest: &str, leaf: usize) {
        let parts = split_path(rest);
        let mut id = prefix.to_string();
        for (k, part) in parts.iter().enumerate() {
            if k > 0 {
                id.push('.');
            }
            let last = k + 1 == parts.len();
            if !last {
                id.push_str(part);
                parent = self.object(parent, &id, part);
                continue;
            }
            match part.find('[') {
                Some(open) => {
                    id.push_str(&part[..open]);
                    self.element(parent, &id, &part[..open], leaf);
                }
                None => {
                    id.push_str(part);
                    self.push(ModelNode {
                        id: id.clone(),
                        name: part.to_string(),
                        parent: Some(parent),
                        kind: NodeKind::Variable {
                            leaves: vec![leaf],
                            dims: None,
                        },
                    });
                }
            }
        }
    }

    /// The Object `id` under `parent` (made on first use).
    fn object(&mut self, parent: usize, id: &str, name: &str) -> usize {
        if let Some(&i) = self.by_id.get(id) {
            return i;
        }
        self.push(ModelNode {
            id: id.to_string(),
            name: name.to_string(),
            parent: Some(parent),
            kind: NodeKind::Object,
        })
    }

    /// Adds `leaf` as the next element of the array Variable `id`.
    fn element(&mut self, parent: usize, id: &str, name: &str, leaf: usize) {
        if let Some(&i) = self.by_id.get(id)
            && let NodeKind::Variable {
                leaves,
                dims: Some(_),
            } = &mut self.nodes[i].kind
        {
            leaves.push(leaf);
            return;
        }
        self.push(ModelNode {
            id: id.to_string(),
            name: name.to_string(),
            parent: Some(parent),
            kind: NodeKind::Variable {
                leaves: vec![leaf],
                dims: Some(Vec::new()),
            },
        });
    }

    /// The leaves of node `node` if it is a Variable.
    pub(crate) fn leaves_of(&self, node: usize) -> Option<&[usize]> {
        match &self.nodes[node].kind {
            NodeKind::Variable { leaves, .. } => Some(leaves),
            _ => None,
        }
    }
}

/// The name of the array an element path belongs to (`a.b[2]` → `a.b`),
/// `None` when the path does not end in an index.
fn array_name(path: &str) -> Option<&str> {
    if !path.ends_with(']') {
        return None;
    }
    let open = path.rfind('[')?;
    Some(&path[..open])
}

/// The member steps of a path: `a.b[2].c` → `a`, `b[2]`, `c`. A direct
/// address (`%IX0.1`) is one step.
fn split_path(path: &str) -> Vec<&str> {
    if path.starts_with('%') {
        return vec![path];
    }
    path.split('.').collect()
}

/// The indexes of an element path's last part (`a[1,2]` → `[1, 2]`).
fn indexes(path: &str) -> Vec<i64> {
    let inner = path
        .rfind('[')
        .map(|open| &path[open + 1..path.len() - 1])
        .unwrap_or("");
    inner
        .split(',')
        .filter_map(|p| p.trim().parse().ok())
        .collect()
}

/// The dimensions of an array whose elements are `leaves` (the last index
/// running fastest): the number of distinct indexes in each position. An
/// array partly exposed is served as one dimension of what is exposed.
fn dimensions(all: &[Leaf], leaves: &[usize]) -> Vec<u32> {
    let rows: Vec<Vec<i64>> = leaves.iter().map(|&l| indexes(&all[l].path)).collect();
    let rank = rows.first().map_or(1, Vec::len);
    let mut dims = Vec::with_capacity(rank);
    for k in 0..rank {
        let mut seen: Vec<i64> = rows.iter().filter_map(|r| r.get(k).copied()).collect();
        seen.sort_unstable();
        seen.dedup();
        dims.push(seen.len() as u32);
    }
    let total: u64 = dims.iter().map(|&d| u64::from(d)).product();
    if total == leaves.len() as u64 {
        dims
    } else {
        vec![leaves.len() as u32]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Options;

    const SRC: &str = "TYPE Pair : STRUCT a : INT; b : BOOL; END_STRUCT; END_TYPE
PROGRAM Main
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR CONSTANT limit : INT := 10; END_VAR
VAR t1 : TON; grid : ARRAY[1..2, 0..2] OF INT; p : Pair; END_VAR
t1(IN := go, PT := T#1s);
IF go AND n < limit THEN n := n + 1; END_IF
END_PROGRAM";

    fn model(globs: &[&str]) -> Model {
        let plc = Plc::compile_files(&[("m.st", SRC)], &Options::default()).unwrap();
        let globs: Vec<String> = globs.iter().map(|s| s.to_string()).collect();
        Model::build(&plc, &Globs::new(&globs))
    }

    fn node<'a>(m: &'a Model, id: &str) -> &'a ModelNode {
        &m.nodes[m.by_id[id]]
    }

    #[test]
    fn folders_objects_arrays_and_scalars() {
        let m = model(&[]);
        assert_eq!(node(&m, "Main").kind, NodeKind::Folder);
        assert_eq!(node(&m, "t1").kind, NodeKind::Object);
        let et = node(&m, "t1.ET");
        assert_eq!(et.name, "ET");
        assert_eq!(et.parent, Some(m.by_id["t1"]));
        let NodeKind::Variable { leaves, dims } = &node(&m, "grid").kind else {
            panic!("grid is not a variable")
        };
        assert_eq!(dims.as_deref(), Some(&[2u32, 3][..]));
        assert_eq!(m.leaves[leaves[1]].path, "grid[1,1]");
        assert_eq!(node(&m, "p").kind, NodeKind::Object);
        assert!(m.by_id.contains_key("p.a"));
        let limit = m.leaves_of(m.by_id["limit"]).unwrap()[0];
        assert!(!m.leaves[limit].writable);
    }

    #[test]
    fn globs_choose_what_is_served() {
        let m = model(&["n", "grid"]);
        assert!(m.by_id.contains_key("n"));
        assert!(m.by_id.contains_key("grid"));
        assert!(!m.by_id.contains_key("go"));
        assert!(!m.by_id.contains_key("t1"));
        let m = model(&["T1.*"]);
        assert!(m.by_id.contains_key("t1.Q"));
        assert!(!m.by_id.contains_key("n"));
    }
}
