//! What TwinCAT programs use most from the Tc2_System, Tc2_Utilities and
//! Tc2_EtherCAT libraries (`T_MaxString`, `PVOID`, `F_LTrim`, `F_RTrim`,
//! `MEMCPY`, `MEMMOVE`, `MEMSET`, `MEMCMP`, `DRAND`, the distributed-clock
//! time `T_DCTIME64` and its functions, the `*_TO_HEXSTR` conversions,
//! `F_ToLCase`, `F_ToUCase`, `GETCPUCOUNTER`, `ST_LibVersion`, the
//! ADS logger (`ADSLOGSTR`, `ADSLOGDINT`, `ADSLOGLREAL`, the
//! `ADSLOG_MSGTYPE_*` constants), `DEFAULT_ADS_TIMEOUT`, `FB_FormatString`
//! with its `T_Arg` arguments (`F_INT`, `F_LREAL`, `F_STRING`...),
//! `FB_MemRingBuffer`, the task
//! information `_TaskInfo` with `GETCURTASKINDEX`/`GETCURTASKINDEXEX`,
//! `IQueryInterface`, `F_GetTaskTime`, the AMS addresses and Tc2_EtherCAT's
//! device states with the blocks that ask for them (failing as without a
//! device), Tc3_EventLogger's `FB_TcMessage` with its arguments, source
//! and the event types (`TcEventEntry`, `TcEventSeverity`, `HRESULT`), its
//! listeners (`FB_ListenerBase`, `FB_TcEvent`, `ITcEventFilterConfig`) and
//! `FB_RequestEventText`,
//! Tc2_Utilities' `FB_HashTableCtrl` and system times (`TIMESTRUCT`,
//! `T_FILETIME`, `FB_LocalSystemTime`, time zones, `SYSTEMTIME_TO_STRING`,
//! `GUID_TO_STRING`, `LEN2`, `STRNCPY`, `FB_GetHostName`,
//! `FB_GetAdaptersInfo`, `FB_GetLocalAmsNetId`, `F_ToASC`, `F_ToCHR`),
//! the application's information `PlcAppSystemInfo`, Tc2_TcpIp's UDP
//! socket blocks, Tc3_JsonXml's `FB_JsonSaxWriter`,
//! `FB_JsonReadWriteDataType` and `FB_JsonDomParser` (with `SJsonValue`),
//! Tc2_Standard's `WLEN`, and the Base Interfaces library's `TypeClass`),
//! written in ST by plcrun
//! (`twincat_library.st`) and added as a source of its own when the
//! sources hold a TwinCAT file: the items they use and what those use. An
//! item the sources declare themselves is left out: theirs wins. Warnings inside it (its `POINTER TO` is a
//! CODESYS extension, for instance) are not the user's and are dropped, and
//! so are the CODESYS-extension warnings of TwinCAT files.

use crate::diagnostics::{Diagnostics, Severity};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::Item;
use crate::syntax::token::{Kw, Tok};
use std::collections::HashSet;

/// The warning for an attribute only tools read (`{attribute 'pytmc'}`):
/// not shown for TwinCAT files, where such attributes are everywhere.
const TOOL_ATTRIBUTE: &str = "W155";
/// The name of the library's source file.
pub(crate) const LIBRARY_SOURCE: &str = "<TwinCAT libraries>";
const LIBRARY: &str = include_str!("twincat_library.st");
/// Tc2_MC2's motion blocks over simulated NC axes, in a file of its own
/// (`twincat_motion.st`; docs/twincat.md, "Motion control").
const MOTION: &str = include_str!("twincat_motion.st");
/// The marker that starts each item of the library text.
const ITEM: &str = "(*@ITEM ";

/// The library's items: (name, text).
fn items() -> impl Iterator<Item = (&'static str, &'static str)> {
    let chunks = LIBRARY.split(ITEM).skip(1);
    chunks
        .chain(MOTION.split(ITEM).skip(1))
        .filter_map(|chunk| {
            let (name, _) = chunk.split_once(" *)")?;
            Some((name.trim(), chunk))
        })
}

/// The names (upper case) of the POUs, types and interfaces `sources`
/// declare. Global variables are not counted: a variable may be named
/// like a type, case aside (TcUnit's `GetCpuCounter : GETCPUCOUNTER;`).
fn declared(sources: &SourceMap) -> HashSet<String> {
    let mut names = HashSet::new();
    for (i, file) in sources.files().iter().enumerate() {
        let unit = crate::syntax::parse_source(FileId(i as u32), file, &mut Diagnostics::new());
        for item in unit.items {
            match item {
                Item::Pou(p) => {
                    names.insert(p.name.key());
                }
                Item::Types(ts) => names.extend(ts.iter().map(|t| t.name.key())),
                Item::Interface(i) => {
                    names.insert(i.name.key());
                }
                // A global variable may bear its type's name
                // (`GetCpuCounter : GETCPUCOUNTER;`, TcUnit): it does not
                // replace the library's POU or type.
                Item::Globals(_) | Item::Configuration(_) => {}
            }
        }
    }
    names
}

/// The names (upper case) an item of the library declares, read from its
/// tokens (a parse of every item took a noticeable part of a small
/// compile): the name after `FUNCTION`, `FUNCTION_BLOCK`, `PROGRAM` or
/// `INTERFACE`; in a `TYPE`, each type name and enumeration value; in a
/// `VAR_GLOBAL` block, each variable. The test `declared_names_are_found`
/// checks this against the parser.
fn declares(tokens: &[Tok]) -> HashSet<String> {
    let mut names = HashSet::new();
    let (mut in_type, mut in_globals, mut depth) = (false, false, 0usize);
    for (k, t) in tokens.iter().enumerate() {
        let next = tokens.get(k + 1);
        match t {
            Tok::Kw(Kw::Type) => in_type = true,
            Tok::Kw(Kw::EndType) => in_type = false,
            Tok::Kw(Kw::VarGlobal) => in_globals = true,
            Tok::Kw(Kw::EndVar) => in_globals = false,
            Tok::LParen => depth += 1,
            Tok::RParen => depth = depth.saturating_sub(1),
            Tok::Kw(Kw::Function | Kw::FunctionBlock | Kw::Program | Kw::Interface) => {
                if let Some(Tok::Ident(n)) = next {
                    names.insert(n.to_ascii_uppercase());
                }
            }
            Tok::Ident(n) => {
                let declared = match (in_type, in_globals, depth) {
                    (true, _, 0) | (_, true, 0) => matches!(next, Some(Tok::Colon | Tok::Comma)),
                    (true, _, _) => matches!(next, Some(Tok::Comma | Tok::RParen | Tok::Assign)),
                    _ => false,
                };
                if declared {
                    names.insert(n.to_ascii_uppercase());
                }
            }
            _ => {}
        }
    }
    names
}

/// One item of the library, read once.
struct LibraryItem {
    /// Its name in the `(*@ITEM name *)` marker.
    name: &'static str,
    /// Its text, marker included.
    text: &'static str,
    /// The names (upper case) it declares.
    declares: HashSet<String>,
    /// The identifiers (upper case) its code uses.
    uses: HashSet<String>,
}

/// The library's items, read once.
fn catalogue() -> &'static [LibraryItem] {
    static CATALOGUE: std::sync::OnceLock<Vec<LibraryItem>> = std::sync::OnceLock::new();
    CATALOGUE.get_or_init(|| {
        items()
            .map(|(name, text)| {
                // Its tokens: comments left aside (they name other items
                // in prose).
                let mut scratch = Diagnostics::new();
                let tokens: Vec<Tok> = crate::syntax::lexer::lex(FileId(0), text, &mut scratch)
                    .into_iter()
                    .map(|(_, t, _)| t)
                    .filter(|t| *t != Tok::Eol)
                    .collect();
                let uses = tokens
                    .iter()
                    .filter_map(|t| match t {
                        Tok::Ident(n) => Some(n.to_ascii_uppercase()),
                        _ => None,
                    })
                    .collect();
                LibraryItem {
                    name,
                    text,
                    declares: declares(&tokens),
                    uses,
                }
            })
            .collect()
    })
}

/// Adds the library to `sources` when one of them is a TwinCAT file and
/// it is not there yet: the items the sources use (a name one of them
/// declares appears in a source), then those these items use, and so on;
/// none the sources declare themselves. An unused item costs nothing to
/// compile, and a program without `_TaskInfo` pays nothing for it.
pub(crate) fn add_library(sources: &mut SourceMap) {
    let files = sources.files();
    if files.iter().any(|f| f.name == LIBRARY_SOURCE)
        || !files
            .iter()
            .any(|f| crate::syntax::twincat::is_twincat(&f.text))
    {
        return;
    }
    let declared = declared(sources);
    let mut used = HashSet::new();
    for f in files {
        crate::syntax::twincat::identifiers(&f.text, &mut used);
        // A type description's event classes name `TcEventEntry` in the
        // declarations the reader writes, not in the file's text.
        let needed = crate::syntax::twincat::type_description::library_names(&f.text);
        used.extend(needed.iter().map(|n| n.to_ascii_uppercase()));
    }
    let catalogue = catalogue();
    let mut chosen = vec![false; catalogue.len()];
    loop {
        let mut grew = false;
        for (k, item) in catalogue.iter().enumerate() {
            if chosen[k]
                || declared.contains(&item.name.to_ascii_uppercase())
                || !item.declares.iter().any(|n| used.contains(n))
            {
                continue;
            }
            chosen[k] = true;
            used.extend(item.uses.iter().cloned());
            grew = true;
        }
        if !grew {
            break;
        }
    }
    let text: String = catalogue
        .iter()
        .zip(&chosen)
        .filter(|(_, c)| **c)
        .map(|(item, _)| format!("{ITEM}{}{}", item.name, &item.text[item.name.len()..]))
        .collect();
    if !text.is_empty() {
        sources.add(LIBRARY_SOURCE, text);
    }
}

/// True for the warnings of a CODESYS extension (`W300`-`W399`), which
/// `--strict` makes errors.
fn is_extension_warning(code: &str) -> bool {
    code.starts_with("W3")
}

/// The diagnostics of a compile of `sources` without those that are not
/// the user's news: the library's warnings, and in TwinCAT files the
/// warnings that a CODESYS extension is used (TwinCAT code is written in
/// that dialect; `--strict` still makes them errors). An error inside the
/// library (which its tests rule out) is moved to the start of the first
/// file, naming the library, so that it can be shown with sources that do
/// not hold the library.
pub(crate) fn drop_expected_warnings(sources: &SourceMap, diags: Diagnostics) -> Diagnostics {
    let files = sources.files();
    let twincat: Vec<bool> = files
        .iter()
        .map(|f| crate::syntax::twincat::is_twincat(&f.text))
        .collect();
    if !twincat.contains(&true) {
        return diags;
    }
    let mut out = Diagnostics::new();
    for mut d in diags.iter().cloned() {
        let file = d.span.file.0 as usize;
        let in_library = files.get(file).is_some_and(|f| f.name == LIBRARY_SOURCE);
        let warning = d.severity == Severity::Warning;
        if in_library && !warning {
            d.message = format!("in plcrun's TwinCAT library: {}", d.message);
            d.span = Span::new(FileId(0), 0, 0);
        } else if (in_library && warning)
            || (warning
                && twincat.get(file) == Some(&true)
                && (is_extension_warning(d.code) || d.code == TOOL_ATTRIBUTE))
        {
            continue;
        }
        out.push(d);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A TwinCAT file that names `names` in its body.
    fn naming(names: &str) -> SourceMap {
        let mut sources = SourceMap::new();
        sources.add(
            "P.TcPOU",
            format!("<?xml version=\"1.0\"?><TcPlcObject><POU Name=\"P\"><Declaration><![CDATA[PROGRAM P]]></Declaration><Implementation><ST><![CDATA[(* {names} *)]]></ST></Implementation></POU></TcPlcObject>"),
        );
        add_library(&mut sources);
        sources
    }

    fn library_items(sources: &SourceMap) -> Vec<String> {
        let Some(lib) = sources.files().iter().find(|f| f.name == LIBRARY_SOURCE) else {
            return Vec::new();
        };
        lib.text
            .split(ITEM)
            .skip(1)
            .filter_map(|c| c.split_once(" *)").map(|(n, _)| n.trim().to_string()))
            .collect()
    }

    #[test]
    fn only_the_items_a_program_uses_are_added_with_what_they_use() {
        assert!(library_items(&naming("nothing here")).is_empty());
        // FB_FormatString brings its helpers, T_Arg, E_ArgType, MEMCPY...
        let items = library_items(&naming("fb : FB_FormatString"));
        for needed in [
            "FB_FormatString",
            "plcrun_FormatArg",
            "T_Arg",
            "E_ArgType",
            "MEMCPY",
            "T_MaxString",
        ] {
            assert!(
                items.iter().any(|i| i == needed),
                "{needed} missing from {items:?}"
            );
        }
        assert!(!items.iter().any(|i| i == "_TaskInfo"), "{items:?}");
        // An enumeration value alone brings its type.
        assert_eq!(library_items(&naming("ARGTYPE_INT")), ["E_ArgType"]);
    }

    /// What the parser says each item declares.
    fn parsed_declares(text: &str) -> HashSet<String> {
        let file = crate::source::SourceFile::new(LIBRARY_SOURCE, text);
        let unit = crate::syntax::parse_source(FileId(0), &file, &mut Diagnostics::new());
        let mut names = HashSet::new();
        for item in unit.items {
            match item {
                Item::Pou(p) => {
                    names.insert(p.name.key());
                }
                Item::Types(ts) => {
                    for t in ts {
                        names.insert(t.name.key());
                        if let crate::syntax::ast::TypeSpec::Enum { values, .. } = &t.ty {
                            names.extend(values.iter().map(|(v, _)| v.key()));
                        }
                    }
                }
                Item::Interface(i) => {
                    names.insert(i.name.key());
                }
                Item::Globals(b) => {
                    names.extend(b.decls.iter().flat_map(|d| &d.names).map(|n| n.key()))
                }
                Item::Configuration(_) => {}
            }
        }
        names
    }

    #[test]
    fn declared_names_are_found() {
        for item in catalogue() {
            let parsed = parsed_declares(item.text);
            let missing: Vec<&String> = parsed.difference(&item.declares).collect();
            assert!(missing.is_empty(), "{}: {missing:?} not found", item.name);
        }
    }

    #[test]
    fn the_whole_library_compiles_without_an_error() {
        let every: String = catalogue()
            .iter()
            .flat_map(|item| item.declares.iter().map(|n| format!("{n} ")))
            .collect();
        let sources = naming(&every);
        assert_eq!(library_items(&sources).len(), catalogue().len());
        let report = crate::check(&sources, &crate::CheckOptions::default());
        assert!(
            !report.diagnostics.has_errors(),
            "{}",
            report.diagnostics.render(&sources)
        );
    }

    #[test]
    fn every_item_is_named_and_the_names_are_distinct() {
        let names: Vec<&str> = items().map(|(n, _)| n).collect();
        assert!(names.len() > 90, "{names:?}");
        let mut seen = HashSet::new();
        for name in &names {
            assert!(
                !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'),
                "{name:?}"
            );
            assert!(seen.insert(name.to_ascii_uppercase()), "{name} twice");
        }
    }
}
