//! Worker threads.

use crate::error::RunError;

/// A rayon pool of `threads` workers (default: one per core), named `rtprof-worker-N`
/// so that profiles and debuggers show whose stack is whose.
pub fn thread_pool(threads: Option<u16>) -> Result<rayon::ThreadPool, RunError> {
    let mut pool = rayon::ThreadPoolBuilder::new().thread_name(|i| format!("rtprof-worker-{i}"));
    if let Some(n) = threads {
        pool = pool.num_threads(usize::from(n));
    }
    pool.build().map_err(|e| RunError::Render {
        context: "worker threads".into(),
        message: format!("cannot start them: {e}"),
    })
}
