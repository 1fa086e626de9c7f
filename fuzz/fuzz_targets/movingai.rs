//! MovingAI maps and scenarios: the input is a map, then a NUL byte, then a scenario for it.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (map, scen) = text.split_once('\0').unwrap_or((text, ""));
    let Ok(grid) = mason_crew::movingai::parse_map(map, "fuzz.map") else {
        return;
    };
    for limit in [usize::MAX, 2] {
        if let Ok(agents) = mason_crew::movingai::parse_scen(scen, "fuzz.scen", &grid, limit) {
            assert!(!agents.is_empty() && agents.len() <= mason_crew::limits::MAX_AGENTS);
            for a in &agents {
                assert!(grid.is_free(a.start) && grid.is_free(a.goal));
            }
        }
    }
});
