//! A headless device on whatever adapter exists, with its optional features probed.

use crate::GpuError;

/// The message for a machine without any adapter: say how to get one.
pub const NO_ADAPTER_HELP: &str = "no GPU adapter found. On a machine without a GPU install Mesa's \
software Vulkan driver (lavapipe): `apt-get install -y mesa-vulkan-drivers` (Debian/Ubuntu). \
`WGPU_BACKEND=gl` selects Mesa's llvmpipe OpenGL driver instead";

/// Optional capabilities plait uses when the adapter has them.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Capabilities {
    /// Timestamps written anywhere in an encoder (`TIMESTAMP_QUERY` +
    /// `TIMESTAMP_QUERY_INSIDE_ENCODERS`), as benchmarks write them. Frames
    /// also carry per-pass times with `TIMESTAMP_QUERY` alone
    /// ([`Gpu::timestamp_way`]).
    pub timestamps: bool,
    /// Additive blending into 32-bit float targets (`FLOAT32_BLENDABLE`).
    pub float32_blendable: bool,
    /// Fragment shaders can force the depth test before they run
    /// (`SHADER_EARLY_DEPTH_TEST`); without it storage writes are guarded by a
    /// test in the shader (`depth_guard`).
    pub early_depth_test: bool,
    /// `max_texture_dimension_2d` of the adapter.
    pub max_texture_dimension: u32,
    /// `max_storage_buffer_binding_size` of the adapter.
    pub max_storage_buffer_binding_size: u64,
    /// Shaders can trace rays through acceleration structures
    /// (`EXPERIMENTAL_RAY_QUERY`; Vulkan's `VK_KHR_ray_query`: Mesa ≥ 25's
    /// lavapipe has it, 22.3's does not). Techniques with `[technique]
    /// adapter = ["ray_query"]` are refused without it ([`crate::support`]).
    pub ray_query: bool,
    /// `max_blas_primitive_count`: the most primitives (strand segments) one
    /// bottom-level acceleration structure holds; 0 without ray queries.
    pub max_blas_primitives: u32,
    /// `max_tlas_instance_count`: the most instances (the strands, each
    /// mesh) one top-level acceleration structure holds; 0 without ray
    /// queries.
    pub max_tlas_instances: u32,
}

impl Capabilities {
    /// The adapter `opts` describes: its limits, and FLOAT32_BLENDABLE as
    /// compile fits formats to it; no timestamps, and no early depth test
    /// (so storage writes are checked as guardable everywhere).
    pub fn of_compile(opts: &plait_graph::CompileOptions) -> Self {
        Capabilities {
            timestamps: false,
            float32_blendable: opts.capabilities.float32_blendable,
            early_depth_test: false,
            max_texture_dimension: opts.max_texture_dimension,
            max_storage_buffer_binding_size: opts.max_buffer_binding_size,
            ray_query: false,
            max_blas_primitives: 0,
            max_tlas_instances: 0,
        }
    }

    /// What compile needs to know of this adapter.
    pub fn compile_capabilities(&self) -> plait_graph::CompileCapabilities {
        plait_graph::CompileCapabilities {
            float32_blendable: self.float32_blendable,
        }
    }
}

/// wgpu's experimental features, asked for only when the adapter has ray
/// queries (the one experimental feature plait uses).
#[allow(unsafe_code)]
fn experimental_features() -> wgpu::ExperimentalFeatures {
    // SAFETY: `enabled` is unsafe as an acknowledgement that experimental
    // APIs may have bugs, not for memory safety of this call. plait uses only
    // ray queries from them, and declares each ray query in a function
    // outside any loop: one declared in a loop made naga emit a null
    // constant of the ray-query type, which Mesa rejects and the device is
    // lost at submit (wgpu PR 9945).
    unsafe { wgpu::ExperimentalFeatures::enabled() }
}

/// The device plait renders with.
pub struct Gpu {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub capabilities: Capabilities,
    /// Formats, downlevel flags and limits, probed once: what schedules are
    /// checked against before anything is created ([`crate::support`]).
    pub support: crate::AdapterSupport,
    /// Pipelines built on this device, shared by every schedule rendered on it
    /// (an A/B run builds the same passes for many variants).
    pub pipelines: crate::cache::PipelineCache,
    uncaptured: std::sync::Arc<std::sync::Mutex<Vec<String>>>,
}

impl Gpu {
    /// Open the best adapter: Vulkan first (lavapipe on CI), then GL; `WGPU_BACKEND` overrides.
    pub fn new() -> Result<Gpu, GpuError> {
        Self::new_without_features(&[])
    }

    /// [`Gpu::new`] pretending the adapter lacks the named optional features
    /// (as `PLAIT_DISABLE_FEATURES` does): how tests reach the fallbacks.
    pub fn new_without_features(names: &[&str]) -> Result<Gpu, GpuError> {
        crate::wait::wait_for(Self::new_async(names)).map_err(GpuError::Device)?
    }

    /// [`Gpu::new_without_features`], awaited: how a browser opens its
    /// WebGPU adapter (it cannot block).
    pub async fn new_async(disabled: &[&str]) -> Result<Gpu, GpuError> {
        // Vulkan first (lavapipe on CI); GL (llvmpipe) only when Vulkan has no
        // adapter, since probing EGL prints noise on headless machines.
        // WGPU_BACKEND picks one explicitly. In a browser: its WebGPU.
        let explicit = wgpu::Backends::from_env();
        let tries = match explicit {
            _ if cfg!(target_arch = "wasm32") => vec![wgpu::Backends::BROWSER_WEBGPU],
            Some(b) => vec![b],
            None => vec![wgpu::Backends::VULKAN, wgpu::Backends::GL],
        };
        let mut last_error = String::from("no backend tried");
        let mut found = None;
        for backends in tries {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            // Debug labels (VK_EXT_debug_utils) crash Mesa 22's lavapipe in
            // vkCmdBeginDebugUtilsLabelEXT; they are opt-in with WGPU_DEBUG=1.
            desc.flags = wgpu::InstanceFlags::empty().with_env();
            let instance = wgpu::Instance::new(desc);
            match instance
                .request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::HighPerformance,
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    apply_limit_buckets: false,
                })
                .await
            {
                Ok(a) => {
                    found = Some(a);
                    break;
                }
                Err(e) => last_error = e.to_string(),
            }
        }
        let Some(adapter) = found else {
            return Err(GpuError::NoAdapter(format!(
                "{NO_ADAPTER_HELP} ({last_error})"
            )));
        };
        let info = adapter.get_info();
        let available = adapter.features();
        let wanted = wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
            | wgpu::Features::FLOAT32_BLENDABLE
            | wgpu::Features::SHADER_EARLY_DEPTH_TEST
            | wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES
            // The engine zeroes storage-texture outputs that do not load
            // with `clear_texture`, which wgpu allows only with this feature
            // (a compute pass writing a texture failed validation without it).
            | wgpu::Features::CLEAR_TEXTURE
            // Ray-traced techniques (issue 48); the device then needs the
            // experimental features and acceleration-structure limits below.
            | wgpu::Features::EXPERIMENTAL_RAY_QUERY;
        let mut features = available & wanted;
        // PLAIT_DISABLE_FEATURES=FLOAT32_BLENDABLE,TIMESTAMP_QUERY pretends the
        // adapter lacks them: how the fallbacks for weaker adapters are tested here.
        let from_env = std::env::var("PLAIT_DISABLE_FEATURES").unwrap_or_default();
        {
            let names = from_env
                .split(',')
                .map(str::trim)
                .chain(disabled.iter().copied());
            for name in names.filter(|n| !n.is_empty()) {
                match wgpu::Features::from_name(name) {
                    Some(f) => features.remove(f),
                    None => {
                        return Err(GpuError::Device(format!(
                            "PLAIT_DISABLE_FEATURES: unknown feature `{name}`"
                        )));
                    }
                }
            }
        }
        // A page asks for WebGPU's default limits, not its adapter's: what
        // runs there then runs in every reader's browser, and what does not
        // is refused by the same check as on a weak native adapter.
        let limits = if cfg!(target_arch = "wasm32") {
            wgpu::Limits::default()
        } else {
            adapter.limits()
        };
        let ray_query = features.contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY);
        let (limits, experimental_features) = if ray_query {
            let mut limits = limits.using_acceleration_structure_values(adapter.limits());
            // PLAIT_MAX_BLAS_PRIMITIVES=N asks for a device holding at most N
            // primitives per bottom-level structure (never more than the
            // adapter's): how the refusal of a groom past the limit is
            // tested on a real adapter (plait::structure_limit).
            if let Ok(text) = std::env::var("PLAIT_MAX_BLAS_PRIMITIVES") {
                let n: u32 = text.trim().parse().map_err(|_| {
                    GpuError::Device(format!(
                        "PLAIT_MAX_BLAS_PRIMITIVES: `{text}` is not a primitive count"
                    ))
                })?;
                limits.max_blas_primitive_count = limits.max_blas_primitive_count.min(n);
            }
            (limits, experimental_features())
        } else {
            (limits, wgpu::ExperimentalFeatures::disabled())
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("plait"),
                required_features: features,
                required_limits: limits.clone(),
                experimental_features,
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            })
            .await
            .map_err(|e| GpuError::Device(e.to_string()))?;
        // Errors outside an error scope would panic inside wgpu; keep them for
        // the next `take_uncaptured_errors` instead.
        let uncaptured = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(std::sync::Arc::new(move |e: wgpu::Error| {
            if let Ok(mut list) = sink.lock() {
                list.push(crate::describe_wgpu_error(&e));
            }
        }));
        let timestamps = features.contains(
            wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS,
        );
        let capabilities = Capabilities {
            timestamps,
            float32_blendable: features.contains(wgpu::Features::FLOAT32_BLENDABLE),
            early_depth_test: features.contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST),
            max_texture_dimension: limits.max_texture_dimension_2d,
            max_storage_buffer_binding_size: limits
                .max_storage_buffer_binding_size
                .min(limits.max_buffer_size),
            ray_query,
            max_blas_primitives: if ray_query {
                limits.max_blas_primitive_count
            } else {
                0
            },
            max_tlas_instances: if ray_query {
                limits.max_tlas_instance_count
            } else {
                0
            },
        };
        let support = crate::AdapterSupport::probe(&adapter, &device);
        Ok(Gpu {
            adapter,
            device,
            queue,
            info,
            capabilities,
            support,
            pipelines: Default::default(),
            uncaptured,
        })
    }

    /// How passes are timed on this device: inside the encoder where the
    /// adapter allows it (native), through pass descriptors where it has
    /// `TIMESTAMP_QUERY` alone (a browser's WebGPU), `None` without
    /// timestamps ([`crate::timing`]).
    pub fn timestamp_way(&self) -> Option<crate::timing::TimestampWay> {
        let features = self.device.features();
        if self.capabilities.timestamps {
            Some(crate::timing::TimestampWay::InsideEncoders)
        } else if features.contains(wgpu::Features::TIMESTAMP_QUERY) {
            Some(crate::timing::TimestampWay::PassDescriptors)
        } else {
            None
        }
    }

    /// `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub fn adapter_name(&self) -> &str {
        &self.info.name
    }

    /// The laps a group of invocations may run before the driver ends its
    /// loops (`Some(65_535)`-ish on Mesa 22's lavapipe), or `None` when a
    /// loop of [`crate::loop_budget::PROBE_LAPS`] ran whole: measured by one
    /// dispatch each call ([`crate::loop_budget::probe`]).
    pub fn loop_budget(&self) -> Result<Option<u32>, GpuError> {
        crate::loop_budget::probe(&self.device, &self.queue)
    }

    /// `vulkan`, `gl`, …
    pub fn backend_name(&self) -> String {
        self.info.backend.to_str().to_owned()
    }

    /// Whether the adapter has a named optional feature (names as in `wgpu::Features`,
    /// e.g. `FLOAT32_BLENDABLE`). Unknown names are reported as missing.
    pub fn has_feature(&self, name: &str) -> bool {
        match wgpu::Features::from_name(name) {
            Some(f) => self.device.features().contains(f),
            None => false,
        }
    }

    /// GPU errors raised outside any error scope since the last call.
    pub fn take_uncaptured_errors(&self) -> Vec<String> {
        self.uncaptured
            .lock()
            .map(|mut l| std::mem::take(&mut *l))
            .unwrap_or_default()
    }

    /// Wait for all submitted work.
    pub fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Device(e.to_string()))
    }
}
