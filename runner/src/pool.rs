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

/// The workers worth starting for a job of `pieces` independent pieces (a render's
/// sample rows, its only parallel work): `threads` (default: rayon's, one per core or
/// `RAYON_NUM_THREADS`), but no more than there are pieces, so that a render of one
/// row starts one worker instead of one per core. `None` keeps rayon's default.
pub fn workers_for(threads: Option<u16>, pieces: u64) -> Option<u16> {
    let most = u16::try_from(pieces.max(1)).unwrap_or(u16::MAX);
    match threads {
        Some(n) => Some(n.min(most)),
        // One piece, one worker, whatever the default (without reading the cgroup
        // files that finding the default takes).
        None if most == 1 => Some(1),
        None => {
            let default = std::env::var("RAYON_NUM_THREADS")
                .ok()
                .and_then(|v| v.trim().parse::<usize>().ok())
                .filter(|&n| n > 0)
                .or_else(|| std::thread::available_parallelism().ok().map(|n| n.get()))
                .unwrap_or(1);
            (usize::from(most) < default).then_some(most)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_more_workers_than_pieces() {
        assert_eq!(workers_for(Some(8), 1), Some(1));
        assert_eq!(workers_for(Some(8), 0), Some(1));
        assert_eq!(workers_for(None, 1), Some(1));
        assert_eq!(workers_for(Some(2), 480), Some(2));
        assert_eq!(workers_for(Some(3), 3), Some(3));
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        if std::env::var_os("RAYON_NUM_THREADS").is_none() {
            assert_eq!(workers_for(None, 2), (cores > 2).then_some(2));
            assert_eq!(workers_for(None, 100_000), None);
        }
    }
}
