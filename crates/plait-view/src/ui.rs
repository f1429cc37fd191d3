//! The viewer's panels (egui): what the engine publishes, and controls that
//! send it commands.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::Sender;

use egui::{Color32, RichText, TextureHandle, TextureOptions};
use plait_graph::{ResourceDesc, Value};
use plait_hair::scene::Camera;

use crate::engine::Command;
use crate::inspect::{self, Display, Inspected};
use crate::orbit::{LightAngles, Orbit};
use crate::published::Shared;

/// State of the controls, kept between frames.
#[derive(Default)]
pub struct Controls {
    scene_version: u64,
    base_camera: Option<Camera>,
    orbit: Option<Orbit>,
    light: Option<LightAngles>,
    /// `None`: the pipeline's output.
    inspected: Option<String>,
    display: Option<Display>,
    bit: u32,
    paused: bool,
    /// Param values being edited, refreshed when the engine's change.
    params: Vec<(String, Value)>,
    params_seen: Vec<(String, Value)>,
    gallery: Vec<PathBuf>,
    image: Option<(Arc<Inspected>, TextureHandle)>,
}

impl Controls {
    pub fn new(inspected: Option<String>) -> Self {
        Controls {
            gallery: plait_assets::list("pipelines", "toml"),
            inspected,
            ..Default::default()
        }
    }
}

/// `value` as `--set` text.
fn toml_text(value: &Value) -> String {
    match value {
        Value::Float(f) => format!("{f:?}"),
        Value::Str(s) => format!("{s:?}"),
        other => other.to_string(),
    }
}

/// Whether the user touched a widget, as opposed to the widget adjusting a
/// value it was shown (egui rounds values to what it displays).
fn by_user(r: &egui::Response) -> bool {
    r.dragged() || r.drag_stopped() || r.clicked() || r.has_focus() || r.lost_focus()
}

fn mib(bytes: u64) -> String {
    format!("{:.2}", bytes as f64 / 1048576.0)
}

/// Draw the whole window for this frame.
pub fn draw(ui: &mut egui::Ui, c: &mut Controls, s: &Shared, tx: &Sender<Command>) {
    let send = |cmd: Command| {
        let _ = tx.send(cmd);
    };
    // The scene was (re)loaded: controls start from its camera and light.
    if c.scene_version != s.scene_version {
        c.scene_version = s.scene_version;
        c.base_camera = s.scene_camera.clone();
        c.orbit = s.scene_camera.as_ref().map(Orbit::from_camera);
        c.light = s.scene_light.map(LightAngles::from_direction);
    }
    if c.params_seen != s.params {
        c.params_seen = s.params.clone();
        c.params = s.params.clone();
    }

    egui::Panel::top("status").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(s.pipeline.display().to_string()).strong());
            ui.label(format!("· {}", s.adapter));
            let ms = s
                .frame_median_ms
                .map(|m| format!("{m:.0} ms median"))
                .unwrap_or_else(|| "no GPU times".into());
            ui.label(format!(
                "· frame {} ({ms}) · {} reload{} · {}",
                s.total_frames,
                s.reloads,
                if s.reloads == 1 { "" } else { "s" },
                s.status
            ));
        });
        if let Some(fatal) = &s.fatal {
            ui.colored_label(Color32::RED, format!("stopped: {fatal}"));
        }
        if let Some(error) = &s.error {
            egui::Frame::new()
                .fill(Color32::from_rgb(60, 10, 10))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    ui.label(
                        RichText::new(error)
                            .monospace()
                            .color(Color32::from_rgb(255, 170, 160)),
                    );
                });
        }
    });

    egui::Panel::left("controls")
        .default_size(250.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| controls(ui, c, s, &send))
        });

    egui::Panel::right("passes")
        .default_size(270.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| pass_table(ui, s))
        });

    egui::CentralPanel::default().show(ui, |ui| viewport(ui, c, s, &send));
}

fn controls(ui: &mut egui::Ui, c: &mut Controls, s: &Shared, send: &dyn Fn(Command)) {
    ui.heading("Pipeline");
    let current = s.pipeline.clone();
    let name = |p: &PathBuf| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    egui::ComboBox::from_id_salt("pipeline")
        .selected_text(name(&current))
        .show_ui(ui, |ui| {
            for p in c.gallery.clone() {
                if ui
                    .selectable_label(p == current, name(&p))
                    .on_hover_text(p.display().to_string())
                    .clicked()
                    && p != current
                {
                    send(Command::OpenPipeline(p));
                }
            }
        });
    ui.small("The gallery (pipelines/*.toml on the search path).");
    // Light and camera before the techniques and params, whose lists grow
    // with the pipeline: the default window shows them without scrolling.
    light_controls(ui, c, s, send);
    camera_controls(ui, c, send);

    if !s.techniques.is_empty() {
        ui.separator();
        ui.heading("Techniques");
        egui::Grid::new("techniques").num_columns(2).show(ui, |ui| {
            for t in &s.techniques {
                ui.label(&t.point);
                egui::ComboBox::from_id_salt(("technique", &t.point))
                    .selected_text(&t.chosen)
                    .show_ui(ui, |ui| {
                        for choice in &t.choices {
                            if ui.selectable_label(*choice == t.chosen, choice).clicked()
                                && *choice != t.chosen
                            {
                                send(Command::SetTechnique(t.point.clone(), choice.clone()));
                            }
                        }
                    });
                ui.end_row();
            }
        });
    }

    ui.separator();
    ui.heading("Params");
    egui::Grid::new("params").num_columns(2).show(ui, |ui| {
        for (name, value) in c.params.iter_mut() {
            ui.label(name.as_str());
            let commit = match value {
                // Committed when a drag ends or a typed value is entered.
                Value::Int(i) => {
                    let r = ui.add(egui::DragValue::new(i).speed(1.0));
                    r.drag_stopped() || (r.changed() && by_user(&r) && !r.dragged())
                }
                Value::Float(f) => {
                    let r = ui.add(egui::DragValue::new(f).speed(0.01).max_decimals(6));
                    r.drag_stopped() || (r.changed() && by_user(&r) && !r.dragged())
                }
                Value::Bool(b) => ui.checkbox(b, "").changed(),
                Value::Str(text) => {
                    let r = ui.text_edit_singleline(text);
                    r.lost_focus()
                }
                Value::List(_) => {
                    ui.label(value.to_string());
                    false
                }
            };
            let before = s.params.iter().find(|(k, _)| k == name).map(|(_, v)| v);
            if commit && before != Some(value) {
                send(Command::SetParam(name.clone(), toml_text(value)));
            }
            ui.end_row();
        }
    });
    if !s.edits.is_empty() {
        ui.small(format!("live: {}", s.edits.join(" ")));
        if ui.button("reset edits").clicked() {
            send(Command::ResetParams);
        }
    }

    ui.separator();
    ui.heading("Inspect");
    let label = |r: Option<&String>| match r {
        None => format!("output ({})", s.output_name),
        Some(n) => n.clone(),
    };
    let mut chosen = None;
    egui::ComboBox::from_id_salt("resource")
        .selected_text(label(c.inspected.as_ref()))
        .width(220.0)
        .show_ui(ui, |ui| {
            if ui
                .selectable_label(c.inspected.is_none(), label(None))
                .clicked()
            {
                chosen = Some(None);
            }
            for r in &s.resources {
                let text = format!("{} — {}", r.name, r.label);
                if ui
                    .selectable_label(c.inspected.as_ref() == Some(&r.name), text)
                    .clicked()
                {
                    chosen = Some(Some(r.name.clone()));
                }
            }
        });
    if let Some(choice) = chosen {
        c.inspected = choice;
        c.display = None;
        send(Command::Inspect(c.inspected.clone(), None));
    }
    let shown = c
        .inspected
        .as_ref()
        .and_then(|n| s.resources.iter().find(|r| &r.name == n));
    if let Some(row) = shown {
        let options = inspect::displays(&row.desc, row.words_per_texel);
        let current = c
            .display
            .unwrap_or_else(|| inspect::default_display(&row.desc));
        let mut picked = None;
        egui::ComboBox::from_id_salt("display")
            .selected_text(current.label())
            .show_ui(ui, |ui| {
                for d in options {
                    let same = std::mem::discriminant(&d) == std::mem::discriminant(&current)
                        && (d == current || matches!(d, Display::Bit(_)));
                    if ui.selectable_label(same, d.label()).clicked() {
                        picked = Some(d);
                    }
                }
            });
        if let (Display::Bit(_), ResourceDesc::Buffer { .. }) = (current, &row.desc) {
            let max = (row.words_per_texel * 32).max(1) - 1;
            if ui
                .add(egui::Slider::new(&mut c.bit, 0..=max).text("bit (slice)"))
                .changed()
            {
                picked = Some(Display::Bit(c.bit));
            }
        }
        if let Some(mut d) = picked {
            if let Display::Bit(_) = d {
                d = Display::Bit(c.bit);
            }
            c.display = Some(d);
            send(Command::Inspect(c.inspected.clone(), Some(d)));
        }
    }
}

fn light_controls(ui: &mut egui::Ui, c: &mut Controls, s: &Shared, send: &dyn Fn(Command)) {
    ui.separator();
    ui.heading("Light");
    if let Some(light) = &mut c.light {
        // No step_by: snapping would move the scene's own light on first show.
        let a = ui.add(
            egui::Slider::new(&mut light.azimuth, -180.0..=180.0)
                .text("azimuth °")
                .max_decimals(1),
        );
        let e = ui.add(
            egui::Slider::new(&mut light.elevation, -89.9..=89.9)
                .text("elevation °")
                .max_decimals(1),
        );
        if (a.changed() && by_user(&a)) || (e.changed() && by_user(&e)) {
            send(Command::Light(Some(light.direction())));
        }
    }
    if ui.button("scene light").clicked() {
        c.light = s.scene_light.map(LightAngles::from_direction);
        send(Command::Light(None));
    }
}

fn camera_controls(ui: &mut egui::Ui, c: &mut Controls, send: &dyn Fn(Command)) {
    ui.separator();
    ui.heading("Camera");
    ui.small("drag: orbit · right/shift-drag: pan · scroll: zoom");
    if ui.button("scene camera").clicked() {
        c.orbit = c.base_camera.as_ref().map(Orbit::from_camera);
        send(Command::Camera(None));
    }
    if ui.checkbox(&mut c.paused, "pause rendering").changed() {
        send(Command::Pause(c.paused));
    }
}

fn pass_table(ui: &mut egui::Ui, s: &Shared) {
    ui.heading("Passes");
    ui.small("in execution order; GPU ms = median of the last frames; MiB = what the pass writes");
    egui::Grid::new("pass_table")
        .num_columns(4)
        .striped(true)
        .show(ui, |ui| {
            ui.strong("pass");
            ui.strong("type");
            ui.strong("GPU ms");
            ui.strong("MiB");
            ui.end_row();
            for p in &s.passes {
                ui.label(&p.name);
                ui.label(&p.type_name);
                ui.label(
                    p.median_ms
                        .map(|m| format!("{m:.1}"))
                        .unwrap_or_else(|| "–".into()),
                );
                ui.label(mib(p.writes_bytes));
                ui.end_row();
            }
            ui.strong("frame");
            ui.label("");
            ui.strong(
                s.frame_median_ms
                    .map(|m| format!("{m:.1}"))
                    .unwrap_or_else(|| "–".into()),
            );
            ui.strong(mib(s.peak_bytes));
            ui.end_row();
        });
    ui.small("frame MiB = peak memory of the schedule");
    for (name, reason) in &s.culled {
        ui.small(format!("culled {name}: {reason}"));
    }
    for note in &s.notes {
        ui.small(format!("note: {note}"));
    }
    for line in &s.dropped {
        ui.colored_label(egui::Color32::from_rgb(230, 160, 60), line);
    }
}

fn viewport(ui: &mut egui::Ui, c: &mut Controls, s: &Shared, send: &dyn Fn(Command)) {
    let shown = if c.inspected.is_some() {
        s.inspected.clone()
    } else {
        s.output.clone()
    };
    let Some(shown) = shown else {
        let message = match (&s.inspect_error, &s.error) {
            (Some(e), _) if c.inspected.is_some() => e.as_str(),
            (_, Some(_)) => "no frame yet: fix the error above",
            _ => "building…",
        };
        ui.centered_and_justified(|ui| ui.label(message));
        return;
    };
    let stale = c
        .image
        .as_ref()
        .is_none_or(|(img, _)| !Arc::ptr_eq(img, &shown));
    if stale {
        let size = [shown.image.width() as usize, shown.image.height() as usize];
        let pixels = egui::ColorImage::from_rgba_unmultiplied(size, shown.image.as_raw());
        let texture = match c.image.take() {
            Some((_, mut t)) => {
                t.set(pixels, TextureOptions::NEAREST);
                t
            }
            None => ui
                .ctx()
                .load_texture("frame", pixels, TextureOptions::NEAREST),
        };
        c.image = Some((shown.clone(), texture));
    }
    let Some((_, texture)) = &c.image else {
        return;
    };
    let legend_height = 2.0 * ui.text_style_height(&egui::TextStyle::Small) + 8.0;
    let avail = ui.available_size() - egui::vec2(0.0, legend_height);
    let (w, h) = (shown.image.width() as f32, shown.image.height() as f32);
    let scale = (avail.x / w).min(avail.y / h).max(0.05);
    let response = ui.add(
        egui::Image::new(texture)
            .fit_to_exact_size(egui::vec2(w * scale, h * scale))
            .sense(egui::Sense::click_and_drag()),
    );
    let mut value = String::new();
    if let Some(pos) = response.hover_pos() {
        let local = (pos - response.rect.min) / scale;
        if let Some(v) = shown.value_at(local.x as u32, local.y as u32) {
            value = v;
        }
    }
    // Camera controls on the picture.
    if let (Some(orbit), Some(base)) = (&mut c.orbit, &c.base_camera) {
        let mut moved = false;
        let delta = response.drag_delta();
        if delta != egui::Vec2::ZERO {
            let pan = response.dragged_by(egui::PointerButton::Secondary)
                || response.dragged_by(egui::PointerButton::Middle)
                || ui.input(|i| i.modifiers.shift);
            if pan {
                orbit.pan(delta.x, delta.y, h * scale, base.fov_y_degrees.to_radians());
            } else {
                orbit.rotate(delta.x, delta.y);
            }
            moved = true;
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                orbit.zoom(scroll / 50.0);
                moved = true;
            }
        }
        if moved {
            send(Command::Camera(Some(orbit.camera(base))));
        }
    }
    ui.small(&shown.legend);
    ui.small(if value.is_empty() {
        format!("{}: hover for values", shown.name)
    } else {
        format!("{}: {value}", shown.name)
    });
}
