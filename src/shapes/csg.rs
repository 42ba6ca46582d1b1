//! Boolean objects (constructive solid geometry): the union, intersection or difference of
//! closed solids, each placed by its own transform and with its own material, nested to any
//! depth up to [`MAX_DEPTH`].
//!
//! A ray is traced by Roth's classification: every operand says where the ray is inside it, as
//! spans `[enter, exit]` along the whole line ([`Shape::crossings`]); the spans of the operands
//! are combined by the boolean operations, and the first boundary of the result inside the
//! asked-for range of `t` is the hit. Since every operand's spans cover the whole line, a ray
//! that starts on or near the surface is classified like any other and neither hits the surface
//! it leaves nor slips through.
//!
//! A node is flattened when it is made: its operands (the leaves of the tree, never CSG nodes
//! themselves) each carry their transform from their own space to the node's, and the tree
//! becomes a postfix program over them, run with fixed-size stacks, so tracing allocates
//! nothing.

use arrayvec::ArrayVec;
use glam::Vec3;

use super::{LocalSurface, Shape, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;
use crate::transform::Transform;

/// How deeply CSG nodes may be nested (a node of plain solids is depth 1).
pub const MAX_DEPTH: usize = 16;

/// How many solids one CSG object may combine, counting those of nested nodes.
pub const MAX_OPERANDS: usize = 64;

/// Most spans a single operand can give (a torus is crossed up to four times).
const MAX_OPERAND_SPANS: usize = 2;

/// Most spans a list can hold: combining lists never gives more spans than they hold together.
const MAX_SPANS: usize = MAX_OPERANDS * MAX_OPERAND_SPANS;

/// A CSG hit's part is the operand's index shifted by this many bits, or-ed with the part of
/// the operand's shape that was hit (every shape has fewer than 16 parts).
pub const PART_BITS: u32 = 4;

/// The three boolean operations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::EnumIter)]
pub enum CsgOperation {
    Union,
    Intersection,
    /// The first child minus all the others.
    Difference,
}

impl CsgOperation {
    /// Whether a point inside `a` or not (`in_a`) and inside `b` or not is inside the result.
    fn contains(self, in_a: bool, in_b: bool) -> bool {
        match self {
            CsgOperation::Union => in_a || in_b,
            CsgOperation::Intersection => in_a && in_b,
            CsgOperation::Difference => in_a && !in_b,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            CsgOperation::Union => "union",
            CsgOperation::Intersection => "intersection",
            CsgOperation::Difference => "difference",
        }
    }
}

/// A child of a CSG node as given to [`Csg::new`]: a closed solid or another CSG node, placed in
/// the node's space by `transform`.
#[derive(Clone, Debug, PartialEq)]
pub struct Operand {
    pub shape: Shape,
    pub transform: Option<Transform>,
    /// Unused for a nested CSG node, whose operands carry their own.
    pub material: u32,
}

/// One solid of a flattened CSG object.
#[derive(Clone, Debug, PartialEq)]
pub struct Leaf {
    pub shape: Shape,
    /// From the solid's space to the space of the outermost node.
    pub transform: Option<Transform>,
    pub material: u32,
    /// Where it sits in the tree, e.g. "child 2 (csg) › child 1 (box)".
    pub label: String,
    /// Whether it is subtracted an odd number of times, so that its normals must be turned round
    /// to face out of the result.
    complemented: bool,
    /// Its bounds in the node's space; `None` for a half-space.
    bounds: Option<Aabb>,
}

/// One step of the postfix program that evaluates the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Step {
    /// Push the spans of leaf `i`.
    Leaf(u16),
    /// Replace the two topmost span lists by their combination.
    Combine(CsgOperation),
}

/// A boolean object.
#[derive(Clone, Debug, PartialEq)]
pub struct Csg {
    pub operation: CsgOperation,
    leaves: Vec<Leaf>,
    program: Vec<Step>,
    bounds: Option<Aabb>,
    depth: usize,
}

/// Where the ray enters or leaves a solid: the ray parameter and the CSG part (leaf and its
/// shape's part).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Boundary {
    t: f32,
    part: u32,
}

/// A stretch of the ray inside a solid; `t` may be infinite at either end (half-spaces).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    enter: Boundary,
    exit: Boundary,
}

type Spans = ArrayVec<Span, MAX_SPANS>;

impl Csg {
    /// Combines `children` (at least one) by `operation`. Open surfaces, nesting deeper than
    /// [`MAX_DEPTH`] and more than [`MAX_OPERANDS`] solids are errors.
    pub fn new(operation: CsgOperation, children: Vec<Operand>) -> Result<Csg, String> {
        if children.is_empty() {
            return Err(format!(
                "a csg {} needs at least one child",
                operation.name()
            ));
        }
        let mut csg = Csg {
            operation,
            leaves: Vec::new(),
            program: Vec::new(),
            bounds: None,
            depth: 1,
        };
        let mut child_bounds = Vec::with_capacity(children.len());
        for (index, child) in children.into_iter().enumerate() {
            let number = index + 1;
            let subtracted = operation == CsgOperation::Difference && index > 0;
            child_bounds.push(
                child
                    .shape
                    .bounds()
                    .map(|b| child.transform.map_or(b, |t| t.bounds_to_world(&b))),
            );
            match child.shape {
                Shape::Csg(inner) => {
                    if inner.depth >= MAX_DEPTH {
                        return Err(format!("csg nodes are nested more than {MAX_DEPTH} deep"));
                    }
                    csg.depth = csg.depth.max(inner.depth + 1);
                    csg.add_node(*inner, number, child.transform, subtracted)?;
                }
                shape => {
                    if !shape.is_solid() {
                        return Err(format!(
                            "child {number} ({}) is an open surface; csg operands must be \
                             closed solids",
                            shape.name()
                        ));
                    }
                    let label = format!("child {number} ({})", shape.name());
                    csg.add_leaf(Leaf {
                        bounds: shape.bounds().map(|b| match &child.transform {
                            Some(t) => t.bounds_to_world(&b),
                            None => b,
                        }),
                        shape,
                        transform: child.transform,
                        material: child.material,
                        label,
                        complemented: subtracted,
                    })?;
                }
            }
            if index > 0 {
                csg.program.push(Step::Combine(operation));
            }
        }
        csg.bounds = combined_bounds(operation, &child_bounds);
        Ok(csg)
    }

    /// Appends a leaf and the step that pushes its spans.
    fn add_leaf(&mut self, leaf: Leaf) -> Result<(), String> {
        if self.leaves.len() >= MAX_OPERANDS {
            return Err(format!(
                "a csg object combines at most {MAX_OPERANDS} solids"
            ));
        }
        self.program.push(Step::Leaf(self.leaves.len() as u16));
        self.leaves.push(leaf);
        Ok(())
    }

    /// Appends a nested node, child `number`, with its leaves moved into this node's space.
    fn add_node(
        &mut self,
        inner: Csg,
        number: usize,
        transform: Option<Transform>,
        subtracted: bool,
    ) -> Result<(), String> {
        let first = self.leaves.len() as u16;
        for leaf in inner.leaves {
            let moved = match (leaf.transform, transform) {
                (Some(own), Some(outer)) => Some(own.then(&outer)),
                (own, outer) => own.or(outer),
            };
            if self.leaves.len() >= MAX_OPERANDS {
                return Err(format!(
                    "a csg object combines at most {MAX_OPERANDS} solids"
                ));
            }
            self.leaves.push(Leaf {
                bounds: leaf.shape.bounds().map(|b| match &moved {
                    Some(t) => t.bounds_to_world(&b),
                    None => b,
                }),
                transform: moved,
                label: format!("child {number} (csg) › {}", leaf.label),
                complemented: leaf.complemented != subtracted,
                ..leaf
            });
        }
        self.program
            .extend(inner.program.into_iter().map(|step| match step {
                Step::Leaf(i) => Step::Leaf(first + i),
                combine => combine,
            }));
        Ok(())
    }

    /// The node's bounds in its own space: `None` when it reaches infinitely far (a union with
    /// a half-space).
    pub fn bounds(&self) -> Option<Aabb> {
        self.bounds
    }

    /// The solids, in the order their parts number them.
    pub fn leaves(&self) -> &[Leaf] {
        &self.leaves
    }

    /// The postfix program over [`Self::leaves`] that evaluates the tree.
    pub fn program(&self) -> &[Step] {
        &self.program
    }

    /// The index of the leaf a hit's `part` belongs to.
    pub fn leaf_index(&self, part: u32) -> usize {
        (part >> PART_BITS) as usize
    }

    /// The leaf a hit's `part` belongs to.
    pub fn leaf(&self, part: u32) -> &Leaf {
        &self.leaves[self.leaf_index(part)]
    }

    /// The first boundary of the result in `(t_min, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        self.spans(ray, t_min, t_max)
            .iter()
            .flat_map(|span| [span.enter, span.exit])
            .find(|b| b.t > t_min && b.t < t_max)
            .map(|b| ShapeHit {
                t: b.t,
                part: b.part,
            })
    }

    /// Where the ray is inside the result. Exact inside `(t_min, t_max)`; an operand whose box
    /// the ray misses there is taken as missed altogether, which changes nothing inside.
    fn spans(&self, ray: &Ray, t_min: f32, t_max: f32) -> Spans {
        let inv_dir = ray.dir.recip();
        let mut stack = Spans::new();
        // Where each pending list starts in `stack`: at most one per enclosing node, and two
        // for the node being combined.
        let mut starts = ArrayVec::<usize, { MAX_DEPTH + 2 }>::new();
        let mut combined = Spans::new();
        for step in &self.program {
            match *step {
                Step::Leaf(i) => {
                    starts.push(stack.len());
                    let leaf = &self.leaves[i as usize];
                    let missed = leaf
                        .bounds
                        .is_some_and(|b| b.entry(ray.origin, inv_dir, t_min, t_max).is_none());
                    if !missed {
                        leaf.push_spans(ray, u32::from(i) << PART_BITS, &mut stack);
                    }
                }
                Step::Combine(operation) => {
                    let b = starts.pop().expect("a combine step follows two lists");
                    let a = *starts.last().expect("a combine step follows two lists");
                    combine(operation, &stack[a..b], &stack[b..], &mut combined);
                    stack.truncate(a);
                    stack.extend(combined.drain(..));
                }
            }
        }
        stack
    }

    /// The surface of the leaf that `part` names, in the node's space, its normal facing out
    /// of the result.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        let leaf = self.leaf(part);
        let shape_part = part & ((1 << PART_BITS) - 1);
        let local = match &leaf.transform {
            Some(t) => {
                let mut s = leaf
                    .shape
                    .surface(t.object_from_world.transform_point3(p), shape_part);
                s.normal = t.normal_to_world(s.normal);
                s
            }
            None => leaf.shape.surface(p, shape_part),
        };
        LocalSurface {
            normal: if leaf.complemented {
                -local.normal
            } else {
                local.normal
            },
            uv: local.uv,
        }
    }
}

impl Leaf {
    /// Whether the leaf is subtracted an odd number of times, so that [`Csg::surface`] turns
    /// its normals round.
    pub fn is_complemented(&self) -> bool {
        self.complemented
    }

    /// Pushes the spans where `ray` (in the node's space) is inside the leaf, tagged with
    /// `part_base`.
    fn push_spans(&self, ray: &Ray, part_base: u32, out: &mut Spans) {
        let crossings = match &self.transform {
            Some(t) => self.shape.crossings(&t.ray_to_object(ray)),
            None => self.shape.crossings(ray),
        };
        let boundary = |h: &ShapeHit| Boundary {
            t: h.t,
            part: part_base | h.part,
        };
        for pair in crossings.chunks_exact(2) {
            out.push(Span {
                enter: boundary(&pair[0]),
                exit: boundary(&pair[1]),
            });
        }
    }
}

/// The bounds of a node from those of its children (`None`: unbounded).
fn combined_bounds(operation: CsgOperation, children: &[Option<Aabb>]) -> Option<Aabb> {
    match operation {
        CsgOperation::Union => children
            .iter()
            .try_fold(Aabb::EMPTY, |all, b| b.map(|b| all.union(b))),
        CsgOperation::Intersection => {
            let overlap = children
                .iter()
                .flatten()
                .copied()
                .reduce(|a, b| Aabb::new(a.min.max(b.min), a.max.min(b.max)))?;
            // Solids that do not overlap leave nothing: a point box, never hit.
            Some(Aabb::new(overlap.min, overlap.max.max(overlap.min)))
        }
        CsgOperation::Difference => children[0],
    }
}

/// Sweeps along the boundaries of `a` and `b` (each sorted and disjoint) and writes the spans
/// where `operation` says the ray is inside the result. Boundaries at the same `t` are taken
/// together, so that solids that touch (a union of two boxes sharing a face) leave no surface
/// between them.
fn combine(operation: CsgOperation, a: &[Span], b: &[Span], out: &mut Spans) {
    let boundary = |list: &[Span], i: usize| {
        let span = list[i / 2];
        if i.is_multiple_of(2) {
            span.enter
        } else {
            span.exit
        }
    };
    let (a_end, b_end) = (2 * a.len(), 2 * b.len());
    let (mut i, mut j) = (0, 0);
    let mut inside = false;
    let mut enter = None;
    while i < a_end || j < b_end {
        let next = |list, k, end| {
            if k < end {
                boundary(list, k).t
            } else {
                f32::INFINITY
            }
        };
        let t = next(a, i, a_end).min(next(b, j, b_end));
        let mut first = None;
        while i < a_end && boundary(a, i).t <= t {
            first.get_or_insert(boundary(a, i));
            i += 1;
        }
        while j < b_end && boundary(b, j).t <= t {
            first.get_or_insert(boundary(b, j));
            j += 1;
        }
        // Boundaries alternate enter, exit: an odd count passed means inside.
        let now = operation.contains(i % 2 == 1, j % 2 == 1);
        if now != inside {
            inside = now;
            let here = first.expect("at least one boundary is passed at each step");
            match enter.take() {
                None => enter = Some(here),
                Some(enter) => out.push(Span { enter, exit: here }),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spans(list: &[(f32, f32)], leaf: u32) -> Vec<Span> {
        list.iter()
            .map(|&(t0, t1)| Span {
                enter: Boundary { t: t0, part: leaf },
                exit: Boundary { t: t1, part: leaf },
            })
            .collect()
    }

    fn combined(operation: CsgOperation, a: &[(f32, f32)], b: &[(f32, f32)]) -> Vec<(f32, f32)> {
        let mut out = Spans::new();
        combine(operation, &spans(a, 0), &spans(b, 1), &mut out);
        out.iter().map(|s| (s.enter.t, s.exit.t)).collect()
    }

    #[test]
    fn combines_spans_by_each_operation() {
        let a = [(0.0, 2.0), (5.0, 7.0)];
        let b = [(1.0, 6.0)];
        assert_eq!(combined(CsgOperation::Union, &a, &b), [(0.0, 7.0)]);
        assert_eq!(
            combined(CsgOperation::Intersection, &a, &b),
            [(1.0, 2.0), (5.0, 6.0)]
        );
        assert_eq!(
            combined(CsgOperation::Difference, &a, &b),
            [(0.0, 1.0), (6.0, 7.0)]
        );
        assert_eq!(combined(CsgOperation::Difference, &b, &a), [(2.0, 5.0)]);
    }

    #[test]
    fn touching_solids_leave_no_surface_between_them() {
        let a = [(0.0, 1.0)];
        let b = [(1.0, 2.0)];
        assert_eq!(combined(CsgOperation::Union, &a, &b), [(0.0, 2.0)]);
        assert_eq!(combined(CsgOperation::Intersection, &a, &b), []);
        assert_eq!(combined(CsgOperation::Difference, &a, &b), [(0.0, 1.0)]);
    }

    #[test]
    fn half_spaces_reach_infinitely_far() {
        let inf = f32::INFINITY;
        let behind = [(-inf, 3.0)];
        let a = [(1.0, 5.0)];
        assert_eq!(combined(CsgOperation::Union, &a, &behind), [(-inf, 5.0)]);
        assert_eq!(
            combined(CsgOperation::Intersection, &a, &behind),
            [(1.0, 3.0)]
        );
        assert_eq!(
            combined(CsgOperation::Difference, &a, &behind),
            [(3.0, 5.0)]
        );
    }

    #[test]
    fn the_boundary_keeps_the_part_it_came_from() {
        let mut out = Spans::new();
        combine(
            CsgOperation::Difference,
            &spans(&[(0.0, 4.0)], 7),
            &spans(&[(1.0, 2.0)], 9),
            &mut out,
        );
        let parts: Vec<(u32, u32)> = out.iter().map(|s| (s.enter.part, s.exit.part)).collect();
        assert_eq!(parts, [(7, 9), (9, 7)]);
    }
}
