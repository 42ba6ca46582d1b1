//! A GPU for computing, without any window: the adapter `WGPU_BACKEND` and `WGPU_ADAPTER_NAME`
//! choose (as wgpu reads them), or the best one there is, and its device opened with every limit
//! the adapter offers; the compute pipelines compiled for it; and reading back what the GPU
//! wrote.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use crate::memory::Bytes;

/// An adapter, its device and queue, and the compute pipelines compiled for it.
pub struct GpuDevice {
    /// The instance the adapter came from: a window's surface on it may show what the GPU made.
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// The pipelines compiled so far, by module and entry point: each is compiled once, when
    /// first asked for ([`Self::pipeline`]), as a software GPU takes a minute or more.
    pipelines: Mutex<HashMap<(&'static str, &'static str), Arc<ComputeEntry>>>,
}

/// A compiled compute entry point and the layout of the lists it reads and writes.
pub struct ComputeEntry {
    pub pipeline: wgpu::ComputePipeline,
    pub work: wgpu::BindGroupLayout,
}

/// What to install where no adapter is found.
pub const INSTALL_HINT: &str = "without a GPU, install Mesa's software Vulkan (Debian: \
                                apt-get install mesa-vulkan-drivers libvulkan1)";

impl GpuDevice {
    /// Opens the GPU with every limit its adapter offers; the error says what was looked for and
    /// what to install.
    pub fn new() -> Result<GpuDevice, String> {
        GpuDevice::with_limits(|offered| offered)
    }

    /// [`Self::new`], with the limits `choose` makes of those the adapter offers (lower ones,
    /// to see what a smaller GPU refuses).
    pub fn with_limits(
        choose: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<GpuDevice, String> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        GpuDevice::open(instance, choose)
    }

    /// [`Self::new`] on `instance`: one made with a display's handle, so that a window's surface
    /// on it can show what the GPU made without copying it through the CPU.
    pub fn on_instance(instance: wgpu::Instance) -> Result<GpuDevice, String> {
        GpuDevice::open(instance, |offered| offered)
    }

    fn open(
        instance: wgpu::Instance,
        choose: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<GpuDevice, String> {
        pollster::block_on(async {
            let adapter = pick_adapter(&instance).await?;
            let (device, queue) = adapter
                .request_device(&wgpu::DeviceDescriptor {
                    label: Some("raylab compute"),
                    required_limits: choose(adapter.limits()),
                    ..Default::default()
                })
                .await
                .map_err(|e| format!("cannot open the GPU device: {e}"))?;
            Ok(GpuDevice {
                instance,
                adapter,
                device,
                queue,
                pipelines: Mutex::default(),
            })
        })
    }

    /// The adapter's name and backend, as `raylab` names the device it traces on.
    pub fn name(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({})", info.name, info.backend)
    }

    /// The pipeline `entry` (a module's name and an entry point's), made by `compile` the first
    /// time it is asked for on this device and kept.
    pub fn pipeline(
        &self,
        entry: (&'static str, &'static str),
        compile: impl FnOnce(&wgpu::Device) -> ComputeEntry,
    ) -> Arc<ComputeEntry> {
        let mut compiled = self
            .pipelines
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let entry_pipeline = compiled
            .entry(entry)
            .or_insert_with(|| Arc::new(compile(&self.device)));
        Arc::clone(entry_pipeline)
    }

    /// Checks that a storage buffer of `bytes` for `what` fits the device's limits; the error
    /// says how much it needs and how much the GPU allows, and to trace on the CPU instead.
    pub fn check_storage(&self, what: &str, bytes: u64) -> Result<(), String> {
        let limits = self.device.limits();
        let allowed = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        if bytes <= allowed {
            Ok(())
        } else {
            Err(format!(
                "{what} need {} on the GPU, which allows {} in one buffer: the scene is too \
                 large for this GPU, use --device cpu",
                Bytes(bytes),
                Bytes(allowed)
            ))
        }
    }

    /// Whether the adapter is a GPU emulated on the processor (Mesa's lavapipe, llvmpipe), which
    /// compiles the tracer for a minute or more.
    pub fn is_software(&self) -> bool {
        self.adapter.get_info().device_type == wgpu::DeviceType::Cpu
    }
}

/// The adapter whose name contains `WGPU_ADAPTER_NAME` (in any case), if that is set; otherwise
/// the one wgpu prefers (`WGPU_POWER_PREF` may say which). The error names what was looked for
/// and what there is, or what to install.
async fn pick_adapter(instance: &wgpu::Instance) -> Result<wgpu::Adapter, String> {
    let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") else {
        return instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::from_env().unwrap_or_default(),
                ..Default::default()
            })
            .await
            .map_err(|e| format!("no GPU adapter found ({e}); {INSTALL_HINT}"));
    };
    let adapters = instance.enumerate_adapters(wgpu::Backends::all()).await;
    let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
    adapters
        .into_iter()
        .find(|a| {
            a.get_info()
                .name
                .to_lowercase()
                .contains(&wanted.to_lowercase())
        })
        .ok_or_else(|| {
            format!(
                "no GPU adapter named like WGPU_ADAPTER_NAME={wanted:?}; there are: {}",
                if names.is_empty() {
                    format!("none ({INSTALL_HINT})")
                } else {
                    names.join(", ")
                }
            )
        })
}

/// The bytes of a buffer made with `MAP_READ`, once the GPU has finished writing it (waits for
/// the work submitted so far).
pub fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, String> {
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("the GPU did not finish: {e}"))?;
    receiver
        .recv()
        .map_err(|e| format!("the read-back never finished: {e}"))?
        .map_err(|e| format!("cannot map the read-back buffer: {e}"))?;
    let mapped = slice
        .get_mapped_range()
        .map_err(|e| format!("cannot read the read-back buffer: {e}"))?;
    let bytes = mapped.to_vec();
    drop(mapped);
    buffer.unmap();
    Ok(bytes)
}
