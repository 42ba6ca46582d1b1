//! The BVH on the GPU: the CPU's eight-wide tree, node for node, with each leaf's primitives
//! copied out in leaf order — a mesh's triangles with their corners, so that a ray reads a
//! triangle in one load, and any other primitive as its object's index. The WGSL that walks it
//! is `shaders/bvh/traverse.wgsl`.

use bytemuck::{Pod, Zeroable};

use crate::bvh::{Bvh, WIDTH};
use crate::primitive::Geometry;

/// WGSL's `WideNode`: [`crate::bvh::WideNode`] with the leaves pointing into
/// [`GpuBvh::triangles`] or [`GpuBvh::refs`]. 256 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuWideNode {
    /// `min[axis][child]`.
    pub min: [[f32; WIDTH]; 3],
    pub max: [[f32; WIDTH]; 3],
    /// An interior child's node index, or where a leaf's entries start.
    pub first: [u32; WIDTH],
    /// `WideNode::INTERIOR` for an interior child, 0 for an unused slot, or a leaf's entry
    /// count with [`TRIANGLE_LEAF`] set for a leaf of triangles.
    pub count: [u32; WIDTH],
}

/// The bit of a leaf's count that says its entries are triangles (else object indices).
pub const TRIANGLE_LEAF: u32 = 1 << 30;

/// WGSL's `Triangle`: the corners of a mesh triangle and its index in the scene's triangles.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTriangle {
    pub p0: [f32; 3],
    /// The triangle's index ([`crate::primitive::PrimId::triangle`]).
    pub index: u32,
    pub p1: [f32; 3],
    /// The id the object view colours it by: its mesh's ([`Geometry::object_id`]).
    pub object: u32,
    pub p2: [f32; 3],
    pub pad2: u32,
}

/// The tree and its leaves' entries as the GPU reads them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GpuBvh {
    pub nodes: Vec<GpuWideNode>,
    /// The triangles of the leaves of triangles, in leaf order.
    pub triangles: Vec<GpuTriangle>,
    /// The object indices of the other leaves, in leaf order, then the unbounded objects
    /// (planes), which every ray tests: the last [`Self::unbounded`] entries.
    pub refs: Vec<u32>,
    pub unbounded: u32,
}

impl GpuBvh {
    /// The GPU's copy of `bvh`, built over `geometry`.
    pub fn new(bvh: &Bvh, geometry: &Geometry) -> GpuBvh {
        let mut gpu = GpuBvh::default();
        gpu.nodes.reserve_exact(bvh.nodes.len());
        for node in &bvh.nodes {
            let mut copy = GpuWideNode {
                min: node.min,
                max: node.max,
                first: node.first,
                count: node.count,
            };
            for k in 0..WIDTH {
                let Some(child) = node.child(k).filter(|c| c.is_leaf()) else {
                    continue;
                };
                let prims = bvh.leaf_prims(child);
                let triangles = prims.first().is_some_and(|p| p.kind().is_err());
                if triangles {
                    copy.first[k] = gpu.triangles.len() as u32;
                    copy.count[k] = prims.len() as u32 | TRIANGLE_LEAF;
                    gpu.triangles.extend(prims.iter().map(|p| {
                        let index = p.kind().expect_err("a leaf holds one kind");
                        let t = geometry.triangle(index);
                        GpuTriangle {
                            p0: t.p0.to_array(),
                            index: index as u32,
                            p1: t.p1.to_array(),
                            object: geometry.object_id(*p),
                            p2: t.p2.to_array(),
                            pad2: 0,
                        }
                    }));
                } else {
                    copy.first[k] = gpu.refs.len() as u32;
                    copy.count[k] = prims.len() as u32;
                    gpu.refs
                        .extend(prims.iter().map(|p| object_index(p.kind())));
                }
            }
            gpu.nodes.push(copy);
        }
        gpu.unbounded = bvh.unbounded.len() as u32;
        gpu.refs
            .extend(bvh.unbounded.iter().map(|p| object_index(p.kind())));
        gpu
    }
}

/// The object index of a primitive that is an object.
fn object_index(kind: Result<usize, usize>) -> u32 {
    kind.expect("a leaf of objects holds only objects") as u32
}
