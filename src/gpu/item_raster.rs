//! The raster pass that draws the item buffer ([`crate::item_buffer`]) on the GPU
//! (`shaders/item_buffer.wgsl`): the mesh triangles as themselves, every object as a proxy that
//! covers it ([`proxy_box`]), each fragment intersecting the exact primitive along its pixel's eye
//! ray, the depth test keeping the nearest ([`ItemRaster`]), then read back ([`GpuItems`]): for
//! the CPU tracer's eye rays ([`CpuItems`]), or to give each of the GPU tracer's pixel samples
//! its item's distance.

use super::record::gpu_record;
use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use wgpu::util::DeviceExt;

use super::bvh::NodeLayout;
use super::device::{GpuDevice, read_buffer};
use super::frame::GpuView;
use super::prelude::{PROXY_BOX, PROXY_FULL_FILM, PROXY_INSTANCE, WorkBinding};
use super::scene::{GpuScene, scene_layout};
use super::storage::storage_entry_in;
use super::tracer::tracer_wgsl;
use crate::aabb::Aabb;
use crate::item_buffer::{Item, ItemBuffer};
use crate::primitive::{Geometry, PrimId};
use crate::render::Assembled;
use crate::scene::Scene;

/// The raster pass's WGSL, which goes with the tracer's into one module.
pub const ITEM_BUFFER_WGSL: &str = include_str!("../../shaders/item_buffer.wgsl");

gpu_record! {
    /// WGSL's `Proxy`: an object's bounding box, or the whole film for an object without
    /// finite bounds, or an instance's bounding box, by its `kind` (`PROXY_BOX`, …).
    pub struct GpuProxy {
        pub lo: [f32; 3],
        /// The object's index, or where the instance's record starts in the references.
        pub object: u32,
        pub hi: [f32; 3],
        pub kind: u32,
    }
}

/// WGSL's `RasterFilm`: the film's size.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
struct RasterFilm {
    width: u32,
    height: u32,
    pad: [u32; 2],
}

/// How much a proxy box is grown on every side, as a share of its distance from the eye (about
/// a thousandth of a radian): so that the rasterizer's rounding at the box's outline never
/// leaves out a pixel whose eye ray meets an object that fills its box (a box, a polygon in a
/// plane of the axes).
pub const PROXY_MARGIN: f32 = 1e-3;

/// The proxy box of the object or instance `id` of `geometry` seen from `eye`: its bounding
/// box grown by [`PROXY_MARGIN`]; `None` where it has no finite bounds (its proxy is the whole
/// film).
pub fn proxy_box(geometry: &Geometry, id: PrimId, eye: Vec3) -> Option<Aabb> {
    let b = geometry.bounds(id).filter(|b| b.is_finite())?;
    let reach = eye.distance(b.center()) + 0.5 * b.extent().length();
    let margin = Vec3::splat(PROXY_MARGIN * reach);
    Some(Aabb::new(b.min - margin, b.max + margin))
}

/// The proxy of every object of `geometry` seen from `eye` ([`proxy_box`]), then of every
/// instance, whose record starts at `instance_records` in the references.
fn proxies(geometry: &Geometry, instance_records: &[u32], eye: Vec3) -> Vec<GpuProxy> {
    let proxy = |id: PrimId, object: u32, kind: u32| {
        let bounds = proxy_box(geometry, id, eye);
        let (lo, hi) = bounds.map_or((Vec3::ZERO, Vec3::ZERO), |b| (b.min, b.max));
        GpuProxy {
            lo: lo.to_array(),
            object,
            hi: hi.to_array(),
            kind: if bounds.is_none() {
                PROXY_FULL_FILM
            } else {
                kind
            },
        }
    };
    let objects =
        (0..geometry.objects.len()).map(|o| proxy(PrimId::object(o), o as u32, PROXY_BOX));
    let instances = (instance_records.iter().enumerate())
        .map(|(i, &record)| proxy(PrimId::instance(i), record, PROXY_INSTANCE));
    objects.chain(instances).collect()
}

/// The item buffer's pipelines, compiled for one device and BVH node layout.
pub struct ItemRaster {
    proxy: wgpu::RenderPipeline,
    triangle: wgpu::RenderPipeline,
    film_layout: wgpu::BindGroupLayout,
}

/// The item buffer's texel: the primitive, the bits of `t`, the part, a triangle's slot in the
/// BVH's leaves.
const ITEM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Bytes of one texel of [`ITEM_FORMAT`].
const ITEM_BYTES: u32 = 16;
/// The primitive of a pixel nothing was drawn on.
const NO_ITEM: u32 = u32::MAX;

/// Where the raster pass's stages see the scene and the film.
const STAGES: wgpu::ShaderStages = wgpu::ShaderStages::VERTEX_FRAGMENT;

/// An item buffer on the GPU: a film's items row by row, `stride` texels a row, as the copy
/// from the raster pass's target lays them out.
pub struct GpuItems {
    buffer: wgpu::Buffer,
    stride: u32,
    width: u32,
    height: u32,
}

impl ItemRaster {
    /// Compiles the raster pass for `gpu` and scenes uploaded with BVH nodes in `nodes` (the
    /// WGSL is the tracer's, with the raster's entry points).
    pub fn new(gpu: &GpuDevice, nodes: NodeLayout) -> ItemRaster {
        let device = &gpu.device;
        let source = tracer_wgsl(nodes) + ITEM_BUFFER_WGSL;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("the item buffer"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let film_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("the item buffer's proxies and film"),
            entries: &[
                storage_entry_in(WorkBinding::Proxies as u32, true, STAGES),
                storage_entry_in(WorkBinding::RasterFilm as u32, true, STAGES),
            ],
        });
        let scene_layout = scene_layout(device, STAGES);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("the item buffer"),
            bind_group_layouts: &[Some(&scene_layout), Some(&film_layout)],
            immediate_size: 0,
        });
        let pipeline = |vertex: &str, fragment: &str| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(fragment),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vertex),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fragment),
                    compilation_options: Default::default(),
                    targets: &[Some(ITEM_FORMAT.into())],
                }),
                // Both sides of every face: the eye may be inside a proxy box.
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    // The depth is 1/t: the nearest surface has the greatest.
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState::default(),
                multiview_mask: None,
                cache: None,
            })
        };
        ItemRaster {
            proxy: pipeline("proxy_corner", "proxy_item"),
            triangle: pipeline("triangle_corner", "triangle_item"),
            film_layout,
        }
    }

    /// Draws the item buffer of `scene` (the one `gpu_scene` holds, seen by its camera; the
    /// frame record already made for that camera and the film, which says where the film lies
    /// in the image) for a film of `size`, into a buffer on the GPU. The error says what
    /// does not fit the GPU: how much it needs, and how much the GPU allows.
    pub fn draw(
        &self,
        gpu: &GpuDevice,
        gpu_scene: &GpuScene,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<GpuItems, String> {
        let device = &gpu.device;
        let (width, height) = size;
        let side = device.limits().max_texture_dimension_2d;
        if width > side || height > side {
            return Err(format!(
                "the item buffer of a {width}×{height} film does not fit this GPU, whose images are \
                 at most {side}×{side} pixels"
            ));
        }
        let row_bytes = row_bytes(width);
        let bytes = u64::from(row_bytes) * u64::from(height);
        let most = device.limits().max_buffer_size;
        if bytes > most {
            return Err(format!(
                "the item buffer of a {width}×{height} film needs {bytes} bytes; this GPU allows \
                 {most} in one buffer"
            ));
        }
        let objects = proxies(
            &scene.geometry,
            gpu_scene.instance_records(),
            scene.camera.eye,
        );
        gpu.check_storage(
            "the item buffer's proxies",
            std::mem::size_of_val(objects.as_slice()) as u64,
        )?;
        let triangle_corners = u32::try_from(gpu_scene.triangle_count() * 3)
            .map_err(|_| "the item buffer draws at most 2³² triangle corners".to_string())?;

        let extent = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let target = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
                view_formats: &[],
            })
        };
        let items = target(
            "the item buffer",
            ITEM_FORMAT,
            wgpu::TextureUsages::COPY_SRC,
        );
        let depth = target(
            "the item buffer's depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::empty(),
        );
        let buffer = |label, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        // A buffer is never empty: without objects it holds one proxy that draws nothing.
        let proxy_bytes: &[u8] = if objects.is_empty() {
            &[0; std::mem::size_of::<GpuProxy>()]
        } else {
            bytemuck::cast_slice(&objects)
        };
        let film = RasterFilm {
            width,
            height,
            pad: [0; 2],
        };
        let film_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("the item buffer's proxies and film"),
            layout: &self.film_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: WorkBinding::Proxies as u32,
                    resource: buffer("the proxies", proxy_bytes).as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: WorkBinding::RasterFilm as u32,
                    resource: buffer("the raster's film", bytemuck::bytes_of(&film))
                        .as_entire_binding(),
                },
            ],
        });
        let (_, scene_group) = gpu_scene.bind_group_in(device, STAGES);
        let on_gpu = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("the item buffer's rows"),
            size: bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });

        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let items_view = items.create_view(&Default::default());
            let depth_view = depth.create_view(&Default::default());
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("the item buffer"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &items_view,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: f64::from(NO_ITEM),
                            g: 0.0,
                            b: 0.0,
                            a: 0.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &scene_group, &[]);
            pass.set_bind_group(1, &film_group, &[]);
            if !objects.is_empty() {
                pass.set_pipeline(&self.proxy);
                pass.draw(0..36, 0..objects.len() as u32);
            }
            if triangle_corners > 0 {
                pass.set_pipeline(&self.triangle);
                pass.draw(0..triangle_corners, 0..1);
            }
        }
        encoder.copy_texture_to_buffer(
            items.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &on_gpu,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: Some(height),
                },
            },
            extent,
        );
        gpu.queue.submit([encoder.finish()]);
        Ok(GpuItems {
            buffer: on_gpu,
            stride: row_bytes / ITEM_BYTES,
            width,
            height,
        })
    }
}

/// Bytes of a row of the item buffer of a film `width` pixels wide, as a copy from a texture lays
/// it out.
fn row_bytes(width: u32) -> u32 {
    (width * ITEM_BYTES).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
}

impl GpuItems {
    /// The items read back to the CPU, for a film at `origin` of an image of `image_size`.
    pub fn read_back(
        &self,
        gpu: &GpuDevice,
        image_size: (u32, u32),
        origin: (u32, u32),
    ) -> Result<ItemBuffer, String> {
        let device = &gpu.device;
        let size = self.buffer.size();
        let read_back = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("the item buffer read back"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.buffer, 0, &read_back, 0, size);
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_buffer(device, &read_back)?;
        let texels: Vec<[u32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        let decoded = texels
            .chunks(self.stride as usize)
            .flat_map(|row| &row[..self.width as usize])
            .map(|&[prim, t, part, _leaf]| {
                (prim != NO_ITEM).then(|| Item {
                    prim: PrimId(prim),
                    part,
                    t: f32::from_bits(t),
                })
            })
            .collect();
        let size = (self.width, self.height);
        Ok(ItemBuffer::new(image_size, origin, size, decoded))
    }
}

/// A scene uploaded to a GPU with the item buffer's raster pass compiled for it: where the CPU
/// tracer's item buffers come from, camera after camera.
pub struct CpuItems {
    gpu: Arc<GpuDevice>,
    gpu_scene: GpuScene,
    raster: ItemRaster,
}

impl CpuItems {
    /// Uploads `assembled`'s scene to `gpu` and compiles the raster pass for it; the error says
    /// what of the scene the GPU does not hold.
    pub fn new(gpu: Arc<GpuDevice>, assembled: &Assembled) -> Result<CpuItems, String> {
        let gpu_scene = GpuScene::upload(&gpu, assembled)?;
        let raster = ItemRaster::new(&gpu, gpu_scene.node_layout);
        Ok(CpuItems {
            gpu,
            gpu_scene,
            raster,
        })
    }

    /// The item buffer of `scene` (the one uploaded, its settings and materials perhaps edited
    /// since) seen by its camera, for a film of `size` at `origin` of the image, drawn and read
    /// back. The error says what does not fit the GPU.
    pub fn draw(
        &self,
        scene: &Scene,
        (origin, size): ((u32, u32), (u32, u32)),
    ) -> Result<ItemBuffer, String> {
        let (gpu, gpu_scene) = (&*self.gpu, &self.gpu_scene);
        gpu_scene.update(gpu, scene, &scene.camera, GpuView::Shaded, origin)?;
        let items = self.raster.draw(gpu, gpu_scene, scene, size)?;
        let image_size = (scene.settings.width, scene.settings.height);
        items.read_back(gpu, image_size, origin)
    }
}
