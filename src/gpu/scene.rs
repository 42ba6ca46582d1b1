//! The scene on the GPU: the records the WGSL reads (`shaders/scene.wgsl`), made from the same
//! [`Scene`] and [`Bvh`] the CPU traces, each buffer checked against the device's limits
//! before it is made, and bound as bind group 0 of every entry point.

use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::bvh::{GpuBinaryNode, GpuBvh, GpuTriangle, GpuWideNode, MAX_TREE_DEPTH, NodeLayout};
use super::caustics::{GpuPhoton, photon_records};
use super::device::GpuDevice;
use super::frame::{
    BALL_BACKDROP, CAUSTICS, CUT_OUTS, GpuFrame, GpuView, OPAQUE, REFLECTIONS, SHADOWS, TEXTURES,
    TRANSMISSION, ViewKind,
};
use super::materials::{
    GpuLight, GpuMaterial, GpuTriangleShading, GpuVertexAttributes, HAS_COLORS, HAS_NORMALS,
    HAS_UVS, MATERIAL_BITS,
};
use super::shapes::{GpuObject, ObjectTable, Word};
use super::storage::storage_entry_in;
use super::texture::{GpuTexture, TextureRecords, background_record};
use crate::aabb::Aabb;
use crate::bvh::Bvh;
use crate::camera::Camera;
use crate::material::{all_opaque, any_cut_outs};
use crate::medium::{Backdrop, Fog, Medium};
use crate::mesh::{Mesh, NO_VERTEX_COLOR};
use crate::photon_map::PhotonMap;
use crate::primitive::Geometry;
use crate::render::Assembled;
use crate::scene::Scene;

/// The records of a scene, before they go to the GPU.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneRecords {
    pub table: ObjectTable,
    pub bvh: GpuBvh,
    /// Beside [`GpuBvh::triangles`], in the same order.
    pub triangle_shading: Vec<GpuTriangleShading>,
    pub vertex_attributes: Vec<GpuVertexAttributes>,
    pub materials: Vec<GpuMaterial>,
    pub lights: Vec<GpuLight>,
    pub textures: TextureRecords,
}

impl SceneRecords {
    /// The records of `scene` and its BVH `bvh`; the error says what of the scene the GPU
    /// tracer does not trace.
    pub fn new(scene: &Scene, bvh: &Bvh) -> Result<SceneRecords, String> {
        // A walk into an instance goes down the scene's tree, then its model's, with the
        // instances of a leaf waiting on the stack.
        let model_depth = bvh.models.iter().map(Bvh::depth).max().map_or(0, |d| d + 1);
        let depth = bvh.depth() + model_depth;
        if depth > MAX_TREE_DEPTH {
            return Err(format!(
                "the BVH is {depth} levels deep with its models' trees; the GPU's walk takes at \
                 most {MAX_TREE_DEPTH}"
            ));
        }
        if scene.materials.len() > MATERIAL_BITS as usize {
            return Err(format!(
                "the scene has {} materials; the GPU tracer takes at most {MATERIAL_BITS}",
                scene.materials.len()
            ));
        }
        let geometry = &scene.geometry;
        let mut table = ObjectTable::new(&geometry.objects)?;
        let instance_transforms: Vec<u32> = (geometry.instances().iter())
            .map(|instance| table.push_transform(&instance.transform))
            .collect();
        let gpu_bvh = GpuBvh::new(bvh, geometry, &instance_transforms);
        // Each mesh's vertex attributes, where it has any, one after another: the world's
        // meshes, then each model's.
        let mut vertex_attributes = Vec::new();
        let mut attribute_starts = |meshes: &[Mesh]| -> Vec<u32> {
            let mut starts = Vec::with_capacity(meshes.len());
            for mesh in meshes {
                starts.push(vertex_attributes.len() as u32);
                if attribute_flags(mesh) != 0 {
                    vertex_attributes.extend((0..mesh.positions.len()).map(|v| {
                        let normal = mesh.normals.get(v).map_or([0.0; 3], |n| n.to_array());
                        let uv = mesh.uvs.get(v).copied().unwrap_or_default();
                        let [red, green, blue] =
                            mesh.colors.get(v).unwrap_or(&NO_VERTEX_COLOR).to_array();
                        GpuVertexAttributes {
                            normal,
                            u: uv.x,
                            v: uv.y,
                            red,
                            green,
                            blue,
                        }
                    }));
                }
            }
            starts
        };
        let world_starts = attribute_starts(&geometry.meshes);
        let model_starts: Vec<Vec<u32>> = (geometry.models().iter())
            .map(|model| attribute_starts(&model.meshes))
            .collect();
        // Each triangle slot's shading, from the mesh of the geometry its tree is over.
        let shading = |owner: &Geometry, starts: &[u32], t: &GpuTriangle| {
            let (mesh_index, face) = owner.triangle_face(t.index as usize);
            let mesh = &owner.meshes[mesh_index];
            let start = starts[mesh_index];
            GpuTriangleShading {
                corners: mesh.faces[face as usize].map(|v| start + v),
                material: mesh.material | attribute_flags(mesh),
            }
        };
        let mut triangle_shading = Vec::with_capacity(gpu_bvh.triangles.len());
        let world = &gpu_bvh.triangles[..gpu_bvh.world_triangles];
        triangle_shading.extend(world.iter().map(|t| shading(geometry, &world_starts, t)));
        for (m, model) in geometry.models().iter().enumerate() {
            let first = gpu_bvh.model_triangles[m];
            let end =
                (gpu_bvh.model_triangles.get(m + 1).copied()).unwrap_or(gpu_bvh.triangles.len());
            let triangles = &gpu_bvh.triangles[first..end];
            triangle_shading.extend(
                triangles
                    .iter()
                    .map(|t| shading(model, &model_starts[m], t)),
            );
        }
        Ok(SceneRecords {
            table,
            bvh: gpu_bvh,
            triangle_shading,
            vertex_attributes,
            materials: scene.materials.iter().map(GpuMaterial::from).collect(),
            lights: scene.lights.iter().map(GpuLight::from).collect(),
            textures: TextureRecords::new(scene)?,
        })
    }
}

/// Which vertex attributes `mesh` has, as the flags of its triangles' material words.
fn attribute_flags(mesh: &Mesh) -> u32 {
    let flag = |has: bool, flag: u32| if has { flag } else { 0 };
    flag(!mesh.normals.is_empty(), HAS_NORMALS)
        | flag(!mesh.uvs.is_empty(), HAS_UVS)
        | flag(!mesh.colors.is_empty(), HAS_COLORS)
}

/// The scene's buffers on the GPU and the bind group that binds them.
pub struct GpuScene {
    /// How the BVH's nodes are laid out: the pipelines that walk them must be compiled for it.
    pub node_layout: NodeLayout,
    pub layout: wgpu::BindGroupLayout,
    pub bind_group: wgpu::BindGroup,
    /// The frame record's buffer, rewritten when the camera or the film moves.
    pub frame: wgpu::Buffer,
    /// The materials' and the lights' buffers, rewritten as they are edited.
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    /// The storage buffers, in binding order (the caustic photons last), bound anew when the
    /// photon map changes.
    buffers: Vec<wgpu::Buffer>,
    /// The caustic photon map uploaded (none: caustics off).
    caustics: Option<Arc<PhotonMap>>,
    /// How many records some buffers hold, as the frame record tells the WGSL.
    counts: RecordCounts,
    /// The box around the bounded objects, which the fog's backdrop takes in.
    object_bounds: Option<Aabb>,
    /// Where each instance's record starts in the references.
    instance_records: Vec<u32>,
}

/// How many records the buffers the WGSL loops over hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct RecordCounts {
    refs: u32,
    triangles: usize,
    unbounded: u32,
    nodes: u32,
    lights: u32,
    objects: u32,
    materials: u32,
}

/// The bindings of bind group 0, the scene, in the order of [`GpuScene`]'s storage buffers:
/// the WGSL names them `SCENE_OBJECTS`, `SCENE_SHAPE_WORDS`, … (`super::prelude`). The frame
/// is a storage buffer too, not a uniform one: Mesa's lavapipe inlines a uniform buffer's
/// values into the shader, so that it compiled the tracer again (for minutes) for every scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::EnumIter)]
pub enum SceneBinding {
    Objects,
    ShapeWords,
    Nodes,
    Triangles,
    Refs,
    TriangleShading,
    VertexAttributes,
    Materials,
    Lights,
    Textures,
    Texels,
    Photons,
    Frame,
}

/// Storage buffers in bind group 0 before the frame's.
const STORAGE_BUFFERS: u32 = SceneBinding::Frame as u32;

impl GpuScene {
    /// Uploads `assembled`'s scene and BVH; the error says what the GPU tracer does not trace,
    /// or what does not fit the GPU: how much it needs, and how much the GPU allows.
    pub fn upload(gpu: &GpuDevice, assembled: &Assembled) -> Result<GpuScene, String> {
        GpuScene::upload_with(gpu, assembled, NodeLayout::default())
    }

    /// [`Self::upload`] with the BVH's nodes in `node_layout`.
    pub fn upload_with(
        gpu: &GpuDevice,
        assembled: &Assembled,
        node_layout: NodeLayout,
    ) -> Result<GpuScene, String> {
        let scene = &assembled.scene;
        let records = SceneRecords::new(scene, &assembled.bvh)?;
        let limits = gpu.device.limits();
        // The frame's, and in bind group 1 two more: the work's input and output.
        let needed = STORAGE_BUFFERS + 3;
        if limits.max_storage_buffers_per_shader_stage < needed {
            return Err(format!(
                "the GPU tracer needs {needed} storage buffers per shader stage; this GPU allows {}",
                limits.max_storage_buffers_per_shader_stage
            ));
        }
        let device = &gpu.device;
        let storage = |what: &str, contents: &[u8]| storage_buffer(gpu, what, contents);
        let binary;
        let (nodes, node_count, refs): (&[u8], usize, &[u32]) = match node_layout {
            NodeLayout::Wide => (
                bytemuck::cast_slice::<GpuWideNode, u8>(&records.bvh.nodes),
                records.bvh.nodes.len(),
                &records.bvh.refs,
            ),
            NodeLayout::Binary => {
                binary = records.bvh.binary_nodes();
                (
                    bytemuck::cast_slice::<GpuBinaryNode, u8>(&binary.0),
                    binary.0.len(),
                    &binary.1,
                )
            }
        };
        // Kept apart as well: edits rewrite them.
        let materials = storage("the materials", bytemuck::cast_slice(&records.materials))?;
        let lights = storage("the lights", bytemuck::cast_slice(&records.lights))?;
        let buffers = [
            storage(
                "the objects",
                bytemuck::cast_slice::<GpuObject, u8>(&records.table.objects),
            )?,
            storage(
                "the shapes",
                bytemuck::cast_slice::<Word, u8>(&records.table.words),
            )?,
            storage("the BVH nodes", nodes)?,
            storage(
                "the triangles",
                bytemuck::cast_slice::<GpuTriangle, u8>(&records.bvh.triangles),
            )?,
            storage("the BVH leaves", bytemuck::cast_slice(refs))?,
            storage(
                "the triangles' shading",
                bytemuck::cast_slice(&records.triangle_shading),
            )?,
            storage(
                "the mesh vertices",
                bytemuck::cast_slice(&records.vertex_attributes),
            )?,
            materials.clone(),
            lights.clone(),
            storage(
                "the textures",
                bytemuck::cast_slice::<GpuTexture, u8>(&records.textures.textures),
            )?,
            storage("the texels", bytemuck::cast_slice(&records.textures.texels))?,
            photons_buffer(gpu, assembled.caustics.as_deref())?,
        ];
        let counts = RecordCounts {
            refs: records.bvh.refs.len() as u32,
            triangles: records.bvh.world_triangles,
            unbounded: records.bvh.unbounded,
            nodes: node_count as u32,
            lights: records.lights.len() as u32,
            objects: records.table.objects.len() as u32,
            materials: records.materials.len() as u32,
        };
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("the frame"),
            size: std::mem::size_of::<GpuFrame>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = scene_layout(device, wgpu::ShaderStages::COMPUTE);
        let bind_group = scene_bind_group(device, &layout, &buffers, &frame);
        let gpu_scene = GpuScene {
            node_layout,
            layout,
            bind_group,
            frame,
            materials,
            lights,
            buffers: buffers.into(),
            caustics: assembled.caustics.clone(),
            counts,
            object_bounds: assembled.bvh.bounds(),
            instance_records: records.bvh.instance_records.clone(),
        };
        let record = gpu_scene.frame_record(scene, &scene.camera, GpuView::Shaded, (0, 0));
        gpu.queue
            .write_buffer(&gpu_scene.frame, 0, bytemuck::bytes_of(&record));
        Ok(gpu_scene)
    }

    /// Where each instance's record starts in the references ([`GpuBvh::instance_records`]).
    pub fn instance_records(&self) -> &[u32] {
        &self.instance_records
    }

    /// How many of the world's own mesh triangles the scene holds (the item buffer draws them;
    /// instances are drawn by proxies).
    pub fn triangle_count(&self) -> usize {
        self.counts.triangles
    }

    /// Bind group 0 for pipelines of other `stages` than compute (a raster pass's): its layout,
    /// and the same buffers bound in it. Made anew with each call: bind it before the next
    /// [`Self::set_caustics`].
    pub fn bind_group_in(
        &self,
        device: &wgpu::Device,
        stages: wgpu::ShaderStages,
    ) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
        let layout = scene_layout(device, stages);
        let bind_group = scene_bind_group(device, &layout, &self.buffers, &self.frame);
        (layout, bind_group)
    }

    /// Uploads `caustics`, the caustic photon map the scene is traced with now (none: caustics
    /// off), unless it is the one uploaded; the error says if it does not fit the GPU.
    pub fn set_caustics(
        &mut self,
        gpu: &GpuDevice,
        caustics: Option<&Arc<PhotonMap>>,
    ) -> Result<(), String> {
        let same = match (caustics, &self.caustics) {
            (Some(new), Some(old)) => Arc::ptr_eq(new, old),
            (new, old) => new.is_none() && old.is_none(),
        };
        if same {
            return Ok(());
        }
        let photons = photons_buffer(gpu, caustics.map(|map| &**map))?;
        *self
            .buffers
            .last_mut()
            .expect("the photons' buffer is bound last") = photons;
        self.bind_group = scene_bind_group(&gpu.device, &self.layout, &self.buffers, &self.frame);
        self.caustics = caustics.cloned();
        Ok(())
    }

    /// The frame record of `scene` (the one uploaded, edited) seen by `camera` in `view`, for a
    /// film at `film_origin` of the image.
    fn frame_record(
        &self,
        scene: &Scene,
        camera: &Camera,
        view: GpuView,
        film_origin: (u32, u32),
    ) -> GpuFrame {
        let counts = self.counts;
        let settings = &scene.settings;
        let flag = |on: bool, bit: u32| if on { bit } else { 0 };
        let fog = Fog::new(
            scene.atmosphere,
            self.object_bounds,
            &scene.lights,
            camera.eye,
        );
        let medium = fog.map_or(Medium::default(), |fog| fog.medium);
        let (ball, center, radius, distance) = match fog.map(|fog| fog.backdrop) {
            Some(Backdrop::Ball { center, radius }) => (true, center.to_array(), radius, 0.0),
            Some(Backdrop::Distance(distance)) => (false, [0.0; 3], 0.0, distance),
            None => (false, [0.0; 3], 0.0, 0.0),
        };
        let map = self.caustics.as_deref();
        // The box around the photons (none without a map: nothing reads it then).
        let (photons_min, photons_max) = map.map_or(([0.0; 3], [0.0; 3]), |map| {
            (map.bounds().min.to_array(), map.bounds().max.to_array())
        });
        let (depth_near, depth_far) = match view {
            GpuView::Depth { near, far } => (near, far),
            _ => (0.0, 0.0),
        };
        GpuFrame {
            eye: camera.eye.to_array(),
            near: camera.near,
            u: camera.u.to_array(),
            half_height: camera.half_height,
            v: camera.v.to_array(),
            width: settings.width,
            n: camera.n.to_array(),
            height: settings.height,
            background: settings.background.to_array(),
            max_depth: settings.max_depth,
            ambient: settings.ambient.to_array(),
            min_weight: settings.min_weight,
            flags: flag(settings.shadows, SHADOWS)
                | flag(settings.reflections, REFLECTIONS)
                | flag(settings.transmission, TRANSMISSION)
                | flag(all_opaque(&scene.materials), OPAQUE)
                | flag(any_cut_outs(&scene.materials), CUT_OUTS)
                | flag(settings.textures, TEXTURES)
                | flag(ball, BALL_BACKDROP)
                | flag(map.is_some(), CAUSTICS),
            unbounded_first: counts.refs - counts.unbounded,
            unbounded: counts.unbounded,
            node_count: counts.nodes,
            light_count: counts.lights,
            object_count: counts.objects,
            film_left: film_origin.0,
            film_top: film_origin.1,
            background_image: background_record(scene),
            fog_steps: settings.fog_steps,
            fog_albedo: medium.albedo,
            backdrop_distance: distance,
            fog_color: medium.color.to_array(),
            fog_density: medium.density,
            backdrop_center: center,
            backdrop_radius: radius,
            view: ViewKind::from(view) as u32,
            depth_near,
            depth_far,
            caustic_gather: settings.caustic_gather,
            photons_min,
            photon_count: map.map_or(0, |map| map.len() as u32),
            photons_max,
            photon_radius: map.map_or(0.0, PhotonMap::max_radius),
            photons_shot: map.map_or(0.0, |map| map.shot() as f32),
            pad0: 0,
            pad1: 0,
            pad2: 0,
        }
    }

    /// Makes the next dispatches see `scene` as it is now (its settings, materials and lights:
    /// the scene uploaded, edited) through `camera` in `view`, on a film at `film_origin` of the
    /// image.
    /// The error says if the scene's lights or materials changed in number.
    pub fn update(
        &self,
        gpu: &GpuDevice,
        scene: &Scene,
        camera: &Camera,
        view: GpuView,
        film_origin: (u32, u32),
    ) -> Result<(), String> {
        let materials: Vec<GpuMaterial> = scene.materials.iter().map(GpuMaterial::from).collect();
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::from).collect();
        if (materials.len(), lights.len())
            != (self.counts.materials as usize, self.counts.lights as usize)
        {
            return Err(format!(
                "the scene on the GPU has {} materials and {} lights, this one {} and {}: upload it again",
                self.counts.materials,
                self.counts.lights,
                materials.len(),
                lights.len()
            ));
        }
        let queue = &gpu.queue;
        let record = self.frame_record(scene, camera, view, film_origin);
        queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(&record));
        if !materials.is_empty() {
            queue.write_buffer(&self.materials, 0, bytemuck::cast_slice(&materials));
        }
        if !lights.is_empty() {
            queue.write_buffer(&self.lights, 0, bytemuck::cast_slice(&lights));
        }
        Ok(())
    }
}

/// A storage buffer holding `contents`, checked against the GPU's limits; never empty: an
/// unused one holds zeros (the frame's counts say so).
fn storage_buffer(gpu: &GpuDevice, what: &str, contents: &[u8]) -> Result<wgpu::Buffer, String> {
    gpu.check_storage(what, contents.len() as u64)?;
    let zeros = [0u8; 256];
    let contents = if contents.is_empty() {
        &zeros[..]
    } else {
        contents
    };
    Ok(gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(what),
            contents,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        }))
}

/// The buffer of the caustic photons of `caustics` (zeros without a map).
fn photons_buffer(gpu: &GpuDevice, caustics: Option<&PhotonMap>) -> Result<wgpu::Buffer, String> {
    let photons = caustics.map(photon_records).unwrap_or_default();
    storage_buffer(
        gpu,
        "the caustic photons",
        bytemuck::cast_slice::<GpuPhoton, u8>(&photons),
    )
}

/// Bind group 0: the storage `buffers` in binding order, then the `frame`.
fn scene_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffers: &[wgpu::Buffer],
    frame: &wgpu::Buffer,
) -> wgpu::BindGroup {
    let mut entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .enumerate()
        .map(|(binding, buffer)| wgpu::BindGroupEntry {
            binding: binding as u32,
            resource: buffer.as_entire_binding(),
        })
        .collect();
    entries.push(wgpu::BindGroupEntry {
        binding: STORAGE_BUFFERS,
        resource: frame.as_entire_binding(),
    });
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("the scene"),
        layout,
        entries: &entries,
    })
}

/// Bind group 0's layout for pipelines of `stages`: the scene's storage buffers, read only, the
/// frame's last.
pub(super) fn scene_layout(
    device: &wgpu::Device,
    stages: wgpu::ShaderStages,
) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..=STORAGE_BUFFERS)
        .map(|binding| storage_entry_in(binding, true, stages))
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("the scene"),
        entries: &entries,
    })
}
