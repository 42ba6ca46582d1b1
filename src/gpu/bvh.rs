//! The BVH on the GPU: the CPU's eight-wide tree, node for node, with each leaf's primitives
//! copied out in leaf order — a mesh's triangles with their corners, so that a ray reads a
//! triangle in one load, and any other primitive as its object's index. The nodes go to the GPU
//! in one of two layouts ([`NodeLayout`]): as they are (256 bytes a node), or as a two-wide tree
//! of 64-byte nodes made of them, over the same leaves. The WGSL that walks them is
//! `shaders/bvh/traverse.wgsl`, with `wide_node.wgsl` or `binary_node.wgsl`.

use super::record::gpu_record;
use bytemuck::Zeroable;

use crate::aabb::Aabb;
use crate::bvh::{Bvh, WIDTH, WideNode};
use crate::primitive::{Geometry, PrimId, PrimKind};

/// How the GPU holds the BVH's nodes.
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase")]
pub enum NodeLayout {
    /// The CPU's eight-wide nodes, 256 bytes each: a shallow tree, a large load per node.
    #[default]
    Wide,
    /// Two-wide nodes of 64 bytes (both children's boxes in one cache line), each eight-wide
    /// node a small tree of them: about three times as deep, a small load per node.
    Binary,
}

impl NodeLayout {
    /// The WGSL of the layout's nodes, after `WIDTH`, the children of a node.
    pub fn wgsl(self) -> String {
        let (width, nodes) = match self {
            NodeLayout::Wide => (WIDTH, include_str!("../../shaders/bvh/wide_node.wgsl")),
            NodeLayout::Binary => (2, include_str!("../../shaders/bvh/binary_node.wgsl")),
        };
        format!("const WIDTH: u32 = {width}u;\n{nodes}")
    }
}

gpu_record! {
    /// WGSL's `WideNode`: [`crate::bvh::WideNode`] with the leaves pointing into
    /// [`GpuBvh::triangles`] or [`GpuBvh::refs`]. 256 bytes.
    pub struct GpuWideNode {
        /// The children's boxes: `lo[axis][child]` to `hi[axis][child]`.
        pub lo: [[f32; WIDTH]; 3],
        pub hi: [[f32; WIDTH]; 3],
        /// An interior child's node index, or where a leaf's entries start.
        pub first: [u32; WIDTH],
        /// `WideNode::INTERIOR` for an interior child, 0 for an unused slot, or a leaf's entry
        /// count with [`TRIANGLE_LEAF`] set for a leaf of triangles.
        pub count: [u32; WIDTH],
    }
}

gpu_record! {
    /// WGSL's `BinaryNode`: two children, each its box and, as in [`GpuWideNode`], an interior
    /// child's node index or a leaf's entries (count 0: no child). 64 bytes.
    pub struct GpuBinaryNode {
        pub lo0: [f32; 3],
        pub first0: u32,
        pub hi0: [f32; 3],
        pub count0: u32,
        pub lo1: [f32; 3],
        pub first1: u32,
        pub hi1: [f32; 3],
        pub count1: u32,
    }
}

/// The bit of a leaf's count that says its entries are triangles (else object indices).
pub const TRIANGLE_LEAF: u32 = 1 << 30;

/// The bit of a leaf's count that says its entries are instances: records of
/// [`INSTANCE_WORDS`] words in [`GpuBvh::refs`] (see [`GpuBvh`]).
pub const INSTANCE_LEAF: u32 = 1 << 29;

/// The words of an instance's record in [`GpuBvh::refs`]: its model, the number of its first
/// triangle ([`Geometry::placed_triangle`]), where its transform starts in the shape words, its
/// material ([`NO_MATERIAL`]: its meshes' own), and the id the object view colours it by.
pub const INSTANCE_WORDS: u32 = 5;

/// An instance's material word when its meshes keep their own materials.
pub const NO_MATERIAL: u32 = u32::MAX;

/// A `count` of an entry of the walk's stack that is an instance to walk into, its `first`
/// where the instance's record starts in the references.
pub const INSTANCE_ENTRY: u32 = 1 << 28;

/// A hit's instance where it is on the world's own triangles or objects.
pub const NO_INSTANCE: u32 = u32::MAX;

/// Entries of the stack of the BVH's walk on the GPU: a visited node of the eight-wide tree
/// leaves at most seven siblings waiting, so a tree up to [`MAX_TREE_DEPTH`] levels deep fits;
/// the two-wide tree made of it is at most seven times as deep, with one sibling waiting per
/// level.
pub const WALK_STACK: u32 = 128;

/// The deepest tree the GPU's walk takes.
pub const MAX_TREE_DEPTH: usize = WALK_STACK as usize / (WIDTH - 1);

gpu_record! {
    /// WGSL's `Triangle`: the corners of a mesh triangle and its index in the scene's triangles.
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
}

/// The tree and its leaves' entries as the GPU reads them: the scene's tree, then each model's
/// tree, in one array of nodes, one of triangles (a model's in the model's own space) and one of
/// references.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GpuBvh {
    pub nodes: Vec<GpuWideNode>,
    /// The triangles of the leaves of triangles, in leaf order: the scene's tree's first.
    pub triangles: Vec<GpuTriangle>,
    /// How many of `triangles` are the scene's tree's, in the world.
    pub world_triangles: usize,
    /// Where each model's triangles start in `triangles`.
    pub model_triangles: Vec<usize>,
    /// First the root node of each model's tree, model by model; then the object indices of
    /// the leaves of objects and the instance records of the leaves of instances, in leaf
    /// order; then the unbounded objects (planes), which every ray tests: the last
    /// [`Self::unbounded`] entries.
    pub refs: Vec<u32>,
    /// How many models the references start with.
    pub models: usize,
    /// Where each instance's record starts in the references.
    pub instance_records: Vec<u32>,
    pub unbounded: u32,
}

impl GpuBvh {
    /// The GPU's copy of `bvh`, built over `geometry`, whose instances' transforms start at
    /// `instance_transforms` in the shape words.
    pub fn new(bvh: &Bvh, geometry: &Geometry, instance_transforms: &[u32]) -> GpuBvh {
        let models = geometry.models();
        let mut gpu = GpuBvh {
            refs: vec![0; models.len()],
            models: models.len(),
            ..GpuBvh::default()
        };
        let leaves = Leaves {
            geometry,
            instance_transforms,
        };
        gpu.instance_records = vec![0; geometry.instances().len()];
        gpu.copy_tree(bvh, &leaves);
        gpu.world_triangles = gpu.triangles.len();
        for (m, tree) in bvh.models.iter().enumerate() {
            gpu.refs[m] = gpu.nodes.len() as u32;
            gpu.model_triangles.push(gpu.triangles.len());
            let model = Leaves {
                geometry: &models[m],
                instance_transforms: &[],
            };
            gpu.copy_tree(tree, &model);
        }
        gpu.unbounded = bvh.unbounded.len() as u32;
        gpu.refs
            .extend(bvh.unbounded.iter().map(|p| object_index(p.kind())));
        gpu
    }

    /// Appends the nodes of `bvh` and the entries of its leaves, over `leaves`' geometry.
    fn copy_tree(&mut self, bvh: &Bvh, leaves: &Leaves) {
        let base = self.nodes.len() as u32;
        self.nodes.reserve_exact(bvh.nodes.len());
        for node in &bvh.nodes {
            let mut copy = GpuWideNode {
                lo: node.min,
                hi: node.max,
                first: node.first,
                count: node.count,
            };
            for k in 0..WIDTH {
                let Some(child) = node.child(k) else {
                    continue;
                };
                if !child.is_leaf() {
                    copy.first[k] += base;
                    continue;
                }
                let prims = bvh.leaf_prims(child);
                let count = prims.len() as u32;
                (copy.first[k], copy.count[k]) = match prims.first().map(|p| p.kind()) {
                    Some(PrimKind::Triangle(_)) => {
                        let first = self.triangles.len() as u32;
                        self.triangles
                            .extend(prims.iter().map(|&p| leaves.triangle(p)));
                        (first, count | TRIANGLE_LEAF)
                    }
                    Some(PrimKind::Instance(_)) => {
                        let first = self.refs.len() as u32;
                        for &p in &prims {
                            if let PrimKind::Instance(i) = p.kind() {
                                self.instance_records[i] = self.refs.len() as u32;
                            }
                            self.refs.extend(leaves.instance_record(p));
                        }
                        (first, count | INSTANCE_LEAF)
                    }
                    _ => {
                        let first = self.refs.len() as u32;
                        self.refs
                            .extend(prims.iter().map(|p| object_index(p.kind())));
                        (first, count)
                    }
                };
            }
            self.nodes.push(copy);
        }
    }
}

/// What the leaves of a tree copied to the GPU read their entries from.
struct Leaves<'a> {
    geometry: &'a Geometry,
    instance_transforms: &'a [u32],
}

impl Leaves<'_> {
    /// Triangle `prim`, its corners as the geometry holds them (a model's in its own space).
    fn triangle(&self, prim: PrimId) -> GpuTriangle {
        let PrimKind::Triangle(index) = prim.kind() else {
            unreachable!("a leaf holds one kind")
        };
        let t = self.geometry.triangle(index);
        GpuTriangle {
            p0: t.p0.to_array(),
            index: index as u32,
            p1: t.p1.to_array(),
            object: self.geometry.object_id(prim),
            p2: t.p2.to_array(),
            pad2: 0,
        }
    }

    /// The record of instance `prim` ([`INSTANCE_WORDS`]).
    fn instance_record(&self, prim: PrimId) -> [u32; INSTANCE_WORDS as usize] {
        let PrimKind::Instance(i) = prim.kind() else {
            unreachable!("a leaf holds one kind")
        };
        let instance = &self.geometry.instances()[i];
        [
            instance.model,
            self.geometry.placed_triangle(i, 0).0,
            self.instance_transforms[i],
            instance.material.unwrap_or(NO_MATERIAL),
            self.geometry.object_id(prim),
        ]
    }
}

/// A child of a wide node, or a pair of them joined under a two-wide node.
enum Part {
    Child {
        bounds: Aabb,
        first: u32,
        count: u32,
    },
    Pair {
        bounds: Aabb,
        parts: Box<[Part; 2]>,
    },
}

impl Part {
    fn bounds(&self) -> Aabb {
        match self {
            Part::Child { bounds, .. } | Part::Pair { bounds, .. } => *bounds,
        }
    }
}

/// Half the surface area of `b`: what the surface area heuristic compares.
fn half_area(b: &Aabb) -> f32 {
    let d = b.max - b.min;
    d.x * d.y + d.y * d.z + d.z * d.x
}

impl GpuBvh {
    /// The trees as two-wide nodes over the same leaves, the scene's root first: each
    /// eight-wide node becomes a small tree over its children, made by joining, again and
    /// again, the two parts whose joint box has the least surface area (the most likely to be
    /// entered together). With them, the references with the models' roots in those nodes.
    pub fn binary_nodes(&self) -> (Vec<GpuBinaryNode>, Vec<u32>) {
        let mut out = Vec::with_capacity(self.nodes.len() * 3);
        let mut refs = self.refs.clone();
        if !self.nodes.is_empty() {
            self.push_wide(0, &mut out);
        }
        for root in &mut refs[..self.models] {
            *root = self.push_wide(*root as usize, &mut out);
        }
        (out, refs)
    }

    /// Pushes the small tree of wide node `w` (and below it, its subtrees); returns its root.
    fn push_wide(&self, w: usize, out: &mut Vec<GpuBinaryNode>) -> u32 {
        let node = &self.nodes[w];
        let mut parts: Vec<Part> = (0..WIDTH)
            .filter(|&k| node.count[k] != 0)
            .map(|k| {
                let corner = |c: &[[f32; WIDTH]; 3]| glam::Vec3::new(c[0][k], c[1][k], c[2][k]);
                Part::Child {
                    bounds: Aabb::new(corner(&node.lo), corner(&node.hi)),
                    first: node.first[k],
                    count: node.count[k],
                }
            })
            .collect();
        while parts.len() > 2 {
            let mut best = (f32::INFINITY, 0, 1);
            for i in 0..parts.len() {
                for j in i + 1..parts.len() {
                    let area = half_area(&parts[i].bounds().union(parts[j].bounds()));
                    if area < best.0 {
                        best = (area, i, j);
                    }
                }
            }
            let (_, i, j) = best;
            let b = parts.swap_remove(j);
            let a = parts.swap_remove(i);
            let bounds = a.bounds().union(b.bounds());
            parts.push(Part::Pair {
                bounds,
                parts: Box::new([a, b]),
            });
        }
        self.push_pair(parts, out)
    }

    /// Pushes a two-wide node over `parts` (one or two) and the nodes below it; returns it.
    fn push_pair(&self, parts: Vec<Part>, out: &mut Vec<GpuBinaryNode>) -> u32 {
        let index = out.len();
        let empty = ([f32::INFINITY; 3], [f32::INFINITY; 3], 0, 0);
        out.push(GpuBinaryNode::zeroed());
        let mut slots = [empty; 2];
        for (slot, part) in slots.iter_mut().zip(parts) {
            let bounds = part.bounds();
            let (first, count) = match part {
                Part::Child { first, count, .. } if count == WideNode::INTERIOR => {
                    (self.push_wide(first as usize, out), count)
                }
                Part::Child { first, count, .. } => (first, count),
                Part::Pair { parts, .. } => {
                    let [a, b] = *parts;
                    (self.push_pair(vec![a, b], out), WideNode::INTERIOR)
                }
            };
            *slot = (bounds.min.to_array(), bounds.max.to_array(), first, count);
        }
        let [(lo0, hi0, first0, count0), (lo1, hi1, first1, count1)] = slots;
        out[index] = GpuBinaryNode {
            lo0,
            first0,
            hi0,
            count0,
            lo1,
            first1,
            hi1,
            count1,
        };
        index as u32
    }
}

/// The object index of a primitive that is an object.
fn object_index(kind: PrimKind) -> u32 {
    let PrimKind::Object(index) = kind else {
        unreachable!("a leaf of objects holds only objects")
    };
    index as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::large_mesh::bumpy_sphere_scene;
    use crate::render::assemble;

    /// Walks the two-wide tree from node `n` inside `bounds`: every child's box inside its
    /// parent's, and each leaf met counted by where its entries start.
    fn walk(nodes: &[GpuBinaryNode], n: u32, bounds: Aabb, leaves: &mut Vec<(u32, u32)>) -> usize {
        let node = nodes[n as usize];
        let children = [
            (node.lo0, node.hi0, node.first0, node.count0),
            (node.lo1, node.hi1, node.first1, node.count1),
        ];
        let mut depth = 0;
        for (lo, hi, first, count) in children.into_iter().filter(|c| c.3 != 0) {
            let child = Aabb::new(lo.into(), hi.into());
            assert_eq!(
                bounds.union(child),
                bounds,
                "node {n}'s child leaves its box"
            );
            if count == WideNode::INTERIOR {
                depth = depth.max(walk(nodes, first, child, leaves));
            } else {
                leaves.push((first, count));
            }
        }
        depth + 1
    }

    #[test]
    fn the_two_wide_tree_holds_every_leaf_of_the_eight_wide_one_once_inside_its_boxes() {
        let assembled = assemble(bumpy_sphere_scene(20_000, 8, 8)).unwrap();
        let gpu = GpuBvh::new(&assembled.bvh, &assembled.scene.geometry, &[]);
        let (binary, _) = gpu.binary_nodes();
        let mut wide_leaves: Vec<(u32, u32)> = gpu
            .nodes
            .iter()
            .flat_map(|node| (0..WIDTH).map(|k| (node.first[k], node.count[k])))
            .filter(|&(_, count)| count != 0 && count != WideNode::INTERIOR)
            .collect();
        let mut leaves = Vec::new();
        let everything = Aabb::new(glam::Vec3::splat(-1e30), glam::Vec3::splat(1e30));
        let depth = walk(&binary, 0, everything, &mut leaves);
        wide_leaves.sort_unstable();
        leaves.sort_unstable();
        assert_eq!(leaves, wide_leaves);
        // Each wide node's children make a small tree of one to seven two-wide nodes.
        assert!(binary.len() > gpu.nodes.len() && binary.len() <= 7 * gpu.nodes.len());
        let wide_depth = assembled.bvh.depth();
        assert!(
            depth >= wide_depth && depth <= 7 * wide_depth,
            "{depth} vs {wide_depth}"
        );
    }
}
