//! Fuzz target: a glTF or GLB model opened on its own ([`raylab_fuzz::gltf`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::gltf(data);
});
