// The two-wide node layout: 64 bytes, a node holding its two children's boxes, so that a ray
// tests both after one load of a cache line (`GpuBinaryNode` in src/gpu/bvh.rs makes it of the
// eight-wide tree, each wide node a small tree of its own).

// `GpuBinaryNode`: each child's box, with where the child is beside it.
struct BinaryNode {
    lo0: vec3<f32>,
    first0: u32,
    hi0: vec3<f32>,
    count0: u32,
    lo1: vec3<f32>,
    first1: u32,
    hi1: vec3<f32>,
    count1: u32,
}

alias Node = BinaryNode;

// Child `k` of `node` (`NodeChild` in traverse.wgsl).
fn node_child(node: Node, k: u32) -> NodeChild {
    if k == 0u {
        return NodeChild(node.lo0, node.hi0, node.first0, node.count0);
    }
    return NodeChild(node.lo1, node.hi1, node.first1, node.count1);
}
