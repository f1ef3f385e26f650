//! Our SIGPROF handler: installed in front of pprof's for a sampling run, it reads the
//! phase probe of the interrupted thread into a fixed lock-free table (atomics only, no
//! allocation, no lock: async-signal-safe), then calls pprof's handler, so every signal
//! gives both a phase key and a native stack. One run at a time per process
//! ([`BusyFlag`]): the handler and pprof's profiler are process-wide.

use super::error::ProfileError;
use super::sample_options::PhaseProbe;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};

/// Held while a sampling run is under way; released on drop (also on a panic).
pub(super) struct BusyFlag;

static BUSY: AtomicBool = AtomicBool::new(false);

impl BusyFlag {
    pub(super) fn take() -> Result<Self, ProfileError> {
        BUSY.compare_exchange(false, true, Ordering::AcqRel, Ordering::Acquire)
            .map(|_| BusyFlag)
            .map_err(|_| ProfileError::Busy)
    }
}

impl Drop for BusyFlag {
    fn drop(&mut self) {
        BUSY.store(false, Ordering::Release);
    }
}

// The signal handler's state. Statics, because a signal handler has no other way in;
// written only while no handler of ours is installed or recording (see
// `PhaseHandler`), read in the handler with atomics only.

/// Slots of the phase-key table (a power of two). Keys are phase stacks (4 bits a
/// level), so a render has tens of distinct keys, not thousands.
const KEY_SLOTS: usize = 1 << KEY_SLOT_BITS;
const KEY_SLOT_BITS: u32 = 10;
/// Open addressing: a slot's key (0 = free), claimed by compare-and-swap.
static KEYS: [AtomicU64; KEY_SLOTS] = [const { AtomicU64::new(0) }; KEY_SLOTS];
static KEY_COUNTS: [AtomicU64; KEY_SLOTS] = [const { AtomicU64::new(0) }; KEY_SLOTS];
/// Samples whose key was 0 (outside any phase): 0 cannot be a table key.
static OUTSIDE_COUNT: AtomicU64 = AtomicU64::new(0);
/// Samples whose key found no free slot.
static DROPPED: AtomicU64 = AtomicU64::new(0);
/// Signals seen while recording.
static SIGNALS: AtomicU64 = AtomicU64::new(0);
/// The probe (a `PhaseProbe` as an address), 0 = none.
static PROBE: AtomicUsize = AtomicUsize::new(0);
/// Whether the handler records (cleared before the table is read).
static RECORDING: AtomicBool = AtomicBool::new(false);
/// Handlers of ours running now (the table is read only once this is 0).
static IN_HANDLER: AtomicUsize = AtomicUsize::new(0);
/// The handler ours replaced (pprof's): its address and whether it takes siginfo.
static PREVIOUS_HANDLER: AtomicUsize = AtomicUsize::new(0);
static PREVIOUS_SIGINFO: AtomicBool = AtomicBool::new(false);

/// Signals seen so far in the run under way.
pub(super) fn signals_so_far() -> u64 {
    SIGNALS.load(Ordering::Relaxed)
}

/// What the phase handler recorded over one run.
pub(crate) struct PhaseCounts {
    pub(crate) keys: BTreeMap<u64, u64>,
    pub(crate) dropped: u64,
    pub(crate) signals: u64,
}

/// Our SIGPROF handler, installed over pprof's for the run; puts pprof's back on
/// `finish` or drop.
pub(super) struct PhaseHandler {
    /// pprof's action, restored as it was.
    previous: libc::sigaction,
    restored: bool,
}

impl PhaseHandler {
    pub(super) fn install(probe: Option<PhaseProbe>) -> Result<Self, ProfileError> {
        for (key, count) in KEYS.iter().zip(&KEY_COUNTS) {
            key.store(0, Ordering::Relaxed);
            count.store(0, Ordering::Relaxed);
        }
        OUTSIDE_COUNT.store(0, Ordering::Relaxed);
        DROPPED.store(0, Ordering::Relaxed);
        SIGNALS.store(0, Ordering::Relaxed);
        PROBE.store(probe.map_or(0, |p| p as usize), Ordering::Relaxed);
        // SAFETY: all-zero is a valid `sigaction` (no handler, empty mask, no flags).
        let mut previous: libc::sigaction = unsafe { std::mem::zeroed() };
        // SAFETY: a null new action only reads the current one into `previous`.
        if unsafe { libc::sigaction(libc::SIGPROF, std::ptr::null(), &mut previous) } != 0 {
            return Err(ProfileError::Start(format!(
                "cannot read the SIGPROF action: {}",
                std::io::Error::last_os_error()
            )));
        }
        // Stored before ours is installed, so its first signal already chains.
        PREVIOUS_HANDLER.store(previous.sa_sigaction, Ordering::SeqCst);
        PREVIOUS_SIGINFO.store(previous.sa_flags & libc::SA_SIGINFO != 0, Ordering::SeqCst);
        RECORDING.store(true, Ordering::SeqCst);
        // SAFETY: as above.
        let mut ours: libc::sigaction = unsafe { std::mem::zeroed() };
        ours.sa_sigaction = on_sigprof as *const () as usize;
        ours.sa_flags = libc::SA_SIGINFO | libc::SA_RESTART;
        // SAFETY: `ours` is a complete action whose handler has the 3-argument
        // signature SA_SIGINFO calls for; the mask is emptied in place.
        let installed = unsafe {
            libc::sigemptyset(&mut ours.sa_mask);
            libc::sigaction(libc::SIGPROF, &ours, std::ptr::null_mut())
        } == 0;
        if !installed {
            RECORDING.store(false, Ordering::SeqCst);
            return Err(ProfileError::Start(format!(
                "cannot install the phase handler: {}",
                std::io::Error::last_os_error()
            )));
        }
        Ok(PhaseHandler {
            previous,
            restored: false,
        })
    }

    /// Stops recording, waits out handlers still running, puts pprof's handler back
    /// and reads the table.
    pub(super) fn finish(mut self) -> Result<PhaseCounts, ProfileError> {
        self.restore()?;
        let mut keys = BTreeMap::new();
        for (key, count) in KEYS.iter().zip(&KEY_COUNTS) {
            let key = key.load(Ordering::Acquire);
            if key != 0 {
                *keys.entry(key).or_default() += count.load(Ordering::Acquire);
            }
        }
        let with_probe = PROBE.load(Ordering::Relaxed) != 0;
        let outside = OUTSIDE_COUNT.load(Ordering::Acquire);
        if with_probe && outside > 0 {
            keys.insert(0, outside);
        }
        Ok(PhaseCounts {
            keys,
            dropped: DROPPED.load(Ordering::Acquire),
            signals: SIGNALS.load(Ordering::Acquire),
        })
    }

    fn restore(&mut self) -> Result<(), ProfileError> {
        if self.restored {
            return Ok(());
        }
        self.restored = true;
        // A handler that starts after this sees RECORDING false and only chains; one
        // that started before has counted itself in IN_HANDLER (both SeqCst), so
        // once IN_HANDLER is 0 nothing writes the table any more.
        RECORDING.store(false, Ordering::SeqCst);
        while IN_HANDLER.load(Ordering::SeqCst) != 0 {
            std::hint::spin_loop();
        }
        // SAFETY: `previous` is the action read from the kernel at install.
        if unsafe { libc::sigaction(libc::SIGPROF, &self.previous, std::ptr::null_mut()) } != 0 {
            return Err(ProfileError::Report(format!(
                "cannot restore the profiler's SIGPROF handler: {}",
                std::io::Error::last_os_error()
            )));
        }
        Ok(())
    }
}

impl Drop for PhaseHandler {
    fn drop(&mut self) {
        // On the error and panic paths; `finish` has restored already otherwise.
        let _ = self.restore();
    }
}

/// The SIGPROF handler: count the signal, record the probe's key, call pprof's
/// handler (which takes the native stack). Async-signal-safe: atomics only, no
/// allocation, no lock; the probe must be async-signal-safe too.
extern "C" fn on_sigprof(
    signal: libc::c_int,
    info: *mut libc::siginfo_t,
    context: *mut libc::c_void,
) {
    IN_HANDLER.fetch_add(1, Ordering::SeqCst);
    if RECORDING.load(Ordering::SeqCst) {
        SIGNALS.fetch_add(1, Ordering::Relaxed);
        let probe = PROBE.load(Ordering::Relaxed);
        if probe != 0 {
            // SAFETY: PROBE holds a `PhaseProbe` stored as its address.
            let probe = unsafe { std::mem::transmute::<usize, PhaseProbe>(probe) };
            record_key(probe());
        }
    }
    let previous = PREVIOUS_HANDLER.load(Ordering::SeqCst);
    if previous != libc::SIG_DFL && previous != libc::SIG_IGN {
        if PREVIOUS_SIGINFO.load(Ordering::SeqCst) {
            type Action = extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void);
            // SAFETY: the kernel action had SA_SIGINFO, so its handler has this type.
            let action = unsafe { std::mem::transmute::<usize, Action>(previous) };
            action(signal, info, context);
        } else {
            type Handler = extern "C" fn(libc::c_int);
            // SAFETY: without SA_SIGINFO a handler takes the signal number only.
            let handler = unsafe { std::mem::transmute::<usize, Handler>(previous) };
            handler(signal);
        }
    }
    IN_HANDLER.fetch_sub(1, Ordering::SeqCst);
}

/// Counts one sample of `key` in the lock-free table (called from the handler).
fn record_key(key: u64) {
    if key == 0 {
        OUTSIDE_COUNT.fetch_add(1, Ordering::Relaxed);
        return;
    }
    // Fibonacci hashing: the top bits of key x 2^64/phi.
    let home = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - KEY_SLOT_BITS)) as usize;
    for step in 0..KEY_SLOTS {
        let slot = (home + step) & (KEY_SLOTS - 1);
        let current = KEYS[slot].load(Ordering::Acquire);
        let ours = current == key
            || (current == 0
                && match KEYS[slot].compare_exchange(0, key, Ordering::AcqRel, Ordering::Acquire) {
                    Ok(_) => true,
                    Err(claimed) => claimed == key,
                });
        if ours {
            KEY_COUNTS[slot].fetch_add(1, Ordering::Relaxed);
            return;
        }
    }
    DROPPED.fetch_add(1, Ordering::Relaxed);
}
