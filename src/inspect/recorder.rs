//! The inspector: traces one pixel's eye ray with the renderer's own code and an observer that
//! records every event as a [`RayTree`]; and the object each pixel's eye ray sees.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::ray_tree::{
    Blocker, Cut, FirstHitSource, LightShare, NodeFog, NodeHit, RayNode, RayTree, ShadowRay,
};
use crate::bvh::cost::TraversalCost;
use crate::camera::PIXEL_CENTRE;
use crate::color::Color;
use crate::item_buffer::{Item, far_limit};
use crate::primitive::{Hit, SurfacePoint};
use crate::ray::Ray;
use crate::scene::Scene;
use crate::stats::RayCounts;
use crate::whitted::{
    EYE_RAY_T_MIN, LightTerms, LocalTerms, RayKind, ShadowEvent, StopReason, Tracer, TreeObserver,
};

/// The ray tree of pixel (x, y) of the scene's `width × height` image (y from the top): the
/// eye ray through the pixel's centre, as the first pass of [`crate::progressive::render`]
/// traces it, so `tree.color` is the rendered pixel at one sample per pixel. A pixel outside
/// the image is clamped to its edge.
///
/// ```
/// use raylab::bvh::Bvh;
/// use raylab::formats::load_any;
/// use raylab::inspect::trace_ray_tree;
/// use raylab::whitted::{RayKind, Tracer};
///
/// let scene = load_any("assets/scenes/glass.toml")?;
/// let bvh = Bvh::build(&scene.geometry);
/// let tree = trace_ray_tree(&Tracer::new(&scene, &bvh), 320, 240); // the middle pixel
///
/// // The root is the eye ray; through the glass ball the tree grows transmitted rays.
/// assert_eq!(tree.nodes[0].kind, RayKind::Eye);
/// assert!(tree.nodes.iter().any(|node| node.kind == RayKind::Transmitted));
/// println!("{}", tree.to_text());
/// # Ok::<(), raylab::formats::SceneError>(())
/// ```
pub fn trace_ray_tree(tracer: &Tracer, x: u32, y: u32) -> RayTree {
    let settings = &tracer.scene.settings;
    let (x, y) = (
        x.min(settings.width.saturating_sub(1)),
        y.min(settings.height.saturating_sub(1)),
    );
    let mut recorder = Recorder {
        scene: tracer.scene,
        nodes: Vec::new(),
        open: Vec::new(),
    };
    let ray = eye_ray(tracer, x, y);
    let color = tracer.trace_eye_observed(&ray, &mut RayCounts::default(), &mut recorder);
    RayTree {
        pixel: (x, y),
        nodes: recorder.nodes,
        color,
        first_hit: tracer
            .item_buffer
            .map(|items| first_hit_source(tracer, items.at(x, y), &ray)),
    }
}

/// Where the first hit of the eye ray `ray`, whose pixel's item is `item`, comes from: the
/// renderer's own search ([`crate::whitted::Tracer::first_hits`]).
fn first_hit_source(tracer: &Tracer, item: Option<Item>, ray: &Ray) -> FirstHitSource {
    let geometry = &tracer.scene.geometry;
    let Some(item) = item.filter(|item| geometry.contains(item.prim)) else {
        return FirstHitSource::NoItem;
    };
    let named = Hit {
        t: item.t,
        prim: item.prim,
        part: item.part,
        bary: Vec2::ZERO,
    };
    let label = geometry.hit_label(&named);
    let limit = far_limit(geometry, Some(item), ray, EYE_RAY_T_MIN);
    let found = limit
        .is_finite()
        .then(|| tracer.bvh.closest_hit(geometry, ray, EYE_RAY_T_MIN, limit));
    match found.flatten() {
        Some(hit) => FirstHitSource::ItemBuffer {
            item: label,
            t: hit.t,
        },
        None => FirstHitSource::ItemMissed { item: label },
    }
}

/// The eye ray through the centre of pixel (x, y) of the scene's image, y from the top, as the
/// renderer builds it.
fn eye_ray(tracer: &Tracer, x: u32, y: u32) -> Ray {
    let settings = &tracer.scene.settings;
    let size = (settings.width, settings.height);
    tracer.scene.camera.eye_ray((x, y), PIXEL_CENTRE, size)
}

/// Per pixel (row-major, top row first) the object id ([`crate::primitive::Geometry::object_id`])
/// the eye ray through its centre sees, `u32::MAX` where it sees none.
pub fn object_ids(tracer: &Tracer) -> Vec<u32> {
    let settings = &tracer.scene.settings;
    let (width, height) = (settings.width, settings.height);
    let geometry = &tracer.scene.geometry;
    (0..width * height)
        .into_par_iter()
        .map(|i| {
            let ray = eye_ray(tracer, i % width, i / width);
            tracer
                .closest_hit(&ray, EYE_RAY_T_MIN)
                .map_or(u32::MAX, |hit| geometry.object_id(hit.prim))
        })
        .collect()
}

/// Builds the tree from the tracer's events.
struct Recorder<'a> {
    scene: &'a Scene,
    nodes: Vec<RayNode>,
    /// The rays started and not yet done: the path from the eye ray to the current one.
    open: Vec<usize>,
}

impl Recorder<'_> {
    fn current(&mut self) -> &mut RayNode {
        let index = *self
            .open
            .last()
            .expect("events arrive between `ray` and `done`");
        &mut self.nodes[index]
    }
}

impl TraversalCost for Recorder<'_> {}

impl TreeObserver for Recorder<'_> {
    const RECORDS_BLOCKERS: bool = true;
    const USES_SHADOW_CACHE: bool = false;
    const RECORDS_TERMS: bool = true;
    const WANTS_UV: bool = true;

    fn ray(&mut self, kind: RayKind, depth: u32, ray: &Ray, weight: f32, scale: Color) {
        let parent = self.open.last().copied();
        let factor = parent.map_or(Color::ONE, |p| self.nodes[p].factor) * scale;
        let index = self.nodes.len();
        if let Some(p) = parent {
            self.nodes[p].children.push(index);
        }
        self.nodes.push(RayNode {
            kind,
            depth,
            origin: ray.origin,
            dir: ray.dir.normalize(),
            weight,
            factor,
            hit: None,
            shadows: Vec::new(),
            lights: Vec::new(),
            local_color: Color::ZERO,
            color: Color::ZERO,
            contribution: Color::ZERO,
            fog: None,
            caustic: None,
            stop: None,
            cuts: Vec::new(),
            children: Vec::new(),
            parent,
        });
        self.open.push(index);
    }

    fn hit(&mut self, hit: &Hit, surface: &SurfacePoint, normal: Vec3, entering: bool) {
        let scene = self.scene;
        let geometry = &scene.geometry;
        let node = self.current();
        // The reported `t` is along the unit direction, as a distance.
        let t = (surface.point - node.origin).length();
        node.hit = Some(NodeHit {
            object: geometry.object_id(hit.prim),
            label: geometry.hit_label(hit),
            material: surface.material,
            material_name: scene.material_name(surface.material),
            t,
            point: surface.point,
            normal,
            uv: surface.uv,
            entering,
            emission: Color::ZERO,
            ambient: Color::ZERO,
        });
    }

    fn miss(&mut self, background: Color) {
        let node = self.current();
        node.local_color = background;
        node.stop = Some(StopReason::Miss);
    }

    fn shadow(&mut self, shadow: ShadowEvent) {
        let geometry = &self.scene.geometry;
        let mut met = shadow.blockers.to_vec();
        met.sort_by(|a, b| a.0.t.total_cmp(&b.0.t));
        let mut passed = Color::ONE;
        let blockers = met
            .iter()
            .map(|(hit, tint)| {
                passed *= *tint;
                Blocker {
                    object: geometry.object_id(hit.prim),
                    label: geometry.hit_label(hit),
                    t: hit.t,
                    transmittance_after: passed.to_array(),
                }
            })
            .collect();
        self.current().shadows.push(ShadowRay {
            light: shadow.light,
            origin: shadow.ray.origin,
            dir: shadow.ray.dir,
            distance: shadow.distance,
            blockers,
            blocked: shadow.arrived == Color::ZERO,
            light_color: shadow.arrived,
        });
    }

    fn local_terms(&mut self, terms: LocalTerms) {
        if let Some(hit) = &mut self.current().hit {
            hit.emission = terms.emission;
            hit.ambient = terms.ambient;
        }
    }

    fn light(&mut self, terms: LightTerms) {
        self.current().lights.push(LightShare {
            light: terms.light,
            diffuse: terms.arrived * terms.diffuse,
            specular: terms.arrived * terms.specular,
            unshadowed_diffuse: terms.unshadowed * terms.diffuse,
            unshadowed_specular: terms.unshadowed * terms.specular,
        });
    }

    fn caustic(&mut self, irradiance: Color) {
        self.current().caustic = Some(irradiance);
    }

    fn local(&mut self, color: Color) {
        self.current().local_color = color;
    }

    fn stop(&mut self, reason: StopReason) {
        self.current().stop = Some(reason);
    }

    fn cut(&mut self, branch: RayKind, reason: StopReason, weight: f32) {
        self.current().cuts.push(Cut {
            branch,
            reason,
            weight,
        });
    }

    fn fog(&mut self, transmittance: f32, in_scattered: Color) {
        // The fog dims the ray's whole colour: its local colour and all its descendants' (the
        // nodes after it, since it is heard once they are done).
        let index = *self.open.last().expect("fog is heard before `done`");
        for node in &mut self.nodes[index + 1..] {
            node.factor *= transmittance;
            node.contribution *= transmittance;
        }
        self.current().fog = Some(NodeFog {
            transmittance,
            in_scattered,
        });
    }

    fn done(&mut self, color: Color) {
        let node = self.current();
        node.color = color;
        node.contribution = match node.fog {
            Some(fog) => node.factor * (fog.transmittance * node.local_color + fog.in_scattered),
            None => node.factor * node.local_color,
        };
        self.open.pop();
    }
}
