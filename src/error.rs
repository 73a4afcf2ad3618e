//! The core's error type. Every failure a user can cause is a variant here; the binding layer
//! (`src/python/`) maps each variant to one Python exception class, exhaustively.

use thiserror::Error;

/// Errors of the knitwear core. Messages are written for the person who caused them: they
/// say what was wrong and, where it helps, what to do instead.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum KnitError {
    /// The input surface cannot be knitted: wrong buffer sizes, NaN or infinite coordinates,
    /// no area, no UV triangle with area, and the like.
    #[error("bad surface: {0}")]
    Surface(String),
    /// A stitch or colour pattern text that does not parse, named by row and column.
    #[error("bad pattern: {0}")]
    Pattern(String),
    /// A setting out of its range (zero gauge, negative yarn radius, too few ring segments).
    #[error("bad setting: {0}")]
    Parameter(String),
    /// The output would exceed the memory budget; nothing was allocated.
    #[error("over budget: {0}")]
    Budget(String),
    /// The call was stopped on request ([`crate::cancel`]); nothing it made was kept.
    #[error("cancelled: the knit was stopped before it finished")]
    Cancelled,
    /// A bug in knitwear (a caught panic, a broken invariant). Not the user's fault.
    #[error("internal error (please report it): {0}")]
    Internal(String),
}

/// Result alias used across the core.
pub type Result<T> = std::result::Result<T, KnitError>;
