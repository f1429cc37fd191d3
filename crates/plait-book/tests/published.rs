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

/// A copy of the registry, its records and their pages, with one page's
/// table then edited by hand: the check must name that figure alone.
#[test]
fn a_hand_edited_table_is_caught() {
    let repo = repo();
    let registry = Registry::load(&repo).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let copy = |rel: &str| {
        let to = dir.path().join(rel);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(repo.join(rel), &to).unwrap();
    };
    copy(published::REGISTRY);
    for figure in &registry.figures {
        copy(&figure.page);
        copy(&format!("{}/{}.json", published::RECORDS, figure.id));
        for m in figure.measures.iter().chain(&figure.except) {
            std::fs::create_dir_all(dir.path().join(m)).unwrap();
        }
    }
    assert_eq!(
        published::consistency(dir.path()).unwrap(),
        Vec::<String>::new()
    );
    // One frame time in the first figure's table changed by hand.
    let figure = &registry.figures[0];
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
            && problems[0].contains(&format!("`{}`", figure.id)),
        "{problems:?}"
    );
}
