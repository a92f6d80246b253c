//! What a program needs of a CPU: the operation groups, operand ranges, block kinds, built-in
//! blocks, bracket depth and accumulators its checks asked a profile for. Gathered while it is
//! compiled for one profile, they tell which other profiles would compile it without errors
//! (`awl check` without `--cpu`) without compiling it again.

use crate::ast::BlockId;
use crate::mnemonics::{Area, BlockKind};
use crate::profile::{Feature, Profile};

use super::builtin::IntegralFb;
use crate::address::range::{SizeOf, extent};

/// One thing a check asks of the CPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Need {
    /// An operation of a group only some CPUs have.
    Feature(Feature),
    /// An address: its area's size must reach past it.
    Address { area: Area, index: u16 },
    /// FX and DX blocks.
    ExtendedBlocks,
    /// A call of a block the program does not define: an integral FB or a system OB.
    BuiltinBlock(BlockId),
    /// This many brackets open at once.
    Brackets(u8),
    /// ACCU 3 and 4 (`ENT`).
    FourAccumulators,
}

impl Need {
    pub fn met_by(self, profile: &Profile) -> bool {
        match self {
            Need::Feature(feature) => profile.has(feature),
            Need::Address { area, index } => {
                let (size, span) = extent(area);
                u32::from(index) + u32::from(span) <= u32::from(size.of(&profile.sizes))
            }
            Need::ExtendedBlocks => profile.extended_blocks,
            Need::BuiltinBlock(id) => builtin_on(id, profile),
            Need::Brackets(depth) => depth <= profile.bracket_depth,
            Need::FourAccumulators => profile.accumulators == 4,
        }
    }
}

/// Whether `profile` has block `id` built in, for a program that does not define it.
pub fn builtin_on(id: BlockId, profile: &Profile) -> bool {
    let Ok(number) = u8::try_from(id.number) else {
        return false;
    };
    match id.kind {
        BlockKind::Fb => profile.has_integral_fb(number) && IntegralFb::of(number).is_some(),
        BlockKind::Ob => profile.system_ob(number).is_some(),
        _ => false,
    }
}

/// Everything a program's checks asked of the CPU, kept as the most of each kind.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Needs {
    features: Vec<Feature>,
    /// The size each area kind must have, in its units (bytes, timers, data words).
    sizes: [u32; SizeOf::ALL.len()],
    extended_blocks: bool,
    builtins: Vec<BlockId>,
    brackets: u8,
    four_accumulators: bool,
    /// A need the profile compiled for did not meet: its error may hide other checks of the
    /// same statement, so these needs alone cannot say what another profile reports.
    unmet: bool,
}

impl Needs {
    /// Records `need`; whether `profile` (the one compiled for) meets it.
    pub fn ask(&mut self, need: Need, profile: &Profile) -> bool {
        self.add(need);
        let met = need.met_by(profile);
        self.unmet |= !met;
        met
    }

    /// Records a need that was not checked against a profile (an assignment list's operand).
    pub fn add(&mut self, need: Need) {
        match need {
            Need::Feature(feature) => {
                if !self.features.contains(&feature) {
                    self.features.push(feature);
                }
            }
            Need::Address { area, index } => {
                let (size, span) = extent(area);
                let slot = &mut self.sizes[size as usize];
                *slot = (*slot).max(u32::from(index) + u32::from(span));
            }
            Need::ExtendedBlocks => self.extended_blocks = true,
            Need::BuiltinBlock(id) => {
                if !self.builtins.contains(&id) {
                    self.builtins.push(id);
                }
            }
            Need::Brackets(depth) => self.brackets = self.brackets.max(depth),
            Need::FourAccumulators => self.four_accumulators = true,
        }
    }

    /// Whether every need was met by the profile compiled for.
    pub fn all_met(&self) -> bool {
        !self.unmet
    }

    /// Whether `profile` meets every need.
    pub fn met_by(&self, profile: &Profile) -> bool {
        self.features.iter().all(|feature| profile.has(*feature))
            && SizeOf::ALL
                .iter()
                .all(|size| self.sizes[*size as usize] <= u32::from(size.of(&profile.sizes)))
            && (!self.extended_blocks || profile.extended_blocks)
            && self.builtins.iter().all(|id| builtin_on(*id, profile))
            && self.brackets <= profile.bracket_depth
            && (!self.four_accumulators || profile.accumulators == 4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::find;

    #[test]
    fn an_address_needs_its_whole_width() {
        let cpu = find("sinumerik-840c").unwrap();
        let last_word = Need::Address {
            area: Area::FlagWord,
            index: 254,
        };
        let past_the_end = Need::Address {
            area: Area::FlagWord,
            index: 255,
        };
        assert!(last_word.met_by(cpu));
        assert!(!past_the_end.met_by(cpu));
    }

    #[test]
    fn needs_keep_the_most_of_each_kind() {
        let small = find("s5-95u").unwrap();
        let mut needs = Needs::default();
        assert!(needs.ask(Need::Brackets(2), small));
        assert!(needs.met_by(small));
        needs.add(Need::Address {
            area: Area::Timer,
            index: 200,
        });
        assert!(!needs.met_by(small));
        assert!(needs.met_by(find("sinumerik-840c").unwrap()));
        assert!(needs.all_met());
        assert!(!needs.ask(Need::ExtendedBlocks, small));
        assert!(!needs.all_met());
    }
}
