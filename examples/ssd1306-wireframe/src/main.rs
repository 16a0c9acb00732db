//! zscan on an STM32F411 "black pill" (Cortex-M4F at 100 MHz, 128 KB of RAM) driving a
//! 128 × 64 SSD1306 monochrome OLED over I²C: the standard bunny, compiled into flash by
//! `zscan mesh`, turns as a wireframe with hidden lines removed
//! (`zscan_board_common::Wire`: `Wireframe::Hidden` into an 8-bit frame, then `pack_pages`
//! into the controller's 1,024 bytes of pages).
//!
//! This file holds only the board: clocks, the I²C bus, the display's initialisation and the
//! loop that sends each frame's pages (the ssd1306 crate's basic mode: the address window,
//! then the bytes as they are; its buffered graphics mode and its second copy of the picture
//! are not used).
//!
//! Wiring (I2C1, 400 kHz, the module's address 0x3C): SCL PB6, SDA PB7.
//!
//! ```text
//! cargo build --release --target thumbv7em-none-eabihf
//! ```
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use hal::i2c::I2c;
use hal::pac;
use hal::prelude::*;
use panic_halt as _;
use ssd1306::prelude::*;
use ssd1306::{I2CDisplayInterface, Ssd1306};
use stm32f4xx_hal as hal;
use zscan_board_common::{Wire, WireMemory, MONO_H, MONO_W};

/// Frames in a turn of the bunny.
const FRAMES_PER_TURN: u32 = 120;

#[entry]
fn main() -> ! {
    // The animation's memory (77 KB), built in place (`.bss`).
    static mut MEMORY: WireMemory = WireMemory::new();
    let dp = pac::Peripherals::take().unwrap();
    // The black pill's 25 MHz crystal, the core at 100 MHz.
    let clocks = dp
        .RCC
        .constrain()
        .cfgr
        .use_hse(25.MHz())
        .sysclk(100.MHz())
        .freeze();
    let gpiob = dp.GPIOB.split();
    let i2c = I2c::new(dp.I2C1, (gpiob.pb6, gpiob.pb7), 400.kHz(), &clocks);

    // Horizontal addressing (the basic mode's `init`): the bytes of a window fill its
    // columns, then its next page, which is the order of `pack_pages`.
    let interface = I2CDisplayInterface::new(i2c);
    let mut display = Ssd1306::new(interface, DisplaySize128x64, DisplayRotation::Rotate0);
    let Ok(()) = display.init() else { halt() };
    let Ok(mut wire) = Wire::new(MEMORY, FRAMES_PER_TURN) else {
        halt()
    };
    let mut frame = 0u32;
    loop {
        let Ok(pages) = wire.frame(frame) else { halt() };
        // The whole display's window (columns 0 to 127, pages 0 to 7), then its 1,024 bytes.
        let window = display.set_draw_area((0, 0), (MONO_W as u8, MONO_H as u8));
        if window.and_then(|()| display.draw(pages)).is_err() {
            halt();
        }
        frame = frame.wrapping_add(1);
    }
}

/// Stops on an error (the display keeps its last frame).
fn halt() -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}
