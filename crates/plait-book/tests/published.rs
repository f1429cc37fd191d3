//! The published figures (docs/figures.toml) are what their records say:
//! every registered figure has its record and its block on its page, each
//! block is exactly its record's table and provenance line (no table typed
//! or edited by hand), and no page carries a figure marker nobody registered.
//! No GPU: re-measuring is `bash scripts/bench.sh --check`.

use std::path::{Path, PathBuf};

use plait_book::published::{self, Registry};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn every_published_block_is_its_records_table() {
    let problems = published::consistency(&repo()).expect("the registry and pages read");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    let registry = Registry::load(&repo()).unwrap();
    assert!(registry.figure("transparency-480").is_some());
}

/// A copy of the registry (this figure alone), its record and its page, with
/// the page's table then edited by hand: the check must name the figure.
#[test]
fn a_hand_edited_table_is_caught() {
    let repo = repo();
    let registry = Registry::load(&repo).unwrap();
    let figure = &registry.figures[0];
    let dir = tempfile::tempdir().unwrap();
    let copy = |rel: &str| {
        let to = dir.path().join(rel);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(repo.join(rel), &to).unwrap();
    };
    copy(&figure.page);
    copy(&format!("{}/{}.json", published::RECORDS, figure.id));
    let text = std::fs::read_to_string(repo.join(published::REGISTRY)).unwrap();
    let mine = text
        .split("[[figure]]")
        .find(|part| part.contains(&format!("id = \"{}\"", figure.id)))
        .unwrap();
    std::fs::write(
        dir.path().join(published::REGISTRY),
        format!("[[figure]]{mine}"),
    )
    .unwrap();
    for m in &figure.measures {
        std::fs::create_dir_all(dir.path().join(m)).unwrap();
    }
    assert_eq!(
        published::consistency(dir.path()).unwrap(),
        Vec::<String>::new()
    );
    // One frame time in the table changed by hand.
    let page = dir.path().join(&figure.page);
    let text = std::fs::read_to_string(&page).unwrap();
    let block = published::block(&text, &figure.id).unwrap();
    let row = block
        .lines()
        .find(|l| l.starts_with("| ") && !l.starts_with("| variant"))
        .unwrap();
    let edited = row.replacen(" | ", " | 1", 1);
    std::fs::write(&page, text.replacen(row, &edited, 1)).unwrap();
    let problems = published::consistency(dir.path()).unwrap();
    assert!(
        problems.len() == 1
            && problems[0].contains("edited by hand")
            && problems[0].contains(&figure.id),
        "{problems:?}"
    );
}
