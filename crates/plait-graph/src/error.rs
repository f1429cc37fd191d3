//! Errors with the place in a pipeline file (or the command-line flag) they come from.

use std::fmt;
use std::path::PathBuf;

/// Where a value came from: a position in a file, or a command-line override.
#[derive(Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(tag = "origin", rename_all = "snake_case")]
pub enum Location {
    /// 1-based line and column in a file.
    File {
        path: PathBuf,
        line: u32,
        column: u32,
    },
    /// A whole file, where no line is meant (it cannot be read at all).
    Path { path: PathBuf },
    /// A `--set key=value` flag (the whole flag text).
    Flag { flag: String },
    /// Built in defaults (a pass type's default param, the default scene…).
    Builtin,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::File { path, line, column } => {
                write!(f, "{}:{line}:{column}", path.display())
            }
            Location::Path { path } => write!(f, "{}", path.display()),
            Location::Flag { flag } => write!(f, "--set {flag}"),
            Location::Builtin => f.write_str("<builtin>"),
        }
    }
}

/// A value with the place it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    pub value: T,
    pub location: Location,
}

impl<T> Spanned<T> {
    pub fn new(value: T, location: Location) -> Self {
        Spanned { value, location }
    }
}

impl<T> std::ops::Deref for Spanned<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

/// One problem found in a pipeline, printed as `file:line:col: message`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{location}: {kind}")]
pub struct Error {
    pub location: Location,
    pub kind: ErrorKind,
}

impl Error {
    pub fn new(location: Location, kind: ErrorKind) -> Self {
        Error { location, kind }
    }
}

/// What went wrong. Variants carry the names involved so a message can say
/// exactly which pass, resource or param is at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    /// The file the location names cannot be read.
    #[error("cannot read file: {0}")]
    Io(String),
    /// A file named at the location (`extends`, `includes`) cannot be read:
    /// `PATH: cannot read file: …`, the form every missing input file has.
    #[error("{}: cannot read file: {reason}", path.display())]
    ReadFile { path: PathBuf, reason: String },
    #[error("TOML syntax error: {0}")]
    Syntax(String),
    #[error("{0}")]
    Schema(String),
    #[error("`extends` chain loops back to {0}")]
    ExtendsCycle(PathBuf),
    #[error("malformed --set `{flag}`: {reason}")]
    MalformedSet { flag: String, reason: String },
    /// A `--set` key that names nothing in the pipeline (the location is the flag).
    #[error("{reason}")]
    UnknownSetKey { key: String, reason: String },
    #[error("`${{{0}}}` is not defined in [params]")]
    UndefinedParam(String),
    #[error("unknown pass type `{name}`{} (known: {known})", hint(name, known))]
    UnknownPassType { name: String, known: String },
    #[error(
        "pass `{pass}` of type `{pass_type}` has no param `{param}`{} (it has: {known})",
        hint(param, known)
    )]
    UnknownParam {
        pass: String,
        pass_type: String,
        param: String,
        known: String,
    },
    #[error("param `{param}` of pass `{pass}`: {reason}")]
    BadParam {
        pass: String,
        param: String,
        reason: String,
    },
    /// One `--set` value refused the same way by several passes (a param
    /// every hair draw takes): one error, naming them all.
    #[error("param `{param}` of passes {}: {reason}", passes.iter().map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", "))]
    BadParamOfPasses {
        passes: Vec<String>,
        param: String,
        reason: String,
    },
    #[error(
        "pass `{pass}` of type `{pass_type}` has no {direction} slot `{slot}`{} (it has: {known})",
        hint(slot, known)
    )]
    UnknownSlot {
        pass: String,
        pass_type: String,
        direction: &'static str,
        slot: String,
        known: String,
    },
    #[error("pass `{pass}` does not bind its required {direction} slot `{slot}`")]
    MissingSlot {
        pass: String,
        direction: &'static str,
        slot: String,
    },
    #[error("resource `{name}` is used but not declared in [resources]{hint}")]
    UndeclaredResource {
        name: String,
        /// `; did you mean …?` or empty.
        hint: String,
    },
    #[error("resource `{resource}` is read by pass `{reader}` but no pass writes it")]
    NeverWritten { resource: String, reader: String },
    #[error(
        "resource `{resource}` is written by passes `{first}` and `{second}` with no order between them"
    )]
    UnorderedWriters {
        resource: String,
        first: String,
        second: String,
    },
    #[error("cycle between passes: {}", .0.join(" -> "))]
    Cycle(Vec<String>),
    #[error(
        "resource `{resource}` has format {declared}, but pass `{pass}` slot `{slot}` accepts {accepted}"
    )]
    FormatMismatch {
        resource: String,
        declared: String,
        pass: String,
        slot: String,
        accepted: String,
    },
    #[error(
        "resource `{resource}` is a {declared}, but pass `{pass}` slot `{slot}` needs a {expected}"
    )]
    KindMismatch {
        resource: String,
        declared: String,
        pass: String,
        slot: String,
        expected: String,
    },
    #[error("output `{name}` is not a declared resource{hint}")]
    UnknownOutput {
        name: String,
        /// `; did you mean …?` or empty.
        hint: String,
    },
    #[error("output `{0}` is not written by any pass")]
    OutputNeverWritten(String),
    #[error("shader {path}: {message}")]
    Shader { path: PathBuf, message: String },
    #[error(
        "pass `{pass}`: shader binding `{binding}` (group {group}, binding {index}) is not provided by the pipeline file"
    )]
    MissingBinding {
        pass: String,
        binding: String,
        group: u32,
        index: u32,
    },
    #[error("pass `{pass}`: {message}")]
    Pass { pass: String, message: String },
    #[error("params refer to each other in a loop: {}", .0.join(" -> "))]
    ParamCycle(Vec<String>),
    #[error("pass `{pass}` does not set its required param `{param}` (no default)")]
    MissingParam { pass: String, param: String },
    #[error(
        "texture `{resource}` is {width}x{height}; each side must be between 1 and the device limit {limit}"
    )]
    TextureSize {
        resource: String,
        width: i64,
        height: i64,
        limit: u32,
    },
    #[error("resource `{resource}`: {reason}")]
    BadResource { resource: String, reason: String },
    /// `NAME.previous…` of a resource that keeps no (or too short a) history.
    #[error("`{name}` is not declared: {reason}")]
    NoHistory { name: String, reason: String },
    #[error(
        "pass `{reader}` reads `{previous}`, an earlier frame's `{resource}`, but no pass writes `{resource}`"
    )]
    HistoryNeverWritten {
        previous: String,
        resource: String,
        reader: String,
    },
    #[error(
        "pass `{pass}` writes `{previous}`, an earlier frame's `{resource}`, which is read-only: write `{resource}` and the engine keeps its history"
    )]
    WritesHistory {
        pass: String,
        previous: String,
        resource: String,
    },
}

/// `; did you mean …?` for `name` among a `known` list joined by ", ".
fn hint(name: &str, known: &str) -> String {
    crate::suggest::did_you_mean(name, known.split(", "))
}

/// Every problem found in one load or compile; `Display` prints one per line.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub struct Errors(pub Vec<Error>);

impl fmt::Display for Errors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "error: {e}")?;
        }
        Ok(())
    }
}

impl From<Error> for Errors {
    fn from(e: Error) -> Self {
        Errors(vec![e])
    }
}
