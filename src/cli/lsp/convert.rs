//! plcrun's answers as Language Server Protocol values.

use super::position::Columns;
use lsp_types as lsp;
use plcrun::{
    Analysis, Completion, CompletionKind, Diagnostic, OutlineItem, Severity, SourceFile,
    SymbolKind, TokenKind, TokenMark,
};

/// The semantic token types, in the legend's order ([`token_type`] indexes it).
pub const TOKEN_TYPES: &[lsp::SemanticTokenType] = &[
    lsp::SemanticTokenType::CLASS,
    lsp::SemanticTokenType::TYPE,
    lsp::SemanticTokenType::ENUM,
    lsp::SemanticTokenType::ENUM_MEMBER,
    lsp::SemanticTokenType::FUNCTION,
    lsp::SemanticTokenType::METHOD,
    lsp::SemanticTokenType::PARAMETER,
    lsp::SemanticTokenType::VARIABLE,
    lsp::SemanticTokenType::PROPERTY,
    lsp::SemanticTokenType::new("label"),
];

/// The semantic token modifiers, in the legend's order (bit 0, bit 1).
pub const TOKEN_MODIFIERS: &[lsp::SemanticTokenModifier] = &[
    lsp::SemanticTokenModifier::DECLARATION,
    lsp::SemanticTokenModifier::READONLY,
];

fn token_type(kind: TokenKind) -> u32 {
    match kind {
        TokenKind::Class => 0,
        TokenKind::Type => 1,
        TokenKind::Enum => 2,
        TokenKind::EnumMember => 3,
        TokenKind::Function => 4,
        TokenKind::Method => 5,
        TokenKind::Parameter => 6,
        TokenKind::Variable => 7,
        TokenKind::Property => 8,
        TokenKind::Label => 9,
    }
}

/// A plcrun diagnostic of `file` as the protocol's.
pub fn diagnostic(d: &Diagnostic, file: &SourceFile, columns: Columns) -> lsp::Diagnostic {
    let mut message = d.message.clone();
    for note in &d.notes {
        message.push('\n');
        message.push_str(note);
    }
    lsp::Diagnostic {
        range: columns.range(file, d.span.start, d.span.end),
        severity: Some(match d.severity {
            Severity::Error => lsp::DiagnosticSeverity::ERROR,
            Severity::Warning => lsp::DiagnosticSeverity::WARNING,
        }),
        code: Some(lsp::NumberOrString::String(d.code.to_string())),
        source: Some("plcrun".into()),
        message,
        ..lsp::Diagnostic::default()
    }
}

/// Semantic tokens, delta-encoded as the protocol wants (a name spanning
/// lines is left out: names do not).
pub fn tokens(marks: &[TokenMark], file: &SourceFile, columns: Columns) -> Vec<lsp::SemanticToken> {
    let mut out = Vec::with_capacity(marks.len());
    let (mut line, mut start) = (0, 0);
    for mark in marks {
        let from = columns.position(file, mark.span.start);
        let to = columns.position(file, mark.span.end);
        if from.line != to.line || to.character <= from.character {
            continue;
        }
        let delta_line = from.line - line;
        let delta_start = if delta_line == 0 {
            from.character - start
        } else {
            from.character
        };
        out.push(lsp::SemanticToken {
            delta_line,
            delta_start,
            length: to.character - from.character,
            token_type: token_type(mark.kind),
            token_modifiers_bitset: u32::from(mark.declaration) | (u32::from(mark.readonly) << 1),
        });
        line = from.line;
        start = from.character;
    }
    out
}

/// A completion proposal as the protocol's.
pub fn completion(c: &Completion) -> lsp::CompletionItem {
    let kind = match c.kind {
        CompletionKind::Variable => lsp::CompletionItemKind::VARIABLE,
        CompletionKind::Function => lsp::CompletionItemKind::FUNCTION,
        CompletionKind::Method => lsp::CompletionItemKind::METHOD,
        CompletionKind::Type => lsp::CompletionItemKind::CLASS,
        CompletionKind::EnumValue => lsp::CompletionItemKind::ENUM_MEMBER,
        CompletionKind::Keyword if c.snippet.is_some() => lsp::CompletionItemKind::SNIPPET,
        CompletionKind::Keyword => lsp::CompletionItemKind::KEYWORD,
        CompletionKind::Other => lsp::CompletionItemKind::REFERENCE,
    };
    lsp::CompletionItem {
        label: c.label.clone(),
        kind: Some(kind),
        detail: c.detail.clone(),
        insert_text: c.snippet.clone(),
        insert_text_format: c.snippet.as_ref().map(|_| lsp::InsertTextFormat::SNIPPET),
        ..lsp::CompletionItem::default()
    }
}

fn symbol_kind(kind: SymbolKind) -> lsp::SymbolKind {
    match kind {
        SymbolKind::Program => lsp::SymbolKind::MODULE,
        SymbolKind::Function => lsp::SymbolKind::FUNCTION,
        SymbolKind::FunctionBlock | SymbolKind::StandardBlock => lsp::SymbolKind::CLASS,
        SymbolKind::Method => lsp::SymbolKind::METHOD,
        SymbolKind::Interface => lsp::SymbolKind::INTERFACE,
        SymbolKind::Struct => lsp::SymbolKind::STRUCT,
        SymbolKind::Enum => lsp::SymbolKind::ENUM,
        SymbolKind::Alias => lsp::SymbolKind::TYPE_PARAMETER,
        SymbolKind::Field | SymbolKind::StandardPin(_) => lsp::SymbolKind::FIELD,
        SymbolKind::EnumValue => lsp::SymbolKind::ENUM_MEMBER,
        SymbolKind::Variable(_) | SymbolKind::Global => lsp::SymbolKind::VARIABLE,
        SymbolKind::Step | SymbolKind::Task => lsp::SymbolKind::EVENT,
        SymbolKind::Action => lsp::SymbolKind::FUNCTION,
        SymbolKind::Transition => lsp::SymbolKind::OPERATOR,
        SymbolKind::Label => lsp::SymbolKind::KEY,
        SymbolKind::Configuration => lsp::SymbolKind::NAMESPACE,
        SymbolKind::Resource => lsp::SymbolKind::PACKAGE,
        SymbolKind::ProgramInstance => lsp::SymbolKind::OBJECT,
    }
}

/// An outline entry as a protocol document symbol.
pub fn document_symbol(
    analysis: &Analysis,
    item: &OutlineItem,
    file: &SourceFile,
    columns: Columns,
) -> Option<lsp::DocumentSymbol> {
    let s = analysis.symbol(item.symbol);
    let location = s.location?;
    let extent = s.extent.unwrap_or(location);
    let selection = columns.range(file, location.start, location.end);
    let mut range = columns.range(file, extent.start, extent.end);
    // The protocol wants the selection inside the range.
    if range.start > selection.start || range.end < selection.end {
        range = selection;
    }
    let children: Vec<lsp::DocumentSymbol> = item
        .children
        .iter()
        .filter_map(|c| document_symbol(analysis, c, file, columns))
        .collect();
    #[allow(deprecated)]
    Some(lsp::DocumentSymbol {
        name: s.name.clone(),
        detail: s.type_text.clone(),
        kind: symbol_kind(s.kind),
        tags: None,
        deprecated: None,
        range,
        selection_range: selection,
        children: (!children.is_empty()).then_some(children),
    })
}

/// A symbol as a protocol workspace symbol, at `location`.
pub fn symbol_information(
    analysis: &Analysis,
    id: plcrun::SymbolId,
    location: lsp::Location,
) -> lsp::SymbolInformation {
    let s = analysis.symbol(id);
    #[allow(deprecated)]
    lsp::SymbolInformation {
        name: s.name.clone(),
        kind: symbol_kind(s.kind),
        tags: None,
        deprecated: None,
        location,
        container_name: s.parent.map(|p| analysis.symbol(p).name.clone()),
    }
}
