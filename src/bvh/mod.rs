//! The bounding volume hierarchy: a tree of boxes over all bounded primitives, built with the
//! surface area heuristic as a binary tree (`build`), collapsed to eight children per node
//! (`wide`) and stored as an array of [`WideNode`]s, each holding its children's boxes axis by
//! axis. Traversal (`traverse`) tests a node's eight child boxes against a ray at once
//! (`ray_box`), with the widest instruction set the processor has (`simd`); a tile of coherent
//! eye rays walks the tree once, together ([`packet`]). A leaf holds one kind of primitive,
//! tested its own way (`leaf`). Unbounded primitives (planes) are kept in a list beside the
//! tree and tested against every ray. A model that instances place has a tree of its own, over
//! its triangles in its own space; the scene's tree holds the instances, which a ray walks into
//! (`instances`): a two-level tree.

mod build;
pub mod cost;
mod instances;
mod leaf;
pub mod packet;
mod ray_box;
mod simd;
mod traverse;
mod walk;
mod wide;

pub use leaf::{Leaf, Reached};
pub use simd::Simd;

use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};
use crate::shapes::{CylinderPack, PolygonPack, SpherePack, TrianglePack};
use leaf::LeafKind;

/// Children per node of the finished tree: one per lane of the box test.
pub const WIDTH: usize = simd::LANES;

/// A node of the binary tree the builder makes: an interior node's children are nodes `first`
/// and `first + 1`; a leaf holds primitives `first .. first + count` of [`Bvh::prims`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    min: [f32; 3],
    first: u32,
    max: [f32; 3],
    /// A leaf's number of primitives; an interior node's number of children plus
    /// [`Node::INTERIOR`].
    count: u32,
}

impl Node {
    /// The bit of `count` that marks an interior node.
    const INTERIOR: u32 = 1 << 31;

    fn is_leaf(&self) -> bool {
        self.count & Node::INTERIOR == 0
    }
}

/// A node of the finished tree: the boxes of up to [`WIDTH`] children, stored axis by axis
/// (`min[axis][child]`) so that one SIMD load fetches one coordinate of every child, and where
/// each child is. 256 bytes, four cache lines, aligned to them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct WideNode {
    pub min: [[f32; WIDTH]; 3],
    pub max: [[f32; WIDTH]; 3],
    /// An interior child's node index, or where a leaf starts in the array of its kind.
    pub first: [u32; WIDTH],
    /// A leaf's number of packs or objects, with its kind in the top bits (`Child::leaf_of`);
    /// [`WideNode::INTERIOR`] for an interior child, 0 for an unused slot.
    pub count: [u32; WIDTH],
}

impl WideNode {
    /// The `count` of an interior child.
    pub const INTERIOR: u32 = u32::MAX;

    /// Child `k`, if the slot is used.
    pub fn child(&self, k: usize) -> Option<Child> {
        (self.count[k] != 0).then_some(Child {
            first: self.first[k],
            count: self.count[k],
        })
    }

    /// The box of child `k`.
    pub fn child_bounds(&self, k: usize) -> Aabb {
        let corner = |c: &[[f32; WIDTH]; 3]| glam::Vec3::new(c[0][k], c[1][k], c[2][k]);
        Aabb::new(corner(&self.min), corner(&self.max))
    }
}

/// Where a child of a [`WideNode`] is: a node, or a leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Child {
    pub first: u32,
    pub count: u32,
}

impl Child {
    /// Where the kind of a leaf starts in `count`.
    const KIND_SHIFT: u32 = 28;

    /// The interior node `index`.
    const fn node(index: u32) -> Child {
        Child {
            first: index,
            count: WideNode::INTERIOR,
        }
    }

    /// A leaf of `count` entries from `first` in the BVH's array of `kind`.
    fn leaf_of(kind: LeafKind, first: u32, count: u32) -> Child {
        Child {
            first,
            count: count | (kind as u32) << Child::KIND_SHIFT,
        }
    }

    pub fn is_leaf(&self) -> bool {
        self.count != WideNode::INTERIOR
    }

    /// A leaf's primitives or instances (it must be a leaf).
    #[inline(always)]
    fn leaf<'a>(&self, bvh: &'a Bvh) -> Reached<'a> {
        let kind = LeafKind::from_bits(self.count >> Child::KIND_SHIFT);
        let count = self.count & ((1 << Child::KIND_SHIFT) - 1);
        Reached::in_bvh(bvh, kind, self.first as usize, count as usize)
    }
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The tree, root first; empty when the scene has no bounded primitive.
    pub nodes: Vec<WideNode>,
    /// The box around all bounded primitives (the root's); `None` when there are none.
    root_bounds: Option<Aabb>,
    /// The triangles of the leaves, in leaf order, four to a pack; each lane's tag is its
    /// [`PrimId`].
    pub packs: Vec<TrianglePack>,
    /// The spheres of the leaves of spheres, likewise.
    pub spheres: Vec<SpherePack>,
    /// The open cylinders of the leaves of cylinders, likewise.
    pub cylinders: Vec<CylinderPack>,
    /// The polygons of the leaves of polygons, likewise.
    pub polygons: Vec<PolygonPack>,
    /// The other bounded objects, and the instances, in leaf order.
    pub objects: Vec<PrimId>,
    /// Primitives without bounds, tested against every ray.
    pub unbounded: Vec<PrimId>,
    /// The trees of the geometry's models, index for index, each over the model's triangles
    /// in its own space.
    pub models: Vec<Bvh>,
    /// The instruction set the traversal uses.
    simd: Simd,
}

impl Bvh {
    /// The tree over the builder's binary tree `binary` (root first) and primitives in leaf
    /// order.
    fn from_binary(
        geometry: &Geometry,
        binary: &[Node],
        prims: &[PrimId],
        unbounded: Vec<PrimId>,
        models: Vec<Bvh>,
    ) -> Bvh {
        let wide::Collapsed {
            nodes,
            packs,
            spheres,
            cylinders,
            polygons,
            objects,
        } = wide::collapse(binary, prims, geometry);
        Bvh {
            nodes,
            root_bounds: binary
                .first()
                .map(|root| Aabb::new(root.min.into(), root.max.into())),
            packs,
            spheres,
            cylinders,
            polygons,
            objects,
            unbounded,
            models,
            simd: Simd::best(),
        }
    }

    /// Bytes held by the tree and its leaves, and by the models' trees.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let models: usize = self.models.iter().map(Bvh::memory_bytes).sum();
        models
            + self.models.capacity() * size_of::<Bvh>()
            + self.nodes.capacity() * size_of::<WideNode>()
            + self.packs.capacity() * size_of::<TrianglePack>()
            + self.spheres.capacity() * size_of::<SpherePack>()
            + self.cylinders.capacity() * size_of::<CylinderPack>()
            + self.polygons.capacity() * size_of::<PolygonPack>()
            + (self.objects.capacity() + self.unbounded.capacity()) * size_of::<PrimId>()
    }

    /// The primitives in the leaf `child`, for statistics and tests.
    pub fn leaf_prims(&self, child: Child) -> Vec<PrimId> {
        child.leaf(self).prims()
    }

    /// The box around all bounded primitives (the root's), `None` when there are none.
    pub fn bounds(&self) -> Option<Aabb> {
        self.root_bounds
    }

    /// The instruction set the traversal uses: [`Simd::best`] unless changed.
    pub fn simd(&self) -> Simd {
        self.simd
    }

    /// Makes the traversal use `simd`, if this processor runs it; otherwise says why not.
    pub fn set_simd(&mut self, simd: Simd) -> Result<(), String> {
        if !simd.is_supported() {
            return Err(format!("this processor cannot run the {simd} path"));
        }
        self.simd = simd;
        for model in &mut self.models {
            model.simd = simd;
        }
        Ok(())
    }

    /// Depth of the tree (0 when empty), for statistics and tests.
    pub fn depth(&self) -> usize {
        fn depth_of(nodes: &[WideNode], i: usize) -> usize {
            let node = &nodes[i];
            1 + (0..WIDTH)
                .filter_map(|k| node.child(k))
                .filter(|c| !c.is_leaf())
                .map(|c| depth_of(nodes, c.first as usize))
                .max()
                .unwrap_or(0)
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }
}
