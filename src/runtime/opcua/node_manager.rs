//! The PLC's namespace inside the OPC UA server: the nodes of the
//! [`Model`], their values as the last frame taken in left them (Read,
//! Browse, TranslateBrowsePaths and monitored items are the in-memory
//! node manager's), and Write, which checks a client's value and queues it
//! for the scan instead of storing it.

use super::exchange::ClientWrite;
use super::model::{Model, NodeKind};
use super::server::Shared;
use super::stats::add;
use super::types::{Kind, value_of, variant};
use async_opcua::server::address_space::{
    AccessLevel, AddressSpace, ObjectBuilder, VariableBuilder,
};
use async_opcua::server::diagnostics::NamespaceMetadata;
use async_opcua::server::node_manager::memory::InMemoryNodeManagerImpl;
use async_opcua::server::node_manager::{
    ParsedWriteValue, RequestContext, ServerContext, WriteNode,
};
use async_opcua::sync::RwLock;
use async_opcua::types::{
    Array, AttributeId, DataTypeId, Identifier, LocalizedText, NodeId, NumericRange, ObjectId,
    ObjectTypeId, QualifiedName, StatusCode, VariableTypeId, Variant,
};
use std::sync::Arc;
use std::sync::mpsc::{SyncSender, TrySendError};

/// The namespace URI of the PLC's nodes.
pub const PLCRUN_NAMESPACE: &str = "urn:plcrun:plc";

/// The node manager of the PLC's namespace.
pub(crate) struct PlcNodes {
    shared: Arc<Shared>,
    writes: SyncSender<ClientWrite>,
    namespace: NamespaceMetadata,
}

impl PlcNodes {
    /// Registers the namespace and fills `space` with the model's nodes,
    /// valued from the shared frame (called once, as the server is built).
    pub(crate) fn new(
        shared: Arc<Shared>,
        writes: SyncSender<ClientWrite>,
        context: ServerContext,
        space: &mut AddressSpace,
    ) -> PlcNodes {
        let index = context
            .type_tree
            .write()
            .namespaces_mut()
            .add_namespace(PLCRUN_NAMESPACE);
        space.add_namespace(PLCRUN_NAMESPACE, index);
        shared
            .namespace
            .store(index, std::sync::atomic::Ordering::Release);
        populate(&shared, index, space);
        PlcNodes {
            shared,
            writes,
            namespace: NamespaceMetadata {
                namespace_uri: PLCRUN_NAMESPACE.to_string(),
                namespace_index: index,
                ..Default::default()
            },
        }
    }

    /// The status of one client write: queued (Good) or why not.
    fn write_one(&self, context: &RequestContext, write: &ParsedWriteValue) -> StatusCode {
        let batch = match checked_write(&self.shared, write, context.token.is_anonymous()) {
            Ok(batch) => batch,
            Err(status) => return status,
        };
        match self.writes.try_send(batch) {
            Ok(()) => {
                add(&self.shared.counters.writes_queued, 1);
                StatusCode::Good
            }
            Err(TrySendError::Full(_)) => {
                add(&self.shared.counters.writes_refused_busy, 1);
                StatusCode::BadResourceUnavailable
            }
            Err(TrySendError::Disconnected(_)) => StatusCode::BadServerHalted,
        }
    }
}

/// The values a client's write gives the PLC's variables, checked: a node
/// of the PLC's namespace, its Value attribute, writable leaves, a user
/// logged in (`anonymous` false), an index range only on an array, and
/// values that fit the variables' types.
pub(crate) fn checked_write(
    shared: &Shared,
    write: &ParsedWriteValue,
    anonymous: bool,
) -> Result<ClientWrite, StatusCode> {
    let model = &shared.model;
    let node = node_of(shared, &write.node_id).ok_or(StatusCode::BadNodeIdUnknown)?;
    let leaves = model.leaves_of(node).ok_or(StatusCode::BadNotWritable)?;
    if write.attribute_id != AttributeId::Value || leaves.iter().any(|&l| !model.leaves[l].writable)
    {
        return Err(StatusCode::BadNotWritable);
    }
    if anonymous {
        return Err(StatusCode::BadUserAccessDenied);
    }
    let value = write
        .value
        .value
        .as_ref()
        .ok_or(StatusCode::BadTypeMismatch)?;
    let is_array = matches!(
        model.nodes[node].kind,
        NodeKind::Variable { dims: Some(_), .. }
    );
    if !is_array && write.index_range.has_range() {
        return Err(StatusCode::BadIndexRangeInvalid);
    }
    values(model, leaves, is_array, &write.index_range, value)
}

/// The node of a NodeId in the PLC's namespace.
fn node_of(shared: &Shared, id: &NodeId) -> Option<usize> {
    if id.namespace != shared.namespace.load(std::sync::atomic::Ordering::Acquire) {
        return None;
    }
    match &id.identifier {
        Identifier::String(s) => shared.model.by_id.get(s.as_ref()).copied(),
        _ => None,
    }
}

/// The values a write of `value` (over `range`) gives `leaves`.
fn values(
    model: &Model,
    leaves: &[usize],
    is_array: bool,
    range: &NumericRange,
    value: &Variant,
) -> Result<ClientWrite, StatusCode> {
    let targets: &[usize] = match range {
        NumericRange::None => leaves,
        NumericRange::Index(i) => leaves
            .get(*i as usize..*i as usize + 1)
            .ok_or(StatusCode::BadIndexRangeNoData)?,
        NumericRange::Range(a, b) => leaves
            .get(*a as usize..=*b as usize)
            .ok_or(StatusCode::BadIndexRangeNoData)?,
        NumericRange::MultipleRanges(_) => return Err(StatusCode::BadIndexRangeInvalid),
    };
    let items: Vec<&Variant> = match value {
        Variant::Array(a) => a.values.iter().collect(),
        scalar if !is_array || range.has_range() && targets.len() == 1 => vec![scalar],
        _ => return Err(StatusCode::BadTypeMismatch),
    };
    if items.len() != targets.len() {
        return Err(StatusCode::BadTypeMismatch);
    }
    targets
        .iter()
        .zip(items)
        .map(|(&leaf, v)| Ok((leaf, value_of(&model.leaves[leaf].kind, v)?)))
        .collect()
}

#[async_trait::async_trait]
impl InMemoryNodeManagerImpl for PlcNodes {
    async fn init(&self, _space: &mut AddressSpace, _context: ServerContext) {}

    fn name(&self) -> &str {
        "plcrun"
    }

    fn namespaces(&self) -> Vec<NamespaceMetadata> {
        vec![self.namespace.clone()]
    }

    async fn write(
        &self,
        context: &RequestContext,
        _space: &RwLock<AddressSpace>,
        nodes_to_write: &mut [&mut WriteNode],
    ) -> Result<(), StatusCode> {
        for node in nodes_to_write {
            let status = self.write_one(context, node.value());
            node.set_status(status);
        }
        Ok(())
    }
}

/// The value of node `node` in the current frame.
pub(crate) fn node_value(shared: &Shared, node: usize, raw: &[u64], text: &[String]) -> Variant {
    let model = &shared.model;
    let (leaves, dims) = match &model.nodes[node].kind {
        NodeKind::Variable { leaves, dims } => (leaves, dims),
        _ => return Variant::Empty,
    };
    let one = |l: usize| variant(&model.leaves[l].kind, raw[l], &text[l]);
    match dims {
        None => one(leaves[0]),
        Some(dims) => {
            let values: Vec<Variant> = leaves.iter().map(|&l| one(l)).collect();
            let ty = model.leaves[leaves[0]].kind.data_type();
            let scalar = scalar_type(&values, ty);
            let array = if dims.len() > 1 {
                Array::new_multi(scalar, values, dims.clone())
            } else {
                Array::new(scalar, values)
            };
            array.map_or(Variant::Empty, |a| Variant::Array(Box::new(a)))
        }
    }
}

/// The Variant scalar type of an array's elements.
fn scalar_type(values: &[Variant], ty: DataTypeId) -> async_opcua::types::VariantScalarTypeId {
    use async_opcua::types::VariantScalarTypeId as S;
    match values.first().and_then(Variant::scalar_type_id) {
        Some(t) => t,
        None => match ty {
            DataTypeId::String => S::String,
            _ => S::Int32,
        },
    }
}

/// Fills the address space with the model's nodes.
fn populate(shared: &Shared, ns: u16, space: &mut AddressSpace) {
    let model: &Model = &shared.model;
    let (raw, text) = shared.published.read(|f| (f.raw.clone(), f.text.clone()));
    let ids: Vec<NodeId> = model
        .nodes
        .iter()
        .map(|n| NodeId::new(ns, n.id.clone()))
        .collect();
    let objects: NodeId = ObjectId::ObjectsFolder.into();
    for (i, node) in model.nodes.iter().enumerate() {
        let name = QualifiedName::new(ns, node.name.as_str());
        let label = LocalizedText::from(node.name.as_str());
        let parent = node.parent.map_or(&objects, |p| &ids[p]);
        let under_folder = node
            .parent
            .is_none_or(|p| model.nodes[p].kind == NodeKind::Folder);
        match &node.kind {
            NodeKind::Folder => {
                space.add_folder(&ids[i], name, label, parent);
            }
            NodeKind::Object => {
                let b = ObjectBuilder::new(&ids[i], name, label)
                    .has_type_definition(ObjectTypeId::BaseObjectType);
                let b = if under_folder {
                    b.organized_by(parent.clone())
                } else {
                    b.component_of(parent.clone())
                };
                b.insert(space);
            }
            NodeKind::Variable { leaves, dims } => {
                let kind = &model.leaves[leaves[0]].kind;
                let writable = leaves.iter().all(|&l| model.leaves[l].writable);
                let access = if writable {
                    AccessLevel::CURRENT_READ | AccessLevel::CURRENT_WRITE
                } else {
                    AccessLevel::CURRENT_READ
                };
                let mut b = VariableBuilder::new(&ids[i], name, label)
                    .data_type(kind.data_type())
                    .value(node_value(shared, i, &raw, &text))
                    .access_level(access)
                    .user_access_level(access)
                    .minimum_sampling_interval(shared.cycle_ms)
                    .has_type_definition(VariableTypeId::BaseDataVariableType);
                if let Some(dims) = dims {
                    b = b.value_rank(dims.len() as i32).array_dimensions(dims);
                } else {
                    b = b.value_rank(-1);
                }
                let b = if under_folder {
                    b.organized_by(parent.clone())
                } else {
                    b.component_of(parent.clone())
                };
                b.insert(space);
                if let Kind::Enum(values) = kind {
                    enum_strings(ns, &ids[i], &node.id, values, space);
                }
            }
        }
    }
}

/// Gives an enumeration's Variable its `EnumStrings` property when its
/// values are 0, 1, 2... (the names in value order).
fn enum_strings(
    ns: u16,
    var: &NodeId,
    path: &str,
    values: &[(String, i64)],
    space: &mut AddressSpace,
) {
    let mut sorted: Vec<&(String, i64)> = values.iter().collect();
    sorted.sort_by_key(|(_, v)| *v);
    if sorted.iter().enumerate().any(|(k, (_, v))| *v != k as i64) {
        return;
    }
    let names: Vec<LocalizedText> = sorted
        .iter()
        .map(|(n, _)| LocalizedText::from(n.as_str()))
        .collect();
    let id = NodeId::new(ns, format!("{path}#EnumStrings"));
    VariableBuilder::new(&id, QualifiedName::new(0, "EnumStrings"), "EnumStrings")
        .data_type(DataTypeId::LocalizedText)
        .value_rank(1)
        .array_dimensions(&[names.len() as u32])
        .value(names)
        .access_level(AccessLevel::CURRENT_READ)
        .user_access_level(AccessLevel::CURRENT_READ)
        .has_type_definition(VariableTypeId::PropertyType)
        .property_of(var.clone())
        .insert(space);
}
