//! Fuzzing every parser a user can feed (issue 14): the pipeline loader
//! (with `extends` and `--set`) and compiler, the scene loader, the `.hair`,
//! `.tfx`, USD text (`.usda`) and binary (`.usdc`) readers, the glTF mesh
//! reader, and shader composition (naga_oil + naga). One file per target.
//!
//! Property-based and mutation-driven with proptest: each input is a file
//! from the repository (pipelines, scenes, shaders, byte-built assets) with
//! up to 8 mutations — bit flips, interesting bytes and words, inserted,
//! deleted or duplicated ranges, and tokens of the target's language. The
//! property: an answer (Ok or an error) and no panic. Where the parser also
//! writes (`.hair`, `.tfx`), what it reads must write back and read again
//! to the same thing.
//!
//! Every input is bounded in time: a watchdog aborts the process, printing
//! the input, if one takes longer than `HANG_SECONDS`. Memory per input is
//! bounded by the parsers' own size checks, and checked: this binary's
//! allocator refuses (the process aborts, naming the target) any single
//! allocation over `MAX_ALLOCATION` or more than `MAX_LIVE` bytes live at
//! once, so a parser that trusts a size a file claims fails here even where
//! the system would have lent it the memory.
//!
//! The suite runs 408,000 inputs (a few seconds per target);
//! `PLAIT_FUZZ_SCALE=K` runs K times as many, and `PLAIT_FUZZ_SEED=N` another
//! deterministic stream (the suite's is fixed, so CI is repeatable). The
//! long run (the book's Reliability page): `PLAIT_FUZZ_SCALE=41 PLAIT_FUZZ_SEED=2 cargo test -p
//! plait-tests --test fuzz -- --nocapture --test-threads=2`.
//!
//! Not coverage-guided: that is `fuzz/` (cargo-fuzz, nightly, its own
//! workspace); proptest runs on stable inside the ordinary test suite, so CI
//! keeps fuzzing every parser, shaders included.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

use plait_hair::tfx::TfxFile;
use plait_hair::{Aabb, Asset, HairFile, Scene, Strands};
use plait_tests::{files_with_ext, pipeline_files, repo_root};

const HANG_SECONDS: u64 = 20;

/// Cases per target: the suite's default times `PLAIT_FUZZ_SCALE` (1).
fn cases(default: u32) -> u32 {
    let scale: u32 = std::env::var("PLAIT_FUZZ_SCALE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    default.saturating_mul(scale)
}

fn runner(default_cases: u32) -> TestRunner {
    let seed: u64 = std::env::var("PLAIT_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(14);
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let config = Config {
        cases: cases(default_cases),
        failure_persistence: None,
        max_shrink_iters: 2000,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &key))
}

// ---------------------------------------------------------------- watchdog

/// One fuzz thread's input being run, and when it started (ms since
/// `EPOCH`; 0 = idle). Each thread has its own, so a hang on one is timed and
/// reported with its own input while the other thread moves on.
#[derive(Default)]
struct Slot {
    started_ms: AtomicU64,
    input: Mutex<(String, Vec<u8>)>,
}

/// Every fuzz thread's slot, for the watchdog to scan.
static SLOTS: Mutex<Vec<Arc<Slot>>> = Mutex::new(Vec::new());
static EPOCH: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();

thread_local! {
    static SLOT: Arc<Slot> = {
        let slot = Arc::new(Slot::default());
        SLOTS.lock().unwrap_or_else(|p| p.into_inner()).push(slot.clone());
        slot
    };
    /// The target this thread runs, for the allocator's refusal message: a
    /// const `Cell` of a `&'static str`, which never allocates.
    static TARGET: Cell<&'static str> = const { Cell::new("") };
}

fn now_ms() -> u64 {
    EPOCH.get_or_init(Instant::now).elapsed().as_millis() as u64 + 1
}

/// Every slot whose input has run longer than `limit_ms` at `now`: its
/// target and input, as the watchdog prints them.
fn hung(slots: &[Arc<Slot>], now: u64, limit_ms: u64) -> Vec<String> {
    slots
        .iter()
        .filter(|slot| {
            let started = slot.started_ms.load(Ordering::Relaxed);
            started != 0 && now.saturating_sub(started) > limit_ms
        })
        .map(|slot| {
            let input = slot.input.lock().unwrap_or_else(|p| p.into_inner());
            format!("{}: {:?}", input.0, String::from_utf8_lossy(&input.1))
        })
        .collect()
}

fn start_watchdog() {
    std::thread::spawn(|| {
        loop {
            std::thread::sleep(Duration::from_millis(500));
            let slots = SLOTS.lock().unwrap_or_else(|p| p.into_inner()).clone();
            let hangs = hung(&slots, now_ms(), HANG_SECONDS * 1000);
            if !hangs.is_empty() {
                eprintln!(
                    "HANG: one input ran for more than {HANG_SECONDS} s:\n{}",
                    hangs.join("\n")
                );
                std::process::abort();
            }
        }
    });
}

/// Runs `f` on `input` under the watchdog, timed in this thread's slot.
fn guarded<T>(target: &'static str, input: &[u8], f: impl FnOnce() -> T) -> T {
    static WATCHDOG: std::sync::Once = std::sync::Once::new();
    WATCHDOG.call_once(start_watchdog);
    TARGET.with(|t| t.set(target));
    SLOT.with(|slot| {
        {
            let mut current = slot.input.lock().unwrap_or_else(|p| p.into_inner());
            current.0.clear();
            current.0.push_str(target);
            current.1.clear();
            current.1.extend_from_slice(input);
        }
        slot.started_ms.store(now_ms(), Ordering::Relaxed);
        // Idle again when `f` returns or unwinds (proptest catches a
        // panicking input, and the thread may end with the test).
        struct Idle<'a>(&'a AtomicU64);
        impl Drop for Idle<'_> {
            fn drop(&mut self) {
                self.0.store(0, Ordering::Relaxed);
            }
        }
        let _idle = Idle(&slot.started_ms);
        f()
    })
}

/// Two threads, one stuck: the watchdog's scan names the stuck one's input,
/// whichever thread started last.
#[test]
fn each_fuzz_thread_has_its_own_hang_timer() {
    let slot = |target: &str, input: &[u8], started_ms: u64| {
        let s = Slot::default();
        *s.input.lock().unwrap() = (target.to_owned(), input.to_vec());
        s.started_ms.store(started_ms, Ordering::Relaxed);
        Arc::new(s)
    };
    // A timer shared by both threads would follow the last start (busy's)
    // and never see the stuck input.
    let stuck = slot("scene", b"stuck input", 1_000);
    let busy = slot("hair", b"quick input", 20_000);
    let idle = slot("tfx", b"done", 0);
    let slots = [stuck, busy, idle];
    assert!(hung(&slots, 20_500, 20_000).is_empty());
    assert_eq!(
        hung(&slots, 21_500, 20_000),
        ["scene: \"stuck input\"".to_owned()]
    );
}

// --------------------------------------------------------------- allocator

/// The largest single allocation a fuzz input may cause.
const MAX_ALLOCATION: usize = 1 << 30;
/// The most bytes live at once (both test threads together).
const MAX_LIVE: usize = 3 << 30;

/// The system allocator, refusing what no small input should need (the
/// refusal aborts the process: the run fails, naming the target).
struct Bounded;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static REFUSED: AtomicBool = AtomicBool::new(false);

impl Bounded {
    fn refuse(size: usize) -> *mut u8 {
        // Once: printing allocates, and must not be refused in turn.
        if !REFUSED.swap(true, Ordering::SeqCst) {
            // This thread's target, without allocating (a thread being
            // torn down has none).
            let target = TARGET.try_with(Cell::get).unwrap_or("");
            eprintln!(
                "OUT OF BOUNDS: fuzz target {target} asked for {size} bytes ({} live): a size a file claims was trusted",
                LIVE.load(Ordering::Relaxed)
            );
        }
        std::ptr::null_mut()
    }
}

// A global allocator is unsafe by nature; this one only counts and refuses.
// SAFETY: forwards to the system allocator, or returns null (allowed).
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Bounded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let size = layout.size();
        if size > MAX_ALLOCATION || LIVE.fetch_add(size, Ordering::Relaxed) + size > MAX_LIVE {
            if size <= MAX_ALLOCATION {
                LIVE.fetch_sub(size, Ordering::Relaxed);
            }
            return Bounded::refuse(size);
        }
        // SAFETY: the caller's layout, as given.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let size = layout.size();
        if size > MAX_ALLOCATION || LIVE.fetch_add(size, Ordering::Relaxed) + size > MAX_LIVE {
            if size <= MAX_ALLOCATION {
                LIVE.fetch_sub(size, Ordering::Relaxed);
            }
            return Bounded::refuse(size);
        }
        // SAFETY: the caller's layout, as given.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: allocated by `System` with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old {
            let grow = new_size - old;
            if new_size > MAX_ALLOCATION
                || LIVE.fetch_add(grow, Ordering::Relaxed) + grow > MAX_LIVE
            {
                if new_size <= MAX_ALLOCATION {
                    LIVE.fetch_sub(grow, Ordering::Relaxed);
                }
                return Bounded::refuse(new_size);
            }
        } else {
            LIVE.fetch_sub(old - new_size, Ordering::Relaxed);
        }
        // SAFETY: allocated by `System` with this layout.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            // The old block stays: undo the accounting.
            if new_size > old {
                LIVE.fetch_sub(new_size - old, Ordering::Relaxed);
            } else {
                LIVE.fetch_add(old - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Bounded = Bounded;

// --------------------------------------------------------------- mutations

#[derive(Debug, Clone)]
enum Mutation {
    FlipBit { at: usize, bit: u8 },
    SetByte { at: usize, byte: u8 },
    SetWord { at: usize, word: usize },
    Insert { at: usize, bytes: Vec<u8> },
    InsertToken { at: usize, token: usize },
    Delete { at: usize, len: usize },
    Duplicate { from: usize, len: usize, to: usize },
}

/// 32-bit values that make parsers take their edge paths: counts, sizes,
/// header sizes, float specials, TressFX versions.
const WORDS: [u32; 18] = [
    0,
    1,
    2,
    3,
    4,
    16,
    64,
    160,
    296,
    65535,
    0x7fff_ffff,
    0xffff_ffff,
    0x4040_0000, // 3.0
    0x4080_0000, // 4.0
    0x7fc0_0000, // NaN
    0x7f80_0000, // +inf
    0xff80_0000, // -inf
    0x0000_0001, // smallest subnormal
];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::FlipBit { at, bit }),
        (
            any::<usize>(),
            prop_oneof![Just(0u8), Just(0xff), Just(0x7f), Just(0x80), any::<u8>()]
        )
            .prop_map(|(at, byte)| Mutation::SetByte { at, byte }),
        (any::<usize>(), 0..WORDS.len()).prop_map(|(at, word)| Mutation::SetWord { at, word }),
        (any::<usize>(), vec(any::<u8>(), 1..16))
            .prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
        (any::<usize>(), any::<usize>())
            .prop_map(|(at, token)| Mutation::InsertToken { at, token }),
        (any::<usize>(), 1usize..64).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (any::<usize>(), 1usize..256, any::<usize>())
            .prop_map(|(from, len, to)| Mutation::Duplicate { from, len, to }),
    ]
}

fn apply(mut data: Vec<u8>, mutations: &[Mutation], tokens: &[&str]) -> Vec<u8> {
    for m in mutations {
        let n = data.len();
        match m {
            Mutation::FlipBit { at, bit } if n > 0 => data[at % n] ^= 1 << bit,
            Mutation::SetByte { at, byte } if n > 0 => data[at % n] = *byte,
            Mutation::SetWord { at, word } if n >= 4 => {
                // aligned, as header fields are
                let at = (at % (n / 4)) * 4;
                data[at..at + 4].copy_from_slice(&WORDS[*word].to_le_bytes());
            }
            Mutation::Insert { at, bytes } => {
                let at = at % (n + 1);
                data.splice(at..at, bytes.iter().copied());
            }
            Mutation::InsertToken { at, token } if !tokens.is_empty() => {
                let at = at % (n + 1);
                data.splice(at..at, tokens[token % tokens.len()].bytes());
            }
            Mutation::Delete { at, len } if n > 0 => {
                let at = at % n;
                data.drain(at..(at + len).min(n));
            }
            Mutation::Duplicate { from, len, to } if n > 0 => {
                let from = from % n;
                let piece = data[from..(from + len).min(n)].to_vec();
                let to = to % (n + 1);
                data.splice(to..to, piece);
            }
            _ => {}
        }
    }
    data
}

/// A seed (by index) with up to 8 mutations.
fn mutated(seeds: &[Vec<u8>], tokens: &'static [&'static str]) -> impl Strategy<Value = Vec<u8>> {
    let seeds = seeds.to_vec();
    (0..seeds.len(), vec(mutation(), 0..8))
        .prop_map(move |(i, ms)| apply(seeds[i].clone(), &ms, tokens))
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("seed {}: {e}", path.display()))
}

/// Runs the target over its cases and prints how many and how fast. At
/// least `min_accepted` (a fraction) of the *mutated* inputs must be
/// accepted: an input equal to one of `seeds` (no mutation drawn, about 1 in
/// 8, or mutations that undo each other) is counted apart, so a reader that
/// accepted its seeds and rejected every mutant would fail. Each target's
/// floor is half the fraction measured at the default seed.
fn fuzz(
    target: &'static str,
    default_cases: u32,
    min_accepted: f64,
    seeds: &[Vec<u8>],
    strategy: impl Strategy<Value = Vec<u8>>,
    check: impl FnMut(&[u8]) -> Result<bool, TestCaseError>,
) {
    let seeds: std::collections::HashSet<&[u8]> = seeds.iter().map(Vec::as_slice).collect();
    let mut runner = runner(default_cases);
    let check = std::cell::RefCell::new(check);
    // (inputs, accepted) for the seeds as they are, then for mutated inputs.
    let counts = std::cell::Cell::new([[0u64; 2]; 2]);
    let start = Instant::now();
    let result = runner.run(&strategy, |input| {
        let ok = guarded(target, &input, || (check.borrow_mut())(&input))?;
        let mut c = counts.get();
        let row = &mut c[usize::from(!seeds.contains(input.as_slice()))];
        row[0] += 1;
        row[1] += u64::from(ok);
        counts.set(c);
        Ok(())
    });
    let elapsed = start.elapsed().as_secs_f64();
    let [[seed_inputs, seeds_accepted], [mutants, accepted]] = counts.get();
    let n = seed_inputs + mutants;
    if let Err(e) = result {
        panic!("fuzz {target}: after {n} inputs: {e}");
    }
    let fraction = accepted as f64 / mutants.max(1) as f64;
    // The watchdog aborts on a hang, so reaching here means none.
    eprintln!(
        "fuzz {target}: {n} inputs in {elapsed:.1} s ({:.0}/s), 0 panics, 0 hangs; \
         {accepted} of {mutants} mutated inputs accepted ({:.2}%, floor {:.2}%), \
         {seeds_accepted} of {seed_inputs} unmutated seeds",
        n as f64 / elapsed.max(1e-9),
        100.0 * fraction,
        100.0 * min_accepted
    );
    assert!(
        accepted > 0 && fraction >= min_accepted,
        "fuzz {target}: only {accepted} of {mutants} mutated inputs accepted ({:.2}%, at least \
         {:.2}% expected): the mutations no longer reach the reader's valid inputs, or it \
         rejects valid ones",
        100.0 * fraction,
        100.0 * min_accepted
    );
}

// ------------------------------------------------------------- the targets

const TOML_TOKENS: &[&str] = &[
    "[",
    "]",
    "{",
    "}",
    "=",
    "\"",
    "\n",
    ",",
    ".",
    "#",
    "${",
    "}",
    "${light_size}",
    "${missing}",
    "extends = \"occupancy.toml\"\n",
    "extends = \"fuzz.toml\"\n",
    "extends = \"../pipelines\"\n",
    "1e308",
    "-1",
    "0",
    "4294967296",
    "nan",
    "inf",
    "-inf",
    "\"screen/0\"",
    "\"screen\"",
    "[[x]]\n",
    "\"fit\"",
    "true",
    "[0, 0, 0]",
    "[1e30, 1e30, 1e30]",
    "\"\"",
    "'''",
    "\"\"\"",
    "screen_width * screen_height * 99999",
    "/ 0",
    "type = \"fullscreen\"\n",
    "shader = \"../../etc/passwd\"\n",
    "procedural",
    "file = \"x.tfx\"",
    "follow_strands = 4000000000\n",
    "scale = 0\n",
    "camera = \"fit\"\n",
    "light = \"fit\"\n",
    "[hair.transform]\n",
];

mod gltf;
mod hair;
mod pipeline;
mod scene;
mod shader;
mod tfx;
mod usd;
mod usdc;
