//! The guide's runnable commands: a fenced block marked ```` ```sh,runnable ````
//! holds `plait` commands that a test runs on the small scene (as `cargo
//! test` runs doctests), so the guide cannot drift from the CLI.

use std::path::{Path, PathBuf};

use crate::error::BookError;

/// The fence info string that marks a block as runnable.
pub const RUNNABLE: &str = "sh,runnable";

/// One command of a runnable block.
#[derive(Clone, Debug)]
pub struct Runnable {
    pub file: PathBuf,
    /// 1-based line of the command's first line.
    pub line: usize,
    /// The command, continuation lines joined, its trailing comment removed.
    pub command: String,
    /// Its lines' trailing comments, joined (what the text says it does).
    pub comment: String,
}

/// Every runnable command of the Markdown files under `dir`, in file order.
pub fn commands(dir: &Path) -> Result<Vec<Runnable>, BookError> {
    let mut files = Vec::new();
    collect(dir, &mut files)?;
    files.sort();
    let mut out = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).map_err(BookError::io(&file))?;
        out.extend(in_text(&file, &text));
    }
    Ok(out)
}

/// The runnable commands of one Markdown file (the README's tour).
pub fn in_file(file: &Path) -> Result<Vec<Runnable>, BookError> {
    let text = std::fs::read_to_string(file).map_err(BookError::io(file))?;
    Ok(in_text(file, &text))
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), BookError> {
    for e in std::fs::read_dir(dir).map_err(BookError::io(dir))? {
        let p = e.map_err(BookError::io(dir))?.path();
        if p.is_dir() {
            collect(&p, out)?;
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
    Ok(())
}

fn in_text(file: &Path, text: &str) -> Vec<Runnable> {
    let mut out = Vec::new();
    let mut inside = false;
    let mut pending: Option<Runnable> = None;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(info) = t.strip_prefix("```") {
            inside = !inside && info.trim() == RUNNABLE;
            continue;
        }
        if !inside {
            continue;
        }
        let code = strip_comment(t);
        if code.is_empty() && pending.is_none() {
            continue;
        }
        let (part, continues) = match code.strip_suffix('\\') {
            Some(p) => (p.trim_end(), true),
            None => (code, false),
        };
        let cmd = pending.get_or_insert_with(|| Runnable {
            file: file.to_path_buf(),
            line: i + 1,
            command: String::new(),
            comment: String::new(),
        });
        if let Some(i) = t.find(" #").filter(|_| !t.starts_with('#')) {
            cmd.comment.push_str(t[i + 2..].trim());
        }
        if !cmd.command.is_empty() {
            cmd.command.push(' ');
        }
        cmd.command.push_str(part);
        if !continues {
            out.extend(pending.take());
        }
    }
    out
}

/// The command without its ` # comment` (or a line that is only a comment).
fn strip_comment(line: &str) -> &str {
    if line.starts_with('#') {
        return "";
    }
    match line.find(" #") {
        Some(i) => line[..i].trim_end(),
        None => line,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_continuations_and_comments() {
        let text = "```sh\nplait not_this\n```\n\n```sh,runnable\n# a comment\nplait render --out a.png   # why\n\
                    plait ab x.toml \\\n    --reference y.toml --out r\n```\n";
        let found = in_text(Path::new("p.md"), text);
        let cmds: Vec<(&str, usize)> = found.iter().map(|r| (r.command.as_str(), r.line)).collect();
        assert_eq!(
            cmds,
            [
                ("plait render --out a.png", 7),
                ("plait ab x.toml --reference y.toml --out r", 8)
            ]
        );
    }
}
