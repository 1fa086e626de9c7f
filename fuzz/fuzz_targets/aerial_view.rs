//! Aerial views (PNG and JPEG photographs of the floor), read with a given grid, with corners,
//! and with the grid found from painted lines, and audited past the cells' refusals (the same
//! reading when nothing is refused). Images over a million pixels are skipped to keep
//! executions fast (the reader's limit, aerial::MAX_PIXELS, is checked from the header and has
//! a regression test).
#![no_main]
mod common;
use libfuzzer_sys::fuzz_target;
use mason_crew::aerial::{audit_aerial, read_aerial, AerialConfig};

fuzz_target!(|data: &[u8]| {
    if common::png_size(data).is_some_and(|n| n > 1_000_000) {
        return;
    }
    let grid = AerialConfig {
        grid: Some((8, 5)),
        ..AerialConfig::default()
    };
    let corners = AerialConfig {
        corners: Some([(2.0, 1.0), (60.0, 3.0), (58.0, 40.0), (1.0, 38.0)]),
        ..grid.clone()
    };
    for config in [grid, corners, AerialConfig::default()] {
        let read = read_aerial(data, "fuzz", &config);
        if let Ok(seen) = &read {
            assert!(!seen.robots.is_empty() && seen.robots.len() <= seen.goals.len());
            for m in seen.robots.iter().chain(&seen.goals) {
                assert!(seen.grid.is_free(m.cell));
                assert!((0.0..=1.0).contains(&m.confidence));
            }
        }
        if let Ok(audited) = audit_aerial(data, "fuzz", &config) {
            let seen = &audited.reading;
            assert!(!seen.robots.is_empty() && seen.robots.len() <= seen.goals.len());
            match &read {
                Ok(r) => assert!(audited.doubts.is_empty() && r.grid == seen.grid),
                Err(e) => assert_eq!(
                    audited.doubts.first().map(|d| d.to_string()),
                    Some(e.to_string())
                ),
            }
        }
    }
});
