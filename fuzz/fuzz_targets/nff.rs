//! Fuzz target: an NFF file, written back and read again ([`raylab_fuzz::nff`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::nff(data);
});
