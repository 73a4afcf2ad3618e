//! Stopping long work on request: Ctrl-C in Python, Esc in Blender (through
//! `knitwear.cancel()`), within a fraction of a second.
//!
//! One flag for the whole process, as Ctrl-C is: a request stops every core call running at
//! that moment. Long loops poll [`requested`] (a relaxed atomic load: free next to their
//! work) and stop early; each stage then returns [`KnitError::Cancelled`] through [`check`].
//! Work stopped half-way is thrown away, never cached. The flag clears when the last call
//! that was running ends ([`Call`]), so the next call starts afresh.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::error::{KnitError, Result};

static REQUESTED: AtomicBool = AtomicBool::new(false);
static ACTIVE: AtomicUsize = AtomicUsize::new(0);

/// Asks every core call now running to stop.
pub fn request() {
    if ACTIVE.load(Ordering::SeqCst) > 0 {
        REQUESTED.store(true, Ordering::SeqCst);
    }
}

/// Whether a stop was asked for: long loops poll this and stop early.
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// [`KnitError::Cancelled`] if a stop was asked for: stages call this after their loops, so
/// that what a stopped loop left half-made goes no further.
pub fn check() -> Result<()> {
    if requested() {
        Err(KnitError::Cancelled)
    } else {
        Ok(())
    }
}

/// One core call, from its start to its end (a guard): the last call to end clears the flag.
pub struct Call(());

impl Call {
    pub fn begin() -> Self {
        ACTIVE.fetch_add(1, Ordering::SeqCst);
        Call(())
    }
}

impl Drop for Call {
    fn drop(&mut self) {
        if ACTIVE.fetch_sub(1, Ordering::SeqCst) == 1 {
            REQUESTED.store(false, Ordering::SeqCst);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_stops_running_calls_and_clears_when_they_end() {
        // Without a running call, a request is ignored (nothing to stop, nothing to leak
        // into the next call).
        request();
        assert!(check().is_ok());
        let call = Call::begin();
        request();
        assert_eq!(check(), Err(KnitError::Cancelled));
        drop(call);
        let next = Call::begin();
        assert!(check().is_ok());
        drop(next);
    }
}
