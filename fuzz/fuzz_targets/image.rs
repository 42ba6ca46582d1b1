//! Fuzz target: an image file as `raylab diff` reads it, any format ([`raylab_fuzz::image`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::image(data);
});
