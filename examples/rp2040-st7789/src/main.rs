//! zscan on a Raspberry Pi Pico (RP2040, Cortex-M0+ at 125 MHz) driving a 240 × 240 ST7789
//! display over SPI0: the standard bunny, compiled into flash by `zscan mesh`, turns under a
//! directional light with a frame counter, drawn in double-buffered bands of 16 rows
//! (`zscan_board_common::run`) while DMA channel 0 sends the previous band.
//!
//! This file holds only the board: clocks, pins, the display's initialisation (mipidsi, over
//! the SPI bus borrowed for the occasion) and [`DmaSpi`], the band sink over rp2040-hal's
//! single-buffer DMA transfer.
//!
//! Wiring (SPI0): SCK GP18, MOSI GP19, CS GP17, DC GP16, RST GP20, backlight GP21.
//!
//! ```text
//! cargo build --release --target thumbv6m-none-eabi
//! ```
#![no_std]
#![no_main]

use core::convert::Infallible;
use embedded_graphics::primitives::Rectangle;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::dma::single_buffer::{Config, Transfer};
use hal::dma::{DMAExt, SingleChannel, WriteTarget};
use hal::fugit::RateExtU32;
use hal::{pac, Clock};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use panic_halt as _;
use rp2040_hal as hal;
use zscan::prelude::BandSink;
use zscan_board_common::{as_bytes, as_words, open_window, run, Memory, SinkError, Spin, BAND};

/// The second-stage bootloader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

const XTAL_FREQ_HZ: u32 = 12_000_000;

const W: u16 = 240;
const H: u16 = 240;
/// Pixels in a band.
const BAND_PIXELS: usize = W as usize * BAND as usize;

#[hal::entry]
fn main() -> ! {
    // The animation's memory (about 100 KB), built in place (`.bss`); cortex-m-rt hands it
    // over as a `&'static mut`, which the DMA channel's buffers need.
    static mut MEMORY: Memory<BAND_PIXELS> = Memory::new();
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .unwrap();
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );

    let sclk = pins.gpio18.into_function::<hal::gpio::FunctionSpi>();
    let mosi = pins.gpio19.into_function::<hal::gpio::FunctionSpi>();
    let mut spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI0, (mosi, sclk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let mut cs = pins.gpio17.into_push_pull_output();
    let mut dc = pins.gpio16.into_push_pull_output();
    let rst = pins.gpio20.into_push_pull_output();
    let mut backlight = pins.gpio21.into_push_pull_output();
    backlight.set_high().unwrap();

    // mipidsi sends the panel's initialisation over the borrowed bus and pins; the display
    // keeps its settings (colour mode, inversion) when the driver is dropped.
    {
        let device = ExclusiveDevice::new(&mut spi, &mut cs, timer).unwrap();
        let mut buffer = [0u8; 64];
        let interface = SpiInterface::new(device, &mut dc, &mut buffer);
        Builder::new(ST7789, interface)
            .display_size(W, H)
            .invert_colors(ColorInversion::Inverted)
            .reset_pin(rst)
            .init(&mut timer)
            .unwrap();
    }

    let dma = pac.DMA.split(&mut pac.RESETS);
    let sink = DmaSpi {
        bus: Bus::Idle(dma.ch0, spi),
        held: None,
        dc,
        cs,
    };
    let spin = Spin {
        width: W,
        height: H,
        frames_per_turn: 120,
    };
    // Returns only on an error (the panel then keeps its last frame).
    let _ = run(MEMORY, spin, sink, || timer.get_counter_low(), |_, _| true);
    loop {
        cortex_m::asm::wfi();
    }
}

/// The SPI bus between bands (with its DMA channel) or sending one.
enum Bus<CH: SingleChannel, S: WriteTarget<TransmittedWord = u8>> {
    Idle(CH, S),
    Sending(Transfer<CH, &'static mut [u8], S>),
    /// Only while `start` or `wait` moves the bus between the two.
    Moving,
}

/// A DMA-driven band sink: `start` opens the band's window with blocking writes, then starts
/// the channel on the band's bytes and returns; `wait` waits for the channel and for the SPI
/// to shift out its last byte, then ends the transfer (chip select high).
struct DmaSpi<CH: SingleChannel, S: WriteTarget<TransmittedWord = u8>, DC, CS> {
    bus: Bus<CH, S>,
    /// A buffer `start` refused, for `wait` to give back.
    held: Option<&'static mut [u16]>,
    dc: DC,
    cs: CS,
}

impl<CH, S, DC, CS> BandSink<'static, u16> for DmaSpi<CH, S, DC, CS>
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u8> + SpiBus<u8, Error = Infallible>,
    DC: OutputPin<Error = Infallible>,
    CS: OutputPin<Error = Infallible>,
{
    type Error = SinkError<Infallible>;

    fn start(&mut self, pixels: &'static mut [u16], area: Rectangle) -> Result<(), Self::Error> {
        let band = area.size.width as usize * area.size.height as usize;
        let (ch, mut spi) = match core::mem::replace(&mut self.bus, Bus::Moving) {
            Bus::Idle(ch, spi) if pixels.len() == band => (ch, spi),
            other => {
                // Kept for `wait`, unsent: a band that is not the whole buffer, or a transfer
                // still running (which `DoubleBands` never does).
                let error = match other {
                    Bus::Idle(..) => SinkError::Length {
                        band,
                        buffer: pixels.len(),
                    },
                    _ => SinkError::Busy,
                };
                self.bus = other;
                self.held = Some(pixels);
                return Err(error);
            }
        };
        let (dc, cs) = (&mut self.dc, &mut self.cs);
        // The DMA transfers leave stale bytes in the receive FIFO, so the HAL's blocking
        // `write` (which waits for each byte's echo) may return early: `flush` waits until
        // the bus is idle before the data/command pin changes.
        let window = cs.set_low().and_then(|()| {
            open_window(&area, |code, parameters| {
                dc.set_low()?;
                spi.write(&[code])?;
                spi.flush()?;
                dc.set_high()?;
                spi.write(parameters)?;
                spi.flush()
            })
        });
        if let Err(e) = window {
            let _ = cs.set_high();
            self.bus = Bus::Idle(ch, spi);
            self.held = Some(pixels);
            return Err(SinkError::Bus(e));
        }
        self.bus = Bus::Sending(Config::new(ch, as_bytes(pixels), spi).start());
        Ok(())
    }

    fn wait(&mut self) -> (&'static mut [u16], Result<(), Self::Error>) {
        let transfer = match core::mem::replace(&mut self.bus, Bus::Moving) {
            Bus::Sending(transfer) => transfer,
            other => {
                self.bus = other;
                return (self.held.take().unwrap_or_default(), Ok(()));
            }
        };
        let (ch, bytes, mut spi) = transfer.wait();
        // The channel is done when the FIFO has the last byte; the bus, when it is shifted.
        let flushed = spi.flush();
        let raised = self.cs.set_high();
        self.bus = Bus::Idle(ch, spi);
        (as_words(bytes), flushed.and(raised).map_err(SinkError::Bus))
    }
}
