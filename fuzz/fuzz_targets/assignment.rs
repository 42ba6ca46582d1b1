//! Fuzz target: a `raylab grade` assignment file ([`raylab_fuzz::assignment`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::assignment(data);
});
