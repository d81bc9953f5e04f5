//! Headless wgpu set-up: instance, adapter, device, queue and the compute
//! pipeline, created once per process ([`GpuContext::global`]) and reused.

use std::fmt;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use super::GpuError;

/// The backends this crate is compiled with (Linux: Vulkan and GL/EGL).
pub const COMPILED_BACKENDS: wgpu::Backends = wgpu::Backends::VULKAN.union(wgpu::Backends::GL);

/// What adapter was chosen, for logs and reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterSummary {
    /// Adapter name, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub name: String,
    /// Backend, e.g. `Vulkan` or `Gl`.
    pub backend: String,
    /// Device type, e.g. `Cpu` (software rasteriser) or `DiscreteGpu`.
    pub device_type: String,
    /// Driver name and version information as reported by the driver.
    pub driver: String,
    /// Whether this is a software (CPU) adapter such as lavapipe or llvmpipe.
    pub software: bool,
}

impl fmt::Display for AdapterSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} [{}, {}", self.name, self.backend, self.device_type)?;
        if !self.driver.is_empty() {
            write!(f, ", {}", self.driver)?;
        }
        write!(f, "]")
    }
}

impl AdapterSummary {
    fn from_info(info: &wgpu::AdapterInfo) -> Self {
        let driver = match (info.driver.is_empty(), info.driver_info.is_empty()) {
            (false, false) => format!("{} {}", info.driver, info.driver_info),
            (false, true) => info.driver.clone(),
            (true, _) => info.driver_info.clone(),
        };
        AdapterSummary {
            name: info.name.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver,
            software: info.device_type == wgpu::DeviceType::Cpu,
        }
    }
}

/// Instance, adapter, device, queue and pipeline. Cheap to share (`&'static`
/// via [`GpuContext::global`]); `Send + Sync`.
pub struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    /// The fused kernel (`kernel.wgsl`, [`super::RenderKernel::Fused`]).
    pub(crate) pipeline: wgpu::ComputePipeline,
    /// The two passes of `separable.wgsl` ([`super::RenderKernel::TwoPass`]): γ, then C.
    pub(crate) two_pass: [wgpu::ComputePipeline; 2],
    /// The real-time lookup pipeline (`realtime.wgsl`), built on first use.
    pub(crate) realtime: OnceLock<Result<super::realtime::Pipelines, GpuError>>,
    /// The compact representation pipeline (`compact.wgsl`), built on first use.
    pub(crate) compact: OnceLock<Result<super::compact::Pipeline, GpuError>>,
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) limits: wgpu::Limits,
    summary: AdapterSummary,
    setup_time: Duration,
    // Kept alive for the lifetime of the device.
    _adapter: wgpu::Adapter,
    _instance: wgpu::Instance,
}

impl fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.summary)
            .finish_non_exhaustive()
    }
}

static GLOBAL: OnceLock<Result<GpuContext, GpuError>> = OnceLock::new();

/// Backends requested by the environment (`WGPU_BACKEND=vulkan|gl|...`),
/// restricted to the compiled ones; all compiled backends when unset.
pub fn requested_backends() -> wgpu::Backends {
    wgpu::Backends::from_env().unwrap_or(COMPILED_BACKENDS)
}

fn backend_names(b: wgpu::Backends) -> String {
    let names: Vec<&str> = [(wgpu::Backends::VULKAN, "Vulkan"), (wgpu::Backends::GL, "GL/EGL")]
        .iter()
        .filter(|(flag, _)| b.contains(*flag))
        .map(|(_, n)| *n)
        .collect();
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}

/// Preference order: hardware first, software last; Vulkan before GL.
fn rank(info: &wgpu::AdapterInfo) -> (u8, u8) {
    let t = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    };
    let b = if info.backend == wgpu::Backend::Vulkan { 0 } else { 1 };
    (t, b)
}

/// A wgpu instance for `backends` (the rest of its descriptor from the environment).
fn instance_for(backends: wgpu::Backends) -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    desc.backends = backends;
    wgpu::Instance::new(desc)
}

/// The adapter [`GpuContext::new`] uses: the first by [`rank`] among all those
/// `instance` enumerates for `backends`, a deterministic choice; else wgpu's own
/// request (without, then with, `force_fallback_adapter`) as a second chance.
///
/// # Errors
/// [`GpuError::NoAdapter`] naming `tried` (the backends) and the last
/// request's error text when there is none.
fn choose_adapter(instance: &wgpu::Instance, backends: wgpu::Backends, tried: &str) -> Result<wgpu::Adapter, GpuError> {
    let mut adapters = pollster::block_on(instance.enumerate_adapters(backends));
    adapters.sort_by_key(|a| rank(&a.get_info()));
    let mut adapter = adapters.into_iter().next();
    let mut last_err = String::from("no adapters enumerated");
    for fallback in [false, true] {
        if adapter.is_some() {
            break;
        }
        let opts = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: fallback,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        match pollster::block_on(instance.request_adapter(&opts)) {
            Ok(a) => adapter = Some(a),
            Err(e) => last_err = e.to_string(),
        }
    }
    adapter.ok_or_else(|| GpuError::NoAdapter {
        tried: tried.to_string(),
        detail: last_err,
    })
}

/// The render kernels' bind group layout and compute pipelines.
struct RenderPipelines {
    /// Input words (read-only), output values, clamped counts: bindings 0, 1, 2.
    layout: wgpu::BindGroupLayout,
    /// The fused kernel (`kernel.wgsl`).
    fused: wgpu::ComputePipeline,
    /// The two passes of `separable.wgsl`: γ, then C.
    two_pass: [wgpu::ComputePipeline; 2],
}

impl RenderPipelines {
    /// Compiles both render shaders (each with `taps.wgsl` prepended) on `device`.
    fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("photosolid render"),
            source: wgpu::ShaderSource::Wgsl(concat!(include_str!("taps.wgsl"), include_str!("kernel.wgsl")).into()),
        });
        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("photosolid render"),
            entries: &[storage(0, true), storage(1, false), storage(2, false)],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("photosolid render"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let compute = |module: &wgpu::ShaderModule, entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let fused = compute(&module, "main");
        let separable = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("photosolid render, two passes"),
            source: wgpu::ShaderSource::Wgsl(concat!(include_str!("taps.wgsl"), include_str!("separable.wgsl")).into()),
        });
        let two_pass = [compute(&separable, "gamma_main"), compute(&separable, "c_main")];
        Self {
            layout,
            fused,
            two_pass,
        }
    }
}

impl GpuContext {
    /// The process-wide context, created on first use (honouring
    /// `WGPU_BACKEND`). A failure is cached too, so a machine without an
    /// adapter pays the probe once.
    pub fn global() -> Result<&'static GpuContext, GpuError> {
        GLOBAL.get_or_init(GpuContext::new).as_ref().map_err(Clone::clone)
    }

    /// Whether [`GpuContext::global`] has already been initialised successfully.
    pub fn global_is_ready() -> bool {
        matches!(GLOBAL.get(), Some(Ok(_)))
    }

    /// A fresh context (instance, adapter, device, pipeline): what the
    /// set-up benchmark measures. Prefer [`GpuContext::global`].
    pub fn new() -> Result<GpuContext, GpuError> {
        let t0 = Instant::now();
        let backends = requested_backends() & COMPILED_BACKENDS;
        let tried = match std::env::var("WGPU_BACKEND") {
            Ok(v) => format!("{} (WGPU_BACKEND={v})", backend_names(backends)),
            Err(_) => backend_names(backends),
        };
        if backends.is_empty() {
            return Err(GpuError::NoAdapter {
                tried,
                detail: "no compiled-in backend selected".into(),
            });
        }
        let instance = instance_for(backends);
        let adapter = choose_adapter(&instance, backends, &tried)?;
        let info = adapter.get_info();
        let summary = AdapterSummary::from_info(&info);

        let limits = adapter.limits();
        // R32Float textures are filterable only with FLOAT32_FILTERABLE,
        // R16Unorm textures exist only with TEXTURE_FORMAT_16BIT_NORM and BC6H
        // ones only with TEXTURE_COMPRESSION_BC (else the real-time path stores
        // R16Float, see `realtime`): each where the adapter has it.
        let features = adapter.features()
            & (wgpu::Features::FLOAT32_FILTERABLE
                | wgpu::Features::TEXTURE_FORMAT_16BIT_NORM
                | wgpu::Features::TEXTURE_COMPRESSION_BC);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("photosolid"),
            required_features: features,
            required_limits: limits.clone(),
            memory_hints: wgpu::MemoryHints::Performance,
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device(format!("{summary}: {e}")))?;
        let RenderPipelines {
            layout,
            fused: pipeline,
            two_pass,
        } = RenderPipelines::new(&device);
        Ok(GpuContext {
            device,
            queue,
            pipeline,
            two_pass,
            realtime: OnceLock::new(),
            compact: OnceLock::new(),
            layout,
            limits,
            summary,
            setup_time: t0.elapsed(),
            _adapter: adapter,
            _instance: instance,
        })
    }

    /// The chosen adapter.
    pub fn adapter(&self) -> &AdapterSummary {
        &self.summary
    }

    /// How long instance + adapter + device + pipeline creation took.
    pub fn setup_time(&self) -> Duration {
        self.setup_time
    }

    /// Largest storage buffer binding (bytes) this device accepts; batches are
    /// split into chunks that fit.
    pub fn max_binding_bytes(&self) -> u64 {
        self.limits
            .max_storage_buffer_binding_size
            .min(self.limits.max_buffer_size)
    }

    /// Whether R32Float textures can be sampled with linear filtering here.
    pub fn float32_filterable(&self) -> bool {
        self.device.features().contains(wgpu::Features::FLOAT32_FILTERABLE)
    }

    /// Whether R16Unorm textures can be created and filtered here
    /// (`TEXTURE_FORMAT_16BIT_NORM`).
    pub fn unorm16(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM)
    }

    /// Whether BC1-7 block-compressed textures (BC6H among them) can be
    /// created and filtered here (`TEXTURE_COMPRESSION_BC`).
    pub fn bc_compression(&self) -> bool {
        self.device.features().contains(wgpu::Features::TEXTURE_COMPRESSION_BC)
    }

    /// Maximum workgroups per dispatch dimension.
    pub fn max_workgroups_per_dim(&self) -> u32 {
        self.limits.max_compute_workgroups_per_dimension
    }
}

/// Adapters visible to this process (for diagnostics), without creating a device.
pub fn list_adapters() -> Vec<AdapterSummary> {
    let backends = requested_backends() & COMPILED_BACKENDS;
    let instance = instance_for(backends);
    let adapters = pollster::block_on(instance.enumerate_adapters(backends));
    adapters
        .iter()
        .map(|a| AdapterSummary::from_info(&a.get_info()))
        .collect()
}
