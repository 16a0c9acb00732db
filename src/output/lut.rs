//! The 256-entry colour look-up table (the course's "table de couleurs").
//!
//! An index in the framebuffer selects one of 256 display colours of any embedded-graphics
//! colour type (`Rgb565`, `Rgb888`, `Gray8`, ...). With a *shaded palette* an index encodes
//! material and luminance together: `index = first + material * levels + shade`, so one 8-bit
//! frame shows several lit materials. Builders compute ramps with integer arithmetic only,
//! rounding to nearest: `channel = (base * (shade + 1) + levels / 2) / levels` — shade
//! `levels - 1` is the full base colour and shade 0 is the darkest non-black step.

use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, Rgb888, RgbColor};

/// Why a palette could not be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LutError {
    /// `materials × levels` exceeds the 256 entries (or does not fit after `first`).
    TooManyEntries {
        /// Entries asked for, counting from index 0.
        needed: usize,
    },
    /// Zero shade levels.
    ZeroLevels,
}

impl core::fmt::Display for LutError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LutError::TooManyEntries { needed } => {
                write!(f, "palette needs {needed} entries but a LUT has 256")
            }
            LutError::ZeroLevels => write!(f, "a shaded palette needs at least one level"),
        }
    }
}

/// 256 display colours indexed by a palette index.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, Rgb888, RgbColor};
/// use zscan::output::Lut;
///
/// // Built at compile time, kept in flash.
/// static GREY: Lut<Rgb565> = Lut::<Rgb565>::GREY;
/// assert_eq!(GREY.get(255), Rgb565::WHITE);
/// assert_eq!(GREY, Lut::<Rgb565>::grey_ramp());
///
/// // Two materials of 32 shades each: indices 0..32 red, 32..64 teal.
/// let bases = [Rgb888::new(255, 40, 40), Rgb888::new(0, 160, 160)];
/// let lut = Lut::<Rgb565>::shaded(&bases, 32, 0)?;
/// assert_eq!(lut.get(63), Rgb565::from(bases[1]));
/// # Ok::<(), zscan::output::LutError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Lut<C> {
    entries: [C; 256],
}

impl<C: Copy> Lut<C> {
    /// A table of 256 entries of one colour.
    pub fn filled(colour: C) -> Self {
        Lut {
            entries: [colour; 256],
        }
    }

    /// A table from explicit entries (usable in a `const` or `static`).
    pub const fn from_entries(entries: [C; 256]) -> Self {
        Lut { entries }
    }

    /// The colour of `index`.
    #[inline(always)]
    pub fn get(&self, index: u8) -> C {
        self.entries[index as usize]
    }

    /// Replaces the colour of `index`.
    pub fn set(&mut self, index: u8, colour: C) {
        self.entries[index as usize] = colour;
    }

    /// All 256 entries.
    pub fn entries(&self) -> &[C; 256] {
        &self.entries
    }
}

/// `v` (8 bits) on `bits` bits, rounded to nearest: embedded-graphics' own channel conversion
/// (`Rgb888` → `Rgb565`, …), in a `const fn`.
const fn channel(v: u8, bits: u32) -> u8 {
    let max = (1u32 << bits) - 1;
    ((v as u32 * max + 127) / 255) as u8
}

impl Lut<Rgb565> {
    /// The grey ramp ([`grey_ramp`](Lut::grey_ramp)) as a constant: a `static` of it lives
    /// in flash.
    pub const GREY: Lut<Rgb565> = {
        let mut entries = [Rgb565::BLACK; 256];
        let mut i = 0;
        while i < 256 {
            let v = i as u8;
            entries[i] = Rgb565::new(channel(v, 5), channel(v, 6), channel(v, 5));
            i += 1;
        }
        Lut::from_entries(entries)
    };
}

impl Lut<Rgb888> {
    /// The grey ramp ([`grey_ramp`](Lut::grey_ramp)) as a constant.
    pub const GREY: Lut<Rgb888> = {
        let mut entries = [Rgb888::BLACK; 256];
        let mut i = 0;
        while i < 256 {
            let v = i as u8;
            entries[i] = Rgb888::new(v, v, v);
            i += 1;
        }
        Lut::from_entries(entries)
    };
}

impl Lut<BinaryColor> {
    /// The on/off table of a one-bit display ([`pack_pages`](super::pack_pages), or
    /// [`flush`](super::flush()) to a `DrawTarget<Color = BinaryColor>`): indices `first_on`
    /// to 255 on, those below off. With the grey ramp's indices (index = grey level), 128 is
    /// a threshold at mid-grey; a palette of lines on index 0 takes 1. Other tables are built
    /// entry by entry ([`set`](Lut::set), [`from_entries`](Lut::from_entries)).
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::BinaryColor, prelude::*};
    /// use zscan::prelude::*;
    ///
    /// let mut pixels = [0u8; 4 * 2];
    /// let mut frame = Framebuffer::new(&mut pixels, 4, 2)?;
    /// frame.set_pixel(1, 0, 255);
    /// frame.set_pixel(2, 1, 127);
    /// static ON_OFF: Lut<BinaryColor> = Lut::<BinaryColor>::threshold(128);
    /// let mut display = MockDisplay::<BinaryColor>::new(); // any one-bit DrawTarget
    /// flush(&frame, &ON_OFF, &mut display, None).map_err(|_| zscan::Error::Display)?;
    /// display.assert_pattern(&[".#..", "...."]);
    /// # Ok::<(), zscan::Error>(())
    /// ```
    pub const fn threshold(first_on: u8) -> Self {
        let mut entries = [BinaryColor::Off; 256];
        let mut i = first_on as usize;
        while i < 256 {
            entries[i] = BinaryColor::On;
            i += 1;
        }
        Lut::from_entries(entries)
    }
}

impl<C: Copy + From<Rgb888>> Lut<C> {
    /// The grey ramp: index `i` is the grey level `i` (0 black, 255 white), converted to `C`.
    pub fn grey_ramp() -> Self {
        let mut lut = Lut::filled(C::from(Rgb888::BLACK));
        for i in 0..=255u8 {
            lut.set(i, C::from(Rgb888::new(i, i, i)));
        }
        lut
    }

    /// A shaded palette: for each base colour `m` (in order) and each shade `s < levels`, the
    /// entry `first + m * levels + s` is the base colour scaled by `(s + 1) / levels`.
    /// Entries before `first` and after the last material are black. Errors when the palette
    /// does not fit in 256 entries.
    pub fn shaded(bases: &[Rgb888], levels: u8, first: u8) -> Result<Self, LutError> {
        if levels == 0 {
            return Err(LutError::ZeroLevels);
        }
        let needed = first as usize + bases.len() * levels as usize;
        if needed > 256 {
            return Err(LutError::TooManyEntries { needed });
        }
        let mut lut = Lut::filled(C::from(Rgb888::BLACK));
        let l = levels as u32;
        for (m, base) in bases.iter().enumerate() {
            for s in 0..l {
                let scale = |c: u8| ((c as u32 * (s + 1) + l / 2) / l) as u8;
                let c = Rgb888::new(scale(base.r()), scale(base.g()), scale(base.b()));
                lut.set(
                    (first as usize + m * levels as usize + s as usize) as u8,
                    C::from(c),
                );
            }
        }
        Ok(lut)
    }
}

/// The index of `shade` (0..levels) of `material` in a palette built by [`Lut::shaded`].
/// Shades beyond the ramp saturate at its brightest entry; `levels = 0` (no ramp) gives `first`
/// plus nothing for the shade.
#[inline(always)]
pub const fn shaded_index(first: u8, levels: u8, material: u8, shade: u8) -> u8 {
    let s = if shade >= levels {
        levels.saturating_sub(1)
    } else {
        shade
    };
    first
        .wrapping_add(material.wrapping_mul(levels))
        .wrapping_add(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_constants_equal_the_grey_ramp() {
        assert_eq!(Lut::<Rgb565>::GREY, Lut::<Rgb565>::grey_ramp());
        assert_eq!(Lut::<Rgb888>::GREY, Lut::<Rgb888>::grey_ramp());
    }

    #[test]
    fn from_entries_is_const() {
        const RED: Lut<Rgb565> = Lut::from_entries([Rgb565::RED; 256]);
        assert_eq!(RED, Lut::filled(Rgb565::RED));
        assert_eq!(RED.get(17), Rgb565::RED);
    }
}
