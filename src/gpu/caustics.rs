//! The caustic photon map on the GPU: its photons in the kd-tree's order, each with the axis its
//! node splits, which `shaders/caustics.wgsl` searches as `PhotonMap::irradiance` does.

use super::record::gpu_record;

use crate::photon_map::PhotonMap;

gpu_record! {
    /// WGSL's `Photon`: a photon where it landed, and the axis its node of the tree splits.
    pub struct GpuPhoton {
        pub position: [f32; 3],
        pub axis: u32,
        pub power: [f32; 3],
        pub pad0: u32,
        pub dir: [f32; 3],
        pub pad1: u32,
    }
}

/// The deepest tree the GPU's search takes: its stack (`PHOTON_STACK` in
/// `shaders/caustics.wgsl`) holds one waiting half per level. The tree of the most photons a
/// scene may shoot ([`crate::settings::MAX_CAUSTIC_PHOTONS`]) is less deep (a test checks it).
pub const MAX_PHOTON_TREE_DEPTH: u32 = 32;

/// The photons of `map` as the GPU reads them.
pub fn photon_records(map: &PhotonMap) -> Vec<GpuPhoton> {
    map.photons()
        .iter()
        .zip(map.nodes())
        .map(|(photon, node)| GpuPhoton {
            position: photon.position.to_array(),
            axis: node.w as u32,
            power: photon.power.to_array(),
            pad0: 0,
            dir: photon.dir.to_array(),
            pad1: 0,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon_map::LEAF_SIZE;
    use crate::settings::MAX_CAUSTIC_PHOTONS;

    /// The levels of nodes above the leaves in the tree of `photons` photons: ranges are halved
    /// (less their middle photon) until they hold at most [`LEAF_SIZE`].
    fn tree_depth(photons: usize) -> u32 {
        let mut depth = 0;
        let mut range = photons;
        while range > LEAF_SIZE {
            // The larger half of a range split at its middle `mid`: `mid - lo`.
            range /= 2;
            depth += 1;
        }
        depth
    }

    #[test]
    fn the_largest_photon_map_fits_the_gpus_search() {
        assert!(tree_depth(MAX_CAUSTIC_PHOTONS as usize) <= MAX_PHOTON_TREE_DEPTH);
        assert_eq!(tree_depth(LEAF_SIZE), 0);
        assert_eq!(tree_depth(LEAF_SIZE + 1), 1);
    }
}
