//! Strand geometry (issue 3).
