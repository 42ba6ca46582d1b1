//! The film on the GPU: the twin of [`Film`] (each pixel's mean colour and sample count) in a
//! storage buffer, into which the GPU puts the colours the tracer gave a list of samples and
//! counts their rays, without the colours leaving the GPU ([`GpuFilm`]); read back into a
//! [`Film`] once a pass; and shown: rows of it made the display's bytes on the GPU and copied
//! into a texture on the same device ([`FilmShow`]), as [`Tone::map`] makes them on the CPU.
//! The WGSL is `shaders/film.wgsl`.

use super::record::gpu_record;
use std::ops::Range;
use std::sync::Arc;

use bytemuck::Zeroable;
use wgpu::util::DeviceExt;

use super::device::{ComputeEntry, GpuDevice, read_buffer};
use super::prelude::{FilmBinding, WORKGROUP, prelude};
use super::tracer::{PixelSample, SampleColor, WorkList, upload_list};
use crate::color::{Color, SrgbEncoder};
use crate::film::Film;
use crate::stats::RayCounts;
use crate::tone::Tone;

/// The film's WGSL, as one module: the prelude, the sample lists' records and the film's entry
/// points.
pub fn film_wgsl() -> String {
    prelude() + include_str!("../../shaders/samples.wgsl") + include_str!("../../shaders/film.wgsl")
}

gpu_record! {
    /// WGSL's `FilmPixel`: [`Film::get`] and [`Film::samples`] of a pixel.
    pub struct FilmPixel {
        pub color: [f32; 3],
        pub samples: u32,
    }
}

gpu_record! {
    /// WGSL's `FilmPass`: the film's size and the block side of the pass its samples belong to.
    #[derive(Eq)]
    pub struct FilmPass {
        pub width: u32,
        pub height: u32,
        pub step: u32,
        pub pad: u32,
    }
}

gpu_record! {
    /// WGSL's `Tally`: the rays of the samples of a list put into the film, and how many samples
    /// the driver cut short (not put in).
    #[derive(Default, Eq)]
    pub struct Tally {
        pub primary: u32,
        pub primary_hits: u32,
        pub shadow: u32,
        pub reflected: u32,
        pub transmitted: u32,
        pub over_budget: u32,
        pub cut_short: u32,
        pub from_item_buffer: u32,
    }
}

impl Tally {
    /// The rays counted, as the CPU counts them.
    pub fn counts(&self) -> RayCounts {
        RayCounts {
            primary: self.primary.into(),
            primary_hits: self.primary_hits.into(),
            shadow: self.shadow.into(),
            reflected: self.reflected.into(),
            transmitted: self.transmitted.into(),
            over_budget: self.over_budget.into(),
            from_item_buffer: self.from_item_buffer.into(),
        }
    }
}

gpu_record! {
    /// WGSL's `ShowRows`: which rows of the film to show, through which exposure factor and curve.
    pub struct ShowRows {
        pub width: u32,
        pub first_row: u32,
        pub rows: u32,
        pub row_texels: u32,
        pub scale: f32,
        pub curve: u32,
        pub pad0: u32,
        pub pad1: u32,
    }
}

/// The pipeline of entry point `entry` of the film's WGSL on `gpu`, compiled once per device;
/// its bind group 0 is the layout wgpu derives from what the entry uses.
fn film_pipeline(gpu: &GpuDevice, entry: &'static str) -> Arc<ComputeEntry> {
    gpu.pipeline(("film", entry), |device| {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("the film"),
            source: wgpu::ShaderSource::Wgsl(film_wgsl().into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        let work = pipeline.get_bind_group_layout(0);
        ComputeEntry { pipeline, work }
    })
}

/// A buffer binding of a bind group.
fn binding(binding: FilmBinding, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding: binding as u32,
        resource: buffer.as_entire_binding(),
    }
}

/// A `width × height` film on the GPU, all pixels black with no samples at first.
pub struct GpuFilm {
    width: u32,
    height: u32,
    pixels: wgpu::Buffer,
    film_pass: wgpu::Buffer,
    tally: wgpu::Buffer,
    add: Arc<ComputeEntry>,
}

impl std::fmt::Debug for GpuFilm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "GpuFilm({} × {})", self.width, self.height)
    }
}

impl GpuFilm {
    /// A film of `film`'s size on `gpu`; the error says if it does not fit.
    pub fn new(gpu: &GpuDevice, film: &Film) -> Result<GpuFilm, String> {
        let (width, height) = (film.width(), film.height());
        let bytes = u64::from(width) * u64::from(height) * size_of::<FilmPixel>() as u64;
        gpu.check_storage("the film's pixels", bytes.max(1))?;
        let device = &gpu.device;
        let buffer = |label, size, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as Use;
        Ok(GpuFilm {
            width,
            height,
            pixels: buffer("film pixels", bytes.max(16), Use::STORAGE | Use::COPY_SRC),
            film_pass: buffer(
                "film pass",
                size_of::<FilmPass>() as u64,
                Use::STORAGE | Use::COPY_DST,
            ),
            tally: buffer(
                "sample tally",
                size_of::<Tally>() as u64,
                Use::STORAGE | Use::COPY_SRC | Use::COPY_DST,
            ),
            add: film_pipeline(gpu, "add_samples"),
        })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Puts the colours `list` holds for its samples (of a pass of block side `step`) into the
    /// film, after the work `encoder` holds (the tracing of them), and submits it all. Returns
    /// the rays of the samples put in, and the places in the list of those the driver cut short.
    pub fn add(
        &self,
        gpu: &GpuDevice,
        mut encoder: wgpu::CommandEncoder,
        list: &WorkList,
        step: u32,
    ) -> Result<(Tally, Vec<u32>), String> {
        let device = &gpu.device;
        let film_pass = FilmPass {
            width: self.width,
            height: self.height,
            step,
            pad: 0,
        };
        gpu.queue
            .write_buffer(&self.film_pass, 0, bytemuck::bytes_of(&film_pass));
        gpu.queue
            .write_buffer(&self.tally, 0, bytemuck::bytes_of(&Tally::default()));
        let cut_bytes = (list.len * size_of::<u32>()) as u64;
        let cut = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("samples cut short"),
            size: cut_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("film samples"),
            layout: &self.add.work,
            entries: &[
                binding(FilmBinding::Samples, &list.input),
                binding(FilmBinding::Colors, &list.output),
                binding(FilmBinding::Pixels, &self.pixels),
                binding(FilmBinding::Tally, &self.tally),
                binding(FilmBinding::Cut, &cut),
                binding(FilmBinding::FilmPass, &self.film_pass),
            ],
        });
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.add.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups((list.len as u32).div_ceil(WORKGROUP), 1, 1);
        }
        let tally_bytes = size_of::<Tally>() as u64;
        let tally_read = read_back_buffer(device, tally_bytes);
        encoder.copy_buffer_to_buffer(&self.tally, 0, &tally_read, 0, tally_bytes);
        gpu.queue.submit([encoder.finish()]);
        let tally: Tally = bytemuck::pod_read_unaligned(&read_buffer(device, &tally_read)?);
        if tally.cut_short == 0 {
            return Ok((tally, Vec::new()));
        }
        let bytes = u64::from(tally.cut_short) * size_of::<u32>() as u64;
        let cut_read = read_back_buffer(device, bytes);
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&cut, 0, &cut_read, 0, bytes);
        gpu.queue.submit([encoder.finish()]);
        Ok((
            tally,
            bytemuck::pod_collect_to_vec(&read_buffer(device, &cut_read)?),
        ))
    }

    /// Puts `colors`, of `samples` (of a pass of block side `step`), into the film: colours
    /// made elsewhere, such as the CPU's for the samples the GPU's driver cut short.
    pub fn put(
        &self,
        gpu: &GpuDevice,
        samples: &[PixelSample],
        colors: &[Color],
        step: u32,
    ) -> Result<(), String> {
        if samples.is_empty() {
            return Ok(());
        }
        let colors: Vec<SampleColor> = colors
            .iter()
            .map(|c| SampleColor {
                color: c.to_array(),
                ..SampleColor::zeroed()
            })
            .collect();
        let list = upload_list(gpu, samples, size_of_val(colors.as_slice()) as u64)?;
        gpu.queue
            .write_buffer(&list.output, 0, bytemuck::cast_slice(&colors));
        let encoder = gpu.device.create_command_encoder(&Default::default());
        self.add(gpu, encoder, &list, step).map(|_| ())
    }

    /// Copies the film's pixels, colours and sample counts, into `film` (of the same size).
    pub fn read_into(&self, gpu: &GpuDevice, film: &Film) -> Result<(), String> {
        let device = &gpu.device;
        let bytes = self.pixels.size();
        let read = read_back_buffer(device, bytes);
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.pixels, 0, &read, 0, bytes);
        gpu.queue.submit([encoder.finish()]);
        let pixels: Vec<FilmPixel> = bytemuck::pod_collect_to_vec(&read_buffer(device, &read)?);
        let width = self.width.max(1) as usize;
        for (i, p) in pixels
            .iter()
            .take(self.width as usize * self.height as usize)
            .enumerate()
        {
            let (x, y) = ((i % width) as u32, (i / width) as u32);
            film.put(x, y, Color::from_array(p.color), p.samples);
        }
        Ok(())
    }
}

/// A buffer of `bytes` to copy into and read back.
fn read_back_buffer(device: &wgpu::Device, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read back"),
        size: bytes,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    })
}

/// Shows films of the GPU in textures of the same device: rows of a film made the bytes the
/// display shows (red, green, blue, alpha; the format `Rgba8Unorm`), as [`Tone::map`] makes them.
pub struct FilmShow {
    entry: Arc<ComputeEntry>,
    /// [`SrgbEncoder`]'s table, each bucket its byte and its step's bits.
    table: wgpu::Buffer,
    rows: wgpu::Buffer,
    /// The texels of the last film shown, rows of a multiple of 256 bytes, and its size.
    texels: Option<(wgpu::Buffer, (u32, u32))>,
}

/// Texels in a row of [`FilmShow`]'s buffer: a copy into a texture takes rows of a multiple of
/// 256 bytes.
fn row_texels(width: u32) -> u32 {
    width.div_ceil(64) * 64
}

impl FilmShow {
    pub fn new(gpu: &GpuDevice) -> FilmShow {
        let table: Vec<[u32; 2]> = SrgbEncoder::shared()
            .buckets()
            .iter()
            .map(|&(byte, step)| [byte.into(), step.to_bits()])
            .collect();
        let device = &gpu.device;
        FilmShow {
            entry: film_pipeline(gpu, "show_rows"),
            table: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sRGB table"),
                contents: bytemuck::cast_slice(&table),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            rows: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("rows shown"),
                size: size_of::<ShowRows>() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            texels: None,
        }
    }

    /// Makes `rows` of `film` the bytes shown through `tone` and copies them into the same rows
    /// of `texture` (of the film's size, format `Rgba8Unorm`), on the GPU.
    pub fn show(
        &mut self,
        gpu: &GpuDevice,
        film: &GpuFilm,
        tone: Tone,
        rows: Range<u32>,
        texture: &wgpu::Texture,
    ) {
        let rows = rows.start.min(film.height)..rows.end.min(film.height);
        if rows.is_empty() || film.width == 0 {
            return;
        }
        let device = &gpu.device;
        let size = (film.width, film.height);
        let row_texels = row_texels(film.width);
        let texels = match &self.texels {
            Some((buffer, made_for)) if *made_for == size => buffer,
            _ => {
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("texels shown"),
                    size: u64::from(row_texels) * u64::from(film.height) * 4,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                });
                &self.texels.insert((buffer, size)).0
            }
        };
        let show = ShowRows {
            width: film.width,
            first_row: rows.start,
            rows: rows.len() as u32,
            row_texels,
            scale: tone.scale(),
            curve: tone.curve as u32,
            pad0: 0,
            pad1: 0,
        };
        gpu.queue
            .write_buffer(&self.rows, 0, bytemuck::bytes_of(&show));
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("film shown"),
            layout: &self.entry.work,
            entries: &[
                binding(FilmBinding::Pixels, &film.pixels),
                binding(FilmBinding::Texels, texels),
                binding(FilmBinding::SrgbTable, &self.table),
                binding(FilmBinding::Show, &self.rows),
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.entry.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(film.width.div_ceil(WORKGROUP), show.rows, 1);
        }
        let row_bytes = row_texels * 4;
        encoder.copy_buffer_to_texture(
            wgpu::TexelCopyBufferInfo {
                buffer: texels,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: u64::from(rows.start) * u64::from(row_bytes),
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: Some(show.rows),
                },
            },
            wgpu::TexelCopyTextureInfo {
                origin: wgpu::Origin3d {
                    x: 0,
                    y: rows.start,
                    z: 0,
                },
                ..texture.as_image_copy()
            },
            wgpu::Extent3d {
                width: film.width,
                height: show.rows,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit([encoder.finish()]);
    }
}
