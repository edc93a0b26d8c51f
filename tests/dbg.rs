use plcrun::diagnostics::Diagnostics;
use plcrun::source::FileId;
#[test]
fn dbg() {
    let src = std::env::var("SRC").unwrap().replace("\\n", "\n");
    let mut d = Diagnostics::new();
    let u = plcrun::syntax::parse(FileId(0), &src, &mut d);
    for x in d.iter() { println!("{} {:?} {}", x.code, x.span, x.message); }
    if std::env::var("AST").is_ok() { println!("{u:#?}"); }
}
