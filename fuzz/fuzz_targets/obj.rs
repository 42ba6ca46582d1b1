//! Fuzz target: an OBJ file, loaded as a scene's `type = "obj"` object ([`raylab_fuzz::obj`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::obj(data);
});
