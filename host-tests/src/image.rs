//! Writing frames to image files (PNG through a LUT, PGM, PPM).
