//! Every command of a ```` ```sh,runnable ```` block in the book's guide and
//! in the README's tour runs, with this crate's `plait`, in an empty folder,
//! and succeeds — as `cargo test` runs doctests, so the text cannot drift
//! from the CLI. The blocks use the small scene so each takes seconds.

mod common;

use common::{root, text};
use plait_book::runnable;

#[test]
fn every_runnable_command_of_the_guide_and_readme_succeeds() {
    let mut commands = runnable::commands(&root().join("book/src")).expect("book/src");
    let readme = runnable::in_file(&root().join("README.md")).expect("README.md");
    assert!(
        readme.len() >= 5,
        "the README's tour has {} runnable commands",
        readme.len()
    );
    commands.extend(readme);
    assert!(
        commands.len() >= 10,
        "only {} runnable commands found",
        commands.len()
    );

    let dir = tempfile::tempdir().unwrap();
    let mut failed = Vec::new();
    for c in &commands {
        let at = format!(
            "{}:{}",
            c.file.strip_prefix(root()).unwrap_or(&c.file).display(),
            c.line
        );
        // The blocks are plain words: a quote or shell syntax would be run
        // differently here than in a shell, so it is not allowed in them.
        assert!(
            !c.command
                .contains(['"', '\'', '|', '>', '<', '$', ';', '&', '`']),
            "{at}: a runnable command is plain words: {}",
            c.command
        );
        let words: Vec<&str> = c.command.split_whitespace().collect();
        assert_eq!(
            words.first(),
            Some(&"plait"),
            "{at}: a runnable command runs plait: {}",
            c.command
        );
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_plait"))
            .current_dir(dir.path())
            .args(&words[1..])
            .output()
            .expect("run plait");
        // A file the comment names under the command's `--out` folder
        // (`# report/report.html, …`) is one the command wrote.
        let out_dir = words
            .iter()
            .position(|w| *w == "--out")
            .and_then(|i| words.get(i + 1));
        for named in c.comment.split([' ', ',']).filter(|w| {
            out_dir.is_some_and(|d| w.strip_prefix(d).is_some_and(|r| r.starts_with('/')))
        }) {
            if out.status.success() && !dir.path().join(named).exists() {
                failed.push(format!(
                    "{at}: its comment names {named}, which `{}` did not write",
                    c.command
                ));
            }
        }
        if !out.status.success() {
            failed.push(format!(
                "{at}: `{}` failed ({}):\n{}",
                c.command,
                out.status,
                text(&out.stderr)
            ));
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}
