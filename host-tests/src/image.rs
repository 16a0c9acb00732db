//! Writing frames to image files: PNG and PPM through a LUT, PGM as raw indices.
//!
//! A [`Framebuffer`] holds palette indices; [`write_image`] resolves them through a
//! `Lut<Rgb888>` and picks the format from the file extension:
//!
//! | extension | format | content |
//! |---|---|---|
//! | `.png` | 8-bit RGB PNG | colours through the LUT |
//! | `.ppm` | binary PPM (`P6`) | colours through the LUT |
//! | `.pgm` | binary PGM (`P5`) | the raw palette indices as grey levels (LUT ignored) |
//!
//! The image has the buffer's width and height; for a band, its rows `top..top + height`.
//! Parent directories are created. Every failure is an [`ImageError`] with a message.

use std::fs;
use std::io::{BufWriter, Write};
use std::path::Path;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use zscan::output::{Framebuffer, Lut};

/// An image could not be written or read: a message naming the file and the cause.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ImageError(pub String);

impl std::fmt::Display for ImageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ImageError {}

/// The image formats [`write_image`] can produce.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit RGB PNG through the LUT.
    Png,
    /// Binary PPM (`P6`) through the LUT.
    Ppm,
    /// Binary PGM (`P5`) of the raw palette indices.
    Pgm,
}

impl ImageFormat {
    /// The format named by `path`'s extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<ImageFormat, ImageError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("png") => Ok(ImageFormat::Png),
            Some("ppm") => Ok(ImageFormat::Ppm),
            Some("pgm") => Ok(ImageFormat::Pgm),
            _ => Err(ImageError(format!(
                "{}: unknown image extension (use .png, .ppm or .pgm)",
                path.display()
            ))),
        }
    }
}

/// The frame's colours through `lut`, row-major, 3 bytes (R, G, B) per pixel.
pub fn to_rgb(fb: &Framebuffer<'_>, lut: &Lut<Rgb888>) -> Vec<u8> {
    let mut out = Vec::with_capacity(fb.width() as usize * fb.height() as usize * 3);
    for (_, row) in fb.rows() {
        for &i in row {
            let c = lut.get(i);
            out.extend_from_slice(&[c.r(), c.g(), c.b()]);
        }
    }
    out
}

/// The frame's raw palette indices, row-major, one byte per pixel.
pub fn to_indices(fb: &Framebuffer<'_>) -> Vec<u8> {
    fb.rows().flat_map(|(_, row)| row.iter().copied()).collect()
}

/// Writes `fb` to `path` in the format of its extension (see the module documentation),
/// creating parent directories.
pub fn write_image(path: &Path, fb: &Framebuffer<'_>, lut: &Lut<Rgb888>) -> Result<(), ImageError> {
    let format = ImageFormat::from_path(path)?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir)
            .map_err(|e| ImageError(format!("{}: cannot create directory: {e}", dir.display())))?;
    }
    let file = fs::File::create(path)
        .map_err(|e| ImageError(format!("{}: cannot create: {e}", path.display())))?;
    let mut w = BufWriter::new(file);
    let io = |e: std::io::Error| ImageError(format!("{}: write failed: {e}", path.display()));
    match format {
        ImageFormat::Png => write_png(&mut w, fb, lut)
            .map_err(|e| ImageError(format!("{}: {}", path.display(), e.0)))?,
        ImageFormat::Ppm => write_ppm(&mut w, fb, lut).map_err(io)?,
        ImageFormat::Pgm => write_pgm(&mut w, fb).map_err(io)?,
    }
    w.flush().map_err(io)
}

/// Writes `fb` through `lut` as an 8-bit RGB PNG.
pub fn write_png<W: Write>(
    w: W,
    fb: &Framebuffer<'_>,
    lut: &Lut<Rgb888>,
) -> Result<(), ImageError> {
    let mut enc = png::Encoder::new(w, fb.width() as u32, fb.height() as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc
        .write_header()
        .map_err(|e| ImageError(format!("PNG header: {e}")))?;
    writer
        .write_image_data(&to_rgb(fb, lut))
        .map_err(|e| ImageError(format!("PNG data: {e}")))?;
    writer
        .finish()
        .map_err(|e| ImageError(format!("PNG end: {e}")))
}

/// Writes `fb` through `lut` as a binary PPM (`P6`, maximum value 255).
pub fn write_ppm<W: Write>(
    mut w: W,
    fb: &Framebuffer<'_>,
    lut: &Lut<Rgb888>,
) -> std::io::Result<()> {
    write!(w, "P6\n{} {}\n255\n", fb.width(), fb.height())?;
    w.write_all(&to_rgb(fb, lut))
}

/// Writes the raw indices of `fb` as a binary PGM (`P5`, maximum value 255).
pub fn write_pgm<W: Write>(mut w: W, fb: &Framebuffer<'_>) -> std::io::Result<()> {
    write!(w, "P5\n{} {}\n255\n", fb.width(), fb.height())?;
    w.write_all(&to_indices(fb))
}

/// An image read back as 8-bit RGB.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major R, G, B bytes (`width * height * 3`).
    pub data: Vec<u8>,
}

impl RgbImage {
    /// The colour at `(x, y)`, or `None` outside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        self.data.get(i..i + 3).map(|s| [s[0], s[1], s[2]])
    }
}

/// Reads a PNG file (8-bit grey, grey+alpha, RGB or RGBA; palettes expanded) as RGB bytes.
pub fn read_png_rgb(path: &Path) -> Result<RgbImage, ImageError> {
    let err = |what: &str, e: &dyn std::fmt::Display| {
        ImageError(format!("{}: {what}: {e}", path.display()))
    };
    let file = fs::File::open(path).map_err(|e| err("cannot open", &e))?;
    let mut dec = png::Decoder::new(std::io::BufReader::new(file));
    dec.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = dec.read_info().map_err(|e| err("bad PNG", &e))?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buf)
        .map_err(|e| err("bad PNG data", &e))?;
    let (w, h) = (info.width, info.height);
    let n = w as usize * h as usize;
    let src = &buf[..info.buffer_size()];
    let data: Vec<u8> = match info.color_type {
        png::ColorType::Rgb => src.to_vec(),
        png::ColorType::Rgba => src
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect(),
        png::ColorType::Grayscale => src.iter().flat_map(|&g| [g, g, g]).collect(),
        png::ColorType::GrayscaleAlpha => src.chunks_exact(2).flat_map(|p| [p[0]; 3]).collect(),
        other => return Err(err("unsupported colour type", &format!("{other:?}"))),
    };
    if data.len() != n * 3 {
        return Err(err("unexpected data size", &data.len()));
    }
    Ok(RgbImage {
        width: w,
        height: h,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> std::path::PathBuf {
        std::env::temp_dir()
            .join(format!("zscan-image-test-{}", std::process::id()))
            .join(name)
    }

    #[test]
    fn png_round_trip_and_netpbm_headers() {
        let mut buf: Vec<u8> = (0..12).collect();
        let fb = Framebuffer::new(&mut buf, 4, 3).unwrap();
        let mut lut = Lut::<Rgb888>::filled(Rgb888::BLACK);
        for i in 0..12u8 {
            lut.set(i, Rgb888::new(i * 20, 255 - i, i));
        }
        let png_path = tmp("sub/dir/a.png");
        write_image(&png_path, &fb, &lut).unwrap();
        let img = read_png_rgb(&png_path).unwrap();
        assert_eq!((img.width, img.height), (4, 3));
        assert_eq!(img.pixel(1, 2), Some([9 * 20, 255 - 9, 9]));
        assert_eq!(img.pixel(4, 0), None);

        let pgm_path = tmp("b.PGM");
        write_image(&pgm_path, &fb, &lut).unwrap();
        let pgm = fs::read(&pgm_path).unwrap();
        let header = b"P5\n4 3\n255\n";
        assert_eq!(&pgm[..header.len()], header);
        assert_eq!(&pgm[header.len()..], &(0..12).collect::<Vec<u8>>()[..]);

        let ppm_path = tmp("c.ppm");
        write_image(&ppm_path, &fb, &lut).unwrap();
        let ppm = fs::read(&ppm_path).unwrap();
        let header = b"P6\n4 3\n255\n";
        assert_eq!(&ppm[..header.len()], header);
        assert_eq!(&ppm[header.len()..], &img.data[..]);

        let bad = write_image(&tmp("d.jpg"), &fb, &lut).unwrap_err();
        assert!(bad.0.contains("unknown image extension"), "{bad}");
        let missing = read_png_rgb(&tmp("missing.png")).unwrap_err();
        assert!(missing.0.contains("cannot open"), "{missing}");
        let _ = fs::remove_dir_all(tmp(""));
    }
}
