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
