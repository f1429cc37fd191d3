//! "Did you mean …?" for a name that matches nothing: pass types, params,
//! slots, keys, passes, resources, `--set` paths and `--show` names all go
//! through here, so every message ranks candidates the same way.
//!
//! The distance is optimal-string-alignment edit distance (strsim's
//! `osa_distance`: insertions, deletions, substitutions and swaps of two
//! neighbours), on which a typo like `slice`/`slices` or `shadow_mapp`
//! costs 1.

/// Edit distance up to which a candidate counts as meant: one edit for short
/// names, about one per three characters for longer ones.
fn close_enough(name: &str, distance: usize) -> bool {
    distance <= 1.max(name.chars().count() / 3)
}

fn distance(a: &str, b: &str) -> usize {
    strsim::osa_distance(a, b)
}

/// The candidate `name` was most likely meant to be, if one is close.
/// Ties keep the candidates' order.
pub fn nearest<'a, I>(name: &str, candidates: I) -> Option<&'a str>
where
    I: IntoIterator<Item = &'a str>,
{
    let mut best: Option<(usize, &'a str)> = None;
    for candidate in candidates {
        let d = distance(name, candidate);
        if close_enough(name, d) && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, candidate));
        }
    }
    best.map(|(_, c)| c)
}

/// All candidates, nearest to `name` first (ties in the given order), for
/// lists of valid names.
pub fn nearest_first<'a, I>(name: &str, candidates: I) -> Vec<&'a str>
where
    I: IntoIterator<Item = &'a str>,
{
    let mut ranked: Vec<(usize, usize, &'a str)> = candidates
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            // A name that starts or ends the candidate (`light` → `light_range`)
            // ranks with the near misses.
            let mut d = distance(name, c);
            if !name.is_empty() && (c.starts_with(name) || c.ends_with(name)) {
                d = d.min(1);
            }
            (d, i, c)
        })
        .collect();
    ranked.sort();
    ranked.into_iter().map(|(_, _, c)| c).collect()
}

/// `; did you mean `x`?` when a candidate is close, else nothing: ready to
/// append to an error message's clause. What follows it in the message
/// starts a parenthesis (` (known: …)`), never a `;` or `,`, which would
/// read `did you mean `x`?; …`.
pub fn did_you_mean<'a, I>(name: &str, candidates: I) -> String
where
    I: IntoIterator<Item = &'a str>,
{
    nearest(name, candidates)
        .map(|c| format!("; did you mean `{c}`?"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_find_their_name() {
        assert_eq!(
            nearest("slice", ["light_size", "slices", "slabs"]),
            Some("slices")
        );
        assert_eq!(
            nearest("shadow_mapp", ["shadow_map", "slab"]),
            Some("shadow_map")
        );
        assert_eq!(
            nearest("ocupancy", ["occupancy", "slab"]),
            Some("occupancy")
        );
        // A swap of two neighbours is one edit.
        assert_eq!(nearest("sahdow_map", ["shadow_map"]), Some("shadow_map"));
    }

    #[test]
    fn unrelated_names_suggest_nothing() {
        assert_eq!(nearest("bias", ["visibility", "density"]), None);
        assert_eq!(did_you_mean("zzz", ["slices"]), "");
        assert_eq!(nearest("x", std::iter::empty()), None);
    }

    #[test]
    fn lists_rank_nearest_first() {
        let names = ["final", "hair", "light_range", "camera_range"];
        assert_eq!(
            nearest_first("light_rnage", names),
            ["light_range", "camera_range", "final", "hair"]
        );
        assert_eq!(nearest_first("light", names)[0], "light_range");
    }

    #[test]
    fn message_names_the_suggestion() {
        assert_eq!(
            did_you_mean("slice", ["slices"]),
            "; did you mean `slices`?"
        );
    }
}
