//! Fuzz target: a views file, `NAME.views.toml` ([`raylab_fuzz::views`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::views(data);
});
