//! The built book checked as files: every link and image of every page
//! resolves (a `#fragment` to an id of its page), every `url()` of a
//! stylesheet too, and nothing is loaded from the network — a script, style,
//! font or image from elsewhere is a problem, a link out is not.

use std::path::{Path, PathBuf};

/// One thing wrong with the built book.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// The page or stylesheet, relative to the book's root.
    pub file: String,
    pub target: String,
    pub what: &'static str,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {} `{}`", self.file, self.what, self.target)
    }
}

/// A reference found in a file: whether it is loaded (a resource) or only
/// followed (a link), and its target.
struct Reference {
    loaded: bool,
    target: String,
}

/// Every `.html` under `root`, relative paths, sorted; not the live view's
/// page (`live/`): it is no chapter of the book, and it needs WebGPU, which
/// its own test gives Chromium (`tests/web.rs`).
pub fn pages(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    walk(root, root, &mut out);
    out.retain(|p| p.extension().is_some_and(|x| x == "html"));
    out.retain(|p| !p.starts_with(crate::live::DIR));
    out.sort();
    out
}

fn walk(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(root, &p, out);
        } else if let Ok(rel) = p.strip_prefix(root) {
            out.push(rel.to_path_buf());
        }
    }
}

/// Checks every page and stylesheet of the book at `root`.
pub fn check(root: &Path) -> Vec<Problem> {
    let mut files = Vec::new();
    walk(root, root, &mut files);
    files.sort();
    let mut problems = Vec::new();
    for rel in &files {
        let ext = rel.extension().and_then(|x| x.to_str()).unwrap_or("");
        // mdBook's 404 page is written for a web server: its links are
        // absolute from the site's root (`<base href="/">`), which a file
        // check cannot resolve; every other page links relatively.
        if (ext != "html" && ext != "css") || rel == Path::new("404.html") {
            continue;
        }
        let Ok(text) = std::fs::read_to_string(root.join(rel)) else {
            continue;
        };
        let refs = if ext == "html" {
            html_refs(&text)
        } else {
            css_refs(&text)
        };
        for r in refs {
            if let Some(what) = problem(root, rel, &text, &r) {
                problems.push(Problem {
                    file: rel.display().to_string(),
                    target: r.target,
                    what,
                });
            }
        }
    }
    problems
}

fn problem(root: &Path, page: &Path, text: &str, r: &Reference) -> Option<&'static str> {
    let t = r.target.as_str();
    let external = t.starts_with("http://") || t.starts_with("https://") || t.starts_with("//");
    if external {
        return r.loaded.then_some("loads from the network");
    }
    if t.is_empty()
        || t.starts_with("mailto:")
        || t.starts_with("data:")
        || t.starts_with("javascript:")
    {
        return None;
    }
    let (path, fragment) = match t.split_once('#') {
        Some((p, f)) => (p, Some(f)),
        None => (t, None),
    };
    let path = path.split('?').next().unwrap_or("");
    let (file, target_text) = if path.is_empty() {
        (page.to_path_buf(), Some(text.to_string()))
    } else {
        let file = page.parent().unwrap_or(Path::new("")).join(path);
        let full = root.join(&file);
        let full = if full.is_dir() {
            full.join("index.html")
        } else {
            full
        };
        if !full.is_file() {
            return Some(if r.loaded {
                "missing file"
            } else {
                "broken link"
            });
        }
        (file, std::fs::read_to_string(&full).ok())
    };
    match (fragment, target_text) {
        (Some(f), Some(body)) if !f.is_empty() && file.extension().is_some_and(|x| x == "html") => {
            let id = format!("id=\"{f}\"");
            (!body.contains(&id)).then_some("link to a missing anchor")
        }
        _ => None,
    }
}

/// `src`/`href` of every tag, with whether the tag loads it.
fn html_refs(text: &str) -> Vec<Reference> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let end = rest.find('>').unwrap_or(rest.len());
        let tag = &rest[..end];
        rest = &rest[end..];
        let name: String = tag
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect::<String>()
            .to_ascii_lowercase();
        if name.is_empty() {
            continue;
        }
        for attr in ["src", "href"] {
            if let Some(v) = attribute(tag, attr) {
                // <a href> is followed; <link href>, <script src>, <img src> are loaded.
                let loaded = !(name == "a" && attr == "href");
                out.push(Reference {
                    loaded,
                    target: decode(v),
                });
            }
        }
    }
    out
}

/// The value of ` name="…"` in a tag.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let len = tag[start..].find('"')?;
    Some(&tag[start..start + len])
}

fn decode(v: &str) -> String {
    v.replace("&amp;", "&").replace("%20", " ")
}

/// `url(…)` of a stylesheet (fonts, images): all loaded.
fn css_refs(text: &str) -> Vec<Reference> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("url(") {
        rest = &rest[i + 4..];
        let end = rest.find(')').unwrap_or(rest.len());
        let target = rest[..end].trim().trim_matches(['"', '\'']).to_string();
        out.push(Reference {
            loaded: true,
            target,
        });
        rest = &rest[end..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_broken_links_missing_images_anchors_and_network_loads() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir_all(root.join("a")).unwrap();
        std::fs::write(root.join("ok.png"), b"png").unwrap();
        std::fs::write(
            root.join("a/page.html"),
            "<h2 id=\"here\">x</h2><a href=\"../ok.png\">fine</a><img src=\"../ok.png\">\
             <a href=\"#here\">ok</a><a href=\"#gone\">bad anchor</a><a href=\"nope.html\">broken</a>\
             <img src=\"missing.png\"><a href=\"https://example.org\">out is fine</a>\
             <script src=\"https://cdn.example/x.js\"></script>",
        )
        .unwrap();
        std::fs::write(
            root.join("s.css"),
            "@font-face { src: url('fonts/none.woff2') }",
        )
        .unwrap();
        let found: Vec<(String, &str)> = check(root)
            .into_iter()
            .map(|p| (p.target, p.what))
            .collect();
        assert_eq!(
            found,
            [
                ("#gone".to_string(), "link to a missing anchor"),
                ("nope.html".to_string(), "broken link"),
                ("missing.png".to_string(), "missing file"),
                (
                    "https://cdn.example/x.js".to_string(),
                    "loads from the network"
                ),
                ("fonts/none.woff2".to_string(), "missing file"),
            ]
        );
    }
}
