//! Completion: members after `.`, a call's parameters inside its
//! parentheses, types after a declaration's `:`, and elsewhere the names in
//! scope, the standard functions (as snippets) and the keywords that fit.

use super::std_functions::std_functions;
use super::symbol::{SymbolId, SymbolKind, VarSection};
use super::text_context::{self, Link};
use super::{Analysis, Shape};
use crate::source::FileId;

/// What a completion proposes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompletionKind {
    /// A variable, field or pin.
    Variable,
    /// A function or standard function.
    Function,
    /// A method.
    Method,
    /// A block, structure, interface or other type.
    Type,
    /// An enumeration value.
    EnumValue,
    /// A keyword or statement template.
    Keyword,
    /// A step, action or label.
    Other,
}

/// One proposal.
#[derive(Debug, Clone, PartialEq)]
pub struct Completion {
    /// What the list shows (and inserts when `snippet` is `None`).
    pub label: String,
    /// What it is.
    pub kind: CompletionKind,
    /// Its type or signature.
    pub detail: Option<String>,
    /// Text to insert instead, in the LSP snippet syntax (`$1`, `${1:x}`).
    pub snippet: Option<String>,
}

/// Statement templates offered in code.
const STATEMENTS: &[(&str, &str)] = &[
    ("IF", "IF ${1:condition} THEN\n\t$0\nEND_IF;"),
    ("CASE", "CASE ${1:selector} OF\n\t${2:1}: $0\nEND_CASE;"),
    ("FOR", "FOR ${1:i} := ${2:1} TO ${3:10} DO\n\t$0\nEND_FOR;"),
    ("WHILE", "WHILE ${1:condition} DO\n\t$0\nEND_WHILE;"),
    ("REPEAT", "REPEAT\n\t$0\nUNTIL ${1:condition}\nEND_REPEAT;"),
];

/// Keywords offered in code.
const CODE_KEYWORDS: &[&str] = &[
    "THEN",
    "ELSIF",
    "ELSE",
    "END_IF",
    "OF",
    "END_CASE",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "END_WHILE",
    "UNTIL",
    "END_REPEAT",
    "RETURN",
    "EXIT",
    "CONTINUE",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "MOD",
    "TRUE",
    "FALSE",
];

/// Instruction List operators.
const IL_OPERATORS: &[&str] = &[
    "LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN", "NOT", "ADD",
    "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT", "JMP", "JMPC", "JMPCN", "CAL",
    "CALC", "CALCN", "RET", "RETC", "RETCN",
];

/// What a declaration's type may start with, besides type names.
const TYPE_KEYWORDS: &[&str] = &[
    "ARRAY",
    "STRING",
    "WSTRING",
    "POINTER TO",
    "REFERENCE TO",
    "REF_TO",
];

/// The elementary types.
const ELEMENTARY: &[&str] = &[
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "REAL",
    "LREAL",
    "BYTE",
    "WORD",
    "DWORD",
    "LWORD",
    "TIME",
    "LTIME",
    "DATE",
    "TIME_OF_DAY",
    "TOD",
    "DATE_AND_TIME",
    "DT",
    "STRING",
    "WSTRING",
    "CHAR",
    "WCHAR",
];

/// Top-level declarations offered outside any POU.
const UNITS: &[(&str, &str)] = &[
    (
        "PROGRAM",
        "PROGRAM ${1:Main}\nVAR\n\t$0\nEND_VAR\n\nEND_PROGRAM",
    ),
    (
        "FUNCTION_BLOCK",
        "FUNCTION_BLOCK ${1:Name}\nVAR_INPUT\n\t$2\nEND_VAR\nVAR_OUTPUT\n\t$3\nEND_VAR\n$0\nEND_FUNCTION_BLOCK",
    ),
    (
        "FUNCTION",
        "FUNCTION ${1:Name} : ${2:BOOL}\nVAR_INPUT\n\t$3\nEND_VAR\n$0\nEND_FUNCTION",
    ),
    (
        "TYPE",
        "TYPE ${1:Name} :\nSTRUCT\n\t$0\nEND_STRUCT\nEND_TYPE",
    ),
    ("VAR_GLOBAL", "VAR_GLOBAL\n\t$0\nEND_VAR"),
    (
        "CONFIGURATION",
        "CONFIGURATION ${1:Config}\nRESOURCE ${2:Res} ON PLC\n\tTASK ${3:Main_task}(INTERVAL := T#10ms, PRIORITY := 1);\n\tPROGRAM ${4:main} WITH $3 : ${5:Main};\nEND_RESOURCE\nEND_CONFIGURATION",
    ),
];

impl Analysis {
    /// The proposals at byte `offset` of `file`.
    pub fn completions(&self, file: FileId, offset: u32) -> Vec<Completion> {
        let text = self.text(file);
        let at = offset as usize;
        let scope = self.scope_at(file, offset);
        if let Some(chain) = text_context::member_chain(text, at) {
            return self.member_completions(&scope, &chain);
        }
        if let Some(site) = text_context::call_site(text, at)
            && site.at_start
            && let Some(owner) = self.callee_of(&scope, &site.callee)
        {
            let mut params = self.parameter_completions(owner);
            if !params.is_empty() {
                params.extend(self.scope_completions(&scope));
                return params;
            }
        }
        match text_context::in_declaration(text, at) {
            Some(true) => return self.type_completions(),
            Some(false) => {
                return ["END_VAR", "CONSTANT", "RETAIN", "AT"]
                    .iter()
                    .map(|k| keyword(k))
                    .collect();
            }
            None => {}
        }
        if scope.is_empty() {
            return UNITS
                .iter()
                .map(|(label, snippet)| Completion {
                    label: label.to_string(),
                    kind: CompletionKind::Keyword,
                    detail: Some("declaration".into()),
                    snippet: Some(snippet.to_string()),
                })
                .collect();
        }
        let mut out = self.scope_completions(&scope);
        if self
            .sources
            .file(file)
            .name
            .to_ascii_lowercase()
            .ends_with(".il")
        {
            out.extend(IL_OPERATORS.iter().map(|k| keyword(k)));
        } else {
            out.extend(STATEMENTS.iter().map(|(label, snippet)| Completion {
                label: label.to_string(),
                kind: CompletionKind::Keyword,
                detail: Some("statement".into()),
                snippet: Some(snippet.to_string()),
            }));
            out.extend(CODE_KEYWORDS.iter().map(|k| keyword(k)));
        }
        out
    }

    /// The symbol a chain of names designates from `scope`, following
    /// members, subscripts and dereferences: what the last link names.
    fn chain_target(&self, scope: &[SymbolId], chain: &[Link]) -> Option<ChainEnd> {
        let (first, rest) = chain.split_first()?;
        let Some(mut id) = self.table.lookup(scope, &first.name.to_ascii_uppercase()) else {
            // `GVL.x`: a name the sources do not declare may be a global
            // list's, qualifying the globals.
            return (rest.is_empty() && !first.name.is_empty()).then_some(ChainEnd::Globals);
        };
        let mut shape = self.link_shape(id, first);
        for link in rest {
            let owner = self.table.owner_of(shape.as_ref()?)?;
            id = self.table.member(owner, &link.name.to_ascii_uppercase())?;
            shape = self.link_shape(id, link);
        }
        Some(ChainEnd::Symbol(id, shape))
    }

    /// The shape of the value a link gives: the symbol's, with its
    /// subscripts and dereference applied.
    fn link_shape(&self, id: SymbolId, link: &Link) -> Option<Shape> {
        let mut shape = self.table.value_shape(id)?;
        for _ in 0..link.indexed {
            shape = match self.table.unalias(&shape) {
                Shape::Array(inner) => *inner,
                _ => return None,
            };
        }
        if link.deref {
            shape = match self.table.unalias(&shape) {
                Shape::Ref(inner) => *inner,
                _ => return None,
            };
        }
        Some(shape)
    }

    /// The POU, method or block type whose parameters a call binds.
    pub(super) fn callee_of(&self, scope: &[SymbolId], callee: &[Link]) -> Option<SymbolId> {
        let ChainEnd::Symbol(id, shape) = self.chain_target(scope, callee)? else {
            return None;
        };
        match self.symbol(id).kind {
            SymbolKind::Function | SymbolKind::Method => Some(id),
            _ => self.table.owner_of(shape.as_ref()?),
        }
    }

    fn member_completions(&self, scope: &[SymbolId], chain: &[Link]) -> Vec<Completion> {
        let owner = match self.chain_target(scope, chain) {
            Some(ChainEnd::Globals) => {
                let mut globals: Vec<SymbolId> = self.table.globals.values().copied().collect();
                globals.sort();
                return globals.into_iter().map(|g| self.completion(g)).collect();
            }
            Some(ChainEnd::Symbol(id, shape)) => {
                let symbol = self.symbol(id);
                if symbol.kind.is_type() && symbol.kind != SymbolKind::Enum {
                    return Vec::new();
                }
                match shape.and_then(|s| self.table.owner_of(&s)) {
                    Some(owner) => owner,
                    None => return Vec::new(),
                }
            }
            None => return Vec::new(),
        };
        let from_outside = !scope.contains(&owner);
        self.table
            .members(owner)
            .into_iter()
            .filter(|&m| !from_outside || self.visible_from_outside(m))
            .map(|m| self.completion(m))
            .collect()
    }

    /// Members a `.` reaches from another POU: a block's interface and
    /// methods, every field, enumeration value and step.
    fn visible_from_outside(&self, id: SymbolId) -> bool {
        match self.symbol(id).kind {
            SymbolKind::Variable(section) | SymbolKind::StandardPin(section) => {
                section.is_interface()
            }
            SymbolKind::Label | SymbolKind::Action | SymbolKind::Transition => false,
            _ => true,
        }
    }

    fn parameter_completions(&self, owner: SymbolId) -> Vec<Completion> {
        self.table
            .members(owner)
            .into_iter()
            .filter_map(|m| {
                let s = self.symbol(m);
                let section = match s.kind {
                    SymbolKind::Variable(v) | SymbolKind::StandardPin(v) => v,
                    _ => return None,
                };
                let arrow = match section {
                    VarSection::Input | VarSection::InOut => ":=",
                    VarSection::Output => "=>",
                    _ => return None,
                };
                Some(Completion {
                    label: format!("{} {arrow}", s.name),
                    kind: CompletionKind::Variable,
                    detail: s.type_text.clone(),
                    snippet: Some(format!("{} {arrow} $0", s.name)),
                })
            })
            .collect()
    }

    /// Every name visible from `scope`, and the standard functions.
    fn scope_completions(&self, scope: &[SymbolId]) -> Vec<Completion> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for &owner in scope {
            for m in self.table.members(owner) {
                if seen.insert(self.symbol(m).key()) {
                    out.push(self.completion(m));
                }
            }
        }
        let mut globals: Vec<SymbolId> = self
            .table
            .globals
            .values()
            .chain(self.table.units.values())
            .copied()
            .filter(|&g| {
                let kind = self.symbol(g).kind;
                !matches!(kind, SymbolKind::Configuration | SymbolKind::Program)
            })
            .collect();
        globals.extend(self.table.enum_values.values().flatten().copied());
        globals.sort();
        for g in globals {
            if seen.insert(self.symbol(g).key()) {
                out.push(self.completion(g));
            }
        }
        out.extend(
            std_functions()
                .filter(|f| seen.insert(f.name.clone()))
                .map(|f| {
                    let args: Vec<String> = f
                        .inputs
                        .iter()
                        .enumerate()
                        .map(|(i, (name, _))| format!("${{{}:{name}}}", i + 1))
                        .collect();
                    Completion {
                        label: f.name.clone(),
                        kind: CompletionKind::Function,
                        detail: Some(f.signature()),
                        snippet: Some(format!("{}({})", f.name, args.join(", "))),
                    }
                }),
        );
        out
    }

    fn type_completions(&self) -> Vec<Completion> {
        let mut out: Vec<Completion> = ELEMENTARY
            .iter()
            .map(|t| Completion {
                label: t.to_string(),
                kind: CompletionKind::Type,
                detail: Some("elementary type".into()),
                snippet: None,
            })
            .collect();
        let mut types: Vec<SymbolId> = self
            .table
            .units
            .values()
            .copied()
            .filter(|&u| self.symbol(u).kind.is_type())
            .collect();
        types.sort();
        out.extend(types.into_iter().map(|t| self.completion(t)));
        out.extend(TYPE_KEYWORDS.iter().map(|k| keyword(k)));
        out
    }

    fn completion(&self, id: SymbolId) -> Completion {
        let s = self.symbol(id);
        let kind = match s.kind {
            SymbolKind::Function => CompletionKind::Function,
            SymbolKind::Method => CompletionKind::Method,
            SymbolKind::EnumValue => CompletionKind::EnumValue,
            SymbolKind::Step | SymbolKind::Action | SymbolKind::Label | SymbolKind::Transition => {
                CompletionKind::Other
            }
            k if k.is_type() => CompletionKind::Type,
            SymbolKind::Program | SymbolKind::Configuration | SymbolKind::Resource => {
                CompletionKind::Other
            }
            _ => CompletionKind::Variable,
        };
        let detail = match kind {
            CompletionKind::Function | CompletionKind::Method | CompletionKind::Type => {
                Some(self.declaration_line(id))
            }
            _ => s.type_text.clone(),
        };
        Completion {
            label: s.name.clone(),
            kind,
            detail,
            snippet: None,
        }
    }
}

/// What a chain of names ends on.
enum ChainEnd {
    /// A symbol, and the shape of the value the last link gives.
    Symbol(SymbolId, Option<Shape>),
    /// An undeclared qualifier: the global variables.
    Globals,
}

fn keyword(word: &str) -> Completion {
    Completion {
        label: word.to_string(),
        kind: CompletionKind::Keyword,
        detail: None,
        snippet: None,
    }
}
