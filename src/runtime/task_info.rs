//! TwinCAT's task information: the global array
//! `TwinCAT_SystemInfoVarList._TaskInfo` (one `PlcTaskSystemInfo` per
//! task) and the index of the task that runs (`GETCURTASKINDEX`,
//! `GETCURTASKINDEXEX()`), which plcrun's TwinCAT library declares
//! (docs/twincat.md, "Libraries") and the runtime keeps up to date: before
//! each program runs, the index of its task; at the first program of each
//! activation of a task, its cycle count, first-cycle flag and start time.
//! The settings (cycle time, priority, ADS port, name) are written at
//! start and after every reset. A program without the library's
//! `_TaskInfo` has none of this, and its cycle pays one test per program.

use crate::ir::image::Image;
use crate::ir::type_table::{Member, TypeKind};
use crate::vm::Machine;

/// The library's array of task information, and its element type.
const ARRAY: &str = "_TaskInfo";
const ELEMENT: &str = "PlcTaskSystemInfo";
/// The library's global holding the running task's index.
const CURRENT: &str = "__CurrentTaskIndex";
/// TwinCAT numbers the ADS ports of a runtime's tasks from 350.
const FIRST_ADS_PORT: u64 = 350;

/// Where the task information lives, and the activations counted so far.
#[derive(Debug, Clone)]
pub(crate) struct TaskInfo {
    /// Slot of `__CurrentTaskIndex`.
    current: usize,
    /// Per task (the image's order), the first slot of its `_TaskInfo`
    /// element, when the array has an element of its index.
    elements: Vec<Option<usize>>,
    /// Offsets of the fields in an element.
    fields: Fields,
    /// Per task, its activations so far and the cycle of the last one.
    activations: Vec<(u32, Option<u64>)>,
}

/// Slot offsets of `PlcTaskSystemInfo`'s fields (`None`: not declared).
#[derive(Debug, Clone, Default)]
struct Fields {
    cycle_time: Option<usize>,
    priority: Option<usize>,
    ads_port: Option<usize>,
    cycle_count: Option<usize>,
    dc_task_time: Option<usize>,
    first_cycle: Option<usize>,
    task_name: Option<usize>,
}

impl TaskInfo {
    /// The task information of `image`, when it declares the library's
    /// `_TaskInfo` (an array of `PlcTaskSystemInfo` indexed from 1) and
    /// `__CurrentTaskIndex`.
    pub(crate) fn of(image: &Image) -> Option<TaskInfo> {
        let global = |name: &str| {
            image
                .globals
                .iter()
                .find(|g| g.name.eq_ignore_ascii_case(name))
        };
        let array = global(ARRAY)?;
        let current = global(CURRENT)?.addr as usize;
        let TypeKind::Array { dims, elem } = &image.types.get(array.ty).kind else {
            return None;
        };
        let element = image.types.get(*elem);
        let (TypeKind::Struct { fields }, [dim]) = (&element.kind, dims.as_slice()) else {
            return None;
        };
        if !element.name.eq_ignore_ascii_case(ELEMENT) {
            return None;
        }
        let stride = element.size as usize;
        let elements = (1..=image.tasks.len() as i64)
            .map(|index| {
                (dim.lo..=dim.hi)
                    .contains(&index)
                    .then(|| array.addr as usize + (index - dim.lo) as usize * stride)
            })
            .collect();
        Some(TaskInfo {
            current,
            elements,
            fields: Fields::of(fields),
            activations: vec![(0, None); image.tasks.len()],
        })
    }

    /// Writes each task's settings into its element and forgets the
    /// activations counted (at start, and after a reset). `base_tick` is
    /// the cycle time of a task without an interval of its own.
    pub(crate) fn reset(&mut self, image: &Image, machine: &mut Machine, base_tick: i64) {
        self.activations.fill((0, None));
        let f = &self.fields;
        for (k, task) in image.tasks.iter().enumerate() {
            let Some(at) = self.elements[k] else { continue };
            let interval = if task.interval > 0 {
                task.interval
            } else {
                base_tick
            };
            let mem = &mut machine.mem;
            // TwinCAT counts the cycle time in 100 ns units.
            store(mem, at, f.cycle_time, (interval / 100) as u64);
            store(mem, at, f.priority, task.priority as u64);
            store(mem, at, f.ads_port, FIRST_ADS_PORT + k as u64);
            if let Some(off) = f.task_name
                && let Some(&id) = mem.get(at + off)
                && let Some(name) = machine.strings.get_mut(id as usize)
            {
                name.set(&task.name);
            }
        }
    }

    /// Before a program of task `task` runs in cycle `cycle` at clock
    /// `now` (ns): the task's index, and at the first program of the
    /// activation its count, first-cycle flag and start time.
    #[inline]
    pub(crate) fn enter(&mut self, task: usize, cycle: u64, now: i64, mem: &mut [u64]) {
        if let Some(slot) = mem.get_mut(self.current) {
            *slot = task as u64 + 1;
        }
        let Some((count, last)) = self.activations.get_mut(task) else {
            return;
        };
        if *last == Some(cycle) {
            return;
        }
        *last = Some(cycle);
        *count = count.wrapping_add(1);
        let Some(Some(at)) = self.elements.get(task) else {
            return;
        };
        let f = &self.fields;
        store(mem, *at, f.cycle_count, u64::from(*count));
        store(mem, *at, f.first_cycle, u64::from(*count == 1));
        store(mem, *at, f.dc_task_time, now as u64);
    }
}

impl TaskInfo {
    /// Takes over the activations counted by `old`, the task information
    /// of the version an online change replaces, when the tasks are the
    /// same: the cycle counts go on.
    pub(crate) fn carry_over(&mut self, old: &TaskInfo) {
        if old.activations.len() == self.activations.len() {
            self.activations.clone_from(&old.activations);
        }
    }
}

impl Fields {
    fn of(members: &[Member]) -> Fields {
        let offset = |name: &str| {
            members
                .iter()
                .find(|m| m.name.eq_ignore_ascii_case(name))
                .map(|m| m.offset as usize)
        };
        Fields {
            cycle_time: offset("CycleTime"),
            priority: offset("Priority"),
            ads_port: offset("AdsPort"),
            cycle_count: offset("CycleCount"),
            dc_task_time: offset("DcTaskTime"),
            first_cycle: offset("FirstCycle"),
            task_name: offset("TaskName"),
        }
    }
}

/// Stores `value` in the field at `offset` of the element at `at`.
fn store(mem: &mut [u64], at: usize, offset: Option<usize>, value: u64) {
    if let Some(slot) = offset.and_then(|off| mem.get_mut(at + off)) {
        *slot = value;
    }
}
