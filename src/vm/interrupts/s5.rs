//! The S5 CPUs of the S5-95U to S5-155U profiles: the generic engine, and the time-controlled
//! OBs (OB 10–18, OB 13 on the small CPUs) called by the CPU itself at their intervals. Their
//! interrupt OBs and priorities come from the profile; process interrupts come from the
//! scenario's `interrupt` events. A time-controlled call while the last one of the same OB is
//! still pending is lost, as any second request is.

use crate::profile::Profile;

use super::super::stop::Stop;
use super::{Cpu, FOREIGN_RULES, Rules, RulesState};

/// One time-controlled OB the program has: its interval and next call, in ns.
#[derive(Debug)]
struct Timed {
    ob: u8,
    every_ns: u64,
    next: u64,
}

#[derive(Debug, Default)]
pub struct S5 {
    timed: Vec<Timed>,
}

impl S5 {
    pub fn new(profile: &Profile) -> Self {
        let timed = profile
            .interrupt_obs
            .iter()
            .filter(|entry| entry.every_ms > 0)
            .map(|entry| Timed {
                ob: entry.ob,
                every_ns: u64::from(entry.every_ms) * 1_000_000,
                next: u64::MAX,
            })
            .collect();
        S5 { timed }
    }

    /// The time-controlled OB called next.
    fn earliest(&mut self) -> Option<&mut Timed> {
        self.timed.iter_mut().min_by_key(|timed| timed.next)
    }
}

impl Rules for S5 {
    fn saved(&self) -> RulesState {
        RulesState::S5 {
            next_calls: self
                .timed
                .iter()
                .map(|timed| (timed.ob, timed.next))
                .collect(),
        }
    }

    fn restore(&mut self, state: &RulesState) -> Result<(), &'static str> {
        let RulesState::S5 { next_calls } = state else {
            return Err(FOREIGN_RULES);
        };
        for (ob, next) in next_calls {
            let timed = self.timed.iter_mut().find(|timed| timed.ob == *ob);
            timed.ok_or(FOREIGN_RULES)?.next = *next;
        }
        Ok(())
    }

    fn next_due(&self) -> u64 {
        self.timed
            .iter()
            .map(|timed| timed.next)
            .min()
            .unwrap_or(u64::MAX)
    }

    /// The intervals start with RUN; an OB the program lacks is never called.
    fn start_run(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        for timed in &mut self.timed {
            if cpu.program.ob(timed.ob).is_some() {
                timed.next = cpu.clock + timed.every_ns;
            }
        }
        Ok(())
    }

    fn poll(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        if let Some(timed) = self.earliest() {
            let (ob, at) = (timed.ob, timed.next);
            timed.next = at.saturating_add(timed.every_ns);
            cpu.request(ob, at, None);
        }
        Ok(())
    }
}
