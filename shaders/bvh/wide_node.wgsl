// The eight-wide node layout: the CPU's `WideNode` (src/bvh/mod.rs) node for node, 256 bytes,
// as `GpuWideNode` in src/gpu/bvh.rs copies it: a node is one load of eight children's boxes.

// `WideNode`: eight children's boxes, axis by axis, and where each child is.
struct WideNode {
    lo: array<array<f32, WIDTH>, 3>,
    hi: array<array<f32, WIDTH>, 3>,
    first: array<u32, WIDTH>,
    count: array<u32, WIDTH>,
}

alias Node = WideNode;

// Child `k` of `node` (`NodeChild` in traverse.wgsl).
fn node_child(node: Node, k: u32) -> NodeChild {
    let lo = vec3<f32>(node.lo[0][k], node.lo[1][k], node.lo[2][k]);
    let hi = vec3<f32>(node.hi[0][k], node.hi[1][k], node.hi[2][k]);
    return NodeChild(lo, hi, node.first[k], node.count[k]);
}
