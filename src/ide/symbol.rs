//! The declarations an editor can point at: one [`Symbol`] per declared
//! name, with where it is written and what contains it.

use crate::source::Span;

/// Index of a symbol in an [`super::Analysis`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SymbolId(pub u32);

/// What a declared name is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SymbolKind {
    /// A `PROGRAM`.
    Program,
    /// A `FUNCTION`.
    Function,
    /// A `FUNCTION_BLOCK` (or `CLASS`).
    FunctionBlock,
    /// A `METHOD` of a block or an interface.
    Method,
    /// An `INTERFACE`.
    Interface,
    /// A `TYPE` that is a structure.
    Struct,
    /// A `TYPE` that is an enumeration.
    Enum,
    /// Any other `TYPE` (alias, subrange, array, reference).
    Alias,
    /// A member of a structure.
    Field,
    /// A value of an enumeration.
    EnumValue,
    /// A variable of a POU or method, by section.
    Variable(VarSection),
    /// A global variable (a global list, a configuration or a resource).
    Global,
    /// An SFC step.
    Step,
    /// An SFC action.
    Action,
    /// A named SFC transition.
    Transition,
    /// An IL jump label.
    Label,
    /// A `CONFIGURATION`.
    Configuration,
    /// A `RESOURCE`.
    Resource,
    /// A `TASK`.
    Task,
    /// A program instance of a resource (`PROGRAM inst WITH task : Main`).
    ProgramInstance,
    /// A standard function block plcrun provides (`TON`, `CTU`...).
    StandardBlock,
    /// A pin of a standard function block (`TON.Q`).
    StandardPin(VarSection),
}

/// The section a variable is declared in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VarSection {
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
    /// `VAR_TEMP`
    Temp,
    /// `VAR_INST`
    Inst,
    /// `VAR_STAT`
    Stat,
}

impl VarSection {
    /// The keyword that opens the section.
    pub fn keyword(self) -> &'static str {
        match self {
            VarSection::Local => "VAR",
            VarSection::Input => "VAR_INPUT",
            VarSection::Output => "VAR_OUTPUT",
            VarSection::InOut => "VAR_IN_OUT",
            VarSection::External => "VAR_EXTERNAL",
            VarSection::Temp => "VAR_TEMP",
            VarSection::Inst => "VAR_INST",
            VarSection::Stat => "VAR_STAT",
        }
    }

    /// True for the sections a caller binds (`VAR_INPUT`, `VAR_IN_OUT`,
    /// `VAR_OUTPUT`).
    pub fn is_interface(self) -> bool {
        matches!(
            self,
            VarSection::Input | VarSection::Output | VarSection::InOut
        )
    }
}

impl SymbolKind {
    /// A word for the kind, as hover and outlines show it.
    pub fn describe(self) -> &'static str {
        match self {
            SymbolKind::Program => "program",
            SymbolKind::Function => "function",
            SymbolKind::FunctionBlock => "function block",
            SymbolKind::Method => "method",
            SymbolKind::Interface => "interface",
            SymbolKind::Struct => "structure",
            SymbolKind::Enum => "enumeration",
            SymbolKind::Alias => "type",
            SymbolKind::Field => "field",
            SymbolKind::EnumValue => "enumeration value",
            SymbolKind::Variable(VarSection::Input)
            | SymbolKind::StandardPin(VarSection::Input) => "input",
            SymbolKind::Variable(VarSection::Output)
            | SymbolKind::StandardPin(VarSection::Output) => "output",
            SymbolKind::Variable(VarSection::InOut) => "in-out",
            SymbolKind::Variable(VarSection::External) => "external variable",
            SymbolKind::Variable(VarSection::Temp) => "temporary variable",
            SymbolKind::Variable(_) | SymbolKind::StandardPin(_) => "variable",
            SymbolKind::Global => "global variable",
            SymbolKind::Step => "step",
            SymbolKind::Action => "action",
            SymbolKind::Transition => "transition",
            SymbolKind::Label => "label",
            SymbolKind::Configuration => "configuration",
            SymbolKind::Resource => "resource",
            SymbolKind::Task => "task",
            SymbolKind::ProgramInstance => "program instance",
            SymbolKind::StandardBlock => "standard function block",
        }
    }

    /// True for names that hold data (what a `.` can follow).
    pub fn is_data(self) -> bool {
        matches!(
            self,
            SymbolKind::Variable(_)
                | SymbolKind::Global
                | SymbolKind::Field
                | SymbolKind::StandardPin(_)
                | SymbolKind::ProgramInstance
        )
    }

    /// True for the kinds that name a type (what a declaration's `:`
    /// can be followed by).
    pub fn is_type(self) -> bool {
        matches!(
            self,
            SymbolKind::FunctionBlock
                | SymbolKind::Interface
                | SymbolKind::Struct
                | SymbolKind::Enum
                | SymbolKind::Alias
                | SymbolKind::StandardBlock
        )
    }
}

/// The type of a declared name, reduced to what member access needs.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A type named by its (upper-case) key: elementary, user or block.
    Named(String),
    /// An array of the inner shape.
    Array(Box<Shape>),
    /// A reference or pointer to the inner shape.
    Ref(Box<Shape>),
    /// A type declared in place (a structure or enumeration written in the
    /// declaration): its members are the symbol's own children.
    Inline(SymbolId),
    /// Nothing member access can use (strings, subranges).
    Opaque,
}

/// One declared name.
#[derive(Debug, Clone)]
pub struct Symbol {
    /// The name as declared.
    pub name: String,
    /// What it is.
    pub kind: SymbolKind,
    /// Where the name is written; `None` for what plcrun provides itself.
    pub location: Option<Span>,
    /// The whole declaration (a variable's line, a POU from keyword to end).
    pub extent: Option<Span>,
    /// The POU, method, type, chart or configuration it belongs to.
    pub parent: Option<SymbolId>,
    /// Its type as written (`INT`, `ARRAY[1..3] OF TON`), if it has one.
    pub type_text: Option<String>,
    /// Its type reduced for member access.
    pub shape: Option<Shape>,
    /// Declared `CONSTANT`.
    pub constant: bool,
    /// The POU a block extends (`EXTENDS`), or the structure a structure
    /// extends, as a key.
    pub extends: Option<String>,
}

impl Symbol {
    /// The case-folded key names are compared by.
    pub fn key(&self) -> String {
        self.name.to_ascii_uppercase()
    }
}
