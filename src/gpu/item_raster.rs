//! The raster pass that draws the item buffer ([`crate::item_buffer`]) on the GPU
//! (`shaders/item_buffer.wgsl`): the mesh triangles as themselves, every object as a proxy that
//! covers it ([`proxies`]), each fragment intersecting the exact primitive along its pixel's eye
//! ray, the depth test keeping the nearest; then the buffer read back to the CPU.

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use wgpu::util::DeviceExt;

use super::device::{GpuDevice, read_buffer};
use super::scene::{GpuScene, GpuView, storage_entry_in};
use super::tracer::tracer_wgsl;
use crate::camera::Camera;
use crate::item_buffer::{Item, ItemBuffer};
use crate::primitive::{Geometry, PrimId};
use crate::render::Assembled;
use crate::scene::Scene;

/// WGSL's `Proxy`: an object's bounding box, or the whole film (`full_film` 1) for an object
/// without finite bounds.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuProxy {
    pub lo: [f32; 3],
    pub object: u32,
    pub hi: [f32; 3],
    pub full_film: u32,
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

/// The proxy of every object of `geometry` seen from `eye`: its bounding box grown by
/// [`PROXY_MARGIN`], or the whole film where it has no finite bounds.
pub fn proxies(geometry: &Geometry, eye: Vec3) -> Vec<GpuProxy> {
    (0..geometry.objects.len())
        .map(|o| {
            let object = o as u32;
            match geometry.bounds(PrimId::object(o)).filter(|b| b.is_finite()) {
                Some(b) => {
                    let reach = eye.distance(b.center()) + 0.5 * b.extent().length();
                    let margin = Vec3::splat(PROXY_MARGIN * reach);
                    GpuProxy {
                        lo: (b.min - margin).to_array(),
                        object,
                        hi: (b.max + margin).to_array(),
                        full_film: 0,
                    }
                }
                None => GpuProxy {
                    lo: [0.0; 3],
                    object,
                    hi: [0.0; 3],
                    full_film: 1,
                },
            }
        })
        .collect()
}

/// A scene on a GPU with the item buffer's pipelines compiled for it: what draws its item
/// buffers, camera after camera.
pub struct ItemRaster {
    gpu: Arc<GpuDevice>,
    gpu_scene: GpuScene,
    proxy: wgpu::RenderPipeline,
    triangle: wgpu::RenderPipeline,
    film_layout: wgpu::BindGroupLayout,
}

/// The item buffer's texel: the primitive, the bits of `t`, the part, the triangle's slot.
const ITEM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Bytes of one texel of [`ITEM_FORMAT`].
const ITEM_BYTES: u32 = 16;
/// The primitive of a pixel nothing was drawn on.
const NO_ITEM: u32 = u32::MAX;

/// Where the raster pass's stages see the scene and the film.
const STAGES: wgpu::ShaderStages = wgpu::ShaderStages::VERTEX_FRAGMENT;

impl ItemRaster {
    /// Uploads `assembled`'s scene to `gpu` and compiles the raster pass for it (the WGSL is the
    /// tracer's, with the raster's entry points); the error says what of the scene the GPU does
    /// not hold.
    pub fn new(gpu: Arc<GpuDevice>, assembled: &Assembled) -> Result<ItemRaster, String> {
        let gpu_scene = GpuScene::upload(&gpu, assembled)?;
        let device = &gpu.device;
        let source =
            tracer_wgsl(gpu_scene.node_layout) + include_str!("../../shaders/item_buffer.wgsl");
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("the item buffer"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let film_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("the item buffer's proxies and film"),
            entries: &[
                storage_entry_in(2, true, STAGES),
                storage_entry_in(3, true, STAGES),
            ],
        });
        let scene_layout = super::scene::scene_layout(device, STAGES);
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
        let (proxy, triangle) = (
            pipeline("proxy_corner", "proxy_item"),
            pipeline("triangle_corner", "triangle_item"),
        );
        Ok(ItemRaster {
            gpu,
            gpu_scene,
            proxy,
            triangle,
            film_layout,
        })
    }

    /// Draws the item buffer of `scene` (the one uploaded, its settings and materials perhaps
    /// edited since) seen by `camera`, for a film of `size` at `origin` of the image, and reads
    /// it back. The error says what does not fit the GPU: how much it needs, and how much the GPU
    /// allows.
    pub fn draw(
        &self,
        scene: &Scene,
        camera: &Camera,
        (origin, size): ((u32, u32), (u32, u32)),
    ) -> Result<ItemBuffer, String> {
        let (gpu, gpu_scene) = (&*self.gpu, &self.gpu_scene);
        let device = &gpu.device;
        let (width, height) = size;
        let limits = device.limits();
        let side = limits.max_texture_dimension_2d;
        if width > side || height > side {
            return Err(format!(
                "the item buffer of a {width}×{height} film does not fit this GPU, whose images are \
                 at most {side}×{side} pixels"
            ));
        }
        let row_bytes = (width * ITEM_BYTES).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let read_bytes = u64::from(row_bytes) * u64::from(height);
        if read_bytes > limits.max_buffer_size {
            return Err(format!(
                "the item buffer of a {width}×{height} film needs {read_bytes} bytes to read \
                 back; this GPU allows {} in one buffer",
                limits.max_buffer_size
            ));
        }
        let objects = proxies(&scene.geometry, camera.eye);
        gpu.check_storage(
            "the item buffer's proxies",
            std::mem::size_of_val(objects.as_slice()) as u64,
        )?;
        let triangle_corners = u32::try_from(gpu_scene.triangle_count() * 3)
            .map_err(|_| "the item buffer draws at most 2³² triangle corners".to_string())?;
        gpu_scene.update(gpu, scene, camera, GpuView::Shaded, origin)?;

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
                    binding: 2,
                    resource: buffer("the proxies", proxy_bytes).as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: buffer("the raster's film", bytemuck::bytes_of(&film))
                        .as_entire_binding(),
                },
            ],
        });
        let (_, scene_group) = gpu_scene.bind_group_in(device, STAGES);
        let read_back = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("the item buffer read back"),
            size: read_bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
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
                buffer: &read_back,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: Some(height),
                },
            },
            extent,
        );
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_buffer(device, &read_back)?;
        let texels: Vec<[u32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        let row_texels = (row_bytes / ITEM_BYTES) as usize;
        let decoded = texels
            .chunks(row_texels)
            .flat_map(|row| &row[..width as usize])
            .map(|&[prim, t, part, _slot]| {
                (prim != NO_ITEM).then(|| Item {
                    prim: PrimId(prim),
                    part,
                    t: f32::from_bits(t),
                })
            })
            .collect();
        let image_size = (scene.settings.width, scene.settings.height);
        Ok(ItemBuffer::new(image_size, origin, size, decoded))
    }
}
