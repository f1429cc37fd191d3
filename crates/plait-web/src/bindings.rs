//! What the page calls (wasm-bindgen). Every call returns a promise; an
//! error rejects it with the CLI's text for the same mistake.

use std::cell::RefCell;
use std::rc::Rc;

use js_sys::{Object, Reflect, Uint8Array};
use wasm_bindgen::prelude::*;

use crate::engine::{Engine, Request};

/// The engine the page holds: one device, one build at a time.
#[wasm_bindgen]
pub struct WebEngine {
    /// `None` while a frame renders.
    inner: Rc<RefCell<Option<Engine>>>,
    adapter: String,
}

/// Opens the page's WebGPU device and reads the built-in library.
#[wasm_bindgen]
pub async fn open() -> Result<WebEngine, JsValue> {
    crate::occlusion_shim::install()?;
    let engine = Engine::open().await.map_err(|e| JsValue::from_str(&e))?;
    Ok(WebEngine {
        adapter: engine.adapter(),
        inner: Rc::new(RefCell::new(Some(engine))),
    })
}

/// The gallery's pipeline files, as JSON (a list of names).
#[wasm_bindgen]
pub fn gallery() -> String {
    serde_json::to_string(&crate::engine::gallery()).unwrap_or_default()
}

fn set(object: &Object, key: &str, value: &JsValue) -> Result<(), JsValue> {
    Reflect::set(object, &JsValue::from_str(key), value).map(|_| ())
}

#[wasm_bindgen]
impl WebEngine {
    /// The adapter, as `plait render` names it.
    pub fn adapter(&self) -> String {
        self.adapter.clone()
    }

    /// Renders the request (JSON: pipeline, width, height, sets, yaw,
    /// pitch); resolves to `{width, height, pixels, report, notes,
    /// controls, timings, graph}`: the report, notes, controls and timings
    /// as JSON, the graph as SVG text.
    pub fn render(&self, request: &str) -> js_sys::Promise {
        let inner = self.inner.clone();
        let request: Result<Request, String> =
            serde_json::from_str(request).map_err(|e| format!("bad request: {e}"));
        wasm_bindgen_futures::future_to_promise(async move {
            let request = request.map_err(|e| JsValue::from_str(&e))?;
            // One frame at a time: the engine is taken out while it renders
            // (no borrow held across the await), so a second call meanwhile
            // is refused instead of panicking.
            let mut engine = inner
                .borrow_mut()
                .take()
                .ok_or_else(|| JsValue::from_str("a frame is still rendering"))?;
            let frame = engine.render(&request).await;
            *inner.borrow_mut() = Some(engine);
            let frame = frame.map_err(|e| JsValue::from_str(&e))?;
            let out = Object::new();
            set(&out, "width", &frame.width.into())?;
            set(&out, "height", &frame.height.into())?;
            set(
                &out,
                "pixels",
                &Uint8Array::from(frame.rgba.as_slice()).into(),
            )?;
            let report = serde_json::to_string(&frame.report).unwrap_or_default();
            set(&out, "report", &report.into())?;
            let notes = serde_json::to_string(&frame.notes).unwrap_or_default();
            set(&out, "notes", &notes.into())?;
            let controls = serde_json::to_string(&frame.controls).unwrap_or_default();
            set(&out, "controls", &controls.into())?;
            let timings = serde_json::to_string(&frame.timings).unwrap_or_default();
            set(&out, "timings", &timings.into())?;
            set(&out, "graph", &frame.graph.into())?;
            Ok(out.into())
        })
    }
}
