//! The drawing of an `<FBD>`, `<LD>` or `<SFC>` body as the editor laid it out:
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
    /// `<SFC>` (chart elements, and FBD/LD elements wired to conditions).
    Sfc,
}

impl Language {
    /// The element name of the body (`FBD`, `LD`).
    pub fn tag(self) -> &'static str {
        match self {
            Language::Fbd => "FBD",
            Language::Ld => "LD",
            Language::Sfc => "SFC",
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
    /// `<step name initialStep>` of a chart.
    Step {
        /// The step's name.
        name: String,
        /// `initialStep="true"`.
        initial: bool,
    },
    /// `<transition priority>` of a chart, with its condition.
    Transition {
        /// `priority`, as written.
        priority: Option<String>,
        /// Its `<condition>`.
        condition: Condition,
    },
    /// `<selectionDivergence>`.
    SelectionDivergence,
    /// `<selectionConvergence>`.
    SelectionConvergence,
    /// `<simultaneousDivergence>`.
    SimultaneousDivergence,
    /// `<simultaneousConvergence>`.
    SimultaneousConvergence,
    /// `<jumpStep targetName>`.
    JumpStep(String),
    /// `<actionBlock>` with its associations.
    ActionBlock(Vec<Association>),
}

/// A body written in a language: text, or a drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum BodyModel {
    /// `<ST>` or `<IL>` text (decoded, paragraphs one after another).
    Text {
        /// `ST` or `IL`.
        language: String,
        /// The text.
        text: String,
    },
    /// An `<FBD>` or `<LD>` body.
    Diagram(Diagram),
}

/// What a transition's `<condition>` holds.
#[derive(Debug, Clone, PartialEq)]
pub enum ConditionKind {
    /// No condition element (the importer reports it).
    Missing,
    /// `<reference name>`: a named transition of the POU.
    Reference(String),
    /// `<inline name>` with its body.
    Inline {
        /// `name`, as written.
        name: String,
        /// The body.
        body: BodyModel,
    },
    /// `<connectionPointIn>`: wired to the chart's FBD/LD elements.
    Wired(PointIn),
}

/// A transition's `<condition>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    /// `negated="true"`.
    pub negated: bool,
    /// What it holds.
    pub kind: ConditionKind,
}

/// One `<action>` of an `<actionBlock>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Association {
    /// `localId`, when given.
    pub id: Option<String>,
    /// `qualifier`, `duration`, `indicator`, as written.
    pub qualifier: Option<String>,
    /// `duration`.
    pub duration: Option<String>,
    /// `indicator`.
    pub indicator: Option<String>,
    /// `<relPosition>`.
    pub rel: Option<Point>,
    /// `<reference name>` (a named action) or `<inline>` body.
    pub action: ActionTarget,
    /// Its `<connectionPointOut>`, when written.
    pub output: Option<PointOut>,
}

/// What an association runs.
#[derive(Debug, Clone, PartialEq)]
pub enum ActionTarget {
    /// A named action of the POU, or a variable.
    Reference(String),
    /// An inline body.
    Inline(BodyModel),
    /// Neither (the importer reports it).
    Missing,
}

/// A named `<action>` or `<transition>` of a POU.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedBody {
    /// Its name.
    pub name: String,
    /// Its body (`None` when it has none plcrun reads).
    pub body: Option<BodyModel>,
}

/// An SFC POU's chart as drawn, with its named actions and transitions.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartBody {
    /// The `<SFC>` body.
    pub chart: Diagram,
    /// `<actions>`.
    pub actions: Vec<NamedBody>,
    /// `<transitions>`.
    pub transitions: Vec<NamedBody>,
    /// plcrun's plain statements of the chart (`<addData>`), if any.
    pub statements: Option<String>,
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
            ElementKind::Step { .. } => "step",
            ElementKind::Transition { .. } => "transition",
            ElementKind::SelectionDivergence => "selectionDivergence",
            ElementKind::SelectionConvergence => "selectionConvergence",
            ElementKind::SimultaneousDivergence => "simultaneousDivergence",
            ElementKind::SimultaneousConvergence => "simultaneousConvergence",
            ElementKind::JumpStep(_) => "jumpStep",
            ElementKind::ActionBlock(_) => "actionBlock",
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
    /// A step's `<connectionPointOutAction>`.
    pub action_point: Option<PointOut>,
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
            action_point: None,
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
