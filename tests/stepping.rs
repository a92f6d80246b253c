//! The stepping loop (program status, the debugger) runs programs exactly as the plain loop
//! does: same state, clock, instruction count and interrupt statistics for every sample.

mod common;

use awl::compiler::Op;
use awl::runner::{self, Ran, RunOptions};
use awl::state::State;
use awl::vm::Cpu;
use awl::vm::probe::{Flow, Probe};

/// Looks at every operation and changes nothing; counts what it saw.
struct Counting(std::rc::Rc<std::cell::Cell<u64>>);

impl Probe for Counting {
    fn before(&mut self, _cpu: &mut Cpu) -> Flow {
        Flow::Go
    }

    fn after(&mut self, _cpu: &Cpu, _block: u16, _pc: u32, _op: Op) -> Flow {
        self.0.set(self.0.get() + 1);
        Flow::Go
    }
}

fn run(options: &RunOptions, probe: Option<Counting>) -> Ran {
    let mut prepared = runner::prepare(options).unwrap_or_else(|_| panic!("{options:?}"));
    prepared.cpu.probe = probe.map(|probe| Box::new(probe) as Box<dyn Probe>);
    prepared.run(&mut |_| true)
}

fn summary(ran: &Ran) -> String {
    let stats: Vec<_> = ran
        .cpu
        .engine
        .requested_obs()
        .map(|(ob, s)| (ob, *s))
        .collect();
    format!(
        "{:?}\n{:?} {} {} {} {:?}\n{stats:?}",
        State::capture(&ran.cpu, ran.outcome.stop.as_ref()),
        ran.outcome
            .stop
            .as_ref()
            .map(|stop| (stop.cause, stop.block, stop.pc)),
        ran.outcome.clock_ns,
        ran.outcome.cycles,
        ran.outcome.instructions,
        ran.cpu.longest_block,
    )
}

#[test]
fn every_sample_runs_the_same_with_a_probe() {
    let scenarios = common::sample_scenarios();
    assert!(scenarios.len() > 15);
    for path in scenarios {
        let options = RunOptions {
            scenario: Some(path.clone()),
            ..RunOptions::default()
        };
        let plain = run(&options, None);
        let seen = std::rc::Rc::new(std::cell::Cell::new(0));
        let stepped = run(&options, Some(Counting(seen.clone())));
        assert_eq!(summary(&plain), summary(&stepped), "{}", path.display());
        // Every executed op was shown once.
        assert_eq!(seen.get(), plain.outcome.instructions, "{}", path.display());
    }
}
