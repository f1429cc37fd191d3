//! The occupancy maps as the shaders read them, on the CPU (Sintorn &
//! Assarsson 2009 §3.1-3.2). The `occupancy` and `slab` pass types that build
//! the maps are data (`shaders/passes/occupancy.toml`, `slab.toml`).
//!
//! [`order_estimate`] is the CPU mirror of `order_estimate` in
//! `shaders/lib/occupancy.wgsl` (§3.2); a GPU test proves them equal.

/// The maps of one texel, as the shaders read them.
#[derive(Clone, Debug, Default)]
pub struct TexelMaps {
    /// Occupancy bits, 32 slices per word.
    pub bits: Vec<u32>,
    /// Fragment counts, one per slab of `32 · bits.len() / counts.len()` slices.
    pub counts: Vec<u32>,
}

/// Estimated number of fragments in front of relative depth `rel` in the
/// texel's range (§3.2) — the CPU mirror of the WGSL `order_estimate`.
pub fn order_estimate(maps: &TexelMaps, rel: f32) -> f32 {
    order_estimate_excluding(maps, rel, 0.0)
}

/// The order of a fragment recorded in the maps itself: the fragments
/// strictly in front of it, its own count left out (docs/design.md, "In front
/// of") — the CPU mirror of the WGSL `fragment_order`.
pub fn fragment_order(maps: &TexelMaps, rel: f32) -> f32 {
    order_estimate_excluding(maps, rel, 1.0)
}

/// `own` fragments (0 or 1) at `rel` are not counted in front of it.
fn order_estimate_excluding(maps: &TexelMaps, rel: f32, own: f32) -> f32 {
    let words = maps.bits.len() as u32;
    let slabs = maps.counts.len() as u32;
    if words == 0 || slabs == 0 || rel <= 0.0 {
        return 0.0;
    }
    if rel >= 1.0 {
        return (maps.counts.iter().map(|&c| c as f32).sum::<f32>() - own).max(0.0);
    }
    let slices = words * 32;
    let per_slab = (slices / slabs).max(1);
    let s = rel * slices as f32;
    let slice = (s.floor() as u32).min(slices - 1);
    let frac = (s - slice as f32).clamp(0.0, 1.0);
    let slab = (slice / per_slab).min(slabs - 1);
    let before: f32 = maps.counts[..slab as usize].iter().map(|&c| c as f32).sum();
    let first = slab * per_slab;
    let count_bits = |from: u32, to: u32| {
        (from..to)
            .filter(|&k| maps.bits[(k / 32) as usize] >> (k % 32) & 1 == 1)
            .count() as u32
    };
    let set_in_slab = count_bits(first, first + per_slab);
    let per_bit = if set_in_slab > 0 {
        maps.counts[slab as usize] as f32 / set_in_slab as f32
    } else {
        0.0
    };
    let at_start = before + per_bit * count_bits(first, slice) as f32;
    let at_end = before + per_bit * count_bits(first, slice + 1) as f32;
    at_start + (at_end - at_start - own).max(0.0) * frac
}

/// Build a texel's maps from fragment relative depths in [0, 1], as the
/// occupancy and slab passes do.
pub fn maps_from_depths(depths: &[f32], words: u32, slabs: u32) -> TexelMaps {
    let slices = words * 32;
    let mut maps = TexelMaps {
        bits: vec![0; words as usize],
        counts: vec![0; slabs as usize],
    };
    for &d in depths {
        let slice = ((d.max(0.0) * slices as f32) as u32).min(slices - 1);
        maps.bits[(slice / 32) as usize] |= 1 << (slice % 32);
        let slab = ((d.clamp(0.0, 1.0) * slabs as f32) as u32).min(slabs - 1);
        maps.counts[slab as usize] += 1;
    }
    maps
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(depths: &[f32], rel: f32) -> f32 {
        depths.iter().filter(|&&d| d < rel).count() as f32
    }

    /// A deterministic spread of clustered fragment depths (a stray strand, then a clump).
    fn depths() -> Vec<f32> {
        let mut v = vec![0.01];
        let mut x = 0x1234_5678u32;
        for _ in 0..300 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let u = (x % 10_000) as f32 / 10_000.0;
            v.push(0.35 + 0.3 * u * u);
        }
        v.push(0.97);
        v
    }

    #[test]
    fn exact_at_slab_boundaries() {
        let d = depths();
        let maps = maps_from_depths(&d, 4, 4);
        for boundary in [0.25f32, 0.5, 0.75] {
            let est = order_estimate(&maps, boundary);
            assert!(
                (est - exact(&d, boundary)).abs() < 1e-3,
                "at {boundary}: {est} vs {}",
                exact(&d, boundary)
            );
        }
        assert_eq!(order_estimate(&maps, 1.0), d.len() as f32);
        assert_eq!(order_estimate(&maps, 0.0), 0.0);
    }

    /// Inside a slab the estimate errs by less than that slab's count F_i,
    /// and (for this clustered case) by far less than the occupancy-only estimate.
    #[test]
    fn bounded_inside_slabs() {
        let d = depths();
        let maps = maps_from_depths(&d, 4, 4);
        let no_slab = maps_from_depths(&d, 4, 1);
        let (mut err, mut err_no_slab) = (0.0f32, 0.0f32);
        for i in 0..=1000 {
            let rel = i as f32 / 1000.0;
            let slab = ((rel * 4.0) as usize).min(3);
            let e = (order_estimate(&maps, rel) - exact(&d, rel)).abs();
            assert!(
                e <= maps.counts[slab] as f32 + 1e-3,
                "rel {rel}: error {e} > F_i {}",
                maps.counts[slab]
            );
            err = err.max(e);
            err_no_slab = err_no_slab.max((order_estimate(&no_slab, rel) - exact(&d, rel)).abs());
        }
        assert!(
            err < err_no_slab,
            "slabs should help: {err} vs {err_no_slab}"
        );
    }

    #[test]
    fn monotonic() {
        let d = depths();
        let maps = maps_from_depths(&d, 4, 4);
        let mut last = 0.0;
        for i in 0..=2000 {
            let o = order_estimate(&maps, i as f32 / 2000.0);
            assert!(o + 1e-4 >= last);
            last = o;
        }
    }

    /// A fragment never counts itself (docs/design.md, "In front of"): alone
    /// in its slice it gets exactly the fragments before it.
    #[test]
    fn a_fragment_does_not_count_itself() {
        let d = depths();
        let maps = maps_from_depths(&d, 4, 4);
        assert_eq!(
            fragment_order(&maps, 0.01),
            0.0,
            "the stray fragment in front of all"
        );
        assert_eq!(
            fragment_order(&maps, 0.97),
            (d.len() - 1) as f32,
            "the farthest, alone in its slab"
        );
        assert_eq!(fragment_order(&maps, 1.0), (d.len() - 1) as f32);
        // Each fragment alone in its slice: the strict count exactly, where
        // the point estimate adds the fragment's own fraction of its slice.
        let spread: Vec<f32> = (0..40).map(|i| (i as f32 * 3.0 + 1.3) / 128.0).collect();
        let sparse = maps_from_depths(&spread, 4, 4);
        for (i, &x) in spread.iter().enumerate() {
            assert!(
                (fragment_order(&sparse, x) - i as f32).abs() < 1e-4,
                "fragment {i}"
            );
            assert!(
                order_estimate(&sparse, x) > i as f32 + 0.2,
                "fragment {i} counts itself in part"
            );
        }
        // Never more than the point estimate, never negative.
        for &x in &d {
            let (own_left_out, point) = (fragment_order(&maps, x), order_estimate(&maps, x));
            assert!(
                (0.0..=point + 1e-4).contains(&own_left_out),
                "at {x}: {own_left_out} vs {point}"
            );
        }
    }
}
