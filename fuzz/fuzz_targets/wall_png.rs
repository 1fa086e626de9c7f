//! Wall PNGs. Images over a million pixels are skipped to keep executions fast (the reader's
//! own limit, MAX_PIXELS, is checked from the header and has a regression test).
#![no_main]
mod common;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if common::png_size(data).is_some_and(|n| n > 1_000_000) {
        return;
    }
    if let Ok(wall) = mason_wall::read_png(data, "fuzz") {
        common::check_wall(&wall);
    }
});
