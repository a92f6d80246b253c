//! Blocks the CPU has built in: the integral FBs of the S5-115U (FB 240–243, 250, 251) with
//! their parameters as the S5-115U manual's chapter on integral blocks declares them, and the
//! system OBs a profile lists. A program that defines a block of the same number uses its own.

use crate::ast::{BlockId, Name, ParamDecl, ParamFormat};
use crate::mnemonics::{BlockKind, ConstFormat, ParamKind};
use crate::source::Span;

/// An integral FB of the S5-115U.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegralFb {
    /// FB 240 `COD:B4`: four BCD decades and a sign to a fixed-point number.
    CodB4,
    /// FB 241 `COD:16`: a fixed-point number to a sign and five BCD decades.
    Cod16,
    /// FB 242 `MUL:16`: 16 × 16 bits to 32 bits.
    Mul16,
    /// FB 243 `DIV:16`: 16 / 16 bits, quotient and remainder.
    Div16,
    /// FB 250 `RLG:AE`: read an analog input channel and scale it.
    RlgAe,
    /// FB 251 `RLG:AA`: scale a value and write it to an analog output channel.
    RlgAa,
}

/// What a call of a built-in block runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Builtin {
    Integral(IntegralFb),
    /// A system OB of the profile; awl does not simulate it.
    SystemOb(u8),
}

type Param = (&'static str, ParamKind, Option<ParamFormat>);

const IN_WORD: (ParamKind, Option<ParamFormat>) = (ParamKind::Input, Some(ParamFormat::Word));
const IN_BIT: (ParamKind, Option<ParamFormat>) = (ParamKind::Input, Some(ParamFormat::Bit));
const OUT_WORD: (ParamKind, Option<ParamFormat>) = (ParamKind::Output, Some(ParamFormat::Word));
const OUT_BYTE: (ParamKind, Option<ParamFormat>) = (ParamKind::Output, Some(ParamFormat::Byte));
const OUT_BIT: (ParamKind, Option<ParamFormat>) = (ParamKind::Output, Some(ParamFormat::Bit));
const FIXED: (ParamKind, Option<ParamFormat>) = (
    ParamKind::Data,
    Some(ParamFormat::Constant(ConstFormat::Fixed)),
);
const BYTES: (ParamKind, Option<ParamFormat>) = (
    ParamKind::Data,
    Some(ParamFormat::Constant(ConstFormat::TwoBytes)),
);

const fn param(name: &'static str, (kind, format): (ParamKind, Option<ParamFormat>)) -> Param {
    (name, kind, format)
}

const COD_B4: &[Param] = &[
    param("BCD", IN_WORD),
    param("SBCD", IN_BIT),
    param("DUAL", OUT_WORD),
];
const COD_16: &[Param] = &[
    param("DUAL", IN_WORD),
    param("SBCD", OUT_BIT),
    param("BCD2", OUT_BYTE),
    param("BCD1", OUT_WORD),
];
const MUL_16: &[Param] = &[
    param("Z1", IN_WORD),
    param("Z2", IN_WORD),
    param("Z3=0", OUT_BIT),
    param("Z32", OUT_WORD),
    param("Z31", OUT_WORD),
];
const DIV_16: &[Param] = &[
    param("Z1", IN_WORD),
    param("Z2", IN_WORD),
    param("OV", OUT_BIT),
    param("FEH", OUT_BIT),
    param("Z3=0", OUT_BIT),
    param("Z4=0", OUT_BIT),
    param("Z3", OUT_WORD),
    param("Z4", OUT_WORD),
];
const RLG_AE: &[Param] = &[
    param("BG", FIXED),
    param("KNKT", BYTES),
    param("OGR", FIXED),
    param("UGR", FIXED),
    param("EINZ", IN_BIT),
    param("XA", OUT_WORD),
    param("FB", OUT_BIT),
    param("BU", OUT_BIT),
    param("TBIT", OUT_BIT),
];
const RLG_AA: &[Param] = &[
    param("XE", IN_WORD),
    param("BG", FIXED),
    param("KNKT", BYTES),
    param("OGR", FIXED),
    param("UGR", FIXED),
    param("FEH", OUT_BIT),
    param("BU", OUT_BIT),
];

impl IntegralFb {
    pub fn of(number: u8) -> Option<IntegralFb> {
        Some(match number {
            240 => IntegralFb::CodB4,
            241 => IntegralFb::Cod16,
            242 => IntegralFb::Mul16,
            243 => IntegralFb::Div16,
            250 => IntegralFb::RlgAe,
            251 => IntegralFb::RlgAa,
            _ => return None,
        })
    }

    /// The name in the FB's header, as a PG shows it.
    pub fn name(self) -> &'static str {
        match self {
            IntegralFb::CodB4 => "COD:B4",
            IntegralFb::Cod16 => "COD:16",
            IntegralFb::Mul16 => "MUL:16",
            IntegralFb::Div16 => "DIV:16",
            IntegralFb::RlgAe => "RLG:AE",
            IntegralFb::RlgAa => "RLG:AA",
        }
    }

    fn params(self) -> &'static [Param] {
        match self {
            IntegralFb::CodB4 => COD_B4,
            IntegralFb::Cod16 => COD_16,
            IntegralFb::Mul16 => MUL_16,
            IntegralFb::Div16 => DIV_16,
            IntegralFb::RlgAe => RLG_AE,
            IntegralFb::RlgAa => RLG_AA,
        }
    }

    /// The FB's declarations, for checking a call's parameters like those of a program's FB.
    pub fn declarations(self) -> Vec<ParamDecl> {
        self.params()
            .iter()
            .map(|(name, kind, format)| ParamDecl {
                name: Name {
                    text: (*name).to_string(),
                    span: Span::default(),
                },
                kind: *kind,
                format: *format,
                span: Span::default(),
            })
            .collect()
    }
}

/// `COD:B4` for FB 240; empty for a number that is no integral FB.
pub fn name(fb: u8) -> &'static str {
    IntegralFb::of(fb).map_or("", IntegralFb::name)
}

/// The profiles that have `id` built in: an integral FB or a system OB.
pub fn profiles_with(id: BlockId) -> Vec<&'static str> {
    match id.kind {
        // The built-in blocks' numbers fit a byte.
        BlockKind::Fb => {
            u8::try_from(id.number).map_or(Vec::new(), crate::profile::with_integral_fb)
        }
        BlockKind::Ob => u8::try_from(id.number).map_or(Vec::new(), crate::profile::with_system_ob),
        _ => Vec::new(),
    }
}
