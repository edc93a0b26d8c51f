//! TwinCAT object files written in memory for the tests of the dialect:
//! a `.TcPOU` with its actions, a `.TcDUT` or `.TcGVL`, and the compile of
//! a set of them with `P` as the program.

/// The start of every TwinCAT object file.
pub const HEAD: &str =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n";

/// A `.TcPOU` holding `declaration`, an ST `body`, then `inner` (actions,
/// methods).
pub fn pou(name: &str, declaration: &str, body: &str, inner: &str) -> String {
    format!(
        "{HEAD}<POU Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000001}}\" SpecialFunc=\"None\">\n<Declaration><![CDATA[{declaration}]]></Declaration>\n<Implementation><ST><![CDATA[{body}]]></ST></Implementation>\n{inner}</POU>\n</TcPlcObject>\n"
    )
}

/// An `<Action>` of a POU.
pub fn action(name: &str, body: &str) -> String {
    format!(
        "<Action Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000009}}\"><Implementation><ST><![CDATA[{body}]]></ST></Implementation></Action>\n"
    )
}

/// A `<Method>` of a POU.
pub fn method(declaration: &str, body: &str) -> String {
    format!(
        "<Method Name=\"M\" Id=\"{{00000000-0000-0000-0000-000000000019}}\"><Declaration><![CDATA[{declaration}]]></Declaration><Implementation><ST><![CDATA[{body}]]></ST></Implementation></Method>\n"
    )
}

/// A `.TcDUT` (or, with `tag` "GVL", a `.TcGVL`) holding `declaration`.
pub fn declaration(tag: &str, name: &str, declaration: &str) -> String {
    format!(
        "{HEAD}<{tag} Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000002}}\">\n<Declaration><![CDATA[{declaration}]]></Declaration>\n</{tag}>\n</TcPlcObject>\n"
    )
}

/// Compiles `files` (name, text) with `P` as the program.
pub fn compile(files: &[(&str, &str)]) -> Result<plcrun::Plc, plcrun::CompileError> {
    let options = plcrun::Options {
        program: Some("P".into()),
        ..Default::default()
    };
    plcrun::Plc::compile_files(files, &options)
}

/// The rendered diagnostics of sources that must not compile.
pub fn refused(files: &[(&str, &str)]) -> String {
    match compile(files) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.to_string(),
    }
}

/// The PLC of sources that must compile.
pub fn compile_ok(files: &[(&str, &str)]) -> plcrun::Plc {
    compile(files).unwrap_or_else(|e| panic!("compile error:\n{e}"))
}
