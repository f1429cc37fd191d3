//! Render and compute pipelines keyed by everything that defines them, so a
//! pass built twice — two draws of one pass, or the same pass in several
//! variants of an A/B run — compiles its shader and pipeline once.
//!
//! The key hashes the shader's path, source and defines with the pipeline's
//! fixed-function state and bind group layout entries. Layouts themselves are
//! not part of the key: WebGPU treats bind group layouts with equal entries as
//! interchangeable, so a cached pipeline accepts the bind groups of any
//! schedule whose layout entries match.

use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::Mutex;

/// Pipelines built so far on one device.
#[derive(Default)]
pub struct PipelineCache {
    render: Mutex<HashMap<u64, wgpu::RenderPipeline>>,
    compute: Mutex<HashMap<u64, wgpu::ComputePipeline>>,
    hits: Mutex<u64>,
}

/// A stable digest of the things a pipeline is made from.
pub fn key(parts: &[&dyn std::fmt::Debug]) -> u64 {
    let mut h = DefaultHasher::new();
    for p in parts {
        format!("{p:?}").hash(&mut h);
    }
    h.finish()
}

impl PipelineCache {
    /// The cached render pipeline for `key`, or the one `make` builds.
    pub fn render(
        &self,
        key: u64,
        make: impl FnOnce() -> wgpu::RenderPipeline,
    ) -> wgpu::RenderPipeline {
        self.get_or_make(&self.render, key, make)
    }

    /// The cached compute pipeline for `key`, or the one `make` builds.
    pub fn compute(
        &self,
        key: u64,
        make: impl FnOnce() -> wgpu::ComputePipeline,
    ) -> wgpu::ComputePipeline {
        self.get_or_make(&self.compute, key, make)
    }

    /// How many builds the cache saved.
    pub fn hits(&self) -> u64 {
        self.hits.lock().map(|h| *h).unwrap_or(0)
    }

    fn get_or_make<P: Clone>(
        &self,
        map: &Mutex<HashMap<u64, P>>,
        key: u64,
        make: impl FnOnce() -> P,
    ) -> P {
        if let Some(p) = map.lock().ok().and_then(|m| m.get(&key).cloned()) {
            if let Ok(mut h) = self.hits.lock() {
                *h += 1;
            }
            return p;
        }
        let made = make();
        if let Ok(mut m) = map.lock() {
            m.insert(key, made.clone());
        }
        made
    }
}
