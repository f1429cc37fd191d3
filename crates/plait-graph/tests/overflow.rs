//! `overflow = {…}` on a counter buffer: parsed and checked at load and
//! compile (each mistake at its file:line:column), carried by the schedule
//! with the origin of its sizing param.

use plait_graph::{
    Access, CompileOptions, Formats, PassShape, PassTypeSpec, Registry, ResourceKind, SlotSpec,
    compile, load_str,
};

const PATH: &str = "/virtual/overflow.toml";

/// A pipeline whose `counter` counts what `pool` drops; `overflow` is the
/// declaration's inner text.
fn pipeline(overflow: &str) -> String {
    format!(
        r#"[pipeline]
name = "t"
outputs = ["pool"]

[params]
slots = 3

[resources.pool]
kind = "buffer"
size = "screen_width * screen_height * ${{slots}} * 16"

[resources.counter]
kind = "buffer"
size = "8"
overflow = {{ {overflow} }}
"#
    )
}

/// Every error of loading and compiling, one per line.
fn errors(text: &str, sets: &[&str]) -> String {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match load_str(PATH.as_ref(), text, &sets) {
        Err(e) => e.to_string(),
        Ok(p) => match compile(&p, &Registry::new(), &CompileOptions::default()) {
            Err(e) => e.to_string(),
            Ok(_) => String::new(),
        },
    }
}

const GOOD: &str = r#"of = "pool", dropped = 1, needed = 0, param = "slots", per = "screen_width * screen_height""#;

#[test]
fn unknown_key_is_reported_at_the_key_with_a_suggestion() {
    let e = errors(&pipeline(&format!("{GOOD}, droped = 1")), &[]);
    assert!(
        e.contains("overflow.toml:15:") && e.contains("unknown key `droped`"),
        "{e}"
    );
    assert!(e.contains("did you mean `dropped`"), "{e}");
}

#[test]
fn missing_keys_are_named() {
    let e = errors(&pipeline(r#"of = "pool", param = "slots""#), &[]);
    assert!(e.contains("needs dropped, needed"), "{e}");
}

#[test]
fn a_word_past_the_counter_is_an_error_at_its_value() {
    // 8 bytes: words 0 and 1.
    let text = pipeline(r#"of = "pool", dropped = 2, needed = 0, param = "slots""#);
    let e = errors(&text, &[]);
    let column = text.lines().nth(14).unwrap().find("2,").unwrap() + 1;
    assert!(
        e.contains(&format!("overflow.toml:15:{column}: resource `counter`: word 2 is past the end of the counter (8 bytes = 2 words)")),
        "{e}"
    );
}

/// `incomplete` (the word counting invocations that could not finish) is
/// optional, carried by the schedule, and held inside the counter too.
#[test]
fn the_incomplete_word_is_optional_and_checked_like_the_others() {
    let past = pipeline(&format!("{GOOD}, incomplete = 2"));
    let e = errors(&past, &[]);
    let column = past.lines().nth(14).unwrap().rfind("2 }").unwrap() + 1;
    assert!(
        e.contains(&format!("overflow.toml:15:{column}: resource `counter`: word 2 is past the end of the counter (8 bytes = 2 words)")),
        "{e}"
    );
    let text = pipeline(&format!("{GOOD}, incomplete = 1"))
        + "\n[passes.fill]\ntype = \"fill\"\nwrites = { pool = \"pool\", counter = \"counter\" }\n";
    let p = load_str(PATH.as_ref(), &text, &[]).expect("loads");
    let s = compile(&p, &registry(), &CompileOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.overflow[0].incomplete_word, Some(1));
    let without = pipeline(GOOD)
        + "\n[passes.fill]\ntype = \"fill\"\nwrites = { pool = \"pool\", counter = \"counter\" }\n";
    let p = load_str(PATH.as_ref(), &without, &[]).expect("loads");
    let s = compile(&p, &registry(), &CompileOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.overflow[0].incomplete_word, None);
}

#[test]
fn unknown_param_and_buffer_suggest_the_nearest() {
    let e = errors(
        &pipeline(r#"of = "pol", dropped = 1, needed = 0, param = "slot""#),
        &[],
    );
    assert!(
        e.contains("overflow.of `pol` is not a declared resource; did you mean `pool`?"),
        "{e}"
    );
    assert!(
        e.contains("overflow.param `slot` is not in [params]; did you mean `slots`?"),
        "{e}"
    );
}

/// A compute pass type writing the pool and its counter.
fn registry() -> Registry {
    let slot = |name: &str| SlotSpec {
        name: name.into(),
        kind: ResourceKind::Buffer,
        access: Access::StorageWrite,
        formats: Formats::Any,
        loads: false,
        optional: false,
        doc: String::new(),
        binding: None,
    };
    let mut r = Registry::new();
    r.register(PassTypeSpec {
        outputs: vec![slot("pool"), slot("counter")],
        ..PassTypeSpec::new("fill", PassShape::Compute, "test", "test")
    });
    r
}

#[test]
fn the_schedule_carries_the_counter_and_who_sized_it() {
    let text = pipeline(GOOD)
        + "\n[passes.fill]\ntype = \"fill\"\nwrites = { pool = \"pool\", counter = \"counter\" }\n";
    let opts = CompileOptions {
        screen: (10, 20),
        ..CompileOptions::default()
    };
    let schedule = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let p = load_str(PATH.as_ref(), &text, &sets).expect("loads");
        compile(&p, &registry(), &opts).unwrap_or_else(|e| panic!("{e}"))
    };
    let s = schedule(&[]);
    let [c] = s.overflow.as_slice() else {
        panic!("one counter expected: {:?}", s.overflow)
    };
    assert_eq!(s.resources[c.counter].name, "counter");
    assert_eq!(
        (c.of.as_str(), c.dropped_word, c.needed_word),
        ("pool", Some(1), Some(0))
    );
    assert_eq!((c.param.as_str(), c.value, c.per), ("slots", 3, 200));
    assert_eq!(c.capacity(), 600);
    assert_eq!(c.value_for(601), 4, "rounded up to hold everything");
    // Written in the pipeline file (no technique's default) or by a flag:
    // the user's size, reported and never grown.
    assert!(!c.grows);
    let flagged = schedule(&["params.slots=5"]);
    assert_eq!(flagged.overflow[0].value, 5);
    assert!(!flagged.overflow[0].grows);
}

/// A counter of incomplete invocations only (no bounded buffer behind it):
/// `incomplete` alone; its word is still checked, and a table with some of
/// the bounded keys still needs them all.
#[test]
fn an_incomplete_word_alone_is_a_counter_without_a_bounded_buffer() {
    let text = pipeline("incomplete = 1")
        + "\n[passes.fill]\ntype = \"fill\"\nwrites = { pool = \"pool\", counter = \"counter\" }\n";
    let p = load_str(PATH.as_ref(), &text, &[]).expect("loads");
    let s = compile(&p, &registry(), &CompileOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let [c] = s.overflow.as_slice() else {
        panic!("one counter expected: {:?}", s.overflow)
    };
    assert_eq!(s.resources[c.counter].name, "counter");
    assert_eq!(c.incomplete_word, Some(1));
    assert_eq!((c.dropped_word, c.needed_word), (None, None));
    assert!(!c.grows, "nothing to grow");

    let past = pipeline("incomplete = 2");
    let e = errors(&past, &[]);
    assert!(
        e.contains("resource `counter`: word 2 is past the end of the counter (8 bytes = 2 words)"),
        "{e}"
    );
    let e = errors(&pipeline(r#"of = "pool", incomplete = 1"#), &[]);
    assert!(e.contains("needs dropped, needed, param"), "{e}");
    let e = errors(&pipeline(""), &[]);
    assert!(e.contains("needs of, dropped, needed, param"), "{e}");
}
