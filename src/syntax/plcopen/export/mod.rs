//! Export: parsed sources (IL, ST, SFC, and PLCopen XML) written as a
//! PLCopen TC6 2.01 project. Declarations come from the AST; bodies,
//! initial values and other expressions are the source text as written
//! (so comments in bodies survive). SFC charts become real TC6 networks
//! (steps, transitions, divergences, convergences, action blocks) with
//! localIds, connections and a simple layout. The FBD and LD bodies of a
//! PLCopen file are written back as drawn ([`graphic`]), element for
//! element, so reading the output gives the same networks.

mod config;
mod drawn_chart;
mod graphic;
mod sfc;
mod types;
mod writer;
mod xml_source;

use super::diagram::{PouBody, ProjectPou};
use crate::diagnostics::Diagnostics;
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::{Body, CompilationUnit, Item, Pou, PouKind, Retain, VarBlock, VarKind};
use std::collections::HashMap;
use std::fmt;
use writer::Writer;
use xml_source::xml_bodies;

/// Why sources could not be exported.
#[derive(Debug, Clone, PartialEq)]
pub enum ExportError {
    /// A file is XML export cannot read back (a TwinCAT project).
    NotTextual {
        /// The file's name.
        file: String,
    },
    /// A file is S7-200 STL, a language TC6 XML has no body kind for.
    S7Source {
        /// The file's name.
        file: String,
    },
    /// The sources have syntax errors (rendered as `plcrun check` shows them).
    Syntax {
        /// The rendered diagnostics.
        rendered: String,
    },
    /// A construct TC6 XML has no element for.
    Unrepresentable {
        /// What it is.
        what: String,
        /// `file:line:column` where it is written.
        location: String,
    },
}

impl fmt::Display for ExportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExportError::NotTextual { file } => {
                write!(
                    f,
                    "`{file}` is XML that is not a PLCopen project; export writes IL, ST, SFC and PLCopen sources"
                )
            }
            ExportError::S7Source { file } => {
                write!(
                    f,
                    "`{file}` is S7-200 STL, which PLCopen TC6 XML has no body language for; \
                     export writes IL, ST and SFC sources"
                )
            }
            ExportError::Syntax { rendered } => {
                write!(f, "the sources have syntax errors:\n{rendered}")
            }
            ExportError::Unrepresentable { what, location } => {
                write!(f, "{location}: {what} has no PLCopen TC6 XML form")
            }
        }
    }
}

impl std::error::Error for ExportError {}

/// Writes every POU, data type and configuration of `sources` (IL, ST,
/// SFC and PLCopen files) as one PLCopen TC6 2.01 project, in the shape
/// the OpenPLC Editor and Beremiz read. The FBD and LD bodies of PLCopen
/// files are written back as drawn. The output is deterministic.
///
/// ```
/// use plcrun::{SourceMap, export_plcopen};
/// let mut sources = SourceMap::new();
/// sources.add("p.st", "PROGRAM P VAR_OUTPUT q : INT; END_VAR q := q + 1; END_PROGRAM");
/// let xml = export_plcopen(&sources)?;
/// assert!(xml.contains("<pou name=\"P\" pouType=\"program\">"));
/// # Ok::<(), plcrun::ExportError>(())
/// ```
pub fn export_plcopen(sources: &SourceMap) -> Result<String, ExportError> {
    let mut diags = Diagnostics::new();
    let mut units = Vec::new();
    let mut xml = HashMap::new();
    for (i, file) in sources.files().iter().enumerate() {
        if crate::syntax::twincat::is_twincat(&file.text) {
            return Err(ExportError::NotTextual {
                file: file.name.clone(),
            });
        }
        if super::is_plcopen(&file.text) {
            let bodies = xml_bodies(FileId(i as u32), &file.text).map_err(|what| {
                ExportError::Unrepresentable {
                    what,
                    location: file.name.clone(),
                }
            })?;
            xml.extend(bodies);
        }
        if crate::syntax::s7::recognise(&file.name, &file.text) {
            return Err(ExportError::S7Source {
                file: file.name.clone(),
            });
        }
        units.push(crate::syntax::parse(
            FileId(i as u32),
            &file.text,
            &mut diags,
        ));
    }
    if diags.has_errors() {
        return Err(ExportError::Syntax {
            rendered: diags.render(sources),
        });
    }
    Exporter { sources, xml }.project(&units, matiec_origin(sources))
}

/// True when a source is a PLCopen project of the OpenPLC Editor or
/// Beremiz: its direct addresses are numbered by the `openplc`
/// convention, and the export must say so to run the same.
fn matiec_origin(sources: &SourceMap) -> bool {
    sources
        .files()
        .iter()
        .any(|f| super::is_plcopen(&f.text) && super::origin::written_by_matiec_tools(&f.text))
}

/// The sources being exported (for the text of expressions and bodies).
struct Exporter<'s> {
    sources: &'s SourceMap,
    /// The bodies of the POUs of PLCopen files, by file and upper-case name.
    xml: HashMap<(FileId, String), ProjectPou>,
}

impl Exporter<'_> {
    /// The source text of `span`.
    fn text(&self, span: Span) -> &str {
        let text = &self.sources.file(span.file).text;
        text.get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// The text of a value at `span` (a bound, a length, an initial
    /// value): in a PLCopen file, an attribute's text with its entities
    /// decoded, so that writing it does not escape them twice.
    fn value_text(&self, span: Span) -> std::borrow::Cow<'_, str> {
        let raw = self.text(span);
        if raw.contains('&')
            && super::is_plcopen(&self.sources.file(span.file).text)
            && let Ok(decoded) = super::raw::decode(raw, 0, raw.len())
        {
            return decoded.text.into();
        }
        raw.into()
    }

    /// An [`ExportError::Unrepresentable`] at `span`.
    fn refuse(&self, what: impl Into<String>, span: Span) -> ExportError {
        ExportError::Unrepresentable {
            what: what.into(),
            location: self.sources.location(span),
        }
    }

    /// The whole project.
    fn project(&self, units: &[CompilationUnit], matiec: bool) -> Result<String, ExportError> {
        let items: Vec<&Item> = units.iter().flat_map(|u| &u.items).collect();
        let name = items
            .iter()
            .find_map(|i| match i {
                Item::Pou(p) => Some(p.name.name.as_str()),
                _ => None,
            })
            .unwrap_or("plcrun");
        let mut w = Writer::new();
        let mut root = vec![
            ("xmlns", super::NAMESPACE_0201),
            ("xmlns:xhtml", "http://www.w3.org/1999/xhtml"),
            ("xmlns:xsd", "http://www.w3.org/2001/XMLSchema"),
        ];
        if matiec {
            // The mark of Beremiz's writer (`super::origin`): the project
            // keeps the `openplc` addressing of its sources.
            root.push(("xmlns:ns1", super::NAMESPACE_0201));
        }
        w.open("project", &root);
        header(&mut w, name);
        w.open("types", &[]);
        w.open("dataTypes", &[]);
        for item in &items {
            match item {
                Item::Types(decls) => {
                    for d in decls {
                        self.data_type(&mut w, d)?;
                    }
                }
                Item::Globals(block) => {
                    return Err(
                        self.refuse("a VAR_GLOBAL list outside a CONFIGURATION", block.span)
                    );
                }
                Item::Interface(x) => return Err(self.refuse("an INTERFACE", x.span)),
                Item::Pou(p) if p.oop.is_some() => {
                    return Err(self.refuse(
                        "a FUNCTION_BLOCK with METHODs, EXTENDS or IMPLEMENTS",
                        p.span,
                    ));
                }
                _ => {}
            }
        }
        w.close("dataTypes");
        w.open("pous", &[]);
        for item in &items {
            if let Item::Pou(p) = item {
                self.pou(&mut w, p)?;
            }
        }
        w.close("pous");
        w.close("types");
        w.open("instances", &[]);
        w.open("configurations", &[]);
        for item in &items {
            if let Item::Configuration(c) = item {
                self.configuration(&mut w, c)?;
            }
        }
        w.close("configurations");
        w.close("instances");
        w.close("project");
        Ok(w.finish())
    }

    /// One POU.
    fn pou(&self, w: &mut Writer, pou: &Pou) -> Result<(), ExportError> {
        let kind = match pou.kind {
            PouKind::Program => "program",
            PouKind::Function => "function",
            PouKind::FunctionBlock => "functionBlock",
        };
        w.open("pou", &[("name", &pou.name.name), ("pouType", kind)]);
        w.open("interface", &[]);
        if let Some(ret) = &pou.return_type {
            w.open("returnType", &[]);
            self.type_spec(w, ret)?;
            w.close("returnType");
        }
        let from_xml = self
            .xml
            .get(&(pou.span.file, pou.name.name.to_ascii_uppercase()));
        for block in &pou.var_blocks {
            let hidden = from_xml.is_some_and(|x| x.range.contains(&(block.span.start as usize)));
            if !hidden {
                self.var_block(w, block)?;
            }
        }
        w.close("interface");
        if let Some(x) = from_xml {
            match &x.body {
                PouBody::Plain(body) => {
                    w.open("body", &[]);
                    graphic::body_model(w, body);
                    w.close("body");
                }
                PouBody::Chart(chart) => drawn_chart::chart_pou(w, chart),
            }
            w.close("pou");
            return Ok(());
        }
        match &pou.body {
            Body::Sfc(elements) => self.sfc_pou(w, pou, elements)?,
            Body::St(_) | Body::Il(_) => {
                let lang = if matches!(pou.body, Body::Il(_)) {
                    "IL"
                } else {
                    "ST"
                };
                w.open("body", &[]);
                w.text_body(lang, &self.pou_body_text(pou)?);
                w.close("body");
            }
        }
        w.close("pou");
        Ok(())
    }

    /// The text of a POU's body: after its last declaration, before its
    /// `END_` keyword.
    fn pou_body_text(&self, pou: &Pou) -> Result<String, ExportError> {
        let mut start = pou.name.span.end;
        if let Some(ret) = &pou.return_type {
            start = start.max(ret.span().end);
        }
        for b in &pou.var_blocks {
            start = start.max(b.span.end);
        }
        let end_kw = match pou.kind {
            PouKind::Program => "END_PROGRAM",
            PouKind::Function => "END_FUNCTION",
            PouKind::FunctionBlock => "END_FUNCTION_BLOCK",
        };
        let whole = self.text(Span { start, ..pou.span });
        let body = whole
            .len()
            .checked_sub(end_kw.len())
            .filter(|&cut| whole.is_char_boundary(cut) && whole[cut..].eq_ignore_ascii_case(end_kw))
            .map(|cut| &whole[..cut]);
        match body {
            Some(b) => Ok(trim_body(b)),
            None => Err(self.refuse(format!("a POU body not closed by {end_kw}"), pou.span)),
        }
    }

    /// One `VAR...END_VAR` block as a TC6 variable section.
    fn var_block(&self, w: &mut Writer, block: &VarBlock) -> Result<(), ExportError> {
        let name = match block.kind {
            VarKind::Local => "localVars",
            VarKind::Input => "inputVars",
            VarKind::Output => "outputVars",
            VarKind::InOut => "inOutVars",
            VarKind::External => "externalVars",
            VarKind::Global => "globalVars",
            VarKind::Temp => "tempVars",
            VarKind::Inst => return Err(self.refuse("a VAR_INST block", block.span)),
            VarKind::Stat => return Err(self.refuse("a VAR_STAT block", block.span)),
        };
        let mut attrs: Vec<(&str, &str)> = Vec::new();
        if block.constant {
            attrs.push(("constant", "true"));
        }
        match block.retain {
            Some(Retain::Retain) => attrs.push(("retain", "true")),
            Some(Retain::NonRetain) => attrs.push(("nonretain", "true")),
            Some(Retain::Persistent) => attrs.push(("persistent", "true")),
            None => {}
        }
        w.open(name, &attrs);
        for decl in &block.decls {
            self.var_decl(w, decl)?;
        }
        w.close(name);
        Ok(())
    }
}

/// `<fileHeader>` and `<contentHeader>` (fixed date: the output of one
/// source is always the same bytes).
fn header(w: &mut Writer, name: &str) {
    w.empty(
        "fileHeader",
        &[
            ("companyName", "plcrun"),
            ("productName", "plcrun"),
            ("productVersion", env!("CARGO_PKG_VERSION")),
            ("creationDateTime", "1970-01-01T00:00:00"),
        ],
    );
    w.open(
        "contentHeader",
        &[
            ("name", name),
            ("modificationDateTime", "1970-01-01T00:00:00"),
        ],
    );
    w.open("coordinateInfo", &[]);
    for lang in ["fbd", "ld", "sfc"] {
        w.open(lang, &[]);
        w.empty("scaling", &[("x", "10"), ("y", "10")]);
        w.close(lang);
    }
    w.close("coordinateInfo");
    w.close("contentHeader");
}

/// A body's text without the blank lines around it.
fn trim_body(text: &str) -> String {
    let t = text.trim_end();
    let start = t
        .char_indices()
        .take_while(|(_, c)| c.is_whitespace())
        .filter(|(_, c)| *c == '\n')
        .last()
        .map_or(0, |(i, _)| i + 1);
    format!("{}\n", &t[start..])
}
