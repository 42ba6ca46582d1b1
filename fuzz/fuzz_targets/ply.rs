//! Fuzz target: a PLY file, ASCII or binary ([`raylab_fuzz::ply`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::ply(data);
});
