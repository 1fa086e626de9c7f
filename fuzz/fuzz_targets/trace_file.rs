//! Agent trace files (`mason agent --trace`, read back by `mason launch`, `--remember` and the
//! simulated camera): the one strict reader never panics; whatever it accepts writes back as
//! the same events; a killed agent's reading accepts at least what the strict one does.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.jsonl");
    let strict = mason_fleet::parse_trace(text, path, false);
    let killed = mason_fleet::parse_trace(text, path, true);
    if let Ok(events) = &strict {
        assert_eq!(
            killed.as_ref().ok(),
            Some(events),
            "killed reading accepts what strict does"
        );
        let mut out = String::new();
        for e in events {
            out.push_str(&serde_json::to_string(e).expect("an event serialises"));
            out.push('\n');
        }
        let back = mason_fleet::parse_trace(&out, path, false).expect("written events read back");
        assert_eq!(&back, events);
    }
    if let Err(e) = &strict {
        let msg = e.to_string();
        assert!(msg.starts_with("fuzz.jsonl"), "{msg}");
        assert!(!msg.contains('\n'), "{msg}");
    }
});
