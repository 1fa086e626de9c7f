//! Layer text and MBZIRC: `Ok` (a wall `exact` plans and `order::validate` accepts) or a clean
//! error, never a panic.
#![no_main]
mod common;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(wall) = mason_wall::parse_layer_text(text, "fuzz") {
        common::check_wall(&wall);
    }
    if let Ok(wall) = mason_wall::parse_mbzirc(text, "fuzz") {
        common::check_wall(&wall);
    }
});
