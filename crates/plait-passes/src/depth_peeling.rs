//! `hair_depth_peel`: depth peeling, the ground truth of hair transparency
//! (Sintorn & Assarsson 2009 §2.2 and Fig. 2, "depth-peeling (ground truth …
//! 112 layers)"; §3.4 calls it "the only non-approximate method").
//!
//! The hair is drawn once per depth layer, front to back: layer k keeps the
//! fragments strictly behind layer k-1's depth (sampled, ping-pong between
//! `peel_depth` and `peel_prev`) and in front of the opaque depth, and the
//! depth test (Less) leaves the nearest of them in `layer`; a fullscreen draw
//! blends it UNDER the accumulated `color` (dst += (1-dst.a)·layer). The paper
//! peels back to front with the far test; front to back with "under" gives the
//! same image and lets the loop stop on the first empty layer.
//!
//! Stopping: each peel draw counts its samples in an occlusion query. Every
//! `check_every` layers the pass resolves the queries, submits what it has
//! recorded and waits for the result (mid-frame, through
//! [`RecordContext::device`]/`queue`, continuing in a fresh encoder), and
//! stops at the first layer that drew nothing, or at `max_layers`. The wait
//! is awaited (`record_async`): in a browser it yields to the page's event
//! loop, so the page peels to completion as natively. A read-back that fails
//! fails the frame with the layers peeled (`finish`), never a silent cut. The layers
//! used are reported as the pass stat `layers` (`FrameReport`), with
//! `capped = 1` when the cap cut it short. Fragments at exactly the depth of
//! the previous layer are peeled together with it (only one kept) — the
//! method's usual tie.
//!
//! Cost: `layers` × (one hair draw + one fullscreen blend), plus a CPU↔GPU round
//! trip per `check_every` layers. Memory: the accumulated colour, one layer
//! colour target and two depth buffers at screen size.

use std::cell::{Cell, RefCell};

use plait_gpu::GpuError;
use plait_gpu::pass::{
    BlendPreset, BuildContext, PassType, PreparedPass, RasterState, RecordContext, Recording,
    ShaderDraw, ShaderPass, blend_preset, build_draw, default_defines,
};
use plait_gpu::readback::map_buffer_async;
use plait_graph::{Access, Binding, PassShape, PassTypeSpec, ScheduledPass, SlotId};

use crate::hair_fragment;
use crate::spec_util::{DEPTH, HDR, bound, int, texture};

/// With the params of the library's providers (see [`HairShade`](crate::hair_shade::HairShade)).
pub struct HairDepthPeel {
    shading_inputs: Vec<plait_graph::SlotSpec>,
    shading_params: Vec<plait_graph::ParamSpec>,
}

inventory::submit! { crate::RustPassType(|library| Box::new(HairDepthPeel {
    shading_inputs: hair_fragment::shading_inputs(library),
    shading_params: hair_fragment::shading_params(library),
})) }

/// Its outputs' handles ([`SlotId`]), in `spec`'s order (its inputs are the
/// shading point's, which vary with the library).
pub(crate) const COLOR: SlotId = SlotId::Output(0);
pub(crate) const LAYER: SlotId = SlotId::Output(1);
pub(crate) const PEEL_DEPTH: SlotId = SlotId::Output(2);
pub(crate) const PEEL_PREV: SlotId = SlotId::Output(3);

pub(crate) fn spec(
    shading_inputs: &[plait_graph::SlotSpec],
    shading_params: &[plait_graph::ParamSpec],
) -> PassTypeSpec {
    let mut inputs = shading_inputs.to_vec();
    inputs.push(texture(
        "opaque_depth",
        Access::Sampled,
        DEPTH,
        "camera depth of opaque geometry: hair behind it is not peeled",
    ));
    let mut params = shading_params.to_vec();
    params.push(int(
        "max_layers",
        256,
        1,
        4096,
        "layer cap: peel at most this many layers",
    ));
    params.push(int(
        "check_every",
        4,
        1,
        4096,
        "layers peeled between occlusion-query read-backs (each one a CPU-GPU round trip)",
    ));
    PassTypeSpec {
        inputs,
        outputs: vec![
            texture(
                "color",
                Access::ColorTarget,
                HDR,
                "hair, premultiplied, blended front to back",
            ),
            texture(
                "layer",
                Access::ColorTarget,
                HDR,
                "scratch: the layer being peeled",
            ),
            texture(
                "peel_depth",
                Access::DepthTarget,
                DEPTH,
                "scratch: depth of the layer being peeled",
            ),
            texture(
                "peel_prev",
                Access::DepthTarget,
                DEPTH,
                "scratch: depth of the previous layer (ping-pong with peel_depth)",
            ),
        ],
        params,
        // The peel draw's WGSL is the technique's file, named by its pass
        // (`shader = "peel.wgsl"`): no Rust names a technique's folder.
        needs_shader: true,
        ..PassTypeSpec::new(
            "hair_depth_peel",
            PassShape::Raster,
            "Sintorn & Assarsson 2009 §2.2, §3.4, Fig. 2",
            "Depth peeling front to back until an occlusion query reports no fragments (ground truth).",
        )
    }
}

impl PassType for HairDepthPeel {
    fn spec(&self) -> PassTypeSpec {
        spec(&self.shading_inputs, &self.shading_params)
    }
    fn shader(&self) -> Option<&str> {
        // The pass's `shader = …`, beside the technique file that declares it.
        None
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let spec = self.spec();
        let find = |slot: SlotId| bound(pass, &spec, slot).cloned();
        let (color, layer, depth_a, depth_b) = (
            find(COLOR)?,
            find(LAYER)?,
            find(PEEL_DEPTH)?,
            find(PEEL_PREV)?,
        );
        let int_param = |name: &str, default: i64| match pass.params.get(name) {
            Some(plait_graph::Value::Int(i)) => (*i).max(1) as u32,
            _ => default as u32,
        };
        let max_layers = int_param("max_layers", 256);
        let check_every = int_param("check_every", 4);

        // One peel draw per parity: writes one depth buffer, samples the other.
        let peel_pass = |write: &Binding, prev: &Binding| {
            let mut p = pass.clone();
            p.writes = vec![
                Binding {
                    loads: false,
                    ..layer.clone()
                },
                Binding {
                    slot: "peel_depth".into(),
                    loads: false,
                    access: Access::DepthTarget,
                    ..write.clone()
                },
            ];
            p.reads.push(Binding {
                slot: "peel_prev".into(),
                access: Access::Sampled,
                ..prev.clone()
            });
            p
        };
        // The peel draw: hair, depth test and write (Less), colour replaced —
        // the type's own draw and state.
        let peel_draw = ShaderDraw::of(self, pass, ctx)?;
        let peel = [
            build_draw(&peel_draw, &peel_pass(&depth_a, &depth_b), ctx)?,
            build_draw(&peel_draw, &peel_pass(&depth_b, &depth_a), ctx)?,
        ];
        let mut blend_pass = pass.clone();
        blend_pass.reads = vec![Binding {
            access: Access::Sampled,
            ..layer.clone()
        }];
        blend_pass.writes = vec![Binding {
            loads: true,
            ..color.clone()
        }];
        blend_pass.params.clear();
        // The blend of one layer under the accumulated colour.
        let blend_draw = ShaderDraw::library(
            "shaders/passes/peel_blend.wgsl",
            pass,
            PassShape::Fullscreen,
            default_defines(&blend_pass),
            RasterState {
                blend: vec![blend_preset(BlendPreset::Under)],
                load_colors: true,
                ..RasterState::default()
            },
            ctx,
        )?;
        let blend = build_draw(&blend_draw, &blend_pass, ctx)?;

        let device = ctx.device;
        // Labelled `occlusion:` + the pass's name, the label of its peel
        // draws' render passes: how the page's device finds the set that
        // wgpu's WebGPU backend leaves out of their descriptors
        // (crates/plait-web/src/occlusion_shim.rs).
        let label = format!("occlusion:{}", pass.name);
        let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some(&label),
            ty: wgpu::QueryType::Occlusion,
            count: max_layers,
        });
        let size = max_layers as u64 * 8;
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("depth peeling queries"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("depth peeling query readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Box::new(Peeling {
            name: pass.name.clone(),
            peel,
            blend,
            color: color.id(),
            first_prev: depth_b.id(),
            queries,
            resolve,
            readback,
            max_layers,
            check_every,
            layers: Cell::new(0),
            capped: Cell::new(false),
            failed: RefCell::new(None),
        }))
    }
}

impl Peeling {
    /// Start: nothing accumulated; the "previous layer" at depth 0 lets every fragment through.
    fn clear(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        let view = |id| {
            ctx.pool
                .texture(id)
                .map(|(_, v)| v)
                .expect("peeling targets are textures")
        };
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&self.name),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: view(self.color),
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: view(self.first_prev),
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            // The pass's first wgpu pass: where its time begins in a browser.
            timestamp_writes: ctx.render_timestamps(),
            occlusion_query_set: None,
            multiview_mask: None,
        });
    }

    /// Peel front to back until a layer draws nothing or the cap, reading the
    /// occlusion queries back every `check_every` layers (awaited: in a
    /// browser the mapping completes through the page's event loop).
    async fn peel(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        self.failed.replace(None);
        self.clear(ctx, encoder);
        let mut used = self.max_layers;
        let mut start = 0;
        'peel: while start < self.max_layers {
            let end = (start + self.check_every).min(self.max_layers);
            for k in start..end {
                self.peel[(k % 2) as usize].record_with_query(
                    ctx,
                    encoder,
                    Some((&self.queries, k)),
                );
                self.blend.record(ctx, encoder);
            }
            // (Resolve offsets must be 256-aligned: each batch lands at 0.)
            encoder.resolve_query_set(&self.queries, start..end, &self.resolve, 0);
            encoder.copy_buffer_to_buffer(
                &self.resolve,
                0,
                &self.readback,
                0,
                (end - start) as u64 * 8,
            );
            // Submit what is recorded and wait for the query results; go on in a new encoder.
            // The executor wraps the pass in a debug group: close it in the old encoder, reopen it in the new.
            encoder.pop_debug_group();
            let done = std::mem::replace(
                encoder,
                ctx.device
                    .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                        label: Some(&self.name),
                    }),
            );
            encoder.push_debug_group(&self.name);
            ctx.queue.submit([done.finish()]);
            // The layers recorded so far, should the wait below not return.
            self.layers.set(end);
            self.capped.set(false);
            let bytes = match map_buffer_async(ctx.device, &self.readback).await {
                Ok(bytes) => bytes,
                Err(message) => {
                    self.failed.replace(Some(message));
                    return;
                }
            };
            for k in start..end {
                let at = (k - start) as usize * 8;
                let samples = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or([0; 8]));
                if samples == 0 {
                    used = k;
                    break 'peel;
                }
            }
            start = end;
        }
        self.layers.set(used);
        self.capped.set(used == self.max_layers);
    }
}

struct Peeling {
    name: String,
    peel: [ShaderPass; 2],
    blend: ShaderPass,
    color: plait_graph::ResourceId,
    first_prev: plait_graph::ResourceId,
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    max_layers: u32,
    check_every: u32,
    layers: Cell<u32>,
    capped: Cell<bool>,
    /// Why the last frame's peeling stopped early, if a read-back failed.
    failed: RefCell<Option<String>>,
}

impl PreparedPass for Peeling {
    /// Natively: [`Peeling::peel`], blocking on each read-back. In a browser
    /// nothing can block; the executor calls `record_async` there, and a
    /// caller that records synchronously gets a frame that fails (`finish`).
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        if let Err(message) = plait_gpu::wait::wait_for(self.peel(ctx, encoder)) {
            self.failed.replace(Some(message));
        }
    }

    fn record_async<'a>(
        &'a self,
        ctx: &'a RecordContext<'a>,
        encoder: &'a mut wgpu::CommandEncoder,
    ) -> Recording<'a> {
        Box::pin(self.peel(ctx, encoder))
    }

    /// A read-back that failed mid-frame stopped the peeling: the frame fails
    /// with it rather than showing the layers peeled so far as the answer.
    fn finish(&self, _device: &wgpu::Device) -> Result<(), String> {
        match self.failed.take() {
            Some(message) => Err(format!(
                "depth peeling stopped after {} layers: the occlusion queries could not be read back ({message})",
                self.layers.get()
            )),
            None => Ok(()),
        }
    }

    fn stats(&self) -> Vec<(String, f64)> {
        vec![
            ("layers".into(), self.layers.get() as f64),
            ("capped".into(), if self.capped.get() { 1.0 } else { 0.0 }),
        ]
    }
}
