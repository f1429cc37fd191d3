//! Pass library.
