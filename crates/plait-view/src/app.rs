//! The window: winit events, a wgpu surface on its own device, egui painted
//! through egui-wgpu. Frames come from the engine thread as CPU images.

use std::sync::mpsc::Sender;
use std::sync::{Arc, Mutex};

use winit::application::ApplicationHandler;
use winit::dpi::LogicalSize;
use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::window::{Window, WindowId};

use crate::engine::Command;
use crate::published::Shared;
use crate::ui::{self, Controls};

/// Sent by the engine when it has something new to show.
#[derive(Debug, Clone, Copy)]
pub struct Wake;

/// Small: the window has to be painted by a software rasterizer under Xvfb.
pub const WINDOW_SIZE: LogicalSize<f64> = LogicalSize::new(1000.0, 560.0);

/// The surface and what paints it.
struct Painter {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    renderer: egui_wgpu::Renderer,
    egui: egui_winit::State,
}

pub struct App {
    pub commands: Sender<Command>,
    pub shared: Arc<Mutex<Shared>>,
    painter: Option<Painter>,
    controls: Controls,
    /// Why the window could not be opened or painted.
    pub failure: Option<String>,
}

impl App {
    pub fn new(
        commands: Sender<Command>,
        shared: Arc<Mutex<Shared>>,
        inspect: Option<String>,
    ) -> Self {
        App {
            commands,
            shared,
            painter: None,
            controls: Controls::new(inspect),
            failure: None,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.failure = Some(message);
        let _ = self.commands.send(Command::Quit);
        event_loop.exit();
    }

    fn paint(&mut self) -> Result<(), String> {
        let Some(p) = &mut self.painter else {
            return Ok(());
        };
        let input = p.egui.take_egui_input(&p.window);
        let ctx = p.egui.egui_ctx().clone();
        let commands = self.commands.clone();
        let controls = &mut self.controls;
        let shared = self.shared.clone();
        let mut output = ctx.run_ui(input, |root| {
            if let Ok(s) = shared.lock() {
                ui::draw(root, controls, &s, &commands);
            }
        });
        p.egui
            .handle_platform_output(&p.window, output.platform_output);
        let primitives = ctx.tessellate(output.shapes, output.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [p.config.width, p.config.height],
            pixels_per_point: output.pixels_per_point,
        };
        // egui insists every delta is handled: uploads now, frees after painting
        // (or now, when nothing is painted this time).
        let mut textures = std::mem::take(&mut output.textures_delta);
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                p.renderer.update_texture(&p.device, &p.queue, id, delta);
            }
        }
        let to_free: Vec<egui::TextureId> = textures.free.drain().collect();
        let result = Self::present(p, &primitives, &screen);
        for id in &to_free {
            p.renderer.free_texture(id);
        }
        // egui asks again when an animation or a tooltip needs it.
        if output
            .viewport_output
            .values()
            .any(|v| v.repaint_delay.is_zero())
        {
            p.window.request_redraw();
        }
        result
    }

    /// Paint egui's primitives into the window's next image.
    fn present(
        p: &mut Painter,
        primitives: &[egui::ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
    ) -> Result<(), String> {
        let frame = match p.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(());
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                p.surface.configure(&p.device, &p.config);
                p.window.request_redraw();
                return Ok(());
            }
            other => return Err(format!("the window surface failed: {other:?}")),
        };
        let view = frame.texture.create_view(&Default::default());
        let mut encoder = p.device.create_command_encoder(&Default::default());
        let mut buffers =
            p.renderer
                .update_buffers(&p.device, &p.queue, &mut encoder, primitives, screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            p.renderer
                .render(&mut pass.forget_lifetime(), primitives, screen);
        }
        buffers.push(encoder.finish());
        p.queue.submit(buffers);
        p.queue.present(frame);
        Ok(())
    }
}

/// Open the window's own device on the adapter that can present to it.
fn painter(event_loop: &ActiveEventLoop) -> Result<Painter, String> {
    let window = Arc::new(
        event_loop
            .create_window(
                Window::default_attributes()
                    .with_title("plait view")
                    .with_inner_size(WINDOW_SIZE),
            )
            .map_err(|e| format!("cannot open a window: {e}"))?,
    );
    // As plait's own device: Vulkan first, GL only when Vulkan has no adapter
    // for this window (probing EGL is noisy); WGPU_BACKEND picks one.
    let tries = match wgpu::Backends::from_env() {
        Some(b) => vec![b],
        None => vec![wgpu::Backends::VULKAN, wgpu::Backends::GL],
    };
    let mut last_error = String::from("no backend tried");
    let mut found = None;
    for backends in tries {
        let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(window.clone()));
        // No debug labels: they crash Mesa 22's lavapipe (WGPU_DEBUG=1 turns them on).
        desc.flags = wgpu::InstanceFlags::empty().with_env();
        desc.backends = backends;
        let instance = wgpu::Instance::new(desc);
        let surface = match instance.create_surface(window.clone()) {
            Ok(s) => s,
            Err(e) => {
                last_error = format!("cannot draw into the window: {e}");
                continue;
            }
        };
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }));
        match adapter {
            Ok(a) => {
                found = Some((surface, a));
                break;
            }
            Err(e) => last_error = format!("no GPU adapter can draw into the window: {e}"),
        }
    }
    let (surface, adapter) = found.ok_or(last_error)?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("plait view window"),
        ..Default::default()
    }))
    .map_err(|e| format!("cannot open the window's GPU device: {e}"))?;
    let size = window.inner_size();
    let caps = surface.get_capabilities(&adapter);
    // egui-wgpu writes sRGB-encoded colours: prefer a non-sRGB surface format.
    let format = caps
        .formats
        .iter()
        .copied()
        .find(|f| !f.is_srgb())
        .or_else(|| caps.formats.first().copied())
        .ok_or("the window surface offers no format")?;
    let config = wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        width: size.width.max(1),
        height: size.height.max(1),
        present_mode: wgpu::PresentMode::Fifo,
        desired_maximum_frame_latency: 2,
        alpha_mode: caps
            .alpha_modes
            .first()
            .copied()
            .unwrap_or(wgpu::CompositeAlphaMode::Auto),
        view_formats: vec![],
        color_space: Default::default(),
    };
    surface.configure(&device, &config);
    let renderer = egui_wgpu::Renderer::new(&device, format, Default::default());
    let ctx = egui::Context::default();
    let max_texture = device.limits().max_texture_dimension_2d as usize;
    let egui = egui_winit::State::new(
        ctx,
        egui::ViewportId::ROOT,
        &window,
        Some(window.scale_factor() as f32),
        None,
        Some(max_texture),
    );
    Ok(Painter {
        window,
        surface,
        device,
        queue,
        config,
        renderer,
        egui,
    })
}

impl ApplicationHandler<Wake> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.painter.is_some() {
            return;
        }
        match painter(event_loop) {
            Ok(p) => {
                p.window.request_redraw();
                self.painter = Some(p);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, _: Wake) {
        let finished = self.shared.lock().map(|s| s.finished).unwrap_or(true);
        if finished {
            let _ = self.commands.send(Command::Quit);
            event_loop.exit();
            return;
        }
        if let Some(p) = &self.painter {
            p.window.request_redraw();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(p) = &mut self.painter else {
            return;
        };
        let response = p.egui.on_window_event(&p.window, &event);
        match event {
            WindowEvent::CloseRequested => {
                let _ = self.commands.send(Command::Quit);
                event_loop.exit();
                return;
            }
            WindowEvent::Resized(size) => {
                p.config.width = size.width.max(1);
                p.config.height = size.height.max(1);
                p.surface.configure(&p.device, &p.config);
                p.window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.paint() {
                    self.fail(event_loop, e);
                }
                return;
            }
            _ => {}
        }
        if response.repaint {
            p.window.request_redraw();
        }
    }
}
