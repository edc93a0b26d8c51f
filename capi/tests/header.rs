//! include/plcrun.h is written by hand (no cbindgen: one more build-time
//! dependency tree on a small machine, for a header of thirty lines of
//! declarations). These tests keep it honest: every exported entry point of
//! capi/src is declared with the same parameter and return types and
//! nothing else is; the status codes and the interface version agree; the
//! C compiler sees the same struct layouts as Rust.

#[path = "support/c_build.rs"]
mod c_build;

use std::collections::BTreeMap;
use std::mem::{offset_of, size_of};
use std::process::Command;

/// A function's canonical signature: return type, then parameter types,
/// spelled the C way (`const char*`, `plc_handle`).
type Signatures = BTreeMap<String, String>;

/// Removes `/* */` and `//` comments and preprocessor lines.
fn strip_c(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find("/*") {
        out.push_str(&rest[..start]);
        let end = rest[start..].find("*/").expect("closed comment") + start + 2;
        rest = &rest[end..];
    }
    out.push_str(rest);
    out.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .filter(|l| !l.trim_start().starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `const  char *` → `const char*`.
fn canonical(ty: &str) -> String {
    let words = ty.split_whitespace().collect::<Vec<_>>().join(" ");
    words.replace(" *", "*").replace("* ", "*")
}

/// The declared type of a C parameter (its name removed).
fn c_param_type(param: &str) -> String {
    let p = param.trim();
    let name_start = p
        .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    canonical(&p[..name_start])
}

fn header_signatures(header: &str) -> Signatures {
    let text = strip_c(header);
    let mut sigs = Signatures::new();
    for decl in text.split(';') {
        let Some(open) = decl.find('(') else { continue };
        let head = decl[..open].trim();
        let Some(name_at) = head.rfind("plc_") else {
            continue;
        };
        let name = &head[name_at..];
        let ret = canonical(&head[..name_at]);
        let ret = ret.rsplit('}').next().unwrap_or(&ret).trim().to_string();
        let params = decl[open + 1..decl.rfind(')').expect("closing parenthesis")].trim();
        let mut types = vec![ret];
        if params != "void" {
            types.extend(params.split(',').map(c_param_type));
        }
        assert!(
            sigs.insert(name.to_string(), types.join(" | ")).is_none(),
            "{name} is declared twice"
        );
    }
    sigs
}

/// A Rust FFI type, spelled the C way.
fn c_spelling(rust: &str) -> String {
    let t = rust.trim();
    if let Some(inner) = t.strip_prefix("*const ") {
        return format!("const {}*", c_spelling(inner));
    }
    if let Some(inner) = t.strip_prefix("*mut ") {
        return format!("{}*", c_spelling(inner));
    }
    match t {
        "c_int" => "int",
        "c_char" => "char",
        "bool" => "bool",
        "i64" => "int64_t",
        "u64" => "uint64_t",
        "u32" => "uint32_t",
        "u16" => "uint16_t",
        "u8" => "uint8_t",
        "f64" => "double",
        "usize" => "size_t",
        "PlcHandle" => "plc_handle",
        "PlcVar" => "plc_var",
        "PlcSource" => "plc_source",
        "PlcOptions" => "plc_options",
        "PlcStop" => "plc_stop",
        other => panic!("no C spelling for the Rust type `{other}`: extend this test"),
    }
    .to_string()
}

/// The `#[unsafe(no_mangle)] extern "C"` functions of capi/src (test
/// modules, at the end of a file after `#[cfg(test)]`, left out).
fn rust_signatures() -> Signatures {
    let mut sigs = Signatures::new();
    let dir = c_build::repo_root().join("capi/src");
    for entry in std::fs::read_dir(&dir).expect("capi/src") {
        let path = entry.expect("entry").path();
        let text = std::fs::read_to_string(&path).expect("read a source");
        let text = text.split("#[cfg(test)]").next().unwrap_or("");
        for item in text.split("#[unsafe(no_mangle)]").skip(1) {
            let at = item
                .find("extern \"C\" fn ")
                .expect("an extern \"C\" fn after no_mangle");
            let rest = &item[at + "extern \"C\" fn ".len()..];
            let open = rest.find('(').expect("parameters");
            let close = rest.find(')').expect("end of parameters");
            let name = rest[..open].trim();
            let body = rest.find('{').expect("body");
            let ret = rest[close + 1..body].trim();
            let ret = ret
                .strip_prefix("->")
                .map_or("void".to_string(), c_spelling);
            let mut types = vec![ret];
            types.extend(
                rest[open + 1..close]
                    .split(',')
                    .filter(|p| !p.trim().is_empty())
                    .map(|p| c_spelling(p.split_once(':').expect("name: type").1)),
            );
            sigs.insert(name.to_string(), types.join(" | "));
        }
    }
    sigs
}

#[test]
fn the_header_declares_every_entry_point_with_its_rust_signature() {
    let header = header_signatures(&c_build::repo_text("include/plcrun.h"));
    let rust = rust_signatures();
    assert!(rust.len() >= 30, "found only {} entry points", rust.len());
    assert!(rust.contains_key("plc_create") && rust.contains_key("plc_var_set_f64"));
    for (name, sig) in &rust {
        assert_eq!(header.get(name), Some(sig), "{name}: header vs capi/src");
    }
    for name in header.keys() {
        assert!(
            rust.contains_key(name),
            "{name} is declared but not defined"
        );
    }
}

#[test]
fn the_header_and_the_library_have_the_same_status_codes_and_version() {
    let header = strip_c(&c_build::repo_text("include/plcrun.h"));
    let status_rs = c_build::repo_text("capi/src/status.rs");
    let pairs = |text: &str, sep: &str| -> BTreeMap<String, i32> {
        text.lines()
            .filter_map(|l| {
                let l = l.trim().trim_start_matches("pub const ");
                let (name, value) = l.split_once(sep)?;
                let value = value.trim().trim_end_matches([',', ';']);
                Some((name.trim().to_string(), value.parse().ok()?))
            })
            .filter(|(n, _): &(String, i32)| n.starts_with("PLC_OK") || n.starts_with("PLC_E_"))
            .collect()
    };
    let in_header = pairs(&header, " = ");
    let in_rust = pairs(&status_rs.replace(": c_int =", " ="), " = ");
    assert_eq!(in_header.len(), 21);
    assert_eq!(in_header, in_rust);
    for code in in_header.values() {
        let text = unsafe { std::ffi::CStr::from_ptr(plcrun_capi::plc_status_text(*code)) };
        assert_ne!(text.to_str().unwrap(), "unknown status");
    }
    let version = c_build::repo_text("include/plcrun.h")
        .lines()
        .find_map(|l| l.strip_prefix("#define PLC_ABI_VERSION "))
        .map(|v| v.trim().parse::<i32>().unwrap());
    assert_eq!(version, Some(plcrun_capi::PLC_ABI_VERSION));
    assert_eq!(plcrun_capi::plc_abi_version(), plcrun_capi::PLC_ABI_VERSION);
}

#[test]
fn c_and_rust_agree_on_the_struct_layouts() {
    use plcrun_capi::{PlcHandle, PlcOptions, PlcSource, PlcStop, PlcVar};
    let probe = std::env::temp_dir().join(format!("plcrun-layout-{}.c", std::process::id()));
    std::fs::write(
        &probe,
        "#include <stddef.h>\n#include <stdio.h>\n#include \"plcrun.h\"\n\
         int main(void) {\n\
         printf(\"%zu %zu %zu %zu %zu %zu %zu %zu %zu %zu\\n\",\n\
         sizeof(plc_handle), sizeof(plc_var), sizeof(plc_stop), sizeof(plc_source),\n\
         offsetof(plc_source, text), sizeof(plc_options),\n\
         offsetof(plc_options, cycle_time_ns), offsetof(plc_options, program),\n\
         offsetof(plc_options, watchdog_ns), sizeof(bool));\n\
         return 0;\n}\n",
    )
    .expect("write the probe");
    let exe = c_build::compile(probe.to_str().unwrap(), "layout");
    let out = Command::new(exe).output().expect("run the probe");
    let want = format!(
        "{} {} {} {} {} {} {} {} {} {}\n",
        size_of::<PlcHandle>(),
        size_of::<PlcVar>(),
        size_of::<PlcStop>(),
        size_of::<PlcSource>(),
        offset_of!(PlcSource, text),
        size_of::<PlcOptions>(),
        offset_of!(PlcOptions, cycle_time_ns),
        offset_of!(PlcOptions, program),
        offset_of!(PlcOptions, watchdog_ns),
        size_of::<bool>(),
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), want);
}
