//! A cycle must not allocate: the executor works in preallocated memory.
//! A counting global allocator measures allocations made while cycles run.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator and only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_in_cycles(name: &str, text: &str, cycles: usize) -> usize {
    let mut plc = plcrun::Plc::compile_files(&[(name, text)], &plcrun::Options::default())
        .unwrap_or_else(|e| panic!("{name} does not compile:\n{e}"));
    // Warm up: the first cycles may touch lazily created state.
    for _ in 0..3 {
        plc.run_cycle().expect("cycle");
    }
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for _ in 0..cycles {
        plc.run_cycle().expect("cycle");
    }
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

// One test function: the allocation counter is global to the process, so a
// second test running in parallel would disturb the count.
#[test]
fn cycles_do_not_allocate() {
    // (The instance sizes of the standard FBs are checked by
    // `stdlib::layout::tests::standard_instances_are_small`.)
    let programs = [
        (
            "bench_a",
            include_str!("../benches/programs/bench_a_bool_logic.st"),
        ),
        (
            "bench_b",
            include_str!("../benches/programs/bench_b_int_sieve.st"),
        ),
        (
            "bench_c_array",
            include_str!("../benches/programs/bench_c_fb_array.st"),
        ),
        (
            "bench_d",
            include_str!("../benches/programs/bench_d_real_math.st"),
        ),
        ("cmd_monitor", include_str!("../programs/cmd_monitor.st")),
        ("alg02", include_str!("../programs/alg02.il")),
    ];
    for (name, text) in programs {
        let n = allocations_in_cycles(name, text, 20);
        assert_eq!(n, 0, "{name}: {n} allocations in 20 cycles");
    }
}
