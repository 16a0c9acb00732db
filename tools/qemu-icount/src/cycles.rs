//! A cycle estimate for executed Thumb code: each instruction is decoded into a timing class
//! ([`classify`]) and weighted by the timing table of the core's technical reference manual
//! ([`Model`]): the Cortex-M0+ TRM (ARM DDI 0484, "Cortex-M0+ instruction summary") or the
//! Cortex-M4 TRM (ARM DDI 0439, table 3-1 "Processor instruction set summary").
//!
//! # Assumptions (the estimate is a model, not a measurement)
//! - Zero wait states for every fetch, load and store; no flash accelerator or cache effects
//!   (an RP2040 running from its XIP cache misses, an STM32F411 at 100 MHz needs 3 flash wait
//!   states hidden only partly by its ART accelerator: real frames can be slower).
//! - A taken branch costs the pipeline refill: Cortex-M4 `1 + P` with `P` = 2 (the TRM gives
//!   1 to 3, by the target's alignment and width and whether the address was speculated);
//!   Cortex-M0+ its table's fixed figures (taken conditional or unconditional `B` 2, `BL` 3,
//!   `BX`/`BLX` 2, `POP {…, pc}` 3 + N). A not-taken conditional branch costs 1.
//! - Cortex-M0+ multiply: the 1-cycle multiplier (the RP2040's configuration); the small
//!   32-cycle multiplier is `mul=32`. ARMv6-M has no divide instruction: divisions are the
//!   compiler's software routines, counted instruction by instruction (the RP2040's SIO
//!   hardware divider is not used by that code).
//! - Cortex-M4 `SDIV`/`UDIV`: the TRM gives 2 to 12 cycles (early termination on the
//!   operands' magnitudes, which this model does not see); the estimate takes 12, the worst
//!   case (`div=` changes it; each region also reports its number of divisions).
//! - Cortex-M4 loads and stores: 2 cycles, and 1 when directly after another single load or
//!   store in the same translation block (the TRM's "neighbouring load and store single
//!   instructions can pipeline", `N + 1` for `N` of them), without checking the register
//!   dependency that can break the pairing. Load/store multiple `1 + N` (`+ P` with the PC in
//!   the list), `LDRD`/`STRD` 3, `TBB`/`TBH` `2 + P`.
//! - Instructions inside an IT block cost as executed, whether or not their condition passes.
//! - Interrupts and exceptions are not modelled (the benchmark firmware takes none).

/// Branch kinds: what a taken branch costs differs between them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Branch {
    /// `B<c>` (16 or 32 bit): taken or not.
    Conditional,
    /// `B` (16 or 32 bit).
    Unconditional,
    /// `BL`.
    Call,
    /// `BX Rm`.
    Exchange,
    /// `BLX Rm`.
    ExchangeCall,
    /// `CBZ`/`CBNZ`: taken or not.
    CompareZero,
    /// `TBB`/`TBH`.
    Table,
}

/// Timing classes of Thumb instructions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// Data processing, moves, shifts, extends, compares, hints: 1 cycle.
    Alu,
    /// `IT`, with the number of instructions it makes conditional (1 to 4).
    It(u32),
    /// A single load (`LDR`, `LDRB`, `LDRH`, `LDRSB`, `LDRSH`, literal, exclusive).
    Load,
    /// A single store.
    Store,
    /// `LDRD`.
    LoadPair,
    /// `STRD`.
    StorePair,
    /// `LDM`/`POP`: `n` registers, `pc` when the PC is one of them (a branch).
    LoadMultiple { n: u32, pc: bool },
    /// `STM`/`PUSH`: `n` registers.
    StoreMultiple { n: u32 },
    /// A branch instruction.
    Branch(Branch),
    /// `ADD PC, …` or `MOV PC, …` (a branch).
    PcWrite,
    /// `LDR PC, […]` (a branch).
    LoadPc,
    /// `MUL`/`MULS` and the DSP multiplies with a 32-bit result.
    Multiply,
    /// `MLA`/`MLS`.
    MultiplyAccumulate,
    /// `SMULL`, `UMULL`, `SMLAL`, `UMLAL` and the other 64-bit-result multiplies.
    MultiplyLong,
    /// `SDIV`/`UDIV`.
    Divide,
    /// Floating point add, subtract, multiply, compare, convert, move immediate.
    FpSimple,
    /// Floating point multiply-accumulate (chained or fused).
    FpMultiplyAccumulate,
    /// `VDIV`, `VSQRT`.
    FpDivide,
    /// `VLDR`/`VSTR`.
    FpLoadStore,
    /// `VLDM`/`VSTM`/`VPUSH`/`VPOP`: `words` 32-bit words.
    FpMultiple { words: u32 },
    /// `VMOV` between a core register and a single-precision register, `VMRS`/`VMSR`.
    FpMove,
    /// `VMOV` between two core registers and two singles or a double.
    FpMovePair,
    /// `MSR`, `MRS`, barriers, `SVC`, `BKPT`, `UDF`, other coprocessors.
    System,
}

impl Class {
    /// Whether executing the instruction may write the PC (it ends its translation block).
    pub fn is_branch(self) -> bool {
        matches!(
            self,
            Class::Branch(_)
                | Class::PcWrite
                | Class::LoadPc
                | Class::LoadMultiple { pc: true, .. }
        )
    }

    /// Whether the branch is taken or not by its own condition (`B<c>`, `CBZ`/`CBNZ`); inside
    /// an IT block any branch is.
    fn is_conditional(self) -> bool {
        matches!(
            self,
            Class::Branch(Branch::Conditional) | Class::Branch(Branch::CompareZero)
        )
    }

    fn is_single_load_store(self) -> bool {
        matches!(self, Class::Load | Class::Store)
    }
}

/// The class of one Thumb instruction from its bytes in memory order (2 bytes, or 4 for a
/// 32-bit instruction: two little-endian halfwords, the first one first). Anything shorter
/// or not decodable is [`Class::Alu`] (1 cycle).
pub fn classify(bytes: &[u8]) -> Class {
    let half = |i: usize| -> Option<u16> {
        Some(u16::from_le_bytes([*bytes.get(i)?, *bytes.get(i + 1)?]))
    };
    let Some(h1) = half(0) else {
        return Class::Alu;
    };
    if h1 >> 11 >= 0b11101 {
        match half(2) {
            Some(h2) => thumb32(h1, h2),
            None => Class::Alu,
        }
    } else {
        thumb16(h1)
    }
}

/// Number of set bits of a register list.
fn regs(list: u16) -> u32 {
    list.count_ones()
}

/// 16-bit Thumb (ARMv7-M ARM A5.2).
fn thumb16(h: u16) -> Class {
    match h >> 10 {
        // Data processing (register): MUL is opcode 1101.
        0b010000 => {
            if (h >> 6) & 0xF == 0b1101 {
                Class::Multiply
            } else {
                Class::Alu
            }
        }
        // Special data processing and branch/exchange.
        0b010001 => {
            let op = (h >> 6) & 0xF;
            let rd = ((h >> 4) & 0x8) | (h & 0x7);
            match op >> 2 {
                0b00 | 0b10 if rd == 15 => Class::PcWrite,
                0b11 if op & 0b10 == 0 => Class::Branch(Branch::Exchange),
                0b11 => Class::Branch(Branch::ExchangeCall),
                _ => Class::Alu,
            }
        }
        // LDR (literal).
        0b010010 | 0b010011 => Class::Load,
        // Load/store register offset: opB 000..010 store, 011..111 load.
        0b010100..=0b010111 => {
            if (h >> 9) & 0x7 >= 0b011 {
                Class::Load
            } else {
                Class::Store
            }
        }
        // Load/store immediate offset (word, byte, halfword, SP-relative): bit 11 is L.
        0b011000..=0b100111 => {
            if h & 0x0800 != 0 {
                Class::Load
            } else {
                Class::Store
            }
        }
        0b101100..=0b101111 => misc16(h),
        0b110000 | 0b110001 => Class::StoreMultiple { n: regs(h & 0xFF) },
        0b110010 | 0b110011 => Class::LoadMultiple {
            n: regs(h & 0xFF),
            pc: false,
        },
        // Conditional branch, UDF (cond 1110), SVC (cond 1111).
        0b110100..=0b110111 => {
            if (h >> 8) & 0xF >= 0xE {
                Class::System
            } else {
                Class::Branch(Branch::Conditional)
            }
        }
        0b111000 | 0b111001 => Class::Branch(Branch::Unconditional),
        // Shifts, add/sub, move/compare immediate, ADR, ADD SP.
        _ => Class::Alu,
    }
}

/// 16-bit miscellaneous instructions (`1011 xxxx xxxx xxxx`).
fn misc16(h: u16) -> Class {
    if h & 0xF500 == 0xB100 {
        Class::Branch(Branch::CompareZero)
    } else if h & 0xFE00 == 0xB400 {
        Class::StoreMultiple { n: regs(h & 0x1FF) }
    } else if h & 0xFE00 == 0xBC00 {
        Class::LoadMultiple {
            n: regs(h & 0x1FF),
            pc: h & 0x100 != 0,
        }
    } else if h & 0xFF00 == 0xBF00 && h & 0xF != 0 {
        Class::It(4 - (h & 0xF).trailing_zeros())
    } else if h & 0xFF00 == 0xBE00 {
        Class::System
    } else {
        Class::Alu
    }
}

/// 32-bit Thumb (ARMv7-M ARM A5.3): `h1` the first halfword, `h2` the second.
fn thumb32(h1: u16, h2: u16) -> Class {
    let op2 = (h1 >> 4) & 0x7F;
    let load = h1 & 0x10 != 0;
    match (h1 >> 11) & 0x3 {
        0b01 => {
            if op2 & 0b110_0100 == 0 {
                // Load/store multiple; op 00 and 11 are SRS/RFE.
                match (h1 >> 7) & 0x3 {
                    0b01 | 0b10 if load => Class::LoadMultiple {
                        n: regs(h2),
                        pc: h2 & 0x8000 != 0,
                    },
                    0b01 | 0b10 => Class::StoreMultiple { n: regs(h2) },
                    _ => Class::System,
                }
            } else if op2 & 0b110_0100 == 0b000_0100 {
                // Load/store dual or exclusive, table branch.
                let (op1, op2) = ((h1 >> 7) & 0x3, (h1 >> 4) & 0x3);
                if h1 & 0xFFF0 == 0xE8D0 && h2 & 0xFFE0 == 0xF000 {
                    Class::Branch(Branch::Table)
                } else if op1 == 0b00 || (op1 == 0b01 && op2 & 0b10 == 0) {
                    if load {
                        Class::Load
                    } else {
                        Class::Store
                    }
                } else if load {
                    Class::LoadPair
                } else {
                    Class::StorePair
                }
            } else if op2 & 0b110_0000 == 0b010_0000 {
                Class::Alu // data processing (shifted register)
            } else {
                coprocessor(h1, h2)
            }
        }
        0b10 => {
            if h2 & 0x8000 == 0 {
                return Class::Alu; // data processing (immediate)
            }
            match (h2 >> 12) & 0b101 {
                0b000 if (h1 >> 7) & 0x7 != 0x7 => Class::Branch(Branch::Conditional),
                0b001 => Class::Branch(Branch::Unconditional),
                0b101 => Class::Branch(Branch::Call),
                _ => Class::System, // MSR, MRS, hints, barriers; BLX (immediate) is undefined
            }
        }
        _ => {
            let rt = h2 >> 12;
            if op2 & 0b111_0001 == 0 {
                Class::Store
            } else if op2 & 0b110_0111 == 0b000_0101 {
                if rt == 15 {
                    Class::LoadPc
                } else {
                    Class::Load
                }
            } else if matches!(op2 & 0b110_0111, 0b000_0001 | 0b000_0011) {
                if rt == 15 {
                    Class::Alu // PLD, PLI, hints
                } else {
                    Class::Load
                }
            } else if op2 & 0b111_0000 == 0b010_0000 {
                Class::Alu // data processing (register)
            } else if op2 & 0b111_1000 == 0b011_0000 {
                let (op1, op2) = ((h1 >> 4) & 0x7, (h2 >> 4) & 0x3);
                match (op1, op2) {
                    (0, 0) if rt == 15 => Class::Multiply,
                    (0, _) => Class::MultiplyAccumulate,
                    _ => Class::Multiply, // DSP multiplies, SMMUL, USAD8, ...
                }
            } else if op2 & 0b111_1000 == 0b011_1000 {
                let (op1, op2) = ((h1 >> 4) & 0x7, (h2 >> 4) & 0xF);
                if (op1 == 0b001 || op1 == 0b011) && op2 == 0xF {
                    Class::Divide
                } else {
                    Class::MultiplyLong
                }
            } else if op2 & 0b100_0000 != 0 {
                coprocessor(h1, h2)
            } else {
                Class::System
            }
        }
    }
}

/// Coprocessor space: the floating-point instructions (coprocessors 10 and 11).
fn coprocessor(h1: u16, h2: u16) -> Class {
    if (h2 >> 8) & 0xE != 0xA {
        return Class::System;
    }
    if h1 & 0x0E00 == 0x0C00 {
        if h1 & 0x01E0 == 0x0040 {
            Class::FpMovePair
        } else if h1 & 0x0120 == 0x0100 {
            Class::FpLoadStore
        } else {
            Class::FpMultiple {
                words: (h2 & 0xFF) as u32,
            }
        }
    } else if h1 & 0x0F00 == 0x0E00 {
        if h2 & 0x10 != 0 {
            return Class::FpMove;
        }
        let (opc1, opc2, opc3) = ((h1 >> 4) & 0xB, h1 & 0xF, (h2 >> 6) & 0x3);
        match opc1 {
            0b0000 | 0b0001 | 0b1001 | 0b1010 => Class::FpMultiplyAccumulate,
            0b1000 => Class::FpDivide,
            0b1011 if opc2 == 0b0001 && opc3 == 0b11 => Class::FpDivide,
            _ => Class::FpSimple,
        }
    } else {
        Class::System
    }
}

/// Cycles of one instruction: `cycles` when it does not branch (a not-taken conditional
/// branch), `taken` when it does (equal for other instructions).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cost {
    pub cycles: u32,
    pub taken: u32,
}

impl Cost {
    fn flat(cycles: u32) -> Cost {
        Cost {
            cycles,
            taken: cycles,
        }
    }
}

/// The cores the estimate models, with their options.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Cortex-M0+; `multiply`: 1 (fast multiplier) or 32 (small multiplier).
    M0Plus { multiply: u32 },
    /// Cortex-M4; `divide`: the cycles taken for every `SDIV`/`UDIV` (the TRM: 2 to 12).
    M4 { divide: u32 },
}

/// Cortex-M4 pipeline refill `P` after a taken branch (the TRM: 1 to 3).
pub const M4_REFILL: u32 = 2;

impl Model {
    /// Parses a `cpu=` argument (`m0plus` or `m4`) with the default options.
    pub fn parse(name: &str) -> Option<Model> {
        match name {
            "m0plus" | "cortex-m0plus" | "m0+" => Some(Model::M0Plus { multiply: 1 }),
            "m4" | "cortex-m4" => Some(Model::M4 { divide: 12 }),
            _ => None,
        }
    }

    /// The model's name as printed.
    pub fn name(self) -> &'static str {
        match self {
            Model::M0Plus { .. } => "cortex-m0plus",
            Model::M4 { .. } => "cortex-m4",
        }
    }

    /// What `class` costs; `pipelined`: it directly follows a single load or store in the
    /// same block (Cortex-M4 pairs them).
    pub fn cost(self, class: Class, pipelined: bool) -> Cost {
        match self {
            Model::M0Plus { multiply } => m0plus(class, multiply),
            Model::M4 { divide } => m4(class, divide, pipelined),
        }
    }
}

/// The Cortex-M0+ TRM's table (ARMv6-M has no IT, dual, divide, table branch or FP
/// instruction: those classes never occur and cost as their nearest ARMv7-M relative).
fn m0plus(class: Class, multiply: u32) -> Cost {
    let branch = |not_taken, taken| Cost {
        cycles: not_taken,
        taken,
    };
    match class {
        Class::Load | Class::Store => Cost::flat(2),
        Class::LoadPair | Class::StorePair => Cost::flat(3),
        Class::LoadMultiple { n, pc: false } | Class::StoreMultiple { n } => Cost::flat(1 + n),
        Class::LoadMultiple { n, pc: true } => Cost::flat(3 + n),
        Class::Branch(Branch::Conditional) | Class::Branch(Branch::CompareZero) => branch(1, 2),
        Class::Branch(Branch::Call) => Cost::flat(3),
        Class::Branch(Branch::Table) => Cost::flat(4),
        Class::Branch(_) | Class::PcWrite => Cost::flat(2),
        Class::LoadPc => Cost::flat(4),
        Class::Multiply | Class::MultiplyAccumulate | Class::MultiplyLong => Cost::flat(multiply),
        Class::System => Cost::flat(3),
        Class::FpLoadStore | Class::FpMovePair => Cost::flat(2),
        Class::FpMultiple { words } => Cost::flat(1 + words),
        _ => Cost::flat(1),
    }
}

/// The Cortex-M4 TRM's table 3-1, `P` = [`M4_REFILL`].
fn m4(class: Class, divide: u32, pipelined: bool) -> Cost {
    const P: u32 = M4_REFILL;
    let branch = |not_taken, taken| Cost {
        cycles: not_taken,
        taken,
    };
    match class {
        Class::Load | Class::Store => Cost::flat(if pipelined { 1 } else { 2 }),
        Class::LoadPair | Class::StorePair => Cost::flat(3),
        Class::LoadMultiple { n, pc: false } | Class::StoreMultiple { n } => Cost::flat(1 + n),
        Class::LoadMultiple { n, pc: true } => Cost::flat(1 + n + P),
        Class::Branch(Branch::Conditional) | Class::Branch(Branch::CompareZero) => branch(1, 1 + P),
        Class::Branch(Branch::Table) => Cost::flat(2 + P),
        Class::Branch(_) | Class::PcWrite => Cost::flat(1 + P),
        Class::LoadPc => Cost::flat(2 + P),
        Class::Divide => Cost::flat(divide),
        Class::FpMultiplyAccumulate => Cost::flat(3),
        Class::FpDivide => Cost::flat(14),
        Class::FpLoadStore | Class::FpMovePair => Cost::flat(2),
        Class::FpMultiple { words } => Cost::flat(1 + words),
        _ => Cost::flat(1),
    }
}

/// A translation block's estimate: `cycles` when its last instruction does not branch (or
/// branches always), `taken_extra` more when that instruction is a conditional branch and the
/// next block executed does not start at `fallthrough_offset` past the block's address.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BlockCost {
    pub cycles: u64,
    pub taken_extra: u64,
    /// 1 when the block ends with a branch that is always taken.
    pub always_taken: u64,
    /// Whether the block ends with a branch that may or may not be taken (its condition, or
    /// an IT block): taken when the next block is not the fall-through.
    pub conditional: bool,
    /// `SDIV`/`UDIV` instructions in the block.
    pub divisions: u64,
}

/// The estimate of a block of instructions (each one's bytes, in order).
pub fn block_cost<'a>(model: Model, instructions: impl IntoIterator<Item = &'a [u8]>) -> BlockCost {
    let mut out = BlockCost::default();
    let (mut it_left, mut previous_load_store) = (0u32, false);
    let mut iter = instructions.into_iter().peekable();
    while let Some(bytes) = iter.next() {
        let class = classify(bytes);
        let last = iter.peek().is_none();
        let cost = model.cost(class, previous_load_store);
        let in_it = it_left > 0;
        if last && class.is_branch() {
            if class.is_conditional() || in_it {
                out.conditional = true;
                out.cycles += cost.cycles as u64;
                out.taken_extra = cost.taken.saturating_sub(cost.cycles) as u64;
            } else {
                out.cycles += cost.taken as u64;
                out.always_taken = 1;
            }
        } else {
            out.cycles += cost.cycles as u64;
        }
        out.divisions += (class == Class::Divide) as u64;
        previous_load_store = class.is_single_load_store();
        it_left = match class {
            Class::It(n) => n,
            _ => it_left.saturating_sub(1),
        };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 16-bit instruction's bytes.
    fn t16(h: u16) -> Vec<u8> {
        h.to_le_bytes().to_vec()
    }

    /// A 32-bit instruction's bytes (first halfword first).
    fn t32(h1: u16, h2: u16) -> Vec<u8> {
        let mut v = h1.to_le_bytes().to_vec();
        v.extend_from_slice(&h2.to_le_bytes());
        v
    }

    // Encodings below were assembled by hand from the ARMv7-M ARM and checked against
    // llvm-objdump's disassembly of the same instructions assembled for thumbv7em.

    #[test]
    fn sixteen_bit_classes() {
        let cases: &[(u16, Class, &str)] = &[
            (0x1c08, Class::Alu, "adds r0, r1, #0"),
            (0x4348, Class::Multiply, "muls r0, r1, r0"),
            (0x4008, Class::Alu, "ands r0, r1"),
            (0x4770, Class::Branch(Branch::Exchange), "bx lr"),
            (0x4788, Class::Branch(Branch::ExchangeCall), "blx r1"),
            (0x4487, Class::PcWrite, "add pc, r0"),
            (0x46f7, Class::PcWrite, "mov pc, lr"),
            (0x4684, Class::Alu, "mov ip, r0"),
            (0x4a03, Class::Load, "ldr r2, [pc, #12]"),
            (0x5888, Class::Load, "ldr r0, [r1, r2]"),
            (0x5088, Class::Store, "str r0, [r1, r2]"),
            (0x5e88, Class::Load, "ldrsh r0, [r1, r2]"),
            (0x5488, Class::Store, "strb r0, [r1, r2]"),
            (0x6808, Class::Load, "ldr r0, [r1]"),
            (0x6008, Class::Store, "str r0, [r1]"),
            (0x7808, Class::Load, "ldrb r0, [r1]"),
            (0x8008, Class::Store, "strh r0, [r1]"),
            (0x9801, Class::Load, "ldr r0, [sp, #4]"),
            (0x9001, Class::Store, "str r0, [sp, #4]"),
            (0xa001, Class::Alu, "adr r0, #4"),
            (0xb082, Class::Alu, "sub sp, #8"),
            (0xb2c0, Class::Alu, "uxtb r0, r0"),
            (0xb5f0, Class::StoreMultiple { n: 5 }, "push {r4-r7, lr}"),
            (
                0xbdf0,
                Class::LoadMultiple { n: 5, pc: true },
                "pop {r4-r7, pc}",
            ),
            (
                0xbc0f,
                Class::LoadMultiple { n: 4, pc: false },
                "pop {r0-r3}",
            ),
            (0xc00e, Class::StoreMultiple { n: 3 }, "stmia r0!, {r1-r3}"),
            (
                0xc90c,
                Class::LoadMultiple { n: 2, pc: false },
                "ldmia r1!, {r2, r3}",
            ),
            (0xd1fe, Class::Branch(Branch::Conditional), "bne ."),
            (0xdafe, Class::Branch(Branch::Conditional), "bge ."),
            (0xdf00, Class::System, "svc 0"),
            (0xde00, Class::System, "udf 0"),
            (0xe7fe, Class::Branch(Branch::Unconditional), "b ."),
            (0xe770, Class::Branch(Branch::Unconditional), "b (backward)"),
            (0xb108, Class::Branch(Branch::CompareZero), "cbz r0, +2"),
            (0xb908, Class::Branch(Branch::CompareZero), "cbnz r0, +2"),
            (0xbf08, Class::It(1), "it eq"),
            (0xbf0c, Class::It(2), "ite eq"),
            (0xbf01, Class::It(4), "itttt eq"),
            (0xbf00, Class::Alu, "nop"),
            (0xbe00, Class::System, "bkpt 0"),
        ];
        for &(h, class, text) in cases {
            assert_eq!(classify(&t16(h)), class, "{text} ({h:#06x})");
        }
    }

    #[test]
    fn thirty_two_bit_classes() {
        let cases: &[(u16, u16, Class, &str)] = &[
            (0xf000, 0xf800, Class::Branch(Branch::Call), "bl"),
            (0xf000, 0xb800, Class::Branch(Branch::Unconditional), "b.w"),
            (0xf040, 0x8000, Class::Branch(Branch::Conditional), "bne.w"),
            (0xf7ff, 0xff78, Class::Branch(Branch::Call), "bl (backward)"),
            (
                0xf7ff,
                0xbf76,
                Class::Branch(Branch::Unconditional),
                "b.w (backward)",
            ),
            (
                0xf47f,
                0xaf74,
                Class::Branch(Branch::Conditional),
                "bne.w (backward)",
            ),
            (0xf3bf, 0x8f4f, Class::System, "dsb sy"),
            (0xf3ef, 0x8010, Class::System, "mrs r0, primask"),
            (0xf240, 0x0000, Class::Alu, "movw r0, #0"),
            (0xf101, 0x0001, Class::Alu, "add.w r0, r1, #1"),
            (0xeb01, 0x0002, Class::Alu, "add.w r0, r1, r2"),
            (0xea4f, 0x0041, Class::Alu, "lsl.w r0, r1, #1"),
            (0xfa01, 0xf002, Class::Alu, "lsl.w r0, r1, r2"),
            (0xf8d1, 0x0004, Class::Load, "ldr.w r0, [r1, #4]"),
            (0xf851, 0x0022, Class::Load, "ldr.w r0, [r1, r2, lsl #2]"),
            (0xf8df, 0x0008, Class::Load, "ldr.w r0, [pc, #8]"),
            (0xf8b1, 0x0002, Class::Load, "ldrh.w r0, [r1, #2]"),
            (0xf991, 0x0001, Class::Load, "ldrsb.w r0, [r1, #1]"),
            (0xf8c1, 0x0004, Class::Store, "str.w r0, [r1, #4]"),
            (0xf821, 0x0012, Class::Store, "strh.w r0, [r1, r2, lsl #1]"),
            (0xf801, 0x0b01, Class::Store, "strb r0, [r1], #1"),
            (0xf8d1, 0xf004, Class::LoadPc, "ldr.w pc, [r1, #4]"),
            (0xf891, 0xf000, Class::Alu, "pld [r1]"),
            (0xe9d1, 0x2300, Class::LoadPair, "ldrd r2, r3, [r1]"),
            (0xe9c1, 0x2300, Class::StorePair, "strd r2, r3, [r1]"),
            (0xe851, 0x0f00, Class::Load, "ldrex r0, [r1]"),
            (0xe8d0, 0xf001, Class::Branch(Branch::Table), "tbb [r0, r1]"),
            (
                0xe8d0,
                0xf011,
                Class::Branch(Branch::Table),
                "tbh [r0, r1, lsl #1]",
            ),
            (
                0xe92d,
                0x4ff0,
                Class::StoreMultiple { n: 9 },
                "push.w {r4-r11, lr}",
            ),
            (
                0xe8bd,
                0x8ff0,
                Class::LoadMultiple { n: 9, pc: true },
                "pop.w {r4-r11, pc}",
            ),
            (
                0xe891,
                0x000c,
                Class::LoadMultiple { n: 2, pc: false },
                "ldm.w r1, {r2, r3}",
            ),
            (0xfb01, 0xf002, Class::Multiply, "mul r0, r1, r2"),
            (
                0xfb01,
                0x3002,
                Class::MultiplyAccumulate,
                "mla r0, r1, r2, r3",
            ),
            (
                0xfb01,
                0x3012,
                Class::MultiplyAccumulate,
                "mls r0, r1, r2, r3",
            ),
            (0xfb81, 0x0102, Class::MultiplyLong, "smull r0, r1, r1, r2"),
            (0xfba1, 0x0102, Class::MultiplyLong, "umull r0, r1, r1, r2"),
            (0xfbe1, 0x0102, Class::MultiplyLong, "umlal r0, r1, r1, r2"),
            (0xfb91, 0xf0f2, Class::Divide, "sdiv r0, r1, r2"),
            (0xfbb1, 0xf0f2, Class::Divide, "udiv r0, r1, r2"),
            (0xee30, 0x0a20, Class::FpSimple, "vadd.f32 s0, s0, s1"),
            (0xee20, 0x0a20, Class::FpSimple, "vmul.f32 s0, s0, s1"),
            (
                0xee00,
                0x0a20,
                Class::FpMultiplyAccumulate,
                "vmla.f32 s0, s0, s1",
            ),
            (
                0xeea0,
                0x0a20,
                Class::FpMultiplyAccumulate,
                "vfma.f32 s0, s0, s1",
            ),
            (0xee80, 0x0a20, Class::FpDivide, "vdiv.f32 s0, s0, s1"),
            (0xeeb1, 0x0ac0, Class::FpDivide, "vsqrt.f32 s0, s0"),
            (0xeeb0, 0x0ac0, Class::FpSimple, "vabs.f32 s0, s0"),
            (0xee00, 0x0a10, Class::FpMove, "vmov s0, r0"),
            (0xeef1, 0xfa10, Class::FpMove, "vmrs APSR_nzcv, fpscr"),
            (0xed91, 0x0a01, Class::FpLoadStore, "vldr s0, [r1, #4]"),
            (0xed81, 0x0a01, Class::FpLoadStore, "vstr s0, [r1, #4]"),
            (
                0xed2d,
                0x8b10,
                Class::FpMultiple { words: 16 },
                "vpush {d8-d15}",
            ),
            (0xec41, 0x0b10, Class::FpMovePair, "vmov d0, r0, r1"),
        ];
        for &(h1, h2, class, text) in cases {
            assert_eq!(
                classify(&t32(h1, h2)),
                class,
                "{text} ({h1:#06x} {h2:#06x})"
            );
        }
    }

    #[test]
    fn truncated_bytes_are_one_cycle_alu() {
        assert_eq!(classify(&[]), Class::Alu);
        assert_eq!(classify(&[0x00]), Class::Alu);
        assert_eq!(classify(&[0x00, 0xf0]), Class::Alu); // a 32-bit prefix alone
    }

    const M0: Model = Model::M0Plus { multiply: 1 };
    const M4: Model = Model::M4 { divide: 12 };

    fn block(model: Model, insns: &[Vec<u8>]) -> BlockCost {
        block_cost(model, insns.iter().map(|v| v.as_slice()))
    }

    #[test]
    fn the_trm_tables() {
        // Cortex-M0+: loads/stores 2, multiple 1+N, POP with PC 3+N, BL 3, BX 2, B<c> 1/2.
        assert_eq!(M0.cost(Class::Load, true), Cost::flat(2));
        assert_eq!(M0.cost(Class::StoreMultiple { n: 5 }, false), Cost::flat(6));
        let pop_pc = Class::LoadMultiple { n: 5, pc: true };
        assert_eq!(M0.cost(pop_pc, false), Cost::flat(8));
        assert_eq!(M0.cost(Class::Branch(Branch::Call), false), Cost::flat(3));
        assert_eq!(
            M0.cost(Class::Branch(Branch::Exchange), false),
            Cost::flat(2)
        );
        let bcc = M0.cost(Class::Branch(Branch::Conditional), false);
        assert_eq!((bcc.cycles, bcc.taken), (1, 2));
        assert_eq!(M0.cost(Class::Multiply, false), Cost::flat(1));
        let small = Model::M0Plus { multiply: 32 };
        assert_eq!(small.cost(Class::Multiply, false), Cost::flat(32));
        // Cortex-M4 with P = 2: loads 2 (1 pipelined), LDM 1+N (+P with PC), B 1+P, B<c> 1/1+P,
        // TBB 2+P, MLA 1, divide as chosen, VDIV 14, VMLA 3.
        assert_eq!(M4.cost(Class::Load, false), Cost::flat(2));
        assert_eq!(M4.cost(Class::Store, true), Cost::flat(1));
        assert_eq!(M4.cost(pop_pc, false), Cost::flat(8));
        let ldm = Class::LoadMultiple { n: 4, pc: false };
        assert_eq!(M4.cost(ldm, false), Cost::flat(5));
        assert_eq!(
            M4.cost(Class::Branch(Branch::Unconditional), false),
            Cost::flat(3)
        );
        let bcc = M4.cost(Class::Branch(Branch::Conditional), false);
        assert_eq!((bcc.cycles, bcc.taken), (1, 3));
        assert_eq!(M4.cost(Class::Branch(Branch::Table), false), Cost::flat(4));
        assert_eq!(M4.cost(Class::MultiplyAccumulate, false), Cost::flat(1));
        assert_eq!(M4.cost(Class::Divide, false), Cost::flat(12));
        assert_eq!(
            Model::M4 { divide: 2 }.cost(Class::Divide, false),
            Cost::flat(2)
        );
        assert_eq!(M4.cost(Class::FpDivide, false), Cost::flat(14));
        assert_eq!(M4.cost(Class::FpMultiplyAccumulate, false), Cost::flat(3));
    }

    #[test]
    fn a_loop_block_with_a_conditional_exit() {
        // subs r0, #1; bne back: the spin loop of the benchmark firmware.
        let body = [t16(0x3801), t16(0xd1fd)];
        let m4 = block(M4, &body);
        assert_eq!((m4.cycles, m4.taken_extra, m4.always_taken), (2, 2, 0));
        let m0 = block(M0, &body);
        assert_eq!((m0.cycles, m0.taken_extra, m0.always_taken), (2, 1, 0));
    }

    #[test]
    fn unconditional_exits_cost_taken_always() {
        // push {r4, lr}; bl f: the call is always taken.
        let call = [t16(0xb510), t32(0xf000, 0xf800)];
        assert_eq!(
            block(M4, &call),
            BlockCost {
                cycles: 3 + 3,
                taken_extra: 0,
                always_taken: 1,
                conditional: false,
                divisions: 0
            }
        );
        assert_eq!(block(M0, &call).cycles, 3 + 3);
        // it eq; bxeq lr: conditional through its IT block.
        let ret = [t16(0xbf08), t16(0x4770)];
        let b = block(M4, &ret);
        assert_eq!((b.cycles, b.taken_extra, b.always_taken), (1 + 3, 0, 0));
        assert!(b.conditional);
    }

    #[test]
    fn it_blocks_make_branches_conditional() {
        // cmp r0, #0; it ne; popne {r4, pc}: the POP is costed as executed (its refill
        // included) whether its condition passes or not; the exit is conditional.
        let ret = [t16(0x2800), t16(0xbf18), t16(0xbd10)];
        let b = block(M4, &ret);
        assert_eq!((b.always_taken, b.conditional), (0, true));
        assert_eq!(b.cycles, 1 + 1 + (1 + 2 + 2));
        assert_eq!(b.taken_extra, 0);
        // A conditional branch outside IT blocks: not-taken cost plus the refill when taken.
        let b = block(M4, &[t16(0x2800), t16(0xd1fd)]);
        assert_eq!((b.cycles, b.taken_extra, b.conditional), (2, 2, true));
    }

    #[test]
    fn m4_pairs_neighbouring_loads_and_stores() {
        // ldr r0, [r1]; ldr r2, [r1, #4]; str r0, [r3]; adds r0, #1; ldr r0, [r1]
        let insns = [
            t16(0x6808),
            t16(0x684a),
            t16(0x6018),
            t16(0x3001),
            t16(0x6808),
        ];
        assert_eq!(block(M4, &insns).cycles, 2 + 1 + 1 + 1 + 2);
        assert_eq!(block(M0, &insns).cycles, 2 + 2 + 2 + 1 + 2);
    }

    #[test]
    fn divisions_are_counted() {
        let insns = [t32(0xfbb1, 0xf0f2), t32(0xfb91, 0xf0f2)];
        let b = block(M4, &insns);
        assert_eq!((b.cycles, b.divisions), (24, 2));
    }
}
