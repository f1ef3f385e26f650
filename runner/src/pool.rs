//! Worker threads, and the one rule of how many a user may ask for
//! ([`check_threads`]: the command line's `--threads` and the web app's `threads`).

use crate::error::RunError;

/// Worker threads per logical CPU that can still help: a render keeps every thread
/// busy, so beyond one per CPU threads only queue for the same cores; a few more leave
/// room for measuring oversubscription (and for CPUs the machine reports too few of),
/// thousands only load the machine (1,008 threads on two cores kept a job at
/// "starting" for minutes, issue 40).
pub const THREADS_PER_CPU: usize = 4;

/// A thread count outside the rule of [`check_threads`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "threads {asked}: choose 1 to {max} ({THREADS_PER_CPU} × the {cpus} logical CPU{s} of this machine; more threads only queue for the same cores), or leave it out for one per core",
    s = if *.cpus == 1 { "" } else { "s" }
)]
pub struct ThreadsError {
    pub asked: u64,
    pub max: u16,
    pub cpus: usize,
}

/// The most worker threads a render may use here: [`THREADS_PER_CPU`] × the logical
/// CPUs this process may run on (`std::thread::available_parallelism`, which reads
/// the affinity mask and the cgroup quota), and with it the CPU count.
pub fn max_threads() -> (u16, usize) {
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max = u16::try_from(cpus.saturating_mul(THREADS_PER_CPU)).unwrap_or(u16::MAX);
    (max, cpus)
}

/// `threads` if it is 1 to [`max_threads`]: the one rule of every place a user names
/// a thread count (the CLI exits 2 and the API answers 422 with its message).
pub fn check_threads(threads: u64) -> Result<u16, ThreadsError> {
    let (max, cpus) = max_threads();
    match u16::try_from(threads) {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(ThreadsError {
            asked: threads,
            max,
            cpus,
        }),
    }
}

/// Parses a `--threads` count by [`check_threads`]'s rule.
pub fn parse_threads(text: &str) -> Result<u16, String> {
    let n: u64 = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a thread count: give a whole number such as 2"))?;
    check_threads(n).map_err(|e| e.to_string())
}

/// A rayon pool of `threads` workers (default: one per core), named `rtprof-worker-N`
/// so that profiles and debuggers show whose stack is whose. A count beyond
/// [`check_threads`]'s rule is refused.
pub fn thread_pool(threads: Option<u16>) -> Result<rayon::ThreadPool, RunError> {
    let mut pool = rayon::ThreadPoolBuilder::new().thread_name(|i| format!("rtprof-worker-{i}"));
    if let Some(n) = threads {
        let n = check_threads(u64::from(n)).map_err(|e| RunError::Input(e.to_string()))?;
        pool = pool.num_threads(usize::from(n));
    }
    pool.build().map_err(|e| RunError::Render {
        context: "worker threads".into(),
        message: format!("cannot start them: {e}"),
    })
}

/// Where a render's rows run: on the calling thread, or in a pool of worker threads.
pub enum Workers {
    /// One worker, and the caller is no pool's worker: the rows run on the calling thread
    /// (`tracer::render` does that outside any pool), without starting a thread for it
    /// (a fifth of a 1×1 render's time in the process).
    Calling,
    Pool(rayon::ThreadPool),
}

impl Workers {
    /// `threads` workers (default: one per core), on the calling thread when that is one
    /// and it is not itself a pool's worker (where the tracer would use that pool).
    pub fn new(threads: Option<u16>) -> Result<Self, RunError> {
        if threads == Some(1) && rayon::current_thread_index().is_none() {
            return Ok(Self::Calling);
        }
        thread_pool(threads).map(Self::Pool)
    }

    /// Runs `work` where the workers are.
    pub fn install<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        match self {
            Self::Calling => work(),
            Self::Pool(pool) => pool.install(work),
        }
    }

    /// How many threads trace.
    pub fn threads(&self) -> usize {
        match self {
            Self::Calling => 1,
            Self::Pool(pool) => pool.current_num_threads(),
        }
    }
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
    fn one_worker_is_the_calling_thread_unless_it_is_a_pool_s_worker() {
        let workers = Workers::new(Some(1)).unwrap_or_else(|e| panic!("{e}"));
        assert!(matches!(workers, Workers::Calling));
        assert_eq!(workers.threads(), 1);
        let here = std::thread::current().id();
        assert_eq!(workers.install(|| std::thread::current().id()), here);
        // Inside a pool the tracer would use that pool: one worker gets a pool of its own.
        let outer = thread_pool(Some(2)).unwrap_or_else(|e| panic!("{e}"));
        let inner = outer.install(|| Workers::new(Some(1)).unwrap_or_else(|e| panic!("{e}")));
        assert!(matches!(inner, Workers::Pool(_)));
        assert_eq!(inner.threads(), 1);
        let two = Workers::new(Some(2)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(two.threads(), 2);
        assert_ne!(two.install(|| std::thread::current().id()), here);
    }

    #[test]
    fn thread_counts_are_1_to_4_per_logical_cpu() {
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        let max = 4 * cpus as u64;
        assert_eq!(max_threads(), (max as u16, cpus));
        assert_eq!(check_threads(1), Ok(1));
        assert_eq!(check_threads(max), Ok(max as u16));
        for bad in [0, max + 1, 999 + max, 70_000] {
            let e = check_threads(bad).unwrap_err();
            let message = e.to_string();
            assert!(
                message.starts_with(&format!("threads {bad}: ")),
                "{message}"
            );
            assert!(
                message.contains(&format!("choose 1 to {max} ")),
                "{message}"
            );
        }
        // The pools obey the same rule.
        let too_many = u16::try_from(max + 1).unwrap_or(u16::MAX);
        assert!(
            matches!(thread_pool(Some(too_many)), Err(RunError::Input(m)) if m.contains("choose 1 to"))
        );
        assert!(matches!(Workers::new(Some(0)), Err(RunError::Input(_))));
    }

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
