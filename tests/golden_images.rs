//! Golden images: the comparison every GPU test uses
//! (`tests/golden/<stem>.png`, `PLAIT_BLESS=1` to write them).
//!
//! A golden must tell techniques apart: the gallery's techniques differ from
//! each other mostly in the hair, by a few 1/255 over a few hundred pixels
//! (occupancy with and without its slab map, `tests/goldens.rs`), while the
//! background, the head and the ground are the same in all of them. So the
//! comparison looks at the **hair pixels** — those where the golden or the
//! render differs from the same scene rendered without hair (each scene's
//! `no_hair` golden): the strands, what they hide and the shadows they cast —
//! and holds three things there:
//!
//! 1. **changed pixels**: hair pixels off by more than [`CHANGED`] (2/255),
//!    at most [`MAX_CHANGED_FRACTION`] of them;
//! 2. **the hair mean**: the mean difference over the hair pixels, at most
//!    [`MAX_HAIR_MEAN`] — a change of 1% of every hair pixel's value (1 to
//!    2/255, below the changed-pixel threshold) fails here;
//! 3. **outliers**: pixels off by more than [`OUTLIER`] from every pixel of
//!    the other image's 3×3 neighbourhood, at most [`MAX_OUTLIERS`] — one
//!    strand that vanished fails here however small it is.
//!
//! Why so tight: the goldens are made with, and CI runs on, one driver —
//! Mesa's lavapipe, pinned by `scripts/test.sh` — which renders every gallery
//! pipeline bit for bit the same frame after frame (`tests/determinism.rs`);
//! the only slack needed is for 1/255 roundings of colours summed in another
//! order. Another driver rasterizes lines differently and fails these
//! goldens: on it, look at the difference images and re-bless. So each
//! golden records the driver it was made on (`<stem>.driver`, written when it
//! is blessed), and a failure on another driver names both.

use image::RgbaImage;

use crate::{bless, driver, rel, repo_root};

/// Per-pixel difference: the largest absolute difference over R, G, B, A.
pub fn pixel_diff(a: &image::Rgba<u8>, b: &image::Rgba<u8>) -> u8 {
    a.0.iter()
        .zip(b.0.iter())
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

/// A pixel belongs to the hair when it differs from the hair-less image by more than this.
pub const HAIR: u8 = 2;
/// A hair pixel is changed when it differs from the golden by more than this…
pub const CHANGED: u8 = 2;
/// …and at most this fraction of the hair pixels may be changed (0.1%).
pub const MAX_CHANGED_FRACTION: f64 = 0.001;
/// The mean difference over the hair pixels must stay within 0.25/255.
pub const MAX_HAIR_MEAN: f64 = 0.25;
/// A pixel is an outlier when some channel is off by more than 24/255 from
/// every pixel of the other image's 3×3 neighbourhood (checked both ways)…
pub const OUTLIER: u8 = 24;
/// …and at most 4 may be.
pub const MAX_OUTLIERS: u64 = 4;

#[derive(Debug)]
pub struct Comparison {
    /// Pixels where the golden or the render differs from the hair-less image.
    pub hair_pixels: u64,
    /// Hair pixels whose difference exceeds [`CHANGED`].
    pub changed: u64,
    /// Mean difference over the hair pixels, in 0..=255.
    pub hair_mean: f64,
    /// Pixels farther than [`OUTLIER`] from the other image's neighbourhood.
    pub outliers: u64,
    /// Mean difference over the whole image (for messages).
    pub mean: f64,
    pub max: u8,
    pub difference: RgbaImage,
}

impl Comparison {
    /// The largest number of changed pixels allowed for this many hair pixels.
    pub fn changed_limit(&self) -> u64 {
        (self.hair_pixels as f64 * MAX_CHANGED_FRACTION).floor() as u64
    }

    pub fn passes(&self) -> bool {
        self.changed <= self.changed_limit()
            && self.hair_mean <= MAX_HAIR_MEAN
            && self.outliers <= MAX_OUTLIERS
    }

    pub fn summary(&self) -> String {
        format!(
            "{} of {} hair pixels differ by more than {CHANGED}/255 (limit {}), hair mean {:.3}/255 \
             (limit {MAX_HAIR_MEAN}), {} outliers beyond {OUTLIER}/255 of their neighbourhood \
             (limit {MAX_OUTLIERS}), max {}",
            self.changed,
            self.hair_pixels,
            self.changed_limit(),
            self.hair_mean,
            self.outliers,
            self.max
        )
    }
}

/// The smallest difference between `p` and `other`'s 3×3 neighbourhood of (x, y).
fn nearest(p: &image::Rgba<u8>, other: &RgbaImage, x: u32, y: u32) -> u8 {
    let (w, h) = (other.width() as i64, other.height() as i64);
    let mut best = u8::MAX;
    for dy in -1..=1i64 {
        for dx in -1..=1i64 {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx >= 0 && ny >= 0 && nx < w && ny < h {
                best = best.min(pixel_diff(p, other.get_pixel(nx as u32, ny as u32)));
            }
        }
    }
    best
}

/// Compare a render with its golden over the hair pixels that `no_hair`
/// (the same scene, size and lighting without hair) tells apart.
pub fn compare(actual: &RgbaImage, golden: &RgbaImage, no_hair: &RgbaImage) -> Comparison {
    assert_eq!(
        actual.dimensions(),
        no_hair.dimensions(),
        "the hair-less image must have the render's size"
    );
    let mut difference = RgbaImage::new(actual.width(), actual.height());
    let (mut sum, mut outliers, mut max) = (0u64, 0u64, 0u8);
    let (mut hair_pixels, mut hair_sum, mut changed) = (0u64, 0u64, 0u64);
    for (x, y, d) in difference.enumerate_pixels_mut() {
        let (a, g, n) = (
            actual.get_pixel(x, y),
            golden.get_pixel(x, y),
            no_hair.get_pixel(x, y),
        );
        let diff = pixel_diff(a, g);
        sum += diff as u64;
        max = max.max(diff);
        if pixel_diff(a, n) > HAIR || pixel_diff(g, n) > HAIR {
            hair_pixels += 1;
            hair_sum += diff as u64;
            changed += u64::from(diff > CHANGED);
        }
        if nearest(a, golden, x, y) > OUTLIER || nearest(g, actual, x, y) > OUTLIER {
            outliers += 1;
        }
        // Red where it differs, scaled ×16 so 1/255 is visible; grey background.
        let grey = (g.0[0] as u16 + g.0[1] as u16 + g.0[2] as u16) / 12;
        *d = image::Rgba([
            (diff as u16 * 16).min(255).max(grey) as u8,
            grey as u8,
            grey as u8,
            255,
        ]);
    }
    let n = (actual.width() as u64 * actual.height() as u64).max(1) as f64;
    Comparison {
        hair_pixels,
        changed,
        hair_mean: hair_sum as f64 / hair_pixels.max(1) as f64,
        outliers,
        mean: sum as f64 / n,
        max,
        difference,
    }
}

/// A committed golden image, `tests/golden/<stem>.png`.
pub fn load_golden(stem: &str) -> Result<RgbaImage, String> {
    let path = repo_root().join("tests/golden").join(format!("{stem}.png"));
    image::open(&path)
        .map(|g| g.to_rgba8())
        .map_err(|e| format!("no usable golden image {} ({e})", rel(&path)))
}

/// Compare with `tests/golden/<stem>.png` over the hair pixels `no_hair`
/// tells apart, or write it with `PLAIT_BLESS=1`. On failure writes
/// `<stem>.actual.png` and `<stem>.difference.png` beside it.
pub fn check_golden(stem: &str, actual: &RgbaImage, no_hair: &RgbaImage) -> Result<(), String> {
    let dir = repo_root().join("tests/golden");
    let golden_path = dir.join(format!("{stem}.png"));
    let actual_path = dir.join(format!("{stem}.actual.png"));
    let diff_path = dir.join(format!("{stem}.difference.png"));
    let _ = std::fs::remove_file(&actual_path);
    let _ = std::fs::remove_file(&diff_path);
    if bless() {
        actual
            .save(&golden_path)
            .map_err(|e| format!("writing {}: {e}", golden_path.display()))?;
        let driver_path = dir.join(format!("{stem}.driver"));
        std::fs::write(&driver_path, format!("{}\n", driver()))
            .map_err(|e| format!("writing {}: {e}", driver_path.display()))?;
        eprintln!("blessed {} (on {})", rel(&golden_path), driver());
        return Ok(());
    }
    let save_actual = || {
        actual
            .save(&actual_path)
            .map(|_| rel(&actual_path))
            .unwrap_or_else(|e| format!("(could not write {}: {e})", actual_path.display()))
    };
    let golden = match load_golden(stem) {
        Ok(g) => g,
        Err(e) => {
            return Err(format!(
                "{stem}: {e}; wrote {} — check it and rerun with PLAIT_BLESS=1 to commit it",
                save_actual()
            ));
        }
    };
    if golden.dimensions() != actual.dimensions() {
        return Err(format!(
            "{stem}: golden {} is {:?}, render is {:?}; wrote {}",
            rel(&golden_path),
            golden.dimensions(),
            actual.dimensions(),
            save_actual()
        ));
    }
    let c = compare(actual, &golden, no_hair);
    eprintln!("{stem}: {}", c.summary());
    if c.passes() {
        return Ok(());
    }
    let actual_written = save_actual();
    let _ = c.difference.save(&diff_path);
    Err(format!(
        "{stem}: render differs from {}: {}; see {actual_written} and {}{}",
        rel(&golden_path),
        c.summary(),
        rel(&diff_path),
        driver_note(recorded_driver(stem).as_deref(), driver())
    ))
}

/// The driver `tests/golden/<stem>.driver` says the golden was made on.
pub fn recorded_driver(stem: &str) -> Option<String> {
    let path = repo_root()
        .join("tests/golden")
        .join(format!("{stem}.driver"));
    let text = std::fs::read_to_string(path).ok()?;
    Some(text.trim().to_string()).filter(|t| !t.is_empty())
}

/// What a failed comparison adds about drivers: nothing when the golden was
/// made on this run's driver; otherwise both, so a driver change is named
/// rather than read as a change of the technique.
pub fn driver_note(recorded: Option<&str>, current: &str) -> String {
    match recorded {
        Some(r) if r == current => String::new(),
        Some(r) => format!(
            ". The golden was made on `{r}`; this run renders on `{current}`: another driver \
             rasterizes lines a little differently. Look at the difference image; if only the \
             driver moved it, re-bless on the driver CI installs (scripts/ensure-vulkan.sh)"
        ),
        None => format!(
            ". No driver is recorded for this golden (its .driver file is missing); this run \
             renders on `{current}`"
        ),
    }
}

/// The hair-less image of a golden scene: rendered, held to its own golden
/// `<stem>.png` pixel for pixel (every pixel counts as "hair" against an
/// all-black image), and returned to mask the scene's other goldens.
pub fn check_no_hair(stem: &str, actual: &RgbaImage) -> Result<(), String> {
    let black = RgbaImage::new(actual.width(), actual.height());
    // Against black, every pixel that is not black is a "hair" pixel, so the
    // whole frame is held to the limits.
    check_golden(stem, actual, &black)
}
