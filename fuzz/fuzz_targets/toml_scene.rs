//! Fuzz target: a TOML scene file, with the models and textures it may name
//! ([`raylab_fuzz::toml_scene`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::toml_scene(data);
});
