//! The figure's lines in the scene, in world space: each ray of a pixel's ray tree from its
//! origin to where it ends, the normal at each hit, each shadow ray to its light or its blocker,
//! and the scene camera's image plane with the pixel's cell on it ([`RayFigure`]); and the same
//! lines as an OBJ file of polylines, one group per kind ([`RayFigure::write_obj`]).

use std::io::{self, Write};

use glam::Vec3;

use crate::camera::Camera;
use crate::inspect::RayTree;
use crate::light::Light;
use crate::scene::Scene;
use crate::whitted::RayKind;

/// What a line of the figure stands for; each kind has its colour and its OBJ group.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, strum::EnumIter)]
pub enum SegmentKind {
    Eye,
    /// A shadow ray that reaches its light.
    Shadow,
    /// A shadow ray stopped by an object before its light.
    ShadowBlocked,
    Reflected,
    Transmitted,
    /// The surface normal at a hit.
    Normal,
    /// The frame of the scene camera's image plane and the outline of the pixel's cell on it.
    ImagePlane,
}

impl SegmentKind {
    /// The line's colour, 8-bit sRGB, exactly as the figure writes it.
    pub fn color(self) -> [u8; 3] {
        match self {
            SegmentKind::Eye => [255, 255, 255],
            SegmentKind::Shadow => [255, 220, 0],
            SegmentKind::ShadowBlocked => [230, 40, 40],
            SegmentKind::Reflected => [0, 200, 255],
            SegmentKind::Transmitted => [255, 0, 200],
            SegmentKind::Normal => [0, 220, 0],
            SegmentKind::ImagePlane => [200, 200, 200],
        }
    }

    /// The kind's group in the OBJ export (`g eye`, `g shadow-blocked`, …).
    pub fn group(self) -> &'static str {
        match self {
            SegmentKind::Eye => "eye",
            SegmentKind::Shadow => "shadow",
            SegmentKind::ShadowBlocked => "shadow-blocked",
            SegmentKind::Reflected => "reflected",
            SegmentKind::Transmitted => "transmitted",
            SegmentKind::Normal => "normal",
            SegmentKind::ImagePlane => "image-plane",
        }
    }

    /// What the legend says the colour means.
    pub fn meaning(self) -> &'static str {
        match self {
            SegmentKind::Eye => "eye ray",
            SegmentKind::Shadow => "shadow ray, light reaches",
            SegmentKind::ShadowBlocked => "shadow ray, blocked",
            SegmentKind::Reflected => "reflected ray",
            SegmentKind::Transmitted => "transmitted ray",
            SegmentKind::Normal => "normal",
            SegmentKind::ImagePlane => "image plane, pixel",
        }
    }

    /// The kind of the line a traced ray is drawn as.
    pub fn of_ray(kind: RayKind) -> SegmentKind {
        match kind {
            RayKind::Eye => SegmentKind::Eye,
            RayKind::Reflected => SegmentKind::Reflected,
            RayKind::Transmitted => SegmentKind::Transmitted,
        }
    }
}

/// A line of the figure, from `from` to `to` in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub kind: SegmentKind,
    pub from: Vec3,
    pub to: Vec3,
    /// The index in [`RayTree::nodes`] of the ray it belongs to (a shadow ray or normal belongs
    /// to the ray whose hit it starts at); `None` for the image plane.
    pub node: Option<usize>,
}

/// The normal at a hit is drawn this share of the eye ray's length long (the eye ray's from the
/// eye to its hit, or the scene's reach if it missed).
const NORMAL_SHARE: f32 = 0.12;

/// A pixel's ray tree as the lecture draws it, in world space: the lines, the eye and the lights.
#[derive(Clone, Debug, PartialEq)]
pub struct RayFigure {
    pub segments: Vec<Segment>,
    /// The scene camera's eye.
    pub eye: Vec3,
    /// The lights the figure marks: point and spot lights at their positions (a directional
    /// light has none).
    pub lights: Vec<Vec3>,
    /// The image plane's corners, `N` in front of the eye: top left, top right, bottom right,
    /// bottom left, as the image is seen from the eye.
    pub image_plane: [Vec3; 4],
    /// How far a ray that leaves the scene, or a shadow ray to a directional light, is drawn:
    /// the diameter of the scene's bounding sphere.
    pub reach: f32,
}

impl RayFigure {
    /// The figure of `tree`, traced in `scene` by `camera` on a `width × height` image, up to
    /// the ray tree's generation `generations` (1: the eye ray and its shadow rays; 2 adds the
    /// first reflected and transmitted rays and theirs; …).
    pub fn new(
        tree: &RayTree,
        (scene, camera): (&Scene, &Camera),
        (width, height): (u32, u32),
        generations: u32,
    ) -> RayFigure {
        let reach = scene_reach(scene, camera);
        let mut segments = image_plane_lines(camera, tree.pixel, (width, height));
        let eye_ray_length = tree
            .nodes
            .first()
            .and_then(|eye| eye.hit.as_ref())
            .map_or(reach, |hit| hit.t);
        let normal_length = NORMAL_SHARE * eye_ray_length.min(reach);
        for (index, node) in tree.nodes.iter().enumerate() {
            if node.depth > generations {
                continue;
            }
            let line = |kind, from, to| Segment {
                kind,
                from,
                to,
                node: Some(index),
            };
            let end = node
                .hit
                .as_ref()
                .map_or(node.origin + node.dir * reach, |hit| hit.point);
            segments.push(line(SegmentKind::of_ray(node.kind), node.origin, end));
            if let Some(hit) = &node.hit {
                let tip = hit.point + hit.normal * normal_length;
                segments.push(line(SegmentKind::Normal, hit.point, tip));
            }
            for shadow in &node.shadows {
                let blocker = shadow.blockers.last().filter(|_| shadow.blocked);
                let (kind, length) = match blocker {
                    Some(blocker) => (SegmentKind::ShadowBlocked, blocker.t),
                    None if shadow.distance.is_finite() => (SegmentKind::Shadow, shadow.distance),
                    None => (SegmentKind::Shadow, reach),
                };
                segments.push(line(
                    kind,
                    shadow.origin,
                    shadow.origin + shadow.dir * length,
                ));
            }
        }
        let lights = scene
            .lights
            .iter()
            .filter_map(|light| match light {
                Light::Point { position, .. } => Some(*position),
                Light::Spot(spot) => Some(spot.position),
                Light::Directional { .. } => None,
            })
            .collect();
        RayFigure {
            segments,
            eye: camera.eye,
            lights,
            image_plane: image_plane_corners(camera, (width, height)),
            reach,
        }
    }

    /// The points the figure is about: the eye, the image plane, each ray's origin and hit, the
    /// lights and the blockers. Rays that leave the scene (and shadow rays to a directional
    /// light) run on past them.
    pub fn focus(&self) -> Vec<Vec3> {
        let ends = self.segments.iter().flat_map(|s| {
            let open = s.to.distance(s.from) >= self.reach;
            [Some(s.from), (!open).then_some(s.to)]
        });
        let points = ends.flatten().chain(self.lights.iter().copied());
        points.chain([self.eye]).collect()
    }

    /// Writes the lines as an OBJ file: a vertex (`v`) for each end and a polyline (`l`) for
    /// each line, in one group (`g`) per kind, so that the tree opens beside the scene in
    /// Blender or MeshLab. The ends are written exactly (the shortest decimals that read back
    /// as the same `f32`).
    pub fn write_obj(&self, out: &mut impl Write) -> io::Result<()> {
        use strum::IntoEnumIterator;
        writeln!(
            out,
            "# raylab: a pixel's ray tree, one group per kind of line"
        )?;
        let mut written = 0usize;
        for kind in SegmentKind::iter() {
            let lines: Vec<&Segment> = self.segments.iter().filter(|s| s.kind == kind).collect();
            if lines.is_empty() {
                continue;
            }
            writeln!(out, "g {}", kind.group())?;
            for segment in lines {
                for p in [segment.from, segment.to] {
                    writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
                }
                writeln!(out, "l {} {}", written + 1, written + 2)?;
                written += 2;
            }
        }
        Ok(())
    }
}

/// The diameter of the bounding sphere of the scene's finite objects; without any, twice the
/// distance from `camera`'s eye to its look-at point.
fn scene_reach(scene: &Scene, camera: &Camera) -> f32 {
    let bounds = scene.geometry.finite_bounds();
    let diameter = if bounds.is_finite() && !bounds.is_empty() {
        bounds.extent().length()
    } else {
        0.0
    };
    let camera = &camera.spec;
    let fallback = 2.0 * (camera.eye - camera.look_at).length();
    if diameter > 0.0 { diameter } else { fallback }
}

/// The image plane's corners: the points `eye + dir_rc` at the image's corners.
fn image_plane_corners(camera: &Camera, (width, height): (u32, u32)) -> [Vec3; 4] {
    let (w, h) = (width as f32, height as f32);
    let at = |r: f32, c: f32| camera.eye + camera.dir_rc(r, c, height, width);
    [at(h, 0.0), at(h, w), at(0.0, w), at(0.0, 0.0)]
}

/// The image plane's frame and the outline of pixel `(x, y)`'s cell on it.
fn image_plane_lines(camera: &Camera, (x, y): (u32, u32), size: (u32, u32)) -> Vec<Segment> {
    let (width, height) = size;
    let (top, bottom) = ((height - y) as f32, (height - y - 1) as f32);
    let (left, right) = (x as f32, (x + 1) as f32);
    let at = |r: f32, c: f32| camera.eye + camera.dir_rc(r, c, height, width);
    let cell = [
        at(top, left),
        at(top, right),
        at(bottom, right),
        at(bottom, left),
    ];
    let frame = image_plane_corners(camera, size);
    [frame, cell]
        .iter()
        .flat_map(|corners| {
            (0..4).map(|i| Segment {
                kind: SegmentKind::ImagePlane,
                from: corners[i],
                to: corners[(i + 1) % 4],
                node: None,
            })
        })
        .collect()
}
