//! Shared by the benchmarks: the raster floor of a schedule, the default
//! pipeline written by hand against wgpu, GPU timestamps and medians.
#![allow(dead_code)] // each benchmark uses a part

pub mod floor;
pub mod floor_args;
pub mod handwritten;
pub mod timing;
