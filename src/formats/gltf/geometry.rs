//! A glTF file's geometry: each mesh's triangle primitives read into [`Mesh`]es (lists, strips
//! and fans become triangles; points and lines are refused), and the default scene's node
//! hierarchy walked into placements: which mesh, camera or light sits where in the world.

use std::borrow::Cow;

use glam::{Mat4, Vec2, Vec3};
use gltf::mesh::Mode;

use super::buffers::{COLORS, NORMALS, POSITIONS, TEX_COORDS, read_floats, read_indices};
use super::textures::UvMap;
use crate::color::Color;
use crate::mesh::Mesh;

/// How deep nodes may nest: deeper is taken for a node that is its own ancestor.
pub const MAX_NODE_DEPTH: usize = 64;
/// How many nodes the default scene may place, counting a node each time it is reached.
pub const MAX_PLACEMENTS: usize = 1 << 20;

/// The material index of a primitive that names none (glTF's default material).
pub const NO_MATERIAL: u32 = u32::MAX;

/// What the default scene places, each with its node's world matrix.
#[derive(Default)]
pub struct Placements {
    /// glTF mesh indices.
    pub meshes: Vec<(usize, Mat4)>,
    /// glTF camera indices.
    pub cameras: Vec<(usize, Mat4)>,
    /// KHR_lights_punctual light indices.
    pub lights: Vec<(usize, Mat4)>,
}

/// Walks the default scene (the first scene when none is named) from its roots, parents'
/// matrices times their children's.
pub fn placements(document: &gltf::Document) -> Result<Placements, String> {
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or("the file has no scene to show")?;
    let mut placed = Placements::default();
    let mut reached = 0usize;
    let mut stack: Vec<(gltf::Node, Mat4, usize)> =
        scene.nodes().map(|n| (n, Mat4::IDENTITY, 1)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        reached += 1;
        if reached > MAX_PLACEMENTS {
            return Err(format!(
                "the scene places more than {MAX_PLACEMENTS} nodes (the limit)"
            ));
        }
        if depth > MAX_NODE_DEPTH {
            return Err(format!(
                "node {} is nested more than {MAX_NODE_DEPTH} deep (the limit; is a node its \
                 own ancestor?)",
                node.index()
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        if !world.is_finite() {
            return Err(format!(
                "node {}'s transform is not finite numbers",
                node.index()
            ));
        }
        if let Some(mesh) = node.mesh() {
            placed.meshes.push((mesh.index(), world));
        }
        if let Some(camera) = node.camera() {
            placed.cameras.push((camera.index(), world));
        }
        if let Some(light) = node.light() {
            placed.lights.push((light.index(), world));
        }
        stack.extend(node.children().map(|child| (child, world, depth + 1)));
    }
    // The stack visits last roots first; placements keep the file's order.
    placed.meshes.reverse();
    placed.cameras.reverse();
    placed.lights.reverse();
    Ok(placed)
}

/// The triangles of one primitive as a mesh in the model's own space, its `material` the
/// glTF material index or [`NO_MATERIAL`].
///
/// A primitive in a textured material reads the texture coordinates and tint `map` gives.
pub fn primitive_mesh(
    mesh: &gltf::Mesh,
    primitive: &gltf::Primitive,
    buffers: &[Cow<[u8]>],
    map: Option<&UvMap>,
) -> Result<Mesh, String> {
    let what = format!(
        "mesh {}{} primitive {}",
        mesh.index(),
        mesh.name().map(|n| format!(" ({n})")).unwrap_or_default(),
        primitive.index()
    );
    let drawn = match primitive.mode() {
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
        Mode::Points => Some("points"),
        Mode::Lines | Mode::LineLoop | Mode::LineStrip => Some("lines"),
    };
    if let Some(drawn) = drawn {
        return Err(format!("{what} draws {drawn}; raylab draws only triangles"));
    }
    let attribute = |semantic: gltf::Semantic| primitive.get(&semantic);
    let fail = |e: String| format!("{what}: {e}");
    let positions = attribute(gltf::Semantic::Positions)
        .ok_or_else(|| fail("it has no POSITION".to_string()))?;
    let positions: Vec<Vec3> = read_floats(&positions, buffers, &POSITIONS)
        .map_err(fail)?
        .chunks_exact(3)
        .map(Vec3::from_slice)
        .collect();
    let vertex_count = positions.len();
    let per_vertex = |values: Vec<f32>, width: usize, name: &str| {
        if values.len() / width == vertex_count {
            Ok(values)
        } else {
            Err(fail(format!(
                "its {name} has {} elements for {vertex_count} positions",
                values.len() / width
            )))
        }
    };
    let normals = match attribute(gltf::Semantic::Normals) {
        Some(a) => per_vertex(
            read_floats(&a, buffers, &NORMALS).map_err(fail)?,
            3,
            "NORMAL",
        )?
        .chunks_exact(3)
        .map(Vec3::from_slice)
        .collect(),
        None => Vec::new(),
    };
    // glTF's texture space starts at the image's top left; raylab's, as OBJ's, at its bottom
    // left.
    let set = map.map_or(0, |m| m.set);
    let uvs = match attribute(gltf::Semantic::TexCoords(set)) {
        Some(a) => per_vertex(
            read_floats(&a, buffers, &TEX_COORDS).map_err(fail)?,
            2,
            "TEXCOORD",
        )?
        .chunks_exact(2)
        .map(|uv| {
            let uv = Vec2::new(uv[0], uv[1]);
            let uv = map.map_or(uv, |m| m.apply(uv));
            Vec2::new(uv.x, 1.0 - uv.y)
        })
        .collect(),
        None => Vec::new(),
    };
    let mut colors: Vec<Color> = match attribute(gltf::Semantic::Colors(0)) {
        Some(a) => {
            let width = a.dimensions().multiplicity();
            per_vertex(
                read_floats(&a, buffers, &COLORS).map_err(fail)?,
                width,
                "COLOR_0",
            )?
            .chunks_exact(width)
            .map(|c| Color::new(c[0], c[1], c[2]))
            .collect()
        }
        None => Vec::new(),
    };
    // A texture is multiplied by the base colour factor: raylab multiplies it by the vertex
    // colours.
    if let Some(tint) = map.map(|m| m.tint).filter(|&t| t != Color::ONE) {
        if colors.is_empty() {
            colors = vec![tint; vertex_count];
        } else {
            colors.iter_mut().for_each(|c| *c *= tint);
        }
    }
    let corners = match primitive.indices() {
        Some(indices) => read_indices(&indices, buffers).map_err(fail)?,
        None => (0..vertex_count as u32).collect(),
    };
    let faces = triangles(&corners, primitive.mode());
    Ok(Mesh {
        positions,
        normals,
        uvs,
        colors,
        faces,
        material: primitive
            .material()
            .index()
            .map_or(NO_MATERIAL, |i| i as u32),
    })
}

/// The triangles a primitive of `mode` draws through `corners`, in the corner order the glTF
/// specification gives (3.7.2.1): a strip's odd triangles swap their last two corners, a
/// fan's triangles turn around the first corner. Corners left over at the end are dropped.
fn triangles(corners: &[u32], mode: Mode) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => corners
            .windows(3)
            .enumerate()
            .map(|(i, w)| {
                if i % 2 == 0 {
                    [w[0], w[1], w[2]]
                } else {
                    [w[0], w[2], w[1]]
                }
            })
            .collect(),
        Mode::TriangleFan => match corners.split_first() {
            Some((&first, rest)) => rest.windows(2).map(|w| [w[0], w[1], first]).collect(),
            None => Vec::new(),
        },
        _ => corners
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_become_triangles_in_the_specifications_order() {
        let strip = triangles(&[0, 1, 2, 3, 4], Mode::TriangleStrip);
        assert_eq!(strip, vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]);
        let fan = triangles(&[0, 1, 2, 3], Mode::TriangleFan);
        assert_eq!(fan, vec![[1, 2, 0], [2, 3, 0]]);
        let list = triangles(&[0, 1, 2, 3, 4], Mode::Triangles);
        assert_eq!(list, vec![[0, 1, 2]]);
        assert!(triangles(&[], Mode::TriangleFan).is_empty());
    }
}
