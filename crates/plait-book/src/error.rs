//! What can go wrong building the book; every variant names the file or the
//! command, so `scripts/book.sh` can say what to fix.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum BookError {
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    /// A `plait` command the book runs failed; its stderr says why.
    #[error("`{command}` failed ({status}):\n{stderr}")]
    Command {
        command: String,
        status: String,
        stderr: String,
    },
    /// A file the generator reads does not say what it should.
    #[error("{}: {message}", path.display())]
    Content { path: PathBuf, message: String },
    /// mdBook refused the staged book.
    #[error("mdBook: {0:#}")]
    MdBook(anyhow::Error),
}

impl BookError {
    pub(crate) fn io(path: impl Into<PathBuf>) -> impl FnOnce(std::io::Error) -> BookError {
        let path = path.into();
        move |error| BookError::Io { path, error }
    }

    pub(crate) fn content(path: impl Into<PathBuf>, message: impl Into<String>) -> BookError {
        BookError::Content {
            path: path.into(),
            message: message.into(),
        }
    }
}
