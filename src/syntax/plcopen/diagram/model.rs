//! The drawing of an `<FBD>` or `<LD>` body as the editor laid it out:
//! every element with its `localId`, position, size, pins, connection
//! points and the routes of its connections. Unlike the lowering's
//! network (`super::super::network`), nothing is resolved or dropped
//! (continuations, comments, rails stay as drawn), so the model can be
//! written back ([`crate::export_plcopen`]) and drawn (`plcrun draw`).

pub use super::super::network::{Edge, Storage};

/// A point in the editor's coordinates (x to the right, y down).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point {
    /// Horizontal coordinate.
    pub x: f64,
    /// Vertical coordinate.
    pub y: f64,
}

/// The language of a graphical body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Language {
    /// `<FBD>`.
    Fbd,
    /// `<LD>`.
    Ld,
}

impl Language {
    /// The element name of the body (`FBD`, `LD`).
    pub fn tag(self) -> &'static str {
        match self {
            Language::Fbd => "FBD",
            Language::Ld => "LD",
        }
    }
}

/// What an element is, with the names it carries.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementKind {
    /// `<inVariable>`: an expression read.
    InVariable,
    /// `<outVariable>`: a variable written.
    OutVariable,
    /// `<inOutVariable>`: a variable written, then read.
    InOutVariable,
    /// `<block typeName instanceName>`.
    Block {
        /// The function or function block type.
        type_name: String,
        /// The function block instance (none for a function).
        instance: Option<String>,
    },
    /// `<connector name>`: the entry of a named connection.
    Connector(String),
    /// `<continuation name>`: the exit of a named connection.
    Continuation(String),
    /// `<jump label>`.
    Jump(String),
    /// `<label label>`.
    Label(String),
    /// `<return>`.
    Return,
    /// `<leftPowerRail>`.
    LeftRail,
    /// `<rightPowerRail>`.
    RightRail,
    /// `<contact>`.
    Contact,
    /// `<coil>`.
    Coil,
    /// `<comment>`: text on the drawing.
    Comment,
}

impl ElementKind {
    /// The TC6 element name (`inVariable`, `block`, `coil`...).
    pub fn tag(&self) -> &'static str {
        match self {
            ElementKind::InVariable => "inVariable",
            ElementKind::OutVariable => "outVariable",
            ElementKind::InOutVariable => "inOutVariable",
            ElementKind::Block { .. } => "block",
            ElementKind::Connector(_) => "connector",
            ElementKind::Continuation(_) => "continuation",
            ElementKind::Jump(_) => "jump",
            ElementKind::Label(_) => "label",
            ElementKind::Return => "return",
            ElementKind::LeftRail => "leftPowerRail",
            ElementKind::RightRail => "rightPowerRail",
            ElementKind::Contact => "contact",
            ElementKind::Coil => "coil",
            ElementKind::Comment => "comment",
        }
    }
}

/// Negation, edge and storage of one side of an element or pin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modifiers {
    /// `negated`.
    pub negated: bool,
    /// `edge`.
    pub edge: Edge,
    /// `storage`.
    pub storage: Storage,
}

impl Default for Modifiers {
    fn default() -> Self {
        Modifiers {
            negated: false,
            edge: Edge::None,
            storage: Storage::None,
        }
    }
}

/// A connection into an input point: where it comes from and the route
/// the editor drew for it.
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// `refLocalId`: the element it comes from.
    pub from: String,
    /// `formalParameter`: the output pin of that element, when named.
    pub pin: Option<String>,
    /// The `<position>` points of the line, from this input to the source.
    pub route: Vec<Point>,
}

/// A `<connectionPointIn>`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointIn {
    /// `<relPosition>`, relative to the element's position.
    pub rel: Option<Point>,
    /// The connections feeding it (several are ORed in LD).
    pub connections: Vec<Connection>,
}

/// A `<connectionPointOut>`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointOut {
    /// `formalParameter` (a left power rail names its points).
    pub name: Option<String>,
    /// `<relPosition>`, relative to the element's position.
    pub rel: Option<Point>,
}

/// Which list of a block a pin is declared in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinList {
    /// `<inputVariables>`.
    Input,
    /// `<inOutVariables>`.
    InOut,
    /// `<outputVariables>`.
    Output,
}

/// One `<variable formalParameter>` of a block.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockPin {
    /// Its list.
    pub list: PinList,
    /// `formalParameter`.
    pub name: String,
    /// `negated`, `edge`, `storage`.
    pub modifiers: Modifiers,
    /// `hidden="true"` (the editor does not show it).
    pub hidden: bool,
    /// Its input point (inputs and in-outs).
    pub input: Option<PointIn>,
    /// Its output point (outputs and in-outs).
    pub output: Option<PointOut>,
}

/// One element of a graphical body.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramElement {
    /// What it is.
    pub kind: ElementKind,
    /// `localId`.
    pub id: String,
    /// `<position>`.
    pub position: Point,
    /// `width` and `height`, when given.
    pub size: Option<Point>,
    /// `executionOrderId`, when given.
    pub order: Option<u64>,
    /// The expression of a variable, the variable of a contact or coil,
    /// the text of a comment.
    pub text: String,
    /// The element's own modifiers (the input side of an in-out variable).
    pub modifiers: Modifiers,
    /// The output side of an `<inOutVariable>` (`negatedOut`, ...).
    pub out_modifiers: Modifiers,
    /// Its input points (not for blocks: see `pins`).
    pub inputs: Vec<PointIn>,
    /// Its output points (not for blocks).
    pub outputs: Vec<PointOut>,
    /// A block's pins, in document order.
    pub pins: Vec<BlockPin>,
}

impl DiagramElement {
    /// An element of kind `kind` at `position` with nothing else.
    pub fn new(kind: ElementKind, id: &str, position: Point) -> DiagramElement {
        DiagramElement {
            kind,
            id: id.to_string(),
            position,
            size: None,
            order: None,
            text: String::new(),
            modifiers: Modifiers::default(),
            out_modifiers: Modifiers::default(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            pins: Vec::new(),
        }
    }
}

/// A graphical body as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    /// FBD or LD.
    pub language: Language,
    /// Its elements, in document order.
    pub elements: Vec<DiagramElement>,
}

impl Diagram {
    /// The element whose `localId` is `id`.
    pub fn element(&self, id: &str) -> Option<&DiagramElement> {
        self.elements.iter().find(|e| e.id == id)
    }
}
