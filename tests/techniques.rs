//! Every combination of techniques composes. Rendering the whole product of
//! the choice points grows too fast (9 × 6 × 3 × 4 × 3 × …), so the test
//! renders an all-pairs cover of it: every technique of every point meets
//! every technique of every other point in at least one rendered combination
//! (built with IPOG's horizontal and vertical growth, and checked). Each
//! technique is found in `techniques/`, so a new one is tested without editing
//! this file; each combination is the default pipeline with its
//! `--set techniques.…` keys, checked and rendered on a tiny scene.

use std::collections::BTreeSet;

use plait::session::{SceneData, prepare};
use plait_graph::techniques::TechniqueRoots;
use plait_tests::{open_gpu, repo_root, strands_subset};

/// Combinations (one choice index per point) covering every pair of choices
/// of every two points. `sizes[k]` is point k's number of choices.
fn all_pairs(sizes: &[usize]) -> Vec<Vec<usize>> {
    // Larger points first: the product of the two largest is the start.
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by_key(|&k| std::cmp::Reverse(sizes[k]));
    let mut rows: Vec<Vec<Option<usize>>> = Vec::new();
    match order.as_slice() {
        [] => return vec![Vec::new()],
        [only] => {
            for v in 0..sizes[*only] {
                let mut r = vec![None; sizes.len()];
                r[*only] = Some(v);
                rows.push(r);
            }
        }
        [a, b, ..] => {
            for va in 0..sizes[*a] {
                for vb in 0..sizes[*b] {
                    let mut r = vec![None; sizes.len()];
                    r[*a] = Some(va);
                    r[*b] = Some(vb);
                    rows.push(r);
                }
            }
        }
    }
    for (i, &k) in order.iter().enumerate().skip(2) {
        let earlier = &order[..i];
        let mut uncovered: BTreeSet<(usize, usize, usize)> = earlier
            .iter()
            .flat_map(|&j| {
                (0..sizes[j]).flat_map(move |vj| (0..sizes[k]).map(move |vk| (j, vj, vk)))
            })
            .collect();
        // Horizontal growth: each row takes the value of k that covers most.
        for row in &mut rows {
            let gain = |v: usize| {
                earlier
                    .iter()
                    .filter(|&&j| row[j].is_some_and(|vj| uncovered.contains(&(j, vj, v))))
                    .count()
            };
            let best = (0..sizes[k])
                .max_by_key(|&v| (gain(v), std::cmp::Reverse(v)))
                .unwrap_or(0);
            for &j in earlier {
                if let Some(vj) = row[j] {
                    uncovered.remove(&(j, vj, best));
                }
            }
            row[k] = Some(best);
        }
        // Vertical growth: a pair still missing fills a free cell of a row
        // added for it, or a new row.
        for (j, vj, vk) in uncovered {
            let fits = rows
                .iter_mut()
                .find(|r| r[k] == Some(vk) && r[j].is_none() || r[j] == Some(vj) && r[k].is_none());
            match fits {
                Some(r) => {
                    r[j] = Some(vj);
                    r[k] = Some(vk);
                }
                None => {
                    let mut r = vec![None; sizes.len()];
                    r[j] = Some(vj);
                    r[k] = Some(vk);
                    rows.push(r);
                }
            }
        }
    }
    rows.into_iter()
        .map(|r| r.into_iter().map(|v| v.unwrap_or(0)).collect())
        .collect()
}

/// Every pair of choices of two points appears in some row.
fn covers_all_pairs(rows: &[Vec<usize>], sizes: &[usize]) -> bool {
    (0..sizes.len()).all(|a| {
        (a + 1..sizes.len()).all(|b| {
            (0..sizes[a])
                .all(|va| (0..sizes[b]).all(|vb| rows.iter().any(|r| r[a] == va && r[b] == vb)))
        })
    })
}

/// The all-pairs cover of the techniques, as `--set` flags.
fn combinations() -> Vec<Vec<String>> {
    let roots = TechniqueRoots::at(repo_root().join("techniques"));
    let points: Vec<(String, Vec<String>)> = roots
        .points()
        .into_iter()
        .map(|p| {
            let names = roots.choices(&p);
            assert!(!names.is_empty(), "choice point {p} has no technique");
            (p, names)
        })
        .collect();
    let sizes: Vec<usize> = points.iter().map(|(_, n)| n.len()).collect();
    let rows = all_pairs(&sizes);
    assert!(covers_all_pairs(&rows, &sizes), "the cover misses a pair");
    rows.iter()
        .map(|r| {
            r.iter()
                .zip(&points)
                .map(|(&v, (point, names))| format!("techniques.{point}={}", names[v]))
                .collect()
        })
        .collect()
}

#[test]
fn the_cover_has_every_pair_and_is_far_smaller_than_the_product() {
    for sizes in [
        vec![9, 6, 3, 4, 3, 2],
        vec![3, 3, 3, 3],
        vec![5],
        vec![2, 7],
    ] {
        let rows = all_pairs(&sizes);
        assert!(covers_all_pairs(&rows, &sizes), "{sizes:?}");
        let product: usize = sizes.iter().product();
        let two_largest = {
            let mut s = sizes.clone();
            s.sort_unstable_by(|a, b| b.cmp(a));
            s.iter().take(2).product::<usize>()
        };
        assert!(
            rows.len() >= two_largest && rows.len() <= two_largest + product / 10 + 8,
            "{sizes:?}: {} rows",
            rows.len()
        );
    }
}

/// The small scene cut to 60 strands at 64×48: each frame takes well under a
/// second even when depth peeling.
fn tiny_scene() -> SceneData {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut data = SceneData::load(Some(&path)).expect("small scene");
    let step = data.strands.strand_count() / 60;
    data.strands = strands_subset(&data.strands, |s| s % step == 0);
    data
}

#[test]
fn every_combination_of_techniques_checks_and_renders() {
    let combos = combinations();
    assert!(
        combos.len() >= 54,
        "expected at least the 9 × 6 self-shadowing × transparency pairs, found {}",
        combos.len()
    );
    let (_lock, gpu) = open_gpu();
    let scene = tiny_scene();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let mut failures = Vec::new();
    let render = |sets: &[String]| {
        prepare(&gpu, &pipeline, sets, &scene, (64, 48)).and_then(|p| {
            p.render_unchecked()?;
            Ok(p.image()?)
        })
    };
    // A combination a technique's `[technique.requires]` refuses (Karis or
    // dual scattering on Kajiya-Kay, dual scattering without a strand count,
    // ray-traced transparency of wisps) is refused at load as declared; the
    // row is then rendered with the refused choice repaired
    // (`multiple_scattering = none`, `geometry = strands`), so its other
    // pairs stay covered, and the rows added below render every
    // multiple-scattering technique.
    let mut refused = 0;
    let mut combos = combos;
    for ms in ["karis", "dual_scattering"] {
        combos.push(vec![
            "techniques.shading=chiang".into(),
            "techniques.self_shadow=deep_opacity".into(),
            format!("techniques.multiple_scattering={ms}"),
        ]);
    }
    // Ray-traced techniques compose with every other where the adapter has
    // ray queries; elsewhere they are refused at load (tested in
    // crates/plait-cli/tests/ray_query_cli.rs) and left out here.
    if !gpu.capabilities.ray_query {
        combos.retain(|sets| !sets.iter().any(|s| s.ends_with("=ray_traced")));
    }
    // The technique whose `[technique.requires]` refused a row, and the
    // choice the row is rendered with instead: transparency = ray_traced
    // traces strands, not the wisps' triangles (geometry = strands).
    let repairs = [
        (
            "techniques/multiple_scattering/",
            "multiple_scattering",
            "none",
        ),
        ("techniques/transparency/ray_traced/", "geometry", "strands"),
    ];
    for sets in &combos {
        let mut result = render(sets);
        let mut sets = sets.clone();
        while let Err(e) = &result
            && e.to_string().contains("; declared at ")
            && let Some((_, point, choice)) = repairs.iter().find(|(at, point, choice)| {
                let set = format!("techniques.{point}={choice}");
                e.to_string().contains(at) && !sets.contains(&set)
            })
        {
            refused += 1;
            let key = format!("techniques.{point}=");
            sets.retain(|s| !s.starts_with(&key));
            sets.push(format!("{key}{choice}"));
            result = render(&sets);
        }
        match result {
            Ok(image) => {
                // Hair and head cover part of the frame: not one flat colour.
                let first = image.get_pixel(0, 0);
                if image.pixels().all(|p| p == first) {
                    failures.push(format!("{sets:?}: a flat image"));
                }
            }
            Err(e) => failures.push(format!("{sets:?}: {e}")),
        }
    }
    println!(
        "{refused} refusals as declared in {} combinations, each row rendered with the refused choice repaired",
        combos.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {} combinations failed:\n{}",
        failures.len(),
        combos.len(),
        failures.join("\n")
    );
}
