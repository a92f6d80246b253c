//! Counters 0…999: count up and down on rising RLO edges, set to a BCD value, reset.

use crate::rules::bcd;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct Counter {
    pub value: u16,
    up_edge: bool,
    down_edge: bool,
    set_edge: bool,
    enable_edge: bool,
}

pub const MAX_COUNT: u16 = 999;

/// The count of a KC/BCD word (three digits in bits 0–11).
pub fn decode_count(word: u32) -> u16 {
    let digit = |shift: u32| ((word >> shift) & 0xF).min(9) as u16;
    digit(8) * 100 + digit(4) * 10 + digit(0)
}

impl Counter {
    pub fn up(&mut self, rlo: bool) {
        if rlo && !self.up_edge && self.value < MAX_COUNT {
            self.value += 1;
        }
        self.up_edge = rlo;
    }

    pub fn down(&mut self, rlo: bool) {
        if rlo && !self.down_edge && self.value > 0 {
            self.value -= 1;
        }
        self.down_edge = rlo;
    }

    /// `S C n`: on a rising edge the counter takes the BCD count in ACCU 1.
    pub fn set(&mut self, rlo: bool, word: u32) {
        if rlo && !self.set_edge {
            self.value = decode_count(word);
        }
        self.set_edge = rlo;
    }

    pub fn reset(&mut self, rlo: bool) {
        if rlo {
            self.value = 0;
        }
    }

    /// `FR C n`: a rising edge lets the next `CU`/`CD`/`S` with RLO 1 act without a new edge.
    pub fn enable(&mut self, rlo: bool) {
        if rlo && !self.enable_edge {
            self.up_edge = false;
            self.down_edge = false;
            self.set_edge = false;
        }
        self.enable_edge = rlo;
    }

    pub fn bit(&self) -> bool {
        self.value != 0
    }

    pub fn coded(&self) -> u32 {
        bcd::encode(u32::from(self.value), 3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_edges_within_limits() {
        let mut counter = Counter::default();
        counter.up(true);
        counter.up(true);
        assert_eq!(counter.value, 1, "only the rising edge counts");
        counter.down(true);
        counter.down(false);
        counter.down(true);
        assert_eq!(counter.value, 0);
        assert!(!counter.bit());
        counter.set(true, 0x999);
        counter.up(false);
        counter.up(true);
        assert_eq!(counter.value, 999, "no count above 999");
        assert_eq!(counter.coded(), 0x999);
        counter.reset(true);
        assert_eq!(counter.value, 0);
    }

    #[test]
    fn enable_counts_again_without_an_edge() {
        let mut counter = Counter::default();
        counter.up(true);
        counter.enable(true);
        counter.up(true);
        assert_eq!(counter.value, 2);
    }
}
