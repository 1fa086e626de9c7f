//! Bird's-eye and occupancy PNGs. Images over a million pixels are skipped to keep executions
//! fast (the reader's limit, MAX_CELLS, is checked from the header and has a regression test).
#![no_main]
mod common;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if common::png_size(data).is_some_and(|n| n > 1_000_000) {
        return;
    }
    let _ = mason_crew::image::read_occupancy(data, "fuzz");
    if let Ok(seen) = mason_crew::image::read_birdseye(data, "fuzz") {
        assert!(!seen.robots.is_empty() && seen.robots.len() <= seen.goals.len());
        for c in seen.robots.iter().chain(&seen.goals) {
            assert!(seen.grid.is_free(*c));
        }
    }
});
