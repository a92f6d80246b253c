//! The execution loop allocates nothing: after a warm-up cycle, running many more cycles of a
//! program with calls, FB parameters, timers, counters and data blocks performs no allocation.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use awl::frontend;
use awl::profile;
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn running_cycles_allocates_nothing() {
    let source = std::fs::read_to_string("programs/two_motors.awl").unwrap()
        + "PB 1\n      C  DB 5\n      L  DW 0\n      L  KF +1\n      +F\n      T  DW 0\n      A  I 0.0\n      CU C 1\n      BE\nDB 5\n 0: KF +0\nOB 3\n      BE\n";
    let source = source.replacen("      BE\n", "      JU PB 1\n      BE\n", 1);
    let built = frontend::build_text(
        "alloc.awl",
        &source,
        profile::find("sinumerik-840c").unwrap(),
    );
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    let warm = cpu.run(RunLimit::Cycles(1));
    assert!(warm.stop.is_none());
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let outcome = cpu.run(RunLimit::Cycles(2000));
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(outcome.stop.is_none());
    assert!(outcome.instructions > 50_000);
    assert_eq!(after - before, 0, "allocations while running");
}
