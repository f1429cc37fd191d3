//! GPU timestamps around passes, and the small statistics the benchmarks print.

use plait::gpu::Gpu;

/// One timestamp before the first pass and one after each.
pub struct Timestamps {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    count: u32,
    period_ns: f64,
}

impl Timestamps {
    /// `None` on adapters without timestamp queries.
    pub fn new(gpu: &Gpu, passes: usize) -> Option<Self> {
        if !gpu.capabilities.timestamps {
            return None;
        }
        let count = passes as u32 + 1;
        let size = count as u64 * 8;
        let device = &gpu.device;
        Some(Timestamps {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("bench timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench timestamp resolve"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench timestamp readback"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            count,
            period_ns: gpu.queue.get_timestamp_period() as f64,
        })
    }

    pub fn write(&self, encoder: &mut wgpu::CommandEncoder, index: usize) {
        encoder.write_timestamp(&self.queries, index as u32);
    }

    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..self.count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.count as u64 * 8);
    }

    /// Wait for the frame; (first to last timestamp, each pass) in ms.
    pub fn read(&self, gpu: &Gpu) -> (f64, Vec<f64>) {
        let bytes = plait::gpu::readback::map_buffer(&gpu.device, &self.readback)
            .unwrap_or_else(|e| panic!("reading timestamps: {e}"));
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        let ms = |a: u64, b: u64| b.saturating_sub(a) as f64 * self.period_ns / 1e6;
        let passes = ticks.windows(2).map(|w| ms(w[0], w[1])).collect();
        (ms(ticks[0], ticks[ticks.len() - 1]), passes)
    }
}

/// The median (upper middle for an even count); NaN for none.
pub fn median(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `--name value` from the command line (cargo bench passes `--bench` too).
pub fn arg(name: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
}

/// `--size WxH`, or `default`.
pub fn size_arg(default: (u32, u32)) -> (u32, u32) {
    arg("--size")
        .and_then(|s| {
            let (w, h) = s.split_once(['x', 'X'])?;
            Some((w.parse().ok()?, h.parse().ok()?))
        })
        .unwrap_or(default)
}
