//! Fuzz target: an MTL file, the materials of an OBJ model, whose `map_Kd` lines may name an
//! image ([`raylab_fuzz::mtl`]).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = raylab_fuzz::mtl(data);
});
