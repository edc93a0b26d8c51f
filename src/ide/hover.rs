//! Hover text: what the name under the cursor is, its type and declared
//! line, the range of its type's values, its documentation comment; the
//! signature of a standard function or block.

use super::doc_comment::doc_comment;
use super::std_functions::std_function;
use super::symbol::{Symbol, SymbolId, SymbolKind, VarSection};
use super::{Analysis, text_context};
use crate::elementary::ElemType;
use crate::source::{FileId, Span};

/// What hovering a name shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Hover {
    /// The name hovered.
    pub span: Span,
    /// Markdown: a code block with the declaration, then prose.
    pub markdown: String,
}

impl Analysis {
    /// The hover text for the name at `offset` of `file`.
    pub fn hover(&self, file: FileId, offset: u32) -> Option<Hover> {
        if let Some(o) = self.occurrence_at(file, offset) {
            return Some(Hover {
                span: o.span,
                markdown: self.describe(o.symbol),
            });
        }
        let (start, word) = text_context::word_at(self.text(file), offset as usize)?;
        let span = Span::new(file, start, start + word.len());
        if let Some(f) = std_function(word) {
            let markdown = format!(
                "```iecst\n{}\n```\nstandard function: {}",
                f.signature(),
                f.summary
            );
            return Some(Hover { span, markdown });
        }
        let ty = ElemType::from_name(word)?;
        Some(Hover {
            span,
            markdown: format!("```iecst\n{}\n```\n{}", ty.name(), elementary_note(ty)),
        })
    }

    /// The hover text of a symbol.
    pub fn describe(&self, id: SymbolId) -> String {
        let symbol = self.symbol(id);
        let mut out = format!("```iecst\n{}\n```\n", self.declaration_line(id));
        out.push_str(symbol.kind.describe());
        if let Some(parent) = symbol.parent {
            out.push_str(&format!(" of `{}`", self.symbol(parent).name));
        }
        if let Some(range) = symbol
            .type_text
            .as_deref()
            .and_then(ElemType::from_name)
            .map(elementary_note)
        {
            out.push_str(&format!(" · {range}"));
        }
        if symbol.constant {
            out.push_str(" · CONSTANT");
        }
        if let Some(doc) = self.documentation(symbol) {
            out.push_str("\n\n---\n");
            out.push_str(&doc);
        }
        out
    }

    /// The comment documenting `symbol`, where it has a place in a file.
    pub fn documentation(&self, symbol: &Symbol) -> Option<String> {
        let extent = symbol.extent?;
        let text = self.text(extent.file);
        let end = match symbol.kind {
            // A POU's own line, not its whole body.
            SymbolKind::Program
            | SymbolKind::Function
            | SymbolKind::FunctionBlock
            | SymbolKind::Method
            | SymbolKind::Interface => symbol.location?.end as usize,
            _ => extent.end as usize,
        };
        doc_comment(text, extent.start as usize, end)
    }

    /// The declaration as one line of code: `speed : INT := 5`,
    /// `FUNCTION_BLOCK Motor (start : BOOL) => (run : BOOL)`.
    pub fn declaration_line(&self, id: SymbolId) -> String {
        let s = self.symbol(id);
        let typed = |prefix: &str| match &s.type_text {
            Some(t) => format!("{prefix}{} : {t}", s.name),
            None => format!("{prefix}{}", s.name),
        };
        match s.kind {
            SymbolKind::Program
            | SymbolKind::Function
            | SymbolKind::FunctionBlock
            | SymbolKind::Method
            | SymbolKind::StandardBlock => self.pou_signature(id),
            SymbolKind::Interface => format!("INTERFACE {}", s.name),
            SymbolKind::Struct => format!("TYPE {} : STRUCT", s.name),
            SymbolKind::Enum => {
                let values: Vec<&str> = self
                    .table
                    .children_of(id)
                    .iter()
                    .map(|&v| self.symbol(v).name.as_str())
                    .collect();
                format!("TYPE {} : ({})", s.name, values.join(", "))
            }
            SymbolKind::Alias => typed("TYPE "),
            SymbolKind::Variable(section) | SymbolKind::StandardPin(section) => {
                typed(&format!("{} ", section.keyword()))
            }
            SymbolKind::Global => typed("VAR_GLOBAL "),
            SymbolKind::Step => format!("STEP {}", s.name),
            SymbolKind::Action => format!("ACTION {}", s.name),
            SymbolKind::Transition => format!("TRANSITION {}", s.name),
            SymbolKind::Task => format!("TASK {}", s.name),
            SymbolKind::ProgramInstance => typed("PROGRAM "),
            SymbolKind::Configuration => format!("CONFIGURATION {}", s.name),
            SymbolKind::Resource => format!("RESOURCE {}", s.name),
            SymbolKind::Label => format!("{}:", s.name),
            SymbolKind::Field | SymbolKind::EnumValue => typed(""),
        }
    }

    /// `FUNCTION f(a : INT) : BOOL`, `FUNCTION_BLOCK TON(IN : BOOL, PT :
    /// TIME) => (Q : BOOL, ET : TIME)`.
    fn pou_signature(&self, id: SymbolId) -> String {
        let s = self.symbol(id);
        let keyword = match s.kind {
            SymbolKind::Program => "PROGRAM",
            SymbolKind::Function => "FUNCTION",
            SymbolKind::Method => "METHOD",
            _ => "FUNCTION_BLOCK",
        };
        let params = |want: &[VarSection]| -> Vec<String> {
            self.table
                .members(id)
                .into_iter()
                .map(|m| self.symbol(m))
                .filter(|m| match m.kind {
                    SymbolKind::Variable(v) | SymbolKind::StandardPin(v) => want.contains(&v),
                    _ => false,
                })
                .map(|m| format!("{} : {}", m.name, m.type_text.as_deref().unwrap_or("?")))
                .collect()
        };
        let mut line = format!(
            "{keyword} {}({})",
            s.name,
            params(&[VarSection::Input, VarSection::InOut]).join(", ")
        );
        let outputs = params(&[VarSection::Output]);
        if !outputs.is_empty() {
            line.push_str(&format!(" => ({})", outputs.join(", ")));
        }
        if let Some(ret) = &s.type_text {
            line.push_str(&format!(" : {ret}"));
        }
        if let Some(base) = &s.extends {
            line.push_str(&format!(" EXTENDS {base}"));
        }
        line
    }
}

/// The values an elementary type holds, in words.
fn elementary_note(ty: ElemType) -> String {
    if let Some((lo, hi)) = ty.int_range() {
        return format!("{}: {lo}..{hi}", ty.name());
    }
    let what = match ty.name() {
        "BOOL" => "FALSE or TRUE",
        "REAL" => "32-bit IEEE 754 floating point",
        "LREAL" => "64-bit IEEE 754 floating point",
        "TIME" | "LTIME" => "a duration (T#...)",
        "DATE" | "LDATE" => "a date (D#...)",
        "TOD" | "TIME_OF_DAY" | "LTOD" => "a time of day (TOD#...)",
        "DT" | "DATE_AND_TIME" | "LDT" => "a date and time (DT#...)",
        "STRING" => "single-byte characters",
        "WSTRING" => "UTF-16 characters",
        _ => "elementary type",
    };
    format!("{}: {what}", ty.name())
}
