//! What TwinCAT programs use most from the Tc2_System, Tc2_Utilities and
//! Tc2_EtherCAT libraries (`T_MaxString`, `PVOID`, `F_LTrim`, `F_RTrim`,
//! `MEMCPY`, `MEMMOVE`, `MEMSET`, `MEMCMP`, `DRAND`, the distributed-clock
//! time `T_DCTIME64` and its functions, the `*_TO_HEXSTR` conversions,
//! `F_ToLCase`, `F_ToUCase`, `GETCPUCOUNTER`, `ST_LibVersion`, the
//! `ADSLOG_MSGTYPE_*` constants, `DEFAULT_ADS_TIMEOUT`, `FB_FormatString`
//! with its `T_Arg` arguments (`F_INT`, `F_LREAL`, `F_STRING`...),
//! `FB_MemRingBuffer`, the task
//! information `_TaskInfo` with `GETCURTASKINDEX`/`GETCURTASKINDEXEX`,
//! `IQueryInterface`,
//! Tc2_Standard's `WLEN`, and the Base Interfaces library's `TypeClass`),
//! written in ST by plcrun
//! (`twincat_library.st`) and added as a source of its own when the
//! sources hold a TwinCAT file. An item the sources declare themselves is
//! left out: theirs wins. Warnings inside it (its `POINTER TO` is a
//! CODESYS extension, for instance) are not the user's and are dropped, and
//! so are the CODESYS-extension warnings of TwinCAT files.

use crate::diagnostics::{Diagnostics, Severity};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::Item;
use std::collections::HashSet;

/// The name of the library's source file.
pub(crate) const LIBRARY_SOURCE: &str = "<TwinCAT libraries>";
const LIBRARY: &str = include_str!("twincat_library.st");
/// The marker that starts each item of the library text.
const ITEM: &str = "(*@ITEM ";

/// The library's items: (name, text).
fn items() -> impl Iterator<Item = (&'static str, &'static str)> {
    LIBRARY.split(ITEM).skip(1).filter_map(|chunk| {
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

/// Adds the library to `sources` when one of them is a TwinCAT file and
/// it is not there yet.
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
    let text: String = items()
        .filter(|(name, _)| !declared.contains(&name.to_ascii_uppercase()))
        .map(|(name, chunk)| format!("{ITEM}{name}{}", &chunk[name.len()..]))
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
            || (warning && twincat.get(file) == Some(&true) && is_extension_warning(d.code))
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

    #[test]
    fn every_item_is_named_and_the_names_are_distinct() {
        let names: Vec<&str> = items().map(|(n, _)| n).collect();
        assert_eq!(
            names,
            [
                "T_MaxString",
                "PVOID",
                "F_LTrim",
                "F_RTrim",
                "MEMCPY",
                "MEMMOVE",
                "MEMSET",
                "MEMCMP",
                "DRAND",
                "T_DCTIME64",
                "F_GetCurDcTaskTime64",
                "F_GetCurDcTickTime64",
                "F_GetActualDcTime64",
                "DCTIME64_TO_STRING",
                "WLEN",
                "LWORD_TO_HEXSTR",
                "DWORD_TO_HEXSTR",
                "WORD_TO_HEXSTR",
                "BYTE_TO_HEXSTR",
                "F_ToLCase",
                "F_ToUCase",
                "GETCPUCOUNTER",
                "ST_LibVersion",
                "TypeClass",
                "WRITE_PROTECTED_BOOL",
                "WRITE_PROTECTED_BYTE",
                "WRITE_PROTECTED_WORD",
                "WRITE_PROTECTED_DWORD",
                "WRITE_PROTECTED_SINT",
                "WRITE_PROTECTED_USINT",
                "WRITE_PROTECTED_INT",
                "WRITE_PROTECTED_UINT",
                "WRITE_PROTECTED_DINT",
                "WRITE_PROTECTED_UDINT",
                "WRITE_PROTECTED_REAL",
                "WRITE_PROTECTED_LREAL",
                "WRITE_PROTECTED_LINT",
                "WRITE_PROTECTED_ULINT",
                "WRITE_PROTECTED_LWORD",
                "WRITE_PROTECTED_TIME",
                "IQueryInterface",
                "PlcTaskSystemInfo",
                "_TaskInfo",
                "GETCURTASKINDEX",
                "GETCURTASKINDEXEX",
                "DEFAULT_ADS_TIMEOUT",
                "ADSLOG_MSGTYPE",
                "E_ArgType",
                "T_Arg",
                "F_BYTE",
                "F_WORD",
                "F_DWORD",
                "F_LWORD",
                "F_REAL",
                "F_LREAL",
                "F_SINT",
                "F_INT",
                "F_DINT",
                "F_USINT",
                "F_UINT",
                "F_UDINT",
                "F_STRING",
                "F_BOOL",
                "F_LARGE",
                "F_ULARGE",
                "F_BIGTYPE",
                "plcrun_Digits",
                "plcrun_Fixed",
                "plcrun_FormatArg",
                "FB_FormatString",
                "FB_MemRingBuffer",
            ]
        );
    }
}
