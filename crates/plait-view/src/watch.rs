//! Watching the files a render reads, for the viewer's hot reload and
//! `plait render --watch`.
//!
//! The folders holding the files are watched, not the files: editors save by
//! writing a new file and renaming it over the old one, which a watch on the
//! old file's inode would miss. Events are filtered down to the listed files
//! and gathered until the folder has been quiet for a moment, since one save
//! is often several events (truncate, write, rename).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use notify::{EventKind, RecursiveMode, Watcher};

/// Quiet time that ends one save's burst of events.
const SETTLE: Duration = Duration::from_millis(80);
/// A burst is cut off after this long even if events keep coming.
const MAX_BURST: Duration = Duration::from_millis(400);

#[derive(Debug, thiserror::Error)]
pub enum WatchError {
    #[error("cannot watch files for changes: {0}")]
    Notify(#[from] notify::Error),
}

/// Watches a set of files through their folders.
pub struct FileWatcher {
    watcher: notify::RecommendedWatcher,
    events: Receiver<notify::Result<notify::Event>>,
    /// Absolute paths of the files that matter.
    files: BTreeSet<PathBuf>,
    folders: BTreeSet<PathBuf>,
}

/// An absolute path with its folder resolved through symlinks, the form
/// watch events name files by (the file itself may not exist yet).
pub(crate) fn absolute(path: &Path) -> PathBuf {
    let joined = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    match (joined.parent(), joined.file_name()) {
        (Some(dir), Some(name)) => dir
            .canonicalize()
            .unwrap_or_else(|_| dir.to_path_buf())
            .join(name),
        _ => joined,
    }
}

impl FileWatcher {
    pub fn new() -> Result<Self, WatchError> {
        let (tx, events) = channel();
        let watcher = notify::recommended_watcher(move |e| {
            let _ = tx.send(e);
        })?;
        Ok(FileWatcher {
            watcher,
            events,
            files: BTreeSet::new(),
            folders: BTreeSet::new(),
        })
    }

    /// Watch exactly `files` from now on (folders no longer needed are released).
    pub fn set_files(&mut self, files: &[PathBuf]) -> Result<(), WatchError> {
        let files: BTreeSet<PathBuf> = files.iter().map(|f| absolute(f)).collect();
        let folders: BTreeSet<PathBuf> = files
            .iter()
            .filter_map(|f| f.parent())
            .filter(|d| d.is_dir())
            .map(Path::to_path_buf)
            .collect();
        for gone in self.folders.difference(&folders) {
            let _ = self.watcher.unwatch(gone);
        }
        for new in folders.difference(&self.folders) {
            self.watcher.watch(new, RecursiveMode::NonRecursive)?;
        }
        self.files = files;
        self.folders = folders;
        Ok(())
    }

    /// The files watched, absolute.
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.files.iter().map(PathBuf::as_path)
    }

    /// Listed files changed by one event (reads are not changes).
    fn matching(&self, event: &notify::Result<notify::Event>) -> Vec<PathBuf> {
        let Ok(event) = event else {
            return Vec::new();
        };
        if matches!(event.kind, EventKind::Access(_)) {
            return Vec::new();
        }
        event
            .paths
            .iter()
            .map(|p| absolute(p))
            .filter(|p| self.files.contains(p))
            .collect()
    }

    /// Files changed since the last call: waits up to `timeout` for a first
    /// change, then until the burst it belongs to is over. Empty on timeout.
    pub fn changes(&mut self, timeout: Duration) -> Vec<PathBuf> {
        let mut changed = BTreeSet::new();
        let deadline = Instant::now() + timeout;
        // Wait for the first relevant event.
        while changed.is_empty() {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.events.recv_timeout(left) {
                Ok(e) => changed.extend(self.matching(&e)),
                Err(RecvTimeoutError::Timeout) | Err(RecvTimeoutError::Disconnected) => {
                    return Vec::new();
                }
            }
        }
        // Then gather the rest of the burst.
        let burst_end = Instant::now() + MAX_BURST;
        while Instant::now() < burst_end {
            match self.events.recv_timeout(SETTLE) {
                Ok(e) => changed.extend(self.matching(&e)),
                Err(_) => break,
            }
        }
        changed.into_iter().collect()
    }
}

/// Run `action` now and again after every change to the files it returns
/// (what that run read: an edit can change what is read), until the process
/// is interrupted. `action` reports its own errors; `on_wait` is told how
/// many files are being watched.
pub fn run_on_changes(
    mut action: impl FnMut() -> Vec<PathBuf>,
    mut on_wait: impl FnMut(usize),
) -> Result<(), WatchError> {
    let mut watcher = FileWatcher::new()?;
    loop {
        let files = action();
        watcher.set_files(&files)?;
        on_wait(watcher.files.len());
        while watcher.changes(Duration::from_secs(3600)).is_empty() {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_save_by_rename_is_seen_and_other_files_are_not() {
        let dir = tempfile::tempdir().expect("temp dir");
        let watched = dir.path().join("pipeline.toml");
        let other = dir.path().join("notes.txt");
        std::fs::write(&watched, "a").expect("write");
        let mut w = FileWatcher::new().expect("watcher");
        w.set_files(std::slice::from_ref(&watched)).expect("watch");

        std::fs::write(&other, "x").expect("write");
        assert!(w.changes(Duration::from_millis(300)).is_empty());

        // What editors do: write a temporary file, rename it over the original.
        let tmp = dir.path().join(".pipeline.toml.swp");
        std::fs::write(&tmp, "b").expect("write");
        std::fs::rename(&tmp, &watched).expect("rename");
        let changed = w.changes(Duration::from_secs(5));
        assert_eq!(changed, vec![absolute(&watched)]);

        // A plain in-place write too.
        std::fs::write(&watched, "c").expect("write");
        assert_eq!(w.changes(Duration::from_secs(5)), vec![absolute(&watched)]);
    }

    #[test]
    fn files_in_new_folders_are_watched_after_set_files() {
        let a = tempfile::tempdir().expect("temp dir");
        let b = tempfile::tempdir().expect("temp dir");
        let fa = a.path().join("a.wgsl");
        let fb = b.path().join("b.wgsl");
        std::fs::write(&fa, "").expect("write");
        std::fs::write(&fb, "").expect("write");
        let mut w = FileWatcher::new().expect("watcher");
        w.set_files(std::slice::from_ref(&fa)).expect("watch");
        w.set_files(std::slice::from_ref(&fb)).expect("watch");
        std::fs::write(&fa, "1").expect("write");
        assert!(
            w.changes(Duration::from_millis(300)).is_empty(),
            "a is no longer watched"
        );
        std::fs::write(&fb, "1").expect("write");
        assert_eq!(w.changes(Duration::from_secs(5)), vec![absolute(&fb)]);
    }
}
