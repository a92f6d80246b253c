//! The STEP 7 (S7-300/S7-400) operations on the accumulators and the status word, as small
//! pure functions the execution loop calls ("Statement List (STL) for S7-300 and S7-400
//! Programming" is the reference; `grammar/README.md`, "STEP 7 operations", lists the
//! choices where it leaves one).
//!
//! - [`integer`]: `+I -I *I /I +D -D *D /D MOD NEGI NEGD INVI INVD`, `+ constant`.
//! - [`real`]: `+R -R *R /R`, `SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN`, `ABS NEGR`, and
//!   the status of a REAL result.
//! - [`compare`]: `==I … <=I`, `==D … <=D`, `==R … <=R`.
//! - [`convert`]: `ITD ITB BTI BTD DTB DTR RND RND+ RND- TRUNC CAW CAD`.
//! - [`word_logic`]: `AW OW XOW AD OD XOD`.
//! - [`shift`]: `SSI SSD SLW SRW SLD SRD RLD RRD RLDA RRDA`.
//! - [`accu`]: `TAK PUSH POP ENT LEAVE INC DEC`, and the move of ACCU 3/4 after arithmetic.
//! - [`jump`]: whether each conditional jump jumps and what it does to the status; `LOOP`; the
//!   status conditions `==0 <>0 >0 <0 >=0 <=0 UO OV OS BR` as bit operands.
//!
//! The status word itself (BR, `L STW`/`T STW`) is [`super::status::Status`].

pub mod accu;
pub mod bit_logic;
pub mod compare;
pub mod convert;
pub mod integer;
pub mod jump;
pub mod real;
pub mod shift;
pub mod word_logic;
