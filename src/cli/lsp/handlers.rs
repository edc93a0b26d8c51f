//! The requests the server answers, each turned into a question to the
//! project's [`Analysis`] and its answer into protocol values.

use super::convert;
use super::position::Columns;
use super::server::{Failure, Place, Server};
use super::uri;
use lsp_types as lsp;
use plcrun::{Analysis, Span};
use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// What the server can do, announced at initialisation.
pub fn capabilities(utf8: bool, live: bool) -> lsp::ServerCapabilities {
    lsp::ServerCapabilities {
        position_encoding: Some(if utf8 {
            lsp::PositionEncodingKind::UTF8
        } else {
            lsp::PositionEncodingKind::UTF16
        }),
        text_document_sync: Some(lsp::TextDocumentSyncCapability::Options(
            lsp::TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(lsp::TextDocumentSyncKind::FULL),
                save: Some(lsp::TextDocumentSyncSaveOptions::Supported(true)),
                ..lsp::TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(lsp::HoverProviderCapability::Simple(true)),
        definition_provider: Some(lsp::OneOf::Left(true)),
        declaration_provider: Some(lsp::DeclarationCapability::Simple(true)),
        type_definition_provider: Some(lsp::TypeDefinitionProviderCapability::Simple(true)),
        references_provider: Some(lsp::OneOf::Left(true)),
        rename_provider: Some(lsp::OneOf::Right(lsp::RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: lsp::WorkDoneProgressOptions::default(),
        })),
        completion_provider: Some(lsp::CompletionOptions {
            trigger_characters: Some(vec![".".into()]),
            ..lsp::CompletionOptions::default()
        }),
        signature_help_provider: Some(lsp::SignatureHelpOptions {
            trigger_characters: Some(vec!["(".into(), ",".into()]),
            retrigger_characters: None,
            work_done_progress_options: lsp::WorkDoneProgressOptions::default(),
        }),
        document_symbol_provider: Some(lsp::OneOf::Left(true)),
        workspace_symbol_provider: Some(lsp::OneOf::Left(true)),
        folding_range_provider: Some(lsp::FoldingRangeProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(
            lsp::SemanticTokensServerCapabilities::SemanticTokensOptions(
                lsp::SemanticTokensOptions {
                    legend: lsp::SemanticTokensLegend {
                        token_types: convert::TOKEN_TYPES.to_vec(),
                        token_modifiers: convert::TOKEN_MODIFIERS.to_vec(),
                    },
                    full: Some(lsp::SemanticTokensFullOptions::Bool(true)),
                    range: None,
                    work_done_progress_options: lsp::WorkDoneProgressOptions::default(),
                },
            ),
        ),
        // No formatter: plcrun has none yet (docs/editors.md).
        document_formatting_provider: None,
        // Live values, when a running plcrun is named (`--live`).
        inlay_hint_provider: live.then_some(lsp::OneOf::Left(true)),
        ..lsp::ServerCapabilities::default()
    }
}

type Answer = Result<Value, Failure>;

/// Answers request `method`.
pub fn dispatch(server: &mut Server, method: &str, params: Value) -> Answer {
    use lsp::request::Request as _;
    use lsp::request::*;
    match method {
        HoverRequest::METHOD => hover(server, parse(params)?),
        GotoDefinition::METHOD | GotoDeclaration::METHOD => {
            let p: lsp::GotoDefinitionParams = parse(params)?;
            goto(
                server,
                p.text_document_position_params,
                Analysis::definition,
            )
        }
        GotoTypeDefinition::METHOD => {
            let p: lsp::GotoDefinitionParams = parse(params)?;
            goto(
                server,
                p.text_document_position_params,
                Analysis::type_definition,
            )
        }
        References::METHOD => references(server, parse(params)?),
        PrepareRenameRequest::METHOD => prepare_rename(server, parse(params)?),
        Rename::METHOD => rename(server, parse(params)?),
        Completion::METHOD => completion(server, parse(params)?),
        SignatureHelpRequest::METHOD => signature_help(server, parse(params)?),
        DocumentSymbolRequest::METHOD => document_symbols(server, parse(params)?),
        WorkspaceSymbolRequest::METHOD => workspace_symbols(server, parse(params)?),
        SemanticTokensFullRequest::METHOD => semantic_tokens(server, parse(params)?),
        FoldingRangeRequest::METHOD => folding(server, parse(params)?),
        InlayHintRequest::METHOD => inlay_hints(server, parse(params)?),
        Formatting::METHOD => Err(Failure::refused(
            "plcrun has no formatter yet: formatting is not offered",
        )),
        _ => Err(Failure {
            code: lsp_server::ErrorCode::MethodNotFound as i32,
            message: format!("plcrun lsp does not answer `{method}`"),
        }),
    }
}

/// The running PLC's values beside the names of the requested range.
fn inlay_hints(server: &mut Server, p: lsp::InlayHintParams) -> Answer {
    if server.live.is_none() {
        return json(Vec::<lsp::InlayHint>::new());
    }
    let start = server.place(&p.text_document, p.range.start)?;
    let end = server.place(&p.text_document, p.range.end)?;
    let columns = server.columns;
    let mut live = server.live.take();
    let hints = match (&mut live, server.analysis(&start.project)) {
        (Some(live), Some(analysis)) => {
            live.hints(analysis, start.file, (start.offset, end.offset), columns)
        }
        _ => Vec::new(),
    };
    server.live = live;
    json(hints)
}

fn parse<T: serde::de::DeserializeOwned>(params: Value) -> Result<T, Failure> {
    serde_json::from_value(params).map_err(|e| Failure::invalid(e.to_string()))
}

fn json<T: serde::Serialize>(value: T) -> Answer {
    serde_json::to_value(value).map_err(|e| Failure::refused(e.to_string()))
}

/// The project's files and analysis for `place`.
fn project<'a>(
    server: &'a mut Server,
    key: &Path,
) -> Result<(Vec<PathBuf>, &'a Analysis), Failure> {
    let files = server
        .ws
        .projects
        .get(key)
        .map(|p| p.files.clone())
        .ok_or_else(|| Failure::refused("the project is gone"))?;
    let analysis = server
        .analysis(key)
        .ok_or_else(|| Failure::refused("the project is gone"))?;
    Ok((files, analysis))
}

/// The protocol location of `span` in a project.
fn location(
    files: &[PathBuf],
    analysis: &Analysis,
    columns: Columns,
    span: Span,
) -> Option<lsp::Location> {
    let path = files.get(span.file.0 as usize)?;
    let file = analysis.sources().file(span.file);
    Some(lsp::Location::new(
        uri::from_path(path)?,
        columns.range(file, span.start, span.end),
    ))
}

fn at(server: &mut Server, p: &lsp::TextDocumentPositionParams) -> Result<Place, Failure> {
    server.place(&p.text_document, p.position)
}

fn hover(server: &mut Server, p: lsp::HoverParams) -> Answer {
    let place = at(server, &p.text_document_position_params)?;
    let columns = server.columns;
    let (_, analysis) = project(server, &place.project)?;
    let Some(h) = analysis.hover(place.file, place.offset) else {
        return Ok(Value::Null);
    };
    let file = analysis.sources().file(h.span.file);
    json(lsp::Hover {
        contents: lsp::HoverContents::Markup(lsp::MarkupContent {
            kind: lsp::MarkupKind::Markdown,
            value: h.markdown,
        }),
        range: Some(columns.range(file, h.span.start, h.span.end)),
    })
}

fn goto(
    server: &mut Server,
    p: lsp::TextDocumentPositionParams,
    find: fn(&Analysis, plcrun::FileId, u32) -> Option<Span>,
) -> Answer {
    let place = at(server, &p)?;
    let columns = server.columns;
    let (files, analysis) = project(server, &place.project)?;
    match find(analysis, place.file, place.offset)
        .and_then(|s| location(&files, analysis, columns, s))
    {
        Some(l) => json(lsp::GotoDefinitionResponse::Scalar(l)),
        None => Ok(Value::Null),
    }
}

fn references(server: &mut Server, p: lsp::ReferenceParams) -> Answer {
    let place = at(server, &p.text_document_position)?;
    let columns = server.columns;
    let (files, analysis) = project(server, &place.project)?;
    let Some(id) = analysis.symbol_at(place.file, place.offset) else {
        return json(Vec::<lsp::Location>::new());
    };
    let found: Vec<lsp::Location> = analysis
        .references(id)
        .into_iter()
        .filter(|o| p.context.include_declaration || !o.declaration)
        .filter_map(|o| location(&files, analysis, columns, o.span))
        .collect();
    json(found)
}

fn prepare_rename(server: &mut Server, p: lsp::TextDocumentPositionParams) -> Answer {
    let place = at(server, &p)?;
    let columns = server.columns;
    let (_, analysis) = project(server, &place.project)?;
    let span = analysis
        .prepare_rename(place.file, place.offset)
        .map_err(|e| Failure::refused(e.to_string()))?;
    let file = analysis.sources().file(span.file);
    json(lsp::PrepareRenameResponse::Range(
        columns.range(file, span.start, span.end),
    ))
}

fn rename(server: &mut Server, p: lsp::RenameParams) -> Answer {
    let place = at(server, &p.text_document_position)?;
    let columns = server.columns;
    let (files, analysis) = project(server, &place.project)?;
    let spans = analysis
        .rename(place.file, place.offset, &p.new_name)
        .map_err(|e| Failure::refused(e.to_string()))?;
    // lsp-types keys its edits by `Uri`, whose parsed form caches lazily
    // (interior mutability); the cache never changes its hash or order.
    #[allow(clippy::mutable_key_type)]
    let mut changes: HashMap<lsp::Uri, Vec<lsp::TextEdit>> = HashMap::new();
    for span in spans {
        if let Some(l) = location(&files, analysis, columns, span) {
            changes
                .entry(l.uri)
                .or_default()
                .push(lsp::TextEdit::new(l.range, p.new_name.clone()));
        }
    }
    json(lsp::WorkspaceEdit::new(changes))
}

fn completion(server: &mut Server, p: lsp::CompletionParams) -> Answer {
    let place = at(server, &p.text_document_position)?;
    let (_, analysis) = project(server, &place.project)?;
    let items: Vec<lsp::CompletionItem> = analysis
        .completions(place.file, place.offset)
        .iter()
        .map(convert::completion)
        .collect();
    json(lsp::CompletionResponse::Array(items))
}

fn signature_help(server: &mut Server, p: lsp::SignatureHelpParams) -> Answer {
    let place = at(server, &p.text_document_position_params)?;
    let (_, analysis) = project(server, &place.project)?;
    let Some(sig) = analysis.signature_help(place.file, place.offset) else {
        return Ok(Value::Null);
    };
    let doc = |d: Option<String>| {
        d.map(|value| {
            lsp::Documentation::MarkupContent(lsp::MarkupContent {
                kind: lsp::MarkupKind::Markdown,
                value,
            })
        })
    };
    let params = sig
        .params
        .into_iter()
        .map(|p| lsp::ParameterInformation {
            label: lsp::ParameterLabel::Simple(p.label),
            documentation: doc(p.documentation),
        })
        .collect();
    json(lsp::SignatureHelp {
        signatures: vec![lsp::SignatureInformation {
            label: sig.label,
            documentation: doc(sig.documentation),
            parameters: Some(params),
            active_parameter: sig.active.map(|a| a as u32),
        }],
        active_signature: Some(0),
        active_parameter: sig.active.map(|a| a as u32),
    })
}

fn document_symbols(server: &mut Server, p: lsp::DocumentSymbolParams) -> Answer {
    let place = server.place(&p.text_document, lsp::Position::new(0, 0))?;
    let columns = server.columns;
    let (_, analysis) = project(server, &place.project)?;
    let file = analysis.sources().file(place.file);
    let symbols: Vec<lsp::DocumentSymbol> = analysis
        .outline(place.file)
        .iter()
        .filter_map(|item| convert::document_symbol(analysis, item, file, columns))
        .collect();
    json(lsp::DocumentSymbolResponse::Nested(symbols))
}

fn workspace_symbols(server: &mut Server, p: lsp::WorkspaceSymbolParams) -> Answer {
    let columns = server.columns;
    let files: HashMap<PathBuf, Vec<PathBuf>> = server
        .ws
        .projects
        .iter()
        .map(|(k, p)| (k.clone(), p.files.clone()))
        .collect();
    let mut found = Vec::new();
    for (key, analysis) in server.all_analyses() {
        let files = &files[&key];
        for id in analysis.workspace_symbols(&p.query) {
            let Some(span) = analysis.symbol(id).location else {
                continue;
            };
            if let Some(l) = location(files, analysis, columns, span) {
                found.push(convert::symbol_information(analysis, id, l));
            }
        }
    }
    json(found)
}

fn semantic_tokens(server: &mut Server, p: lsp::SemanticTokensParams) -> Answer {
    let place = server.place(&p.text_document, lsp::Position::new(0, 0))?;
    let columns = server.columns;
    let (_, analysis) = project(server, &place.project)?;
    let file = analysis.sources().file(place.file);
    let data = convert::tokens(&analysis.tokens(place.file), file, columns);
    json(lsp::SemanticTokens {
        result_id: None,
        data,
    })
}

fn folding(server: &mut Server, p: lsp::FoldingRangeParams) -> Answer {
    let place = server.place(&p.text_document, lsp::Position::new(0, 0))?;
    let columns = server.columns;
    let (_, analysis) = project(server, &place.project)?;
    let file = analysis.sources().file(place.file);
    let ranges: Vec<lsp::FoldingRange> = analysis
        .folds(place.file)
        .into_iter()
        .map(|f| {
            let start = columns.position(file, f.start);
            let end = columns.position(file, f.end);
            lsp::FoldingRange {
                start_line: start.line,
                end_line: end.line,
                kind: Some(lsp::FoldingRangeKind::Region),
                ..lsp::FoldingRange::default()
            }
        })
        .filter(|r| r.end_line > r.start_line)
        .collect();
    json(ranges)
}
