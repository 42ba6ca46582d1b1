//! Fuzz target: a part of an image, an OpenEXR file from `raylab render --tile`
//! ([`raylab_fuzz::part`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::part(data);
});
