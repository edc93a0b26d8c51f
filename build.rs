//! Compiles the lalrpop grammars in `grammars/` into `OUT_DIR`.
fn main() {
    lalrpop::Configuration::new()
        .set_in_dir("grammars")
        .process()
        .expect("lalrpop grammar failed to compile");
}
