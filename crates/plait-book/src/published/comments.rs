//! Whether a commit changed only comments in what a figure measures: such a
//! commit cannot move a measured value, so it does not make the figure stale
//! (a stale comment in a technique file could otherwise not be corrected
//! without marking every figure that measures the folder stale).
//!
//! Conservative by design: a line counts as a comment only by its file's own
//! comment syntax (`#` in TOML, shell and Python; `//` in WGSL and Rust —
//! WGSL's `#import` is code), a line with code before its comment is code,
//! and a merge, a binary file or a file of any other kind is a change.

use std::path::Path;
use std::process::Command;

/// True when `commit`'s diff against its parent, restricted to `pathspecs`,
/// adds and removes only comment lines and blank lines. Any git failure
/// counts as a real change.
pub fn comment_only(repo: &Path, commit: &str, pathspecs: &[String]) -> bool {
    let parents = Command::new("git")
        .args(["rev-list", "--parents", "-n", "1", commit])
        .current_dir(repo)
        .output();
    match parents {
        // The commit itself and exactly one parent: not a merge, not a root.
        Ok(o) if o.status.success() && o.stdout.split(|b| *b == b' ').count() == 2 => {}
        _ => return false,
    }
    let mut args = vec![
        "show".to_string(),
        "--format=".to_string(),
        "--no-color".to_string(),
        "--no-ext-diff".to_string(),
        "-U0".to_string(),
        commit.to_string(),
        "--".to_string(),
    ];
    args.extend(pathspecs.iter().cloned());
    match Command::new("git").args(&args).current_dir(repo).output() {
        Ok(o) if o.status.success() => comment_only_diff(&String::from_utf8_lossy(&o.stdout)),
        _ => false,
    }
}

/// The comment marker of a file kind, by extension; None: every line counts.
fn comment_marker(path: &str) -> Option<&'static str> {
    let ext = path.rsplit_once('.').map(|(_, e)| e)?;
    match ext {
        "toml" | "sh" | "py" => Some("#"),
        "wgsl" | "rs" => Some("//"),
        _ => None,
    }
}

/// [`comment_only`] on the text of a unified diff (`git show -U0`).
pub fn comment_only_diff(diff: &str) -> bool {
    let mut marker: Option<&str> = None;
    let mut changed = false;
    for line in diff.lines() {
        if let Some(rest) = line.strip_prefix("diff --git ") {
            // `a/PATH b/PATH`: the new side names the file's kind.
            let path = rest.rsplit_once(" b/").map_or(rest, |(_, p)| p);
            marker = comment_marker(path);
            continue;
        }
        if line.starts_with("Binary files ") || line.starts_with("GIT binary patch") {
            return false;
        }
        let body = match (line.strip_prefix('+'), line.strip_prefix('-')) {
            (Some(b), _) if !line.starts_with("+++ ") => b,
            (_, Some(b)) if !line.starts_with("--- ") => b,
            _ => continue,
        };
        changed = true;
        let text = body.trim();
        if text.is_empty() {
            continue;
        }
        match marker {
            Some(m) if text.starts_with(m) => {}
            _ => return false,
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::comment_only_diff;

    fn diff(path: &str, removed: &[&str], added: &[&str]) -> String {
        let mut d = format!(
            "diff --git a/{path} b/{path}\nindex 1..2 100644\n--- a/{path}\n+++ b/{path}\n@@ -1 +1 @@\n"
        );
        for r in removed {
            d += &format!("-{r}\n");
        }
        for a in added {
            d += &format!("+{a}\n");
        }
        d
    }

    #[test]
    fn comment_lines_in_toml_wgsl_and_rust_are_comments() {
        assert!(comment_only_diff(&diff(
            "techniques/lighting/x/technique.toml",
            &["# old words"],
            &["# new words", ""]
        )));
        assert!(comment_only_diff(&diff(
            "shaders/lib/a.wgsl",
            &["    // why, before"],
            &["    // why, after"]
        )));
        assert!(comment_only_diff(&diff(
            "crates/plait/src/a.rs",
            &["/// doc"],
            &["//! module doc"]
        )));
    }

    #[test]
    fn code_an_import_a_trailing_comment_or_an_unknown_kind_is_a_change() {
        assert!(!comment_only_diff(&diff(
            "techniques/x/technique.toml",
            &["size = 16   # texels"],
            &["size = 32   # texels"]
        )));
        // WGSL's `#import` is a directive, not a comment.
        assert!(!comment_only_diff(&diff(
            "shaders/lib/a.wgsl",
            &["#import plait::a"],
            &["#import plait::b"]
        )));
        // `#` is no comment in Rust.
        assert!(!comment_only_diff(&diff(
            "crates/a.rs",
            &[],
            &["#[inline]"]
        )));
        assert!(!comment_only_diff(&diff(
            "book/a.md",
            &["# Title"],
            &["# Title 2"]
        )));
        assert!(!comment_only_diff(
            "diff --git a/x.png b/x.png\nBinary files a/x.png and b/x.png differ\n"
        ));
        // An empty diff (a mode change, say) is not shown to be comments only.
        assert!(!comment_only_diff(""));
    }

    #[test]
    fn one_code_line_among_comments_is_a_change() {
        let mut d = diff("a.toml", &["# a"], &["# b"]);
        d += &diff("b.wgsl", &["let x = 1.0;"], &["let x = 1.1;"]);
        assert!(!comment_only_diff(&d));
    }
}
