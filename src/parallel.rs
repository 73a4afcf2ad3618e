//! The one place that decides how the core uses threads.
//!
//! Work runs in a private rayon pool of the requested size (never the global pool, so the
//! core does not oversubscribe a machine that is also rendering), cached per size. Results
//! never depend on the pool size: every parallel loop writes disjoint, precomputed slices and
//! all randomness is keyed by stitch, not by thread.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use rayon::{ThreadPool, ThreadPoolBuilder};

use crate::error::{KnitError, Result};

/// Most threads a caller may ask for.
pub const MAX_THREADS: usize = 256;

fn pools() -> &'static Mutex<HashMap<usize, Arc<ThreadPool>>> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<ThreadPool>>>> = OnceLock::new();
    POOLS.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Threads used when the caller does not say: the machine's available parallelism.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs `f` inside a private pool of `threads` threads (`None`: [`default_threads`]).
pub fn run_in_pool<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> Result<R> {
    let n = threads.unwrap_or_else(default_threads);
    if n == 0 || n > MAX_THREADS {
        return Err(KnitError::Parameter(format!(
            "threads must be 1..{MAX_THREADS}, not {n}"
        )));
    }
    let pool = {
        let mut map = pools()
            .lock()
            .map_err(|_| KnitError::Internal("thread pool cache poisoned".into()))?;
        match map.get(&n) {
            Some(p) => p.clone(),
            None => {
                let p = ThreadPoolBuilder::new()
                    .num_threads(n)
                    .thread_name(|i| format!("knitwear-{i}"))
                    .build()
                    .map_err(|e| KnitError::Internal(format!("cannot start {n} threads: {e}")))?;
                let p = Arc::new(p);
                map.insert(n, p.clone());
                p
            }
        }
    };
    Ok(pool.install(f))
}

/// Splits `buf` into consecutive mutable slices of the given lengths (which must add up to at
/// most `buf.len()`), for writing pieces of one output buffer in parallel.
pub fn split_lengths<'a, T>(mut buf: &'a mut [T], lengths: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(lengths.len());
    for &len in lengths {
        let (head, tail) = std::mem::take(&mut buf).split_at_mut(len);
        out.push(head);
        buf = tail;
    }
    out
}
