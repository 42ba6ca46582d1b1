//! Fuzz target: an SDL file, with `def`/`use` and a mesh file ([`raylab_fuzz::sdl`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::sdl(data);
});
