//! Checks of the shared benchmark cases (`benches/cases.rs`): names, the calibration case, and
//! that each case's reported pixel count matches what it draws.
use zscan::output::Framebuffer;
use zscan_host::cli::bench::{cases, run_case};

fn draw(case: &cases::Case) -> (u32, Vec<u8>) {
    let mut pixels = vec![0u8; cases::FB_LEN];
    let mut fb = Framebuffer::new(&mut pixels, cases::WIDTH, cases::HEIGHT).unwrap();
    let mut storage = Box::new(cases::Storage::new()); // cases clear or overwrite what they use
    let px = (case.run)(&mut fb, &mut storage);
    (px, pixels)
}

fn case(name: &str) -> &'static cases::Case {
    cases::CASES.iter().find(|c| c.name == name).unwrap()
}

#[test]
fn names_are_unique_single_words_and_empty_comes_first() {
    assert_eq!(cases::CASES[0].name, "empty");
    for (i, a) in cases::CASES.iter().enumerate() {
        assert!(
            !a.name.is_empty()
                && a.name
                    .bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_'),
            "bad name {:?}",
            a.name
        );
        assert!(
            cases::CASES[i + 1..].iter().all(|b| b.name != a.name),
            "duplicate {}",
            a.name
        );
    }
}

#[test]
fn empty_case_draws_nothing() {
    let (px, pixels) = draw(&cases::CASES[0]);
    assert_eq!(px, 0);
    assert!(pixels.iter().all(|&p| p == 0));
}

#[test]
fn pixel_counts_match_the_pixels_drawn() {
    // Cases whose lines never share a pixel: the count is exactly the pixels set.
    for (name, distinct) in [
        ("line_shallow", 2560),
        ("line_diagonal", 1920),
        ("line_steep", 1920),
    ] {
        let (px, pixels) = draw(case(name));
        let set = pixels.iter().filter(|&&p| p != 0).count() as u32;
        assert_eq!(set, distinct, "{name}");
        assert!(px >= set, "{name}");
    }
    assert_eq!(draw(case("line_short")).0, 256 * 9);
    // Every line case: at least as many writes as pixels set, and something drawn. (Other
    // cases may count covered pixels, clear the frame or draw nothing, so they are not checked.)
    for c in cases::CASES.iter().filter(|c| c.name.starts_with("line_")) {
        let (px, pixels) = draw(c);
        let set = pixels.iter().filter(|&&p| p != 0).count() as u32;
        assert!(set > 0 && px >= set, "{}: {px} written, {set} set", c.name);
    }
}

#[test]
fn clipped_case_writes_one_pixel_per_major_column_or_row_inside() {
    // 8 x-major lines crossing all 320 columns + 8 y-major lines crossing all 240 rows; the
    // 8 × 8 crossings may each share one pixel (drawn twice, set once).
    let (px, pixels) = draw(case("line_clipped"));
    assert_eq!(px, 8 * 320 + 8 * 240);
    let set = pixels.iter().filter(|&&p| p != 0).count() as u32;
    assert!(set <= px && set >= px - 64, "{set} set");
    // Every column holds at least one pixel of each x-major line that was not overdrawn.
    for x in 0..cases::WIDTH as usize {
        let n = (0..cases::HEIGHT as usize)
            .filter(|&y| pixels[y * 320 + x] != 0)
            .count();
        assert!(n >= 8, "column {x}: {n}");
    }
}

#[test]
fn harness_run_is_deterministic() {
    for c in cases::CASES {
        assert_eq!(run_case(c), run_case(c), "{}", c.name);
    }
}

#[test]
fn fnv1a_known_values() {
    assert_eq!(cases::fnv1a(b""), 0x811c_9dc5);
    assert_eq!(cases::fnv1a(b"a"), 0xe40c_292c);
    assert_eq!(cases::fnv1a(b"foobar"), 0xbf9c_f968);
}

/// The Warnock cases draw the z-buffer frame's picture (the standard scenes have no two
/// surfaces within a 16-bit depth step, so the 16-bit `frame_*` equals the 32-bit z-buffer
/// Warnock matches) and report the pixels they drew.
#[test]
fn warnock_cases_draw_the_z_buffer_frames() {
    for scene in ["quad", "cube", "sphere", "bunny"] {
        let (px, pixels) = draw(case(&format!("frame_{scene}_warnock")));
        let (_, z) = draw(case(&format!("frame_{scene}")));
        assert_eq!(pixels, z, "{scene}");
        assert!(px > 0, "{scene}");
    }
}

/// The painter cases draw the z-buffer frame's picture (the bunny too: its pieces judged by
/// their outlines) and report the pixels they drew.
#[test]
fn painter_cases_draw_the_z_buffer_frames() {
    for scene in ["quad", "cube", "sphere", "bunny"] {
        let (px, pixels) = draw(case(&format!("frame_{scene}_painter")));
        let (_, z) = draw(case(&format!("frame_{scene}")));
        assert_eq!(pixels, z, "{scene}");
        assert!(px > 0, "{scene}");
    }
}

/// The compact banded bunny is the full frame's picture, and streaming FNV-1a band by band
/// (as the footprint firmware does) gives the whole frame's checksum.
#[test]
fn compact_bunny_is_the_frame_and_streams_its_checksum() {
    let (px, frame) = draw(case("frame_bunny"));
    let (cpx, compact) = draw(case("frame_bunny_compact"));
    assert!(px > 10_000 && cpx == px, "{cpx} against {px}");
    assert!(compact == frame);
    let mut memory = Box::new(cases::scene::CompactMemory::new());
    let mut h = cases::FNV1A_START;
    let mut bands = 0;
    let covered = cases::scene::compact_bands(&cases::scene::BUNNY, &mut memory, |band| {
        for (_, row) in band.rows() {
            h = cases::fnv1a_from(h, row);
        }
        bands += 1;
        Ok::<(), zscan::render::RenderError>(())
    });
    assert_eq!(covered, Ok(px));
    assert_eq!(
        bands,
        240usize.div_ceil(cases::scene::COMPACT_ROWS as usize)
    );
    assert_eq!(h, cases::fnv1a(&frame));
}

/// The planner's frames of the quad, cube and sphere are back faces alone and draw the
/// z-buffer's `frame_*` picture (same checksum on every core); the plan-only cases draw
/// nothing.
#[test]
fn planned_frames_are_the_z_buffer_frames() {
    for scene in ["quad", "cube", "sphere"] {
        let (px, planned) = draw(case(&format!("frame_{scene}_planned")));
        let (zpx, z) = draw(case(&format!("frame_{scene}")));
        assert!(px > 0, "{scene}: the plan is back faces alone");
        assert_eq!(px, zpx, "{scene}");
        assert!(planned == z, "{scene}: the planned picture differs");
    }
    for name in ["plan_sphere", "plan_bunny"] {
        let (px, pixels) = draw(case(name));
        assert_eq!(px, 0);
        assert!(pixels.iter().all(|&p| p == 0), "{name} draws nothing");
    }
}

/// The wireframe cases draw, and the two-ended walk draws the one-ended picture.
#[test]
fn wireframe_cases_draw_and_both_walks_agree() {
    for mesh in ["cube", "sphere", "bunny"] {
        let count = |mode: &str| {
            let (px, pixels) = draw(case(&format!("wire_{mesh}_{mode}")));
            let set = pixels.iter().filter(|&&p| p != 0).count() as u32;
            assert!(px >= set && set > 0, "wire_{mesh}_{mode}: {px} {set}");
            set
        };
        let (all, front, hidden) = (count("all"), count("front"), count("hidden"));
        assert!(
            hidden <= front && front <= all,
            "{mesh}: {all} {front} {hidden}"
        );
    }
    // Appel's pictures: the cube's and the sphere's are the z-buffer's hidden lines (convex,
    // `tests/appel.rs`); the bunny's lie inside them, a few pulled pixels short.
    for mesh in ["cube", "sphere", "bunny"] {
        let (px, appel) = draw(case(&format!("wire_{mesh}_appel")));
        let (_, hidden) = draw(case(&format!("wire_{mesh}_hidden")));
        let lit = |p: &[u8]| p.iter().filter(|&&x| x != 0).count();
        assert!(px as usize >= lit(&appel) && lit(&appel) > 0, "{mesh}");
        let extra = appel
            .iter()
            .zip(&hidden)
            .filter(|(a, h)| **a != **h)
            .count();
        assert!(
            appel.iter().zip(&hidden).all(|(&a, &h)| a == 0 || h != 0),
            "{mesh}"
        );
        match mesh {
            "bunny" => assert!(extra * 200 <= lit(&hidden), "{mesh}: {extra}"),
            _ => assert_eq!(extra, 0, "{mesh}"),
        }
    }
    for mesh in ["sphere", "bunny"] {
        let one = draw(case(&format!("wire_{mesh}_all")));
        let two = draw(case(&format!("wire_{mesh}_all_two_ended")));
        assert!(one == two, "{mesh}");
    }
}
