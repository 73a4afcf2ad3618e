//! Helpers shared by the integration tests. Each test file uses some of them.
#![allow(dead_code)]

pub mod cameras;
pub mod digest;
pub mod surfaces;
