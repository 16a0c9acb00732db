//! zscan on an STM32F411 "black pill" (Cortex-M4F at 100 MHz, 128 KB of RAM) driving a
//! 320 × 240 ILI9341 display over SPI1: the standard bunny, compiled into flash by
//! `zscan mesh`, turns under a directional light with a frame counter, drawn in
//! double-buffered bands of 16 rows (`zscan_board_common::run`) while DMA2 stream 3 sends the
//! previous band.
//!
//! This file holds only the board: clocks, pins, the display's initialisation (mipidsi, over
//! the SPI bus borrowed for the occasion) and [`DmaSpi`], the band sink over stm32f4xx-hal's
//! DMA streams.
//!
//! Wiring (SPI1): SCK PA5, MISO PA6, MOSI PA7, CS PA4, DC PA3, RST PA2, backlight PA1.
//!
//! ```text
//! cargo build --release --target thumbv7em-none-eabihf
//! ```
#![no_std]
#![no_main]

use core::convert::Infallible;
use cortex_m::peripheral::DWT;
use cortex_m_rt::entry;
use embedded_graphics::primitives::Rectangle;
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::dma::config::DmaConfig;
use hal::dma::{MemoryToPeripheral, StreamX, StreamsTuple, Transfer};
use hal::gpio::alt::SpiCommon;
use hal::pac::{self, DMA2, SPI1};
use hal::prelude::*;
use hal::rcc::Clocks;
use hal::spi::{Mode, Phase, Polarity, Spi};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ILI9341Rgb565;
use mipidsi::options::{ColorOrder, Orientation, Rotation};
use mipidsi::Builder;
use panic_halt as _;
use stm32f4xx_hal as hal;
use zscan::prelude::BandSink;
use zscan_board_common::{as_bytes, as_words, open_window, run, Memory, SinkError, Spin, BAND};

const W: u16 = 320;
const H: u16 = 240;
/// Pixels in a band.
const BAND_PIXELS: usize = W as usize * BAND as usize;
/// SPI mode 0.
const MODE: Mode = Mode {
    polarity: Polarity::IdleLow,
    phase: Phase::CaptureOnFirstTransition,
};

#[entry]
fn main() -> ! {
    // The animation's memory (about 100 KB), built in place (`.bss`); cortex-m-rt hands it
    // over as a `&'static mut`, which the DMA channel's buffers need.
    static mut MEMORY: Memory<BAND_PIXELS> = Memory::new();
    let dp = pac::Peripherals::take().unwrap();
    let mut cp = cortex_m::Peripherals::take().unwrap();
    // The black pill's 25 MHz crystal, the core at 100 MHz.
    let clocks = dp
        .RCC
        .constrain()
        .cfgr
        .use_hse(25.MHz())
        .sysclk(100.MHz())
        .freeze();
    let mut delay = cp.SYST.delay(&clocks);

    let gpioa = dp.GPIOA.split();
    let (sck, miso, mosi) = (gpioa.pa5, gpioa.pa6, gpioa.pa7);
    let mut spi = Spi::new(dp.SPI1, (sck, miso, mosi), MODE, 25.MHz(), &clocks);
    let mut cs = gpioa.pa4.into_push_pull_output();
    let mut dc = gpioa.pa3.into_push_pull_output();
    let rst = gpioa.pa2.into_push_pull_output();
    let mut backlight = gpioa.pa1.into_push_pull_output();
    backlight.set_high();

    // mipidsi sends the panel's initialisation over the borrowed bus and pins; the display
    // keeps its settings (colour order, orientation) when the driver is dropped.
    {
        let device = ExclusiveDevice::new_no_delay(&mut spi, &mut cs).unwrap();
        let mut buffer = [0u8; 64];
        let interface = SpiInterface::new(device, &mut dc, &mut buffer);
        Builder::new(ILI9341Rgb565, interface)
            .color_order(ColorOrder::Bgr)
            .orientation(Orientation::new().rotate(Rotation::Deg90).flip_horizontal())
            .reset_pin(rst)
            .init(&mut delay)
            .unwrap();
    }

    // The cycle counter, read as a microsecond clock (100 cycles a microsecond).
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    let (mut cycles, mut before) = (0u64, DWT::cycle_count());
    let clock_us = move || {
        let now = DWT::cycle_count();
        cycles += now.wrapping_sub(before) as u64;
        before = now;
        (cycles / 100) as u32
    };

    let streams = StreamsTuple::new(dp.DMA2);
    let sink = DmaSpi {
        bus: Bus::Idle(spi),
        stream: Some(streams.3),
        held: None,
        clocks,
        dc,
        cs,
    };
    let spin = Spin {
        width: W,
        height: H,
        frames_per_turn: 120,
    };
    // Returns only on an error (the panel then keeps its last frame).
    let _ = run(MEMORY, spin, sink, clock_us, |_, _| true);
    loop {
        cortex_m::asm::wfi();
    }
}

/// SPI1's transmit stream (DMA2 stream 3, channel 3).
type Stream = StreamX<DMA2, 3>;
/// SPI1's pins.
type Pins = (
    <SPI1 as SpiCommon>::Sck,
    <SPI1 as SpiCommon>::Miso,
    <SPI1 as SpiCommon>::Mosi,
);

/// SPI1 between bands (the HAL's blocking bus) or sending one (the peripheral lent to the DMA
/// stream; the HAL's bus is rebuilt when the stream is done).
enum Bus {
    Idle(Spi<SPI1>),
    Sending(
        Transfer<Stream, 3, SPI1, MemoryToPeripheral, &'static mut [u8]>,
        Pins,
    ),
    /// Only while `start` or `wait` moves the bus between the two.
    Moving,
}

/// A DMA-driven band sink: `start` opens the band's window with blocking writes, then lends
/// SPI1 to the DMA stream on the band's bytes and returns; `wait` waits for the stream and
/// for the SPI to shift out its last byte, ends the transfer (chip select high) and takes the
/// bus back.
struct DmaSpi<DC, CS> {
    bus: Bus,
    /// The stream between transfers.
    stream: Option<Stream>,
    /// A buffer `start` refused, for `wait` to give back.
    held: Option<&'static mut [u16]>,
    clocks: Clocks,
    dc: DC,
    cs: CS,
}

impl<DC, CS> BandSink<'static, u16> for DmaSpi<DC, CS>
where
    DC: OutputPin<Error = Infallible>,
    CS: OutputPin<Error = Infallible>,
{
    type Error = SinkError<hal::spi::Error>;

    fn start(&mut self, pixels: &'static mut [u16], area: Rectangle) -> Result<(), Self::Error> {
        let band = area.size.width as usize * area.size.height as usize;
        let (mut spi, stream) = match (
            core::mem::replace(&mut self.bus, Bus::Moving),
            self.stream.take(),
        ) {
            (Bus::Idle(spi), Some(stream)) if pixels.len() == band => (spi, stream),
            (other, stream) => {
                // Kept for `wait`, unsent: a band that is not the whole buffer, or a transfer
                // still running (which `DoubleBands` never does).
                let error = match other {
                    Bus::Idle(_) => SinkError::Length {
                        band,
                        buffer: pixels.len(),
                    },
                    _ => SinkError::Busy,
                };
                self.bus = other;
                self.stream = stream;
                self.held = Some(pixels);
                return Err(error);
            }
        };
        let (dc, cs) = (&mut self.dc, &mut self.cs);
        let _ = cs.set_low();
        // The HAL's blocking write waits for each byte's echo: the bus is idle after it.
        let window = open_window(&area, |code, parameters| {
            let _ = dc.set_low();
            spi.write(&[code])?;
            let _ = dc.set_high();
            spi.write(parameters)
        });
        if let Err(e) = window {
            let _ = cs.set_high();
            self.bus = Bus::Idle(spi);
            self.stream = Some(stream);
            self.held = Some(pixels);
            return Err(SinkError::Bus(e));
        }
        let (spi1, pins) = spi.release();
        spi1.cr2().modify(|_, w| w.txdmaen().enabled());
        let config = DmaConfig::default().memory_increment(true);
        let mut transfer =
            Transfer::init_memory_to_peripheral(stream, spi1, as_bytes(pixels), None, config);
        transfer.start(|_| {});
        self.bus = Bus::Sending(transfer, pins);
        Ok(())
    }

    fn wait(&mut self) -> (&'static mut [u16], Result<(), Self::Error>) {
        let (transfer, pins) = match core::mem::replace(&mut self.bus, Bus::Moving) {
            Bus::Sending(transfer, pins) => (transfer, pins),
            other => {
                self.bus = other;
                return (self.held.take().unwrap_or_default(), Ok(()));
            }
        };
        transfer.wait();
        let (stream, spi1, bytes, _) = transfer.release();
        // The stream is done when the data register has the last byte; the bus, when it is
        // shifted out.
        while spi1.sr().read().txe().bit_is_clear() || spi1.sr().read().bsy().bit_is_set() {}
        let _ = self.cs.set_high();
        // A fresh blocking bus (the HAL resets SPI1: the stream's request and the unread
        // received bytes are cleared).
        self.bus = Bus::Idle(Spi::new(spi1, pins, MODE, 25.MHz(), &self.clocks));
        self.stream = Some(stream);
        (as_words(bytes), Ok(()))
    }
}
