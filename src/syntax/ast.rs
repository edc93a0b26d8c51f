//! The abstract syntax tree shared by Structured Text, Instruction List and
//! textual SFC. The parser builds it; semantic analysis reads it.
//! Names keep the spelling the user wrote; comparisons are case-insensitive
//! and done by the resolver, not here.

use crate::source::Span;

/// An identifier with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct Ident {
    /// The name as written.
    pub name: String,
    /// Where it was written.
    pub span: Span,
}

impl Ident {
    /// The case-folded key used for lookups.
    pub fn key(&self) -> String {
        self.name.to_ascii_uppercase()
    }
}

/// One parsed source file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CompilationUnit {
    /// The top-level declarations, in source order.
    pub items: Vec<Item>,
}

/// A top-level declaration.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// PROGRAM, FUNCTION or FUNCTION_BLOCK.
    Pou(Pou),
    /// `TYPE ... END_TYPE` (one or more type declarations).
    Types(Vec<TypeDecl>),
    /// `CONFIGURATION ... END_CONFIGURATION`.
    Configuration(Configuration),
    /// A top-level `VAR_GLOBAL ... END_VAR` block (CODESYS-style global list).
    Globals(VarBlock),
    /// `INTERFACE ... END_INTERFACE` (edition 3).
    Interface(crate::syntax::oop::Interface),
}

/// Kind of program organisation unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PouKind {
    /// `PROGRAM`
    Program,
    /// `FUNCTION`
    Function,
    /// `FUNCTION_BLOCK`
    FunctionBlock,
}

/// A program organisation unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Pou {
    /// PROGRAM / FUNCTION / FUNCTION_BLOCK.
    pub kind: PouKind,
    /// Its name.
    pub name: Ident,
    /// A FUNCTION's result type (`FUNCTION f : INT`); `None` otherwise
    /// (a function without one returns nothing, a CODESYS extension).
    pub return_type: Option<TypeSpec>,
    /// Declaration blocks in source order.
    pub var_blocks: Vec<VarBlock>,
    /// The body.
    pub body: Body,
    /// Span of the whole POU (keyword to END_ keyword).
    pub span: Span,
    /// Methods, EXTENDS, IMPLEMENTS and modifiers of an edition-3 FB.
    pub oop: Option<Box<crate::syntax::oop::PouOop>>,
    /// Declared after `{attribute 'no_check'}` (CODESYS): its code (its
    /// methods' too) calls no implicit check function.
    pub no_check: bool,
}

/// The body of a POU, action or transition.
#[derive(Debug, Clone, PartialEq)]
pub enum Body {
    /// Structured Text statements.
    St(Vec<Stmt>),
    /// Instruction List lines.
    Il(Vec<IlLine>),
    /// A textual SFC: steps, transitions, actions, and plain statements.
    Sfc(Vec<SfcElement>),
}

/// Section keyword of a variable block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarKind {
    /// `VAR`
    Local,
    /// `VAR_INPUT`
    Input,
    /// `VAR_OUTPUT`
    Output,
    /// `VAR_IN_OUT`
    InOut,
    /// `VAR_EXTERNAL`
    External,
    /// `VAR_GLOBAL`
    Global,
    /// `VAR_TEMP`
    Temp,
    /// `VAR_INST` (CODESYS / TwinCAT, in a METHOD only): the method's
    /// variables that keep their values between calls, one set per instance.
    Inst,
    /// `VAR_STAT` (CODESYS, TwinCAT): one copy shared by every instance
    /// and call of the POU, kept from call to call.
    Stat,
}

/// RETAIN / NON_RETAIN / PERSISTENT qualifier.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Retain {
    /// `RETAIN`
    Retain,
    /// `NON_RETAIN`
    NonRetain,
    /// `PERSISTENT`, alone or with `RETAIN` in either order (CODESYS writes
    /// `VAR_GLOBAL PERSISTENT RETAIN`).
    Persistent,
}

/// A `VAR... END_VAR` block.
#[derive(Debug, Clone, PartialEq)]
pub struct VarBlock {
    /// Which section.
    pub kind: VarKind,
    /// `CONSTANT` given.
    pub constant: bool,
    /// `RETAIN` / `NON_RETAIN` / `PERSISTENT` given.
    pub retain: Option<Retain>,
    /// The declarations.
    pub decls: Vec<VarDecl>,
    /// The whole block.
    pub span: Span,
}

/// `a, b AT %IX0.1 : TYPE := init;`
#[derive(Debug, Clone, PartialEq)]
pub struct VarDecl {
    /// The declared names (several share one type).
    pub names: Vec<Ident>,
    /// `AT %...` location.
    pub location: Option<DirectAddress>,
    /// The type.
    pub ty: TypeSpec,
    /// `:= ...` initial value.
    pub init: Option<Initializer>,
    /// The whole declaration.
    pub span: Span,
    /// `R_EDGE` / `F_EDGE` after the type of a VAR_INPUT (edition 3).
    pub edge: Option<EdgeQualifier>,
    /// `fb : FB_X(a := 1)`: the arguments of the instance's `FB_init`
    /// (CODESYS V3, TwinCAT 3; `src/sema/instance_calls/`).
    pub init_args: Option<InitArgs>,
}

impl VarDecl {
    /// `name : ty;` with no location, initial value or qualifier: a
    /// declaration the compiler writes itself (its span: `span`).
    pub fn simple(name: &str, ty: &str, span: Span) -> VarDecl {
        let ident = |n: &str| Ident {
            name: n.to_string(),
            span,
        };
        VarDecl {
            names: vec![ident(name)],
            location: None,
            ty: TypeSpec::Named(ident(ty)),
            init: None,
            span,
            edge: None,
            init_args: None,
        }
    }
}

/// The arguments an instance declaration gives its `FB_init`.
#[derive(Debug, Clone, PartialEq)]
pub struct InitArgs {
    /// The arguments in source order (formal or positional).
    pub args: Vec<Arg>,
    /// For an array of instances (`ARRAY[1..2] OF FB_X[(1), (2)]`): the
    /// arguments of its first elements, in order (`args` is empty).
    pub elements: Vec<Vec<Arg>>,
    /// From the type's name to the closing parenthesis.
    pub span: Span,
}

/// The edge qualifier of a BOOL input: the input reads TRUE only on the
/// rising (`R_EDGE`) or falling (`F_EDGE`) edge of what the caller passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeQualifier {
    /// `R_EDGE`: FALSE -> TRUE.
    Rising,
    /// `F_EDGE`: TRUE -> FALSE.
    Falling,
}

/// Memory area of a direct address.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Area {
    /// `%I` inputs.
    Input,
    /// `%Q` outputs.
    Output,
    /// `%M` memory.
    Memory,
}

/// Size prefix of a direct address.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AddrSize {
    /// `X` or no prefix: one bit.
    Bit,
    /// `B`
    Byte,
    /// `W`
    Word,
    /// `D`
    Dword,
    /// `L`
    Lword,
}

/// `%IX0.3`, `%QW4`, `%I0.0.0.0.1`, or `%I*` (unspecified, only in declarations).
#[derive(Debug, Clone, PartialEq)]
pub struct DirectAddress {
    /// I, Q or M.
    pub area: Area,
    /// Size prefix (`Bit` when absent).
    pub size: AddrSize,
    /// True when the size prefix was written explicitly.
    pub explicit_size: bool,
    /// The dot-separated numeric fields (empty for `%I*`).
    pub fields: Vec<u64>,
    /// The text as written, e.g. `%IX0.3`.
    pub text: String,
    /// Where.
    pub span: Span,
}

/// A type as written in a declaration.
#[derive(Debug, Clone, PartialEq)]
pub enum TypeSpec {
    /// A type name: elementary (`INT`), user-defined, or FB type (`TON`).
    Named(Ident),
    /// `STRING`, `STRING[n]`, `STRING(n)`, `WSTRING...`.
    String {
        /// WSTRING.
        wide: bool,
        /// Declared maximum length.
        len: Option<Box<Expr>>,
        /// Where.
        span: Span,
    },
    /// `ARRAY[lo..hi, ...] OF elem`.
    Array {
        /// One `(lo, hi)` per dimension.
        ranges: Vec<(Expr, Expr)>,
        /// Element type.
        elem: Box<TypeSpec>,
        /// Where.
        span: Span,
    },
    /// `ARRAY[*, ...] OF elem`: an array whose bounds the caller's
    /// argument gives (CODESYS and TwinCAT, VAR_IN_OUT only).
    OpenArray {
        /// Number of dimensions (one `*` each).
        rank: usize,
        /// Element type.
        elem: Box<TypeSpec>,
        /// Where.
        span: Span,
    },
    /// `INT (lo..hi)`.
    Subrange {
        /// Base integer type.
        base: Ident,
        /// Lower bound.
        lo: Box<Expr>,
        /// Upper bound.
        hi: Box<Expr>,
        /// Where.
        span: Span,
    },
    /// `(Red, Green := 5, Blue)` optionally typed `INT (Red, ...)`.
    Enum {
        /// Explicit base type for valued enums.
        base: Option<Ident>,
        /// Names and optional values.
        values: Vec<(Ident, Option<Expr>)>,
        /// Where.
        span: Span,
    },
    /// `STRUCT ... END_STRUCT` (only inside TYPE).
    Struct {
        /// The structure it extends (`TYPE B EXTENDS A : STRUCT`, CODESYS
        /// and TwinCAT): its fields come first.
        extends: Option<Ident>,
        /// The members.
        fields: Vec<VarDecl>,
        /// Where.
        span: Span,
        /// `UNION ... END_UNION` (CODESYS, TwinCAT): the members share
        /// their memory (docs/semantics.md §27).
        union: bool,
    },
    /// `REF_TO T`, `POINTER TO T`, `REFERENCE TO T`.
    Ref {
        /// Which of the three.
        kind: RefKind,
        /// The type referred to.
        target: Box<TypeSpec>,
        /// Where.
        span: Span,
    },
}

/// The flavour of a reference type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RefKind {
    /// IEC 61131-3 edition 3 `REF_TO`: explicit `^`, no arithmetic.
    RefTo,
    /// CODESYS `POINTER TO`: explicit `^`, byte arithmetic, `ADR`.
    Pointer,
    /// CODESYS `REFERENCE TO`: an alias dereferenced implicitly.
    Reference,
}

impl TypeSpec {
    /// Where the type is written.
    pub fn span(&self) -> Span {
        match self {
            TypeSpec::Named(i) => i.span,
            TypeSpec::String { span, .. }
            | TypeSpec::Array { span, .. }
            | TypeSpec::OpenArray { span, .. }
            | TypeSpec::Subrange { span, .. }
            | TypeSpec::Enum { span, .. }
            | TypeSpec::Struct { span, .. }
            | TypeSpec::Ref { span, .. } => *span,
        }
    }
}

/// `name : spec := init;` inside TYPE.
#[derive(Debug, Clone, PartialEq)]
pub struct TypeDecl {
    /// The new type's name.
    pub name: Ident,
    /// Its definition.
    pub ty: TypeSpec,
    /// Default initial value.
    pub init: Option<Initializer>,
    /// Where.
    pub span: Span,
    /// Declared after `{attribute 'qualified_only'}` (CODESYS): its
    /// enumeration values must be written `Type.Value`.
    pub qualified_only: bool,
    /// Declared after `{attribute 'strict'}` (CODESYS): an enumeration
    /// that never converts to or from an integer implicitly.
    pub strict: bool,
}

/// An initial value.
#[derive(Debug, Clone, PartialEq)]
pub enum Initializer {
    /// A constant expression.
    Expr(Expr),
    /// `[1, 2, 3(0), 2(5)]`.
    Array(Vec<ArrayInitElem>, Span),
    /// `(a := 1, b := (x := 2))`.
    Struct(Vec<(Ident, Initializer)>, Span),
}

/// One element of an array initializer: `v`, `n(v)` or `n()`.
#[derive(Debug, Clone, PartialEq)]
pub struct ArrayInitElem {
    /// Repetition count `n` in `n(v)`.
    pub repeat: Option<Expr>,
    /// The value; `None` for `n()` (n default values).
    pub value: Option<Initializer>,
    /// Where.
    pub span: Span,
}

/// An expression with its span.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub span: Span,
}

/// Expression forms.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A literal.
    Literal(Literal),
    /// A plain name (variable, constant, enum value, step name...).
    Name(Ident),
    /// `base.member` (struct member, FB output, `step.X`, `inst.S3.X`); an
    /// edition-3 partial access `w.%B1` has the member name `%B1`.
    Member(Box<Expr>, Ident),
    /// `base.%X3` bit access on an ANY_BIT value (e.g. `w.3`).
    BitAccess(Box<Expr>, u32),
    /// `base[i, j]`.
    Index(Box<Expr>, Vec<Expr>),
    /// A direct address used in code (`%IX0.1`).
    Direct(DirectAddress),
    /// `-x`, `NOT x`.
    Unary(UnaryOp, Box<Expr>),
    /// `a + b` etc.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// A function call `f(a, b)` or `f(IN1 := a)`.
    Call(Call),
    /// Parenthesised expression (kept so messages can point at it).
    Paren(Box<Expr>),
    /// `r^`: the variable a reference or pointer designates.
    Deref(Box<Expr>),
    /// `(target := value)` inside an expression (CODESYS / TwinCAT): the
    /// value is stored, and the expression has the value stored.
    Assign(Box<Expr>, Box<Expr>),
}

/// Unary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-`
    Neg,
    /// `+`
    Plus,
    /// `NOT`
    Not,
}

/// Binary operators (IEC precedence is encoded by the parser).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    /// `**`
    Pow,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `MOD`
    Mod,
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `<`
    Lt,
    /// `>`
    Gt,
    /// `<=`
    Le,
    /// `>=`
    Ge,
    /// `=`
    Eq,
    /// `<>`
    Ne,
    /// `AND`, `&`
    And,
    /// `XOR`
    Xor,
    /// `OR`
    Or,
    /// `AND_THEN` (CODESYS): AND that skips the right operand when the left is FALSE
    AndThen,
    /// `OR_ELSE` (CODESYS): OR that skips the right operand when the left is TRUE
    OrElse,
}

impl BinaryOp {
    /// True for the six comparisons (`=`, `<>`, `<`, `<=`, `>`, `>=`).
    pub fn is_comparison(self) -> bool {
        matches!(
            self,
            BinaryOp::Eq | BinaryOp::Ne | BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge
        )
    }
}

/// A literal as written, already decoded by the lexer.
#[derive(Debug, Clone, PartialEq)]
pub struct Literal {
    /// The decoded value.
    pub value: LiteralValue,
    /// `INT#`, `WORD#`, `REAL#`, `MyEnum#` prefix if any.
    pub type_prefix: Option<Ident>,
}

/// Decoded literal values.
#[derive(Debug, Clone, PartialEq)]
pub enum LiteralValue {
    /// An integer (decimal, `2#`, `8#`, `16#`); `i128` covers ULINT and a leading `-`.
    Int(i128),
    /// A real number with the text it came from.
    Real(f64),
    /// `TRUE`/`FALSE` (and `BOOL#1`/`BOOL#0`).
    Bool(bool),
    /// `T#`/`TIME#` (nanoseconds; `long` for `LT#`/`LTIME#`).
    Duration {
        /// Signed nanoseconds.
        nanos: i64,
        /// Written as `LT#`/`LTIME#`.
        long: bool,
    },
    /// `D#`/`DATE#` (nanoseconds since 1970-01-01).
    Date {
        /// Nanoseconds since the epoch.
        nanos: i64,
        /// Written as `LD#`/`LDATE#`.
        long: bool,
    },
    /// `TOD#`/`TIME_OF_DAY#` (nanoseconds since midnight).
    TimeOfDay {
        /// Nanoseconds since midnight.
        nanos: i64,
        /// Written as `LTOD#`.
        long: bool,
    },
    /// `DT#`/`DATE_AND_TIME#` (nanoseconds since 1970-01-01T00:00:00).
    DateTime {
        /// Nanoseconds since the epoch.
        nanos: i64,
        /// Written as `LDT#`.
        long: bool,
    },
    /// `'text'` (STRING) or `"text"` (WSTRING), escapes decoded.
    String {
        /// Decoded text.
        value: String,
        /// Double-quoted (WSTRING).
        wide: bool,
    },
    /// `MyEnum#Value`: an enumeration value qualified by its type
    /// (the type is in `Literal::type_prefix`).
    EnumValue(Ident),
}

/// A call with arguments: function call in an expression, FB invocation
/// or function call as a statement.
#[derive(Debug, Clone, PartialEq)]
pub struct Call {
    /// What is called: a function name, or an FB instance expression
    /// (`inst`, `arr[i]`, `a.b`).
    pub callee: Box<Expr>,
    /// The arguments in source order.
    pub args: Vec<Arg>,
    /// The whole call.
    pub span: Span,
}

/// A call argument.
#[derive(Debug, Clone, PartialEq)]
pub enum Arg {
    /// Non-formal: `f(a, b)`.
    Positional(Expr),
    /// `IN := expr`.
    Input {
        /// Parameter name.
        name: Ident,
        /// Value.
        value: Expr,
    },
    /// `Q => var` or `NOT Q => var`.
    Output {
        /// Parameter name.
        name: Ident,
        /// `NOT` given before the name.
        negated: bool,
        /// Where the output is stored.
        target: Expr,
    },
}

/// A statement with its span.
#[derive(Debug, Clone, PartialEq)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where.
    pub span: Span,
}

/// Statement forms.
#[derive(Debug, Clone, PartialEq)]
pub enum StmtKind {
    /// `target := value;`
    Assign {
        /// Assigned place.
        target: Expr,
        /// Value.
        value: Expr,
    },
    /// `f(...);` or `inst(...);`.
    Call(Call),
    /// `IF c THEN ... ELSIF c THEN ... ELSE ... END_IF`.
    If {
        /// `(condition, statements)` for IF and each ELSIF.
        branches: Vec<(Expr, Vec<Stmt>)>,
        /// ELSE part.
        else_branch: Option<Vec<Stmt>>,
    },
    /// `CASE sel OF ... ELSE ... END_CASE`.
    Case {
        /// Selector.
        selector: Expr,
        /// Alternatives in order.
        arms: Vec<CaseArm>,
        /// ELSE part.
        else_branch: Option<Vec<Stmt>>,
    },
    /// `FOR v := a TO b BY c DO ... END_FOR`.
    For {
        /// Control variable: a name, or (CODESYS) an element or field of
        /// a local at a constant position (`FOR Offset[1] := ...`).
        var: Box<Expr>,
        /// Start.
        from: Expr,
        /// End.
        to: Expr,
        /// Step (1 if absent).
        by: Option<Expr>,
        /// Body.
        body: Vec<Stmt>,
    },
    /// `WHILE c DO ... END_WHILE`.
    While {
        /// Condition.
        cond: Expr,
        /// Body.
        body: Vec<Stmt>,
    },
    /// `REPEAT ... UNTIL c END_REPEAT`.
    Repeat {
        /// Body.
        body: Vec<Stmt>,
        /// Exit condition.
        until: Expr,
    },
    /// `EXIT;`
    Exit,
    /// `CONTINUE;`
    Continue,
    /// `RETURN;`
    Return,
    /// `;` alone.
    Empty,
    /// `__TRY ... __CATCH(exc) ... __FINALLY ... __ENDTRY` (CODESYS V3,
    /// TwinCAT 3): a runtime fault in `body` runs `catch` with the fault's
    /// exception code in `exc`, instead of stopping the PLC.
    Try {
        /// The guarded statements.
        body: Vec<Stmt>,
        /// The exception variable and the statements run after a fault.
        catch: Option<(Ident, Vec<Stmt>)>,
        /// The statements run after `body` or `catch`, whichever ran.
        finally: Option<Vec<Stmt>>,
    },
    /// `target REF= value;` (CODESYS): binds a `REFERENCE TO` variable.
    RefAssign {
        /// The reference bound.
        target: Expr,
        /// The variable it is bound to.
        value: Expr,
    },
}

/// One CASE alternative: `1, 3..5, Red: statements`.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseArm {
    /// Its labels.
    pub labels: Vec<CaseLabel>,
    /// Its statements.
    pub body: Vec<Stmt>,
    /// Where the labels are.
    pub span: Span,
}

/// A CASE label.
#[derive(Debug, Clone, PartialEq)]
pub enum CaseLabel {
    /// A single constant (or enum value).
    Value(Expr),
    /// `lo..hi`.
    Range(Expr, Expr),
}

// ---------------------------------------------------------------- IL

/// One IL line: an optional label and an optional instruction.
#[derive(Debug, Clone, PartialEq)]
pub struct IlLine {
    /// `name:` at the start of the line.
    pub label: Option<Ident>,
    /// The instruction, if any.
    pub instr: Option<IlInstr>,
    /// Where.
    pub span: Span,
}

/// An IL instruction.
#[derive(Debug, Clone, PartialEq)]
pub struct IlInstr {
    /// What it is.
    pub kind: IlInstrKind,
    /// Where.
    pub span: Span,
}

/// The operators that act on the current result with one operand
/// (IEC 61131-3 Table 52).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IlOperator {
    /// `LD`
    Ld,
    /// `ST`
    St,
    /// `S`
    S,
    /// `R`
    R,
    /// `AND`, `&`
    And,
    /// `OR`
    Or,
    /// `XOR`
    Xor,
    /// `NOT` (no operand)
    Not,
    /// `ADD`
    Add,
    /// `SUB`
    Sub,
    /// `MUL`
    Mul,
    /// `DIV`
    Div,
    /// `MOD`
    Mod,
    /// `GT`
    Gt,
    /// `GE`
    Ge,
    /// `EQ`
    Eq,
    /// `NE`
    Ne,
    /// `LE`
    Le,
    /// `LT`
    Lt,
}

/// The IL instruction forms.
#[derive(Debug, Clone, PartialEq)]
pub enum IlInstrKind {
    /// `OP[N] operand` (operand absent for `NOT`, and for operators written without one,
    /// which the checker reports).
    Simple {
        /// The operator.
        op: IlOperator,
        /// The `N` modifier.
        negate: bool,
        /// Operand.
        operand: Option<Expr>,
    },
    /// `OP[N]( [operand]`: deferred operation.
    Deferred {
        /// The operator.
        op: IlOperator,
        /// The `N` modifier.
        negate: bool,
        /// Operand on the same line (acts as an implicit LD).
        operand: Option<Expr>,
    },
    /// `)`: apply the innermost deferred operation.
    Close,
    /// `JMP[C[N]] label`.
    Jump {
        /// `None` unconditional, `Some(true)` JMPC, `Some(false)` JMPCN.
        cond: Option<bool>,
        /// Target.
        label: Ident,
    },
    /// `CAL[C[N]] inst[(args | outputs)]`.
    Call {
        /// Condition as for `Jump`.
        cond: Option<bool>,
        /// The FB instance.
        instance: Expr,
        /// Inputs (formal or non-formal) and `=>` outputs.
        args: Vec<Arg>,
        /// Moeller/CoDeSys-2 output list after `|`: `dest := OUTPUT`;
        /// `dest` is `None` for `:= ET`.
        outputs: Vec<IlOutputCopy>,
    },
    /// `RET[C[N]]`.
    Return {
        /// Condition as for `Jump`.
        cond: Option<bool>,
    },
    /// `FUN a, b`: call a function with CR as first argument.
    FunctionCall {
        /// Function name.
        name: Ident,
        /// Further arguments (formal `x := e` allowed).
        args: Vec<Arg>,
    },
    /// FB input operator of Table 53: `S1 ff`, `CLK trig`, `PT tmr`...
    FbInput {
        /// The input name (S1, R1, S, R, CLK, CU, CD, PV, IN, PT, ...).
        pin: Ident,
        /// The FB instance.
        instance: Expr,
    },
}

/// `dest := OUTPUT` after `|` in a Moeller CAL.
#[derive(Debug, Clone, PartialEq)]
pub struct IlOutputCopy {
    /// Destination variable; `None` when empty (`:= ET`).
    pub dest: Option<Expr>,
    /// The FB output name.
    pub output: Ident,
    /// Where.
    pub span: Span,
}

// ---------------------------------------------------------------- SFC

/// An element of a chart body.
#[derive(Debug, Clone, PartialEq)]
pub enum SfcElement {
    /// `STEP` / `INITIAL_STEP`.
    Step(Step),
    /// `TRANSITION`.
    Transition(Transition),
    /// `ACTION`.
    Action(Action),
    /// A plain statement outside chart elements (plcrun extension).
    Statement(Stmt),
}

/// `[INITIAL_]STEP name : associations END_STEP`.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Step name.
    pub name: Ident,
    /// INITIAL_STEP.
    pub initial: bool,
    /// Action associations.
    pub actions: Vec<ActionAssociation>,
    /// Where.
    pub span: Span,
}

/// `A(N)`, `A(L, T#10s)`, `A(D, t#5s, indicator)`, `A()`.
#[derive(Debug, Clone, PartialEq)]
pub struct ActionAssociation {
    /// Action (or BOOL variable) name.
    pub action: Ident,
    /// Qualifier name (N, R, S, L, D, P, P0, P1, SD, DS, SL); `None` means N.
    pub qualifier: Option<Ident>,
    /// Duration for timed qualifiers.
    pub duration: Option<Expr>,
    /// Indicator variables.
    pub indicators: Vec<Ident>,
    /// Where.
    pub span: Span,
}

/// `TRANSITION [name] [(PRIORITY := n)] FROM a TO b := cond; END_TRANSITION`.
#[derive(Debug, Clone, PartialEq)]
pub struct Transition {
    /// Optional name.
    pub name: Option<Ident>,
    /// `(PRIORITY := n)`.
    pub priority: Option<Expr>,
    /// Preceding steps.
    pub from: Vec<Ident>,
    /// Following steps.
    pub to: Vec<Ident>,
    /// The condition.
    pub condition: TransitionCondition,
    /// Where.
    pub span: Span,
}

/// How a transition condition is written.
#[derive(Debug, Clone, PartialEq)]
pub enum TransitionCondition {
    /// `:= expr;`
    Expr(Expr),
    /// `: IL lines` — the condition is the CR at the end.
    Il(Vec<IlLine>),
}

/// `ACTION name : body END_ACTION`.
#[derive(Debug, Clone, PartialEq)]
pub struct Action {
    /// Name.
    pub name: Ident,
    /// ST or IL body.
    pub body: Body,
    /// Where.
    pub span: Span,
}

// ---------------------------------------------------------------- configuration

/// `CONFIGURATION name ... END_CONFIGURATION`.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    /// Name.
    pub name: Ident,
    /// `VAR_GLOBAL` blocks of the configuration.
    pub globals: Vec<VarBlock>,
    /// Resources; a configuration that declares tasks and programs directly
    /// gets one implicit resource (with `name` equal to the configuration's).
    pub resources: Vec<Resource>,
    /// `VAR_CONFIG` lines: addresses and initial values of variables
    /// inside program instances.
    pub var_config: Vec<ConfigInit>,
    /// Where.
    pub span: Span,
}

/// One line of `VAR_CONFIG`:
/// `Res.Prog.inst.var AT %QX1.0 : BOOL := init;`.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigInit {
    /// The dotted path: resource (may be left out with an implicit
    /// resource), program instance, FB instances, variable.
    pub path: Vec<Ident>,
    /// Subscripts after path segments (`valves[2]`): (segment position,
    /// index expressions).
    pub subscripts: Vec<(usize, Vec<Expr>)>,
    /// `AT %...`: the address completing an `AT %I*`-style declaration.
    pub location: Option<DirectAddress>,
    /// The type, as the variable is declared.
    pub ty: TypeSpec,
    /// `:= ...` initial value of this one instance's variable.
    pub init: Option<Initializer>,
    /// The whole line.
    pub span: Span,
}

/// `RESOURCE name ON type ... END_RESOURCE`.
#[derive(Debug, Clone, PartialEq)]
pub struct Resource {
    /// Name.
    pub name: Ident,
    /// The `ON` processor type, if given.
    pub on: Option<Ident>,
    /// Resource-level globals.
    pub globals: Vec<VarBlock>,
    /// Tasks.
    pub tasks: Vec<TaskDecl>,
    /// Program instances.
    pub programs: Vec<ProgramInstance>,
    /// Where.
    pub span: Span,
}

/// `TASK name (INTERVAL := T#10ms, PRIORITY := 1);`
#[derive(Debug, Clone, PartialEq)]
pub struct TaskDecl {
    /// Name.
    pub name: Ident,
    /// `(key := value)` pairs: INTERVAL, PRIORITY, SINGLE.
    pub settings: Vec<(Ident, Expr)>,
    /// Where.
    pub span: Span,
}

/// `PROGRAM inst [WITH task] : Type [(args)];`
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramInstance {
    /// Instance name.
    pub name: Ident,
    /// Task, if any.
    pub task: Option<Ident>,
    /// The PROGRAM type.
    pub type_name: Ident,
    /// Connections (`x := global`, `y => global`).
    pub args: Vec<Arg>,
    /// Where.
    pub span: Span,
}
