//! Compiles the lalrpop grammars in `grammars/` into `OUT_DIR`.
fn main() {
    lalrpop::Configuration::new()
        .set_in_dir("grammars")
        // Rerun only when a grammar changes (without these directives cargo
        // reruns the script, and rebuilds the crate, after any file of the
        // package changes: a test, a doc, a script).
        .emit_rerun_directives(true)
        .process()
        .expect("lalrpop grammar failed to compile");
}
