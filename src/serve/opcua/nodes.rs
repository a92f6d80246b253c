//! The `urn:awl:plc` namespace: the `PLC` object and the program's folders in the server's
//! address space (for browsing), and its values read, written and sampled from the CPU at its
//! control point. A node id is an operand ([`Catalog::resolve`]), so reads, writes and monitored
//! items take any operand, browsed or not.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use async_trait::async_trait;
use opcua_core::sync::RwLock;
use opcua_server::address_space::{AddressSpace, MethodBuilder, ObjectBuilder, VariableBuilder};
use opcua_server::diagnostics::NamespaceMetadata;
use opcua_server::node_manager::memory::InMemoryNodeManagerImpl;
use opcua_server::node_manager::{
    MethodCall, MonitoredItemRef, MonitoredItemUpdateRef, ParsedReadValueId, ParsedWriteValue,
    RequestContext, ServerContext, WriteNode,
};
use opcua_server::{CreateMonitoredItem, MonitoredItemHandle, SubscriptionCache};
use opcua_types::{
    AttributeId, DataTypeId, DataValue, DateTime, Identifier, NodeId, NumericRange, ObjectId,
    QualifiedName, StatusCode, TimestampsToReturn, Variant,
};
use tokio::sync::oneshot;

use super::super::request::{
    Client, Control, ControlError, CpuMode, Item, ItemResult, Probe, Protocol, Reading, Request,
    Requests, Sample,
};
use super::catalog::{CYCLE, CYCLE_TIME, Catalog, Reads, STATE, Variable};
use super::value;

/// The namespace of the PLC's nodes.
pub const NAMESPACE: &str = "urn:awl:plc";

/// The shortest sampling interval a monitored item gets.
pub const FASTEST_SAMPLING_MS: f64 = 10.0;

/// The methods of the `PLC` object and the mode change each asks for.
const METHODS: [(&str, Control); 3] = [
    ("Stop", Control::Stop),
    ("WarmRestart", Control::HotStart),
    ("ColdRestart", Control::ColdStart),
];

/// What a node's value is: one of the `PLC` object's figures, or a variable of the program.
#[derive(Debug, Clone, PartialEq)]
enum Wanted {
    State,
    Cycle,
    CycleTime,
    Value(Variable),
}

/// The sampled nodes: per node, its monitored items' intervals and when it is due.
#[derive(Default)]
struct Monitored {
    nodes: HashMap<NodeId, Watched>,
}

struct Watched {
    wanted: Arc<Wanted>,
    intervals: HashMap<MonitoredItemHandle, Duration>,
    due: Instant,
}

impl Watched {
    fn every(&self) -> Duration {
        self.intervals
            .values()
            .min()
            .copied()
            .unwrap_or(Duration::MAX)
    }
}

pub struct PlcNodes {
    namespace: NamespaceMetadata,
    catalog: Arc<Catalog>,
    requests: Requests,
    read_only: bool,
    monitored: Arc<Mutex<Monitored>>,
}

impl PlcNodes {
    /// The node manager, its namespace registered and its nodes in `address_space`.
    pub fn new(
        context: &ServerContext,
        address_space: &mut AddressSpace,
        catalog: Arc<Catalog>,
        requests: Requests,
        read_only: bool,
    ) -> PlcNodes {
        let index = context
            .type_tree
            .write()
            .namespaces_mut()
            .add_namespace(NAMESPACE);
        address_space.add_namespace(NAMESPACE, index);
        let nodes = PlcNodes {
            namespace: NamespaceMetadata {
                namespace_uri: NAMESPACE.to_string(),
                namespace_index: index,
                ..Default::default()
            },
            catalog,
            requests,
            read_only,
            monitored: Arc::default(),
        };
        nodes.insert(address_space);
        nodes
    }

    fn index(&self) -> u16 {
        self.namespace.namespace_index
    }

    fn id(&self, text: &str) -> NodeId {
        NodeId::new(self.index(), text)
    }

    fn name(&self, text: &str) -> QualifiedName {
        QualifiedName::new(self.index(), text)
    }

    fn insert(&self, address_space: &mut AddressSpace) {
        let plc = self.id("PLC");
        ObjectBuilder::new(&plc, self.name("PLC"), "PLC")
            .organized_by(ObjectId::ObjectsFolder)
            .has_type_definition(opcua_types::ObjectTypeId::BaseObjectType)
            .insert(address_space);
        let figures = [
            (STATE, "State", DataTypeId::String),
            (CYCLE, "Cycle", DataTypeId::UInt64),
            (CYCLE_TIME, "CycleTime", DataTypeId::Double),
        ];
        for (id, name, data_type) in figures {
            VariableBuilder::new(&self.id(id), self.name(name), name)
                .data_type(data_type)
                .value(Variant::Empty)
                .component_of(plc.clone())
                .has_type_definition(opcua_types::VariableTypeId::BaseDataVariableType)
                .insert(address_space);
        }
        for (name, _) in METHODS {
            MethodBuilder::new(&self.id(&format!("PLC.{name}")), self.name(name), name)
                .component_of(plc.clone())
                .executable(true)
                .user_executable(!self.read_only)
                .insert(address_space);
        }
        let access = value::access(self.read_only);
        for node in &self.catalog.nodes {
            let id = self.id(&node.id);
            let parent = self.id(&node.parent);
            let name = self.name(&node.browse_name);
            let Some(variable) = &node.variable else {
                ObjectBuilder::new(&id, name, node.browse_name.as_str())
                    .is_folder()
                    .organized_by(parent)
                    .insert(address_space);
                continue;
            };
            let mut builder = VariableBuilder::new(&id, name, node.browse_name.as_str())
                .data_type(variable.kind.data_type())
                .value(Variant::Empty)
                .access_level(access)
                .user_access_level(access)
                .minimum_sampling_interval(FASTEST_SAMPLING_MS)
                .has_type_definition(opcua_types::VariableTypeId::BaseDataVariableType)
                .organized_by(parent);
            if let Reads::Many(elements) = &variable.reads {
                builder = builder
                    .value_rank(1)
                    .array_dimensions(&[elements.len() as u32]);
            }
            builder.insert(address_space);
        }
    }

    /// What a node id of this namespace stands for.
    fn wanted(&self, id: &NodeId) -> Option<Wanted> {
        let Identifier::String(text) = &id.identifier else {
            return None;
        };
        if id.namespace != self.index() {
            return None;
        }
        Some(match text.as_ref() {
            STATE => Wanted::State,
            CYCLE => Wanted::Cycle,
            CYCLE_TIME => Wanted::CycleTime,
            operand => Wanted::Value(self.catalog.resolve(operand)?),
        })
    }

    fn client(context: &RequestContext) -> Client {
        Client {
            protocol: Protocol::OpcUa,
            number: context.session_id,
        }
    }

    fn layout(&self) -> crate::address::Layout {
        self.catalog.layout()
    }
}

/// Reads the values of `wanted` at one control point; `BadNodeIdUnknown` for `None`.
async fn sample(requests: &Requests, wanted: &[Option<&Wanted>]) -> Vec<DataValue> {
    let probes = wanted
        .iter()
        .flatten()
        .flat_map(|wanted| match wanted {
            Wanted::Value(variable) => probes_of(variable),
            _ => Vec::new(),
        })
        .collect();
    let (reply, answer) = oneshot::channel();
    let answered = match requests.send(Request::Sample { probes, reply }) {
        Ok(()) => answer.await.ok(),
        Err(_) => None,
    };
    match answered {
        Some(sample) => values_of(wanted, &sample),
        None => vec![failed(StatusCode::BadServerHalted); wanted.len()],
    }
}

fn probes_of(variable: &Variable) -> Vec<Probe> {
    match &variable.reads {
        Reads::One(target) => vec![Probe::Operand(*target)],
        Reads::Text(range) => vec![Probe::Bytes(*range)],
        Reads::Many(targets) => targets.iter().map(|&at| Probe::Operand(at)).collect(),
    }
}

fn failed(status: StatusCode) -> DataValue {
    DataValue {
        status: Some(status),
        server_timestamp: Some(DateTime::now()),
        ..Default::default()
    }
}

fn mode_name(mode: CpuMode) -> &'static str {
    match mode {
        CpuMode::Run => "RUN",
        CpuMode::Stop => "STOP",
        CpuMode::Startup => "STARTUP",
        CpuMode::Hold => "HOLD",
    }
}

/// The values a sample gave, each stamped with the simulated time it was read at.
fn values_of(wanted: &[Option<&Wanted>], sample: &Sample) -> Vec<DataValue> {
    let source = value::timestamp(sample.clock_ms);
    let mut readings = sample.readings.iter();
    wanted
        .iter()
        .map(|wanted| {
            let value = match wanted {
                None => Err(StatusCode::BadNodeIdUnknown),
                Some(Wanted::State) => Ok(Variant::from(mode_name(sample.mode))),
                Some(Wanted::Cycle) => Ok(Variant::UInt64(sample.cycles)),
                Some(Wanted::CycleTime) => Ok(Variant::Double(sample.cycle_time_ms)),
                Some(Wanted::Value(variable)) => read_value(variable, &mut readings),
            };
            match value {
                Ok(value) => DataValue {
                    value: Some(value),
                    status: Some(StatusCode::Good),
                    source_timestamp: Some(source),
                    server_timestamp: Some(DateTime::now()),
                    ..Default::default()
                },
                Err(status) => failed(status),
            }
        })
        .collect()
}

/// A variable's value from its readings (taken from `readings`, one per probe).
fn read_value<'a>(
    variable: &Variable,
    readings: &mut impl Iterator<Item = &'a Reading>,
) -> Result<Variant, StatusCode> {
    let mut next = || match readings.next() {
        Some(Reading::Operand(Some(raw))) => Ok(variable.kind.variant(*raw)),
        Some(Reading::Bytes(Ok(bytes))) => Ok(value::text(bytes)),
        Some(Reading::Bytes(Err(error))) => Err(value::status_of(*error)),
        // A data block that is not (or no longer) loaded.
        _ => Err(StatusCode::BadNodeIdUnknown),
    };
    match &variable.reads {
        Reads::One(_) | Reads::Text(_) => next(),
        Reads::Many(targets) => {
            let elements: Vec<_> = targets.iter().map(|_| next()).collect();
            let elements: Result<Vec<_>, _> = elements.into_iter().collect();
            Ok(variable.kind.array(elements?))
        }
    }
}

/// Writes `items` as an S7 client's write; `None` when the CPU no longer answers.
async fn access(requests: &Requests, client: Client, items: Vec<Item>) -> Option<Vec<ItemResult>> {
    let (reply, answer) = oneshot::channel();
    requests
        .send(Request::Access {
            client,
            items,
            reply,
        })
        .ok()?;
    answer.await.ok()
}

impl PlcNodes {
    /// The writes a client's value of a node stands for.
    fn writes(&self, written: &ParsedWriteValue) -> Result<Vec<Item>, StatusCode> {
        let wanted = self
            .wanted(&written.node_id)
            .ok_or(StatusCode::BadNodeIdUnknown)?;
        let (Wanted::Value(variable), AttributeId::Value) = (wanted, written.attribute_id) else {
            return Err(StatusCode::BadNotWritable);
        };
        if self.read_only {
            return Err(StatusCode::BadUserAccessDenied);
        }
        if written.index_range != NumericRange::None {
            return Err(StatusCode::BadWriteNotSupported);
        }
        let value = written
            .value
            .value
            .as_ref()
            .ok_or(StatusCode::BadTypeMismatch)?;
        let layout = self.layout();
        match &variable.reads {
            Reads::One(target) => Ok(vec![value::write_item(
                *target,
                variable.kind.raw(value)?,
                layout,
            )?]),
            Reads::Text(range) => Ok(vec![value::text_write(*range, value)?]),
            Reads::Many(targets) => {
                let Variant::Array(array) = value else {
                    return Err(StatusCode::BadTypeMismatch);
                };
                if array.values.len() != targets.len() {
                    return Err(StatusCode::BadOutOfRange);
                }
                targets
                    .iter()
                    .zip(&array.values)
                    .map(|(&target, element)| {
                        value::write_item(target, variable.kind.raw(element)?, layout)
                    })
                    .collect()
            }
        }
    }

    /// Adds monitored items of `node` to the sampled ones.
    fn watch(&self, node: &NodeId, wanted: Wanted, handle: MonitoredItemHandle, every: Duration) {
        let mut monitored = self.monitored.lock().expect("no sampler panics");
        let watched = monitored
            .nodes
            .entry(node.clone())
            .or_insert_with(|| Watched {
                wanted: Arc::new(wanted),
                intervals: HashMap::new(),
                due: Instant::now() + every,
            });
        watched.intervals.insert(handle, every);
    }

    async fn control(&self, client: Client, command: Control) -> StatusCode {
        let (reply, answer) = oneshot::channel();
        let request = Request::Control {
            client,
            command,
            reply,
        };
        if self.requests.send(request).is_err() {
            return StatusCode::BadServerHalted;
        }
        match answer.await {
            Ok(Ok(())) => StatusCode::Good,
            Ok(Err(ControlError::ReadOnly)) => StatusCode::BadUserAccessDenied,
            Ok(Err(ControlError::AlreadyRunning)) => StatusCode::BadInvalidState,
            Err(_) => StatusCode::BadServerHalted,
        }
    }
}

fn every(interval_ms: f64) -> Duration {
    Duration::from_secs_f64(interval_ms.max(FASTEST_SAMPLING_MS) / 1000.0)
}

#[async_trait]
impl InMemoryNodeManagerImpl for PlcNodes {
    async fn init(&self, _address_space: &mut AddressSpace, context: ServerContext) {
        tokio::spawn(run_sampler(
            Arc::clone(&self.monitored),
            self.requests.clone(),
            context.subscriptions.clone(),
        ));
    }

    fn name(&self) -> &str {
        "awl"
    }

    fn namespaces(&self) -> Vec<NamespaceMetadata> {
        vec![self.namespace.clone()]
    }

    async fn read_values(
        &self,
        _context: &RequestContext,
        _address_space: &RwLock<AddressSpace>,
        nodes: &[&ParsedReadValueId],
        _max_age: f64,
        _timestamps_to_return: TimestampsToReturn,
    ) -> Vec<DataValue> {
        let wanted: Vec<Option<Wanted>> = nodes
            .iter()
            .map(|node| self.wanted(&node.node_id))
            .collect();
        let wanted: Vec<Option<&Wanted>> = wanted.iter().map(Option::as_ref).collect();
        sample(&self.requests, &wanted).await
    }

    async fn create_value_monitored_items(
        &self,
        _context: &RequestContext,
        _address_space: &RwLock<AddressSpace>,
        items: &mut [&mut &mut CreateMonitoredItem],
    ) {
        let wanted: Vec<Option<Wanted>> = items
            .iter()
            .map(|item| self.wanted(&item.item_to_monitor().node_id))
            .collect();
        let values = {
            let wanted: Vec<Option<&Wanted>> = wanted.iter().map(Option::as_ref).collect();
            sample(&self.requests, &wanted).await
        };
        for ((item, wanted), value) in items.iter_mut().zip(wanted).zip(values) {
            let Some(wanted) = wanted else {
                item.set_status(StatusCode::BadNodeIdUnknown);
                continue;
            };
            let interval = item.sampling_interval().max(FASTEST_SAMPLING_MS);
            item.revise_sampling_interval(interval);
            item.set_initial_value(value);
            item.set_status(StatusCode::Good);
            let node = item.item_to_monitor().node_id.clone();
            self.watch(&node, wanted, item.handle(), every(interval));
        }
    }

    async fn modify_monitored_items(
        &self,
        _context: &RequestContext,
        items: &[&MonitoredItemUpdateRef],
    ) {
        let mut monitored = self.monitored.lock().expect("no sampler panics");
        for item in items {
            if let Some(watched) = monitored.nodes.get_mut(item.node_id()) {
                let interval = item.update().revised_sampling_interval;
                watched.intervals.insert(item.handle(), every(interval));
            }
        }
    }

    async fn delete_monitored_items(&self, _context: &RequestContext, items: &[&MonitoredItemRef]) {
        let mut monitored = self.monitored.lock().expect("no sampler panics");
        for item in items {
            if let Some(watched) = monitored.nodes.get_mut(item.node_id()) {
                watched.intervals.remove(&item.handle());
                if watched.intervals.is_empty() {
                    monitored.nodes.remove(item.node_id());
                }
            }
        }
    }

    async fn write(
        &self,
        context: &RequestContext,
        _address_space: &RwLock<AddressSpace>,
        nodes_to_write: &mut [&mut WriteNode],
    ) -> Result<(), StatusCode> {
        let mut items = Vec::new();
        let mut spans = Vec::new();
        for node in nodes_to_write.iter_mut() {
            match self.writes(node.value()) {
                Ok(writes) => {
                    spans.push(Some(items.len()..items.len() + writes.len()));
                    items.extend(writes);
                }
                Err(status) => {
                    node.set_status(status);
                    spans.push(None);
                }
            }
        }
        if items.is_empty() {
            return Ok(());
        }
        let results = access(&self.requests, Self::client(context), items)
            .await
            .ok_or(StatusCode::BadServerHalted)?;
        for (node, span) in nodes_to_write.iter_mut().zip(spans) {
            let Some(span) = span else { continue };
            let error = results[span]
                .iter()
                .find_map(|result| result.as_ref().err());
            node.set_status(error.map_or(StatusCode::Good, |error| value::status_of(*error)));
        }
        Ok(())
    }

    async fn call(
        &self,
        context: &RequestContext,
        _address_space: &RwLock<AddressSpace>,
        methods_to_call: &mut [&mut &mut MethodCall],
    ) -> Result<(), StatusCode> {
        for method in methods_to_call.iter_mut() {
            let command = METHODS
                .iter()
                .find(|(name, _)| *method.method_id() == self.id(&format!("PLC.{name}")))
                .map(|(_, command)| *command);
            let Some(command) = command else {
                method.set_status(StatusCode::BadMethodInvalid);
                continue;
            };
            let status = self.control(Self::client(context), command).await;
            method.set_outputs(Vec::new());
            method.set_status(status);
        }
        Ok(())
    }
}

/// Samples the monitored nodes that are due, all in one request, every
/// [`FASTEST_SAMPLING_MS`], and hands the values to their subscriptions.
async fn run_sampler(
    monitored: Arc<Mutex<Monitored>>,
    requests: Requests,
    subscriptions: Arc<SubscriptionCache>,
) {
    let mut tick = tokio::time::interval(every(FASTEST_SAMPLING_MS));
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    loop {
        tick.tick().await;
        let due = due(&monitored);
        if due.is_empty() {
            continue;
        }
        let wanted: Vec<Option<&Wanted>> = due.iter().map(|(_, wanted)| Some(&**wanted)).collect();
        let values = sample(&requests, &wanted).await;
        if requests.is_closed() {
            return;
        }
        subscriptions.notify_data_change(
            values
                .into_iter()
                .zip(&due)
                .map(|(value, (node, _))| (value, node, AttributeId::Value)),
        );
    }
}

/// The nodes due for a sample now, each then due again after its shortest interval.
fn due(monitored: &Mutex<Monitored>) -> Vec<(NodeId, Arc<Wanted>)> {
    let now = Instant::now();
    let mut monitored = monitored.lock().expect("no sampler panics");
    monitored
        .nodes
        .iter_mut()
        .filter(|(_, watched)| watched.due <= now)
        .map(|(node, watched)| {
            watched.due = now + watched.every();
            (node.clone(), Arc::clone(&watched.wanted))
        })
        .collect()
}
