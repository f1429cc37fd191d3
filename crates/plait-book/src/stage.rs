//! The staged book: a copy of `book/` with the design notes, formats and
//! bibliography of `docs/` as reference pages, the images the guide shows,
//! and (added by the generator) the generated pages. mdBook builds the copy,
//! so nothing generated is ever written into the repository.

use std::path::{Path, PathBuf};

use crate::error::BookError;

/// Pages of `docs/` the book shows as they are, under `src/reference/`.
pub const REFERENCE_DOCS: [&str; 3] = ["design.md", "formats.md", "bibliography.md"];

pub fn copy_tree(from: &Path, to: &Path) -> Result<(), BookError> {
    std::fs::create_dir_all(to).map_err(BookError::io(to))?;
    for entry in std::fs::read_dir(from).map_err(BookError::io(from))? {
        let entry = entry.map_err(BookError::io(from))?;
        let path = entry.path();
        let dest = to.join(entry.file_name());
        if path.is_dir() {
            copy_tree(&path, &dest)?;
        } else {
            std::fs::copy(&path, &dest).map_err(BookError::io(&path))?;
        }
    }
    Ok(())
}

/// Copies `repo/book` to `stage` (emptied first) and the reference docs.
pub fn prepare(repo: &Path, stage: &Path) -> Result<PathBuf, BookError> {
    if stage.exists() {
        std::fs::remove_dir_all(stage).map_err(BookError::io(stage))?;
    }
    copy_tree(&repo.join("book"), stage)?;
    let src = stage.join("src");
    let reference = src.join("reference");
    std::fs::create_dir_all(&reference).map_err(BookError::io(&reference))?;
    for doc in REFERENCE_DOCS {
        let from = repo.join("docs").join(doc);
        std::fs::copy(&from, reference.join(doc)).map_err(BookError::io(&from))?;
    }
    copy_guide_images(repo, &src)?;
    Ok(src)
}

/// The guide's pages show or link a file of the repository as
/// `../docs/x.png` (from `src/guide/`); each one named is copied to
/// `src/docs/x.png`. A file that does not exist is left for the link check
/// to report.
fn copy_guide_images(repo: &Path, src: &Path) -> Result<(), BookError> {
    let mut pages = Vec::new();
    for dir in [src.to_path_buf(), src.join("guide"), src.join("reference")] {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        pages.extend(
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "md")),
        );
    }
    for page in pages {
        let text = std::fs::read_to_string(&page).map_err(BookError::io(&page))?;
        for target in link_targets(&text) {
            let rel = target.trim_start_matches("../");
            let from = repo.join(rel);
            if (rel.starts_with("docs/") || rel.starts_with("tests/")) && from.is_file() {
                let to = src.join(rel);
                std::fs::create_dir_all(to.parent().unwrap()).map_err(BookError::io(&to))?;
                std::fs::copy(&from, &to).map_err(BookError::io(&from))?;
            }
        }
    }
    Ok(())
}

/// The targets of `[…](target)` and `![…](target)` in Markdown, without a
/// `#fragment`.
pub fn link_targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].trim();
        out.push(target.split('#').next().unwrap_or(target).to_string());
        rest = &after[end..];
    }
    out
}
