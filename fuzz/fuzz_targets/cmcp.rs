//! CMCP walls with both size tables, lenient and strict.
#![no_main]
mod common;
use libfuzzer_sys::fuzz_target;
use mason_wall::CmcpSizes;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = mason_wall::looks_like_cmcp(text);
    for sizes in [CmcpSizes::Yaml, CmcpSizes::Swapped] {
        if let Ok(wall) = mason_wall::parse_cmcp(text, "fuzz", sizes) {
            common::check_wall(&wall);
        }
        if let Ok(wall) = mason_wall::parse_cmcp_strict(text, "fuzz", sizes) {
            common::check_wall(&wall);
        }
    }
});
