//! Temporary dump helper (run with `--ignored --nocapture`).
use plcrun::diagnostics::Diagnostics;
use plcrun::source::FileId;

#[test]
#[ignore]
fn dump() {
    let path = std::env::var("DUMP").unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let mut d = Diagnostics::new();
    let unit = plcrun::syntax::parse(FileId(0), &text, &mut d);
    if std::env::var("AST").is_ok() {
        println!("{unit:#?}");
    }
    for x in d.iter() {
        println!("{} {:?} {}", x.code, x.span, x.message);
    }
    println!("items: {}", unit.items.len());
}
