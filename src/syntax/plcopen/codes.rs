//! The diagnostic codes of the PLCopen importer (`E801`-`E829`,
//! `W801`-`W809`), documented in `docs/diagnostics.md`.

/// The file is not well-formed XML.
pub const MALFORMED_XML: &str = "E801";
/// The root element is not `<project>`.
pub const NOT_A_PROJECT: &str = "E802";
/// An element that has no place where it stands.
pub const UNKNOWN_ELEMENT: &str = "E803";
/// A graphical body (FBD, LD) refused: retired since FBD and LD are
/// lowered to ST (issue #29); kept so that the code is never reused.
pub const GRAPHICAL_BODY: &str = "E804";
/// A required attribute is missing or empty.
pub const MISSING_ATTRIBUTE: &str = "E805";
/// A name attribute that is not an IEC identifier.
pub const BAD_NAME: &str = "E806";
/// A TC6 element plcrun cannot represent.
pub const REFUSED: &str = "E807";
/// A `refLocalId` naming no element of the body.
pub const DANGLING_REF: &str = "E808";
/// Two elements of one body with the same `localId`.
pub const DUPLICATE_ID: &str = "E809";
/// An SFC network whose connections do not form steps and transitions.
pub const SFC_STRUCTURE: &str = "E810";
/// A `jumpStep` to a step the chart does not have.
pub const UNKNOWN_JUMP_TARGET: &str = "E811";
/// A reference to a transition or action the POU does not declare.
pub const UNKNOWN_REFERENCE: &str = "E812";
/// Markup inside a textual body or value.
pub const MARKUP_IN_TEXT: &str = "E813";
/// An element is missing a required child (a POU without body...).
pub const MISSING_CHILD: &str = "E814";
/// `addData` whose `handleUnknown="implementation"` says it changes meaning.
pub const MEANINGFUL_ADD_DATA: &str = "E815";
/// The project's namespace is not TC6 XML 2.01 or 2.0.
pub const UNKNOWN_NAMESPACE: &str = "W801";
/// An `<outVariable>`, `<inOutVariable>` or `<coil>` with nothing connected
/// to its input: ignored.
pub const UNWIRED_WRITE: &str = "W802";
/// A `<continuation>` without its `<connector>`, two connectors of one name,
/// or connectors leading back to themselves.
pub const CONNECTOR: &str = "E816";
/// A connection from an output the source element does not have.
pub const BAD_CONNECTION: &str = "E817";
/// A contact, a transition's condition or a block's in-out with nothing
/// connected to it.
pub const UNCONNECTED: &str = "E818";
/// A `<jump>` to a label the body does not have, or a label placed twice.
pub const LABEL: &str = "E819";
/// A function output kept in a hidden variable whose type cannot be worked out.
pub const UNTYPED_VALUE: &str = "E820";
