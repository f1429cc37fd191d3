//! The SVG picture of a schedule: compact, every pass and resource named
//! next to its marks, and made of the plain SVG that every renderer draws
//! alike (ImageMagick's own renderer drew the old layout blank).

mod common;

use common::*;
use plait_graph::*;

/// GOOD plus a culled pass, and an extra resource sharing memory.
fn schedule() -> Schedule {
    let text = format!(
        "{GOOD}\n[resources.debug]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [32, 32]\n\n[passes.debug_view]\ntype = \"blur\"\nreads = {{ src = \"depth\" }}\nwrites = {{ dst = \"debug\" }}\nparams = {{ radius = 1 }}\n"
    );
    compile_text(&text, &[]).expect("compiles")
}

/// Every element of the picture, as `(name, attributes, text)`.
fn elements(svg: &str) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        if rest.starts_with('/') {
            rest = &rest[rest.find('>').expect("closed tag") + 1..];
            continue;
        }
        let end = rest.find('>').expect("tag ends");
        let tag = &rest[..end];
        let name = tag
            .split_whitespace()
            .next()
            .unwrap_or("")
            .trim_end_matches('/');
        let attributes = tag[name.len()..].trim_end_matches('/').to_owned();
        rest = &rest[end + 1..];
        let text = if !tag.ends_with('/') && name == "text" {
            let close = rest.find("</text>").expect("text closes");
            let inner = &rest[..close];
            assert!(!inner.contains('<'), "markup inside <text>: {inner}");
            inner.to_owned()
        } else {
            String::new()
        };
        out.push((name.to_owned(), attributes, text));
    }
    out
}

#[test]
fn the_picture_uses_plain_svg_only() {
    let svg = to_svg(&schedule());
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(svg.trim_end().ends_with("</svg>"));
    for (name, attributes, _) in elements(&svg) {
        assert!(
            ["svg", "rect", "line", "circle", "polygon", "text"].contains(&name.as_str()),
            "<{name}> is not plain SVG every renderer draws"
        );
        for unsupported in ["transform", "marker", "context-stroke", "class="] {
            assert!(
                !attributes.contains(unsupported),
                "<{name}{attributes}> uses {unsupported}"
            );
        }
    }
}

#[test]
fn every_pass_and_resource_is_named() {
    let schedule = schedule();
    let svg = to_svg(&schedule);
    let texts: Vec<String> = elements(&svg)
        .into_iter()
        .filter(|(n, _, _)| n == "text")
        .map(|(_, _, t)| t)
        .collect();
    for name in ["light_range", "shade", "debug_view"] {
        assert!(texts.iter().any(|t| t == name), "pass `{name}`: {texts:?}");
    }
    for resource in &schedule.resources {
        assert_eq!(
            texts.iter().filter(|t| **t == resource.name).count(),
            1,
            "resource `{}`: {texts:?}",
            resource.name
        );
    }
    assert!(texts.iter().any(|t| t == "blur (culled)"), "{texts:?}");
    assert!(texts.iter().any(|t| t == "rg32float 256×256"), "{texts:?}");
    // The culled pass's box is dashed.
    assert!(svg.contains("stroke-dasharray"), "{svg}");
}

#[test]
fn the_picture_is_as_small_as_the_schedule() {
    let svg = to_svg(&schedule());
    let (_, attributes, _) = elements(&svg).remove(0);
    let number = |key: &str| -> f64 {
        let start = attributes.find(&format!("{key}=\"")).expect(key) + key.len() + 2;
        let end = attributes[start..].find('"').expect("quote") + start;
        attributes[start..end].parse().expect("a number")
    };
    let (width, height) = (number("width"), number("height"));
    // Three passes, three resources: a few hundred pixels, not thousands.
    assert!((300.0..800.0).contains(&width), "width {width}");
    assert!((150.0..500.0).contains(&height), "height {height}");
}

/// GOOD with five choice points whose techniques add a (culled) pass each,
/// and one whose technique only sets a param.
fn schedule_with_techniques() -> Schedule {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut choices = String::from("[techniques]\nquiet = \"only_params\"\n");
    for n in 1..=5 {
        let name = format!("a_rather_long_technique_name_number_{n}");
        choices.push_str(&format!("p{n} = \"{name}\"\n"));
        let file = dir
            .path()
            .join(format!("techniques/p{n}/{name}/technique.toml"));
        std::fs::create_dir_all(file.parent().expect("folder")).expect("mkdir");
        std::fs::write(
            &file,
            format!(
                "[technique]\npoint = \"p{n}\"\ndescription = \"x\"\n\n[resources.t{n}]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [4, 4]\n\n[passes.pass{n}]\ntype = \"blur\"\nreads = {{ src = \"depth\" }}\nwrites = {{ dst = \"t{n}\" }}\nparams = {{ radius = 1 }}\n"
            ),
        )
        .expect("write");
    }
    let quiet = dir
        .path()
        .join("techniques/quiet/only_params/technique.toml");
    std::fs::create_dir_all(quiet.parent().expect("folder")).expect("mkdir");
    std::fs::write(
        &quiet,
        "[technique]\npoint = \"quiet\"\ndescription = \"x\"\n\n[params]\nq = 1\n",
    )
    .expect("write");
    let pipeline = dir.path().join("pipelines/p.toml");
    std::fs::create_dir_all(pipeline.parent().expect("folder")).expect("mkdir");
    std::fs::write(&pipeline, format!("{GOOD}\n{choices}")).expect("write");
    let loaded = load(&pipeline, &[]).expect("loads");
    compile(&loaded, &registry(), &CompileOptions::default()).expect("compiles")
}

/// The legend ran past the picture's width (three technique entries of
/// the default pipeline unseen) and named techniques that add no pass.
#[test]
fn the_legend_fits_the_picture_and_names_only_techniques_with_passes() {
    let svg = to_svg(&schedule_with_techniques());
    let all = elements(&svg);
    let attribute = |attributes: &str, key: &str| -> f64 {
        let start = attributes.find(&format!(" {key}=\"")).expect(key) + key.len() + 3;
        let end = attributes[start..].find('"').expect("quote") + start;
        attributes[start..end].parse().expect("a number")
    };
    let width = attribute(&all[0].1, "width");
    let entries: Vec<&(String, String, String)> = all
        .iter()
        .filter(|(n, _, t)| n == "text" && t.starts_with("technique "))
        .collect();
    let names: Vec<&str> = entries.iter().map(|(_, _, t)| t.as_str()).collect();
    for n in 1..=5 {
        let want = format!("technique p{n}/a_rather_long_technique_name_number_{n}");
        assert!(names.contains(&want.as_str()), "{want}: {names:?}");
    }
    assert!(
        !names.iter().any(|t| t.contains("only_params")),
        "a technique without passes in the legend: {names:?}"
    );
    // 7 px a character at 12 px is what the layout assumes for DejaVu Sans.
    for (_, attributes, t) in &entries {
        let right = attribute(attributes, "x") + 7.0 * t.chars().count() as f64;
        assert!(right <= width, "`{t}` ends at {right}, past {width}");
    }
    // More entries than one line holds: they wrap onto several lines.
    let mut lines: Vec<f64> = entries.iter().map(|(_, a, _)| attribute(a, "y")).collect();
    lines.dedup();
    assert!(lines.len() > 1, "{lines:?}");
}
