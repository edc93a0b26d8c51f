//! Helpers of the FBD and LD import tests: random stimulus for BOOL and
//! INT inputs, twin comparison (a graphical project and its hand-written
//! ST twin must print the same trace), one-POU projects, diagnostics.
#![allow(dead_code)]

use super::library;
use super::rng;

// Each test file uses its own part of these.
#[allow(unused_imports)]
pub use library::{TraceRequest, csv_trace, repo_text, run_csv};
use plcrun::{CheckOptions, SourceMap, check};
use rng::Rng;

/// A stimulus CSV of `rows` cycles: every name in `bools` random TRUE or
/// FALSE (one time in three TRUE), every name in `ints` random in 0..10.
pub fn random_stimulus(bools: &[&str], ints: &[&str], rows: u64, seed: u64) -> String {
    let mut rng = Rng(seed.max(1));
    let mut csv = String::from("cycle");
    for n in bools.iter().chain(ints) {
        csv.push(',');
        csv.push_str(n);
    }
    csv.push('\n');
    for row in 0..rows {
        csv.push_str(&row.to_string());
        for _ in bools {
            csv.push_str(if rng.chance(33) { ",TRUE" } else { ",FALSE" });
        }
        for _ in ints {
            csv.push_str(&format!(",{}", rng.below(10)));
        }
        csv.push('\n');
    }
    csv
}

/// The trace of `names` over `stimulus` for the files at `paths`.
pub fn trace_of(paths: &[&str], names: &str, stimulus: &str, cycles: u64) -> String {
    let files: Vec<(String, String)> = paths
        .iter()
        .map(|p| (p.to_string(), repo_text(p)))
        .collect();
    let request = TraceRequest {
        cycles,
        stimulus: Some(stimulus),
        trace: Some(names),
        changes_only: false,
    };
    csv_trace(&files, &request)
}

/// The trace of `names` for a project given as text (an empty
/// `stimulus`: none).
pub fn trace_text(xml: &str, names: &str, stimulus: &str, cycles: u64) -> String {
    let request = TraceRequest {
        cycles,
        stimulus: (!stimulus.is_empty()).then_some(stimulus),
        trace: Some(names),
        changes_only: false,
    };
    csv_trace(&[("t.xml", xml)], &request)
}

/// Panics with the first differing line when two traces differ.
pub fn assert_same(left: &str, right: &str, what: &str) {
    if left == right {
        return;
    }
    let at = left
        .lines()
        .zip(right.lines())
        .position(|(a, b)| a != b)
        .map_or(String::from("(lengths differ)"), |i| {
            format!(
                "line {}:\n  {}\n  {}\n{}",
                i + 1,
                left.lines().nth(i).unwrap_or(""),
                right.lines().nth(i).unwrap_or(""),
                left.lines().next().unwrap_or("")
            )
        });
    panic!("{what}: traces differ at {at}");
}

/// One column of a CSV trace, as text cells.
pub fn column(trace: &str, name: &str) -> Vec<String> {
    let mut lines = trace.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    lines
        .map(|l| l.split(',').nth(col).unwrap_or("").to_string())
        .collect()
}

/// `1`/`0` for the TRUE/FALSE cells of a column.
pub fn bits(trace: &str, name: &str) -> String {
    column(trace, name)
        .iter()
        .map(|c| if c == "TRUE" { '1' } else { '0' })
        .collect()
}

/// A stimulus of BOOL columns, each given as a string of `1`/`0` per cycle.
pub fn bit_stimulus(columns: &[(&str, &str)]) -> String {
    let rows = columns.iter().map(|c| c.1.len()).max().unwrap_or(0);
    let mut csv = String::from("cycle");
    for (n, _) in columns {
        csv.push(',');
        csv.push_str(n);
    }
    csv.push('\n');
    for r in 0..rows {
        csv.push_str(&r.to_string());
        for (_, bits) in columns {
            let on = bits.as_bytes().get(r) == Some(&b'1');
            csv.push_str(if on { ",TRUE" } else { ",FALSE" });
        }
        csv.push('\n');
    }
    csv
}

/// A project with the given `<pou>` texts.
pub fn project(pous: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\" xmlns:xhtml=\"http://www.w3.org/1999/xhtml\">\n<fileHeader companyName=\"x\" productName=\"x\" productVersion=\"1\" creationDateTime=\"2026-01-01T00:00:00\"/>\n<contentHeader name=\"x\"/>\n<types><dataTypes/><pous>\n{pous}\n</pous></types>\n<instances><configurations/></instances>\n</project>\n"
    )
}

/// `(code, file:line:col, message)` of every diagnostic of `text` as `t.xml`.
pub fn diagnostics(text: &str) -> Vec<(String, String, String)> {
    let mut sources = SourceMap::new();
    sources.add("t.xml", text);
    let report = check(&sources, &CheckOptions::default());
    report
        .diagnostics
        .iter()
        .map(|d| {
            (
                d.code.to_string(),
                sources.location(d.span),
                d.message.clone(),
            )
        })
        .collect()
}

/// `t.xml:line:col` of the first occurrence of `needle` in `text`.
pub fn location_of(text: &str, needle: &str) -> String {
    let at = text.find(needle).unwrap_or_else(|| panic!("no {needle}"));
    let line = text[..at].matches('\n').count() + 1;
    let col = text[..at].rsplit('\n').next().unwrap_or("").chars().count() + 1;
    format!("t.xml:{line}:{col}")
}

/// The errors of `text`.
pub fn errors(text: &str) -> Vec<(String, String, String)> {
    diagnostics(text)
        .into_iter()
        .filter(|d| d.0.starts_with('E'))
        .collect()
}

/// `<connectionPointIn>` with a connection to each of `refs` (`"7"`, or
/// `"7:OUT"` for an output pin of a block).
pub fn point(refs: &[&str]) -> String {
    let mut s = String::from("<connectionPointIn>");
    for r in refs {
        match r.split_once(':') {
            Some((id, pin)) => s.push_str(&format!(
                "<connection refLocalId=\"{id}\" formalParameter=\"{pin}\"/>"
            )),
            None => s.push_str(&format!("<connection refLocalId=\"{r}\"/>")),
        }
    }
    s.push_str("</connectionPointIn>");
    s
}

/// `<inVariable>` at row `y`.
pub fn in_var(id: u32, expr: &str, y: u32) -> String {
    format!(
        "<inVariable localId=\"{id}\"><position x=\"10\" y=\"{y}\"/><connectionPointOut/><expression>{expr}</expression></inVariable>"
    )
}

/// `<outVariable>` at row `y` (`extra`: more attributes).
pub fn out_var(id: u32, expr: &str, from: &[&str], y: u32, extra: &str) -> String {
    format!(
        "<outVariable localId=\"{id}\"{extra}><position x=\"300\" y=\"{y}\"/>{}<expression>{expr}</expression></outVariable>",
        point(from)
    )
}

/// `<block>` at row `y`: `inputs` as `(pin, refs)`, `outputs` pin names.
pub fn block(
    id: u32,
    ty: &str,
    y: u32,
    inputs: &[(&str, &[&str])],
    outputs: &[&str],
    extra: &str,
) -> String {
    let ins: String = inputs
        .iter()
        .map(|(p, r)| format!("<variable formalParameter=\"{p}\">{}</variable>", point(r)))
        .collect();
    let outs: String = outputs
        .iter()
        .map(|p| format!("<variable formalParameter=\"{p}\"><connectionPointOut/></variable>"))
        .collect();
    format!(
        "<block localId=\"{id}\" typeName=\"{ty}\"{extra}><position x=\"100\" y=\"{y}\"/><inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables>{outs}</outputVariables></block>"
    )
}

/// A `<pou>` with an interface (its inner XML) and an `<FBD>` or `<LD>` body.
pub fn graphic_pou(name: &str, kind: &str, iface: &str, lang: &str, elements: &[String]) -> String {
    format!(
        "<pou name=\"{name}\" pouType=\"{kind}\"><interface>{iface}</interface><body><{lang}>\n{}\n</{lang}></body></pou>",
        elements.join("\n")
    )
}

/// `<variable name><type><T/></type></variable>` for each `name:T`.
pub fn vars(section: &str, list: &[&str]) -> String {
    let vs: String = list
        .iter()
        .map(|v| {
            let (n, t) = v.split_once(':').unwrap_or((v, "BOOL"));
            let elementary = [
                "BOOL", "INT", "DINT", "UINT", "REAL", "LREAL", "TIME", "WORD", "DT",
            ];
            let ty = if elementary.contains(&t) {
                format!("<{t}/>")
            } else {
                format!("<derived name=\"{t}\"/>")
            };
            format!("<variable name=\"{n}\"><type>{ty}</type></variable>")
        })
        .collect();
    format!("<{section}>{vs}</{section}>")
}
