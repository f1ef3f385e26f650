//! Fuzz target: arbitrary bytes as a probe file through its reader
//! (`rtprof_probe::format::parse`). A panic is a finding; so is a refusal that names a
//! byte beyond the input or line 0, and an accepted file that does not read back equal
//! from the text the writers would write for it.

#![no_main]

use libfuzzer_sys::fuzz_target;
use rtprof_probe::format::parse;

fuzz_target!(|data: &[u8]| {
    match parse(data) {
        Ok(file) => {
            let again = parse(file.to_text().as_bytes());
            assert_eq!(again.as_ref(), Ok(&file), "an accepted file does not read back");
        }
        Err(e) => {
            assert!(e.line >= 1 && e.offset <= data.len(), "{e} for {} bytes", data.len());
        }
    }
});
