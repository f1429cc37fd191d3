//! The floor benchmark's command line (`benches/support/floor_args.rs`),
//! without running the benchmark: `--set` is collected in order, and a bad
//! flag or `--set` is an error naming it, checked by the same loader as
//! `plait render --set` (no GPU).

#[path = "../benches/support/floor_args.rs"]
#[allow(dead_code)] // USAGE and the like are the benchmark's
mod floor_args;

use floor_args::{FloorArgs, Side, check_sets, file_stem, label, parse};
use plait::session::repo_root;

fn args(words: &str) -> Result<FloorArgs, String> {
    let words: Vec<String> = words.split_whitespace().map(str::to_owned).collect();
    parse(&words)
}

#[test]
fn defaults_and_every_flag() {
    let a = args("--bench").unwrap();
    assert_eq!(a.size, (160, 120));
    assert_eq!(a.repeats, 3);
    assert!(a.sets.is_empty() && !a.sets_only && !a.one_draw && !a.help);
    assert_eq!(a.side, Side::Both);

    let a = args(
        "--bench --only occupancy,forward --size 320X240 --repeats 5 --set techniques.shading_space=strand \
         --set=params.shadow_weight=0.3 --sets-only --one-draw --side floor --save out --scene s.toml",
    )
    .unwrap();
    assert_eq!(
        a.only,
        Some(vec!["occupancy".to_owned(), "forward".to_owned()])
    );
    assert_eq!(a.size, (320, 240));
    assert_eq!(a.repeats, 5);
    // Repeatable, in the order given, `--set=K=V` as well as `--set K=V`.
    assert_eq!(
        a.sets,
        [
            "techniques.shading_space=strand",
            "params.shadow_weight=0.3"
        ]
    );
    assert!(a.sets_only && a.one_draw);
    assert_eq!(a.side, Side::Floor);
    assert!(args("--help").unwrap().help);
    assert!(args("-h").unwrap().help);
}

#[test]
fn a_bad_flag_is_an_error_naming_it() {
    let err = |words: &str| args(words).expect_err(words);
    assert!(
        err("--set").contains("--set needs a value"),
        "{}",
        err("--set")
    );
    // The next flag is not the value.
    assert!(err("--set --only occupancy").contains("--set needs a value"));
    let e = err("--sets techniques.shading_space=strand");
    assert!(
        e.contains("`--sets`") && e.contains("did you mean --set?"),
        "{e}"
    );
    assert!(err("--side gpu").contains("expected `plait` or `floor`"));
    assert!(err("--size 320").contains("WIDTHxHEIGHT"));
    assert!(err("--size 0x240").contains("1..=16384"));
    assert!(err("--repeats 0").contains("--repeats 0"));
    assert!(err("--one-draw=yes").contains("takes no value"));
    assert!(err("--sets-only").contains("needs at least one --set"));
}

#[test]
fn sets_are_checked_by_the_pipeline_loader() {
    let occupancy = repo_root().join("pipelines/occupancy.toml");
    check_sets(&occupancy, &["techniques.shading_space=strand".into()]).unwrap();
    check_sets(&occupancy, &[]).unwrap();
    let e = check_sets(&occupancy, &["techniques.shading_spce=strand".into()]).unwrap_err();
    assert!(
        e.contains("--set techniques.shading_spce=strand")
            && e.contains("did you mean `shading_space`"),
        "{e}"
    );
    let e = check_sets(&occupancy, &["techniques.shading_space=strnd".into()]).unwrap_err();
    assert!(e.contains("did you mean `strand`"), "{e}");
    let e = check_sets(&occupancy, &["params.nothing=1".into()]).unwrap_err();
    assert!(e.contains("no param `nothing`"), "{e}");
    let e = check_sets(&occupancy, &["shading_space".into()]).unwrap_err();
    assert!(e.contains("expected `key=value`"), "{e}");
}

#[test]
fn rows_are_labelled_by_their_sets() {
    let sets = [
        "techniques.shading_space=strand".to_owned(),
        "params.a=1".to_owned(),
    ];
    let l = label("occupancy", &sets);
    assert_eq!(
        l,
        "occupancy --set techniques.shading_space=strand --set params.a=1"
    );
    assert_eq!(label("occupancy", &[]), "occupancy");
    assert_eq!(
        file_stem(&l),
        "occupancy_--set_techniques_shading_space_strand_--set_params_a_1"
    );
}
