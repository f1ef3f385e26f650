//! The recorder behind the crate's functions (Linux, glibc, x86-64 or AArch64): the
//! same design as `rtprof.h`.
//!
//! - One flag word, read with one relaxed load on every call: 0 when off. Before the
//!   first call it holds every bit, so the first call (on any thread) takes the slow
//!   path, which reads the environment once ([`init`]).
//! - Per-thread blocks of counters and phase samples, made on a thread's first event,
//!   pushed once under a lock onto a list that readers walk without it, and never
//!   freed: a thread that ends early still counts. Only its thread writes a block
//!   (relaxed atomic loads and stores: plain moves, and defined reads at exit).
//! - A per-thread phase stack in a const-initialized thread-local without a destructor,
//!   so that the SIGPROF handler of the thread's CPU-time timer can read it (as
//!   `tracer::counter::phase` does for rtprof's own sampler).
//! - At exit (atexit) or on SIGINT/SIGTERM: the blocks summed and the file written by
//!   async-signal-safe calls only, from a fixed buffer, to a temporary file renamed
//!   over the named one.

use crate::format::{Header, Reason, Sink, line};
use crate::ids::{COUNTER_KEYS, PHASE_NAMES};
use crate::sys;
use std::cell::{Cell, UnsafeCell};
use std::ffi::{CString, c_int, c_void};
use std::sync::atomic::{
    AtomicBool, AtomicPtr, AtomicU8, AtomicU32, AtomicU64, Ordering::*, compiler_fence,
};
use std::sync::{Mutex, Once, OnceLock};

const COUNTS: u8 = 1;
const PHASES: u8 = 2;
/// Before [`init`]: every bit, so that every call reaches the slow path once.
const UNINIT: u8 = 0xff;

pub(crate) const COUNTERS: usize = 128;
pub(crate) const PHASE_IDS: usize = 64;
const SLOTS: usize = 256;
const NAME: usize = 63;
const BUFFER: usize = 32 * 1024;

static FLAGS: AtomicU8 = AtomicU8::new(UNINIT);

/// One thread's totals.
struct Block {
    counts: [AtomicU64; COUNTERS],
    /// Samples whose innermost phase is the index (0: outside any phase).
    self_samples: [AtomicU64; PHASE_IDS],
    /// Samples with the phase anywhere on the stack.
    total_samples: [AtomicU64; PHASE_IDS],
    samples: AtomicU64,
    cpu_first_ns: u64,
    cpu_last_ns: AtomicU64,
    unbalanced: AtomicU64,
    next: *const Block,
}

/// The list of blocks; pushed under [`LOCK`], walked without it.
static HEAD: AtomicPtr<Block> = AtomicPtr::new(std::ptr::null_mut());
static LOCK: Mutex<()> = Mutex::new(());
static THREADS: AtomicU64 = AtomicU64::new(0);

/// A user id's name: bytes written under [`LOCK`], read by the writer without it.
struct Name {
    length: AtomicU8,
    bytes: [AtomicU8; NAME],
}

static COUNTER_NAMES: [Name; 64] = [const { Name::EMPTY }; 64];
static PHASE_NAMES_USER: [Name; 32] = [const { Name::EMPTY }; 32];

impl Name {
    #[allow(clippy::declare_interior_mutable_const)] // a fresh value per use: the point
    const EMPTY: Name = Name {
        length: AtomicU8::new(0),
        bytes: [const { AtomicU8::new(0) }; NAME],
    };
}

/// The calling thread's phase stack: the phases below `depth` (the deepest slot is
/// overwritten beyond [`SLOTS`] levels).
struct Stack {
    depth: AtomicU32,
    slots: [AtomicU8; SLOTS],
}

thread_local! {
    static BLOCK: Cell<*const Block> = const { Cell::new(std::ptr::null()) };
    static STACK: Stack = const {
        Stack { depth: AtomicU32::new(0), slots: [const { AtomicU8::new(0) }; SLOTS] }
    };
}

/// What [`init`] found in the environment.
struct Config {
    path: CString,
    temp: CString,
    pid: c_int,
    period_ns: u64,
}

static CONFIG: OnceLock<Config> = OnceLock::new();

#[inline(always)]
pub(crate) fn enabled() -> bool {
    let flags = FLAGS.load(Relaxed);
    if flags == UNINIT {
        init();
        return FLAGS.load(Relaxed) != 0;
    }
    flags != 0
}

#[inline(always)]
pub(crate) fn count(id: u16, n: u64) {
    if FLAGS.load(Relaxed) & COUNTS != 0 {
        count_on(id, n);
    }
}

#[inline(always)]
fn count_on(id: u16, n: u64) {
    if let Some(block) = this_block()
        && let Some(cell) = block.counts.get(usize::from(id))
    {
        cell.store(cell.load(Relaxed).wrapping_add(n), Relaxed);
    }
}

#[inline(always)]
pub(crate) fn phase_begin(id: u8) {
    if FLAGS.load(Relaxed) & PHASES != 0 {
        begin_on(id);
    }
}

#[inline(always)]
fn begin_on(id: u8) {
    if this_block().is_none() || FLAGS.load(Relaxed) & PHASES == 0 {
        return;
    }
    STACK.with(|stack| {
        let depth = stack.depth.load(Relaxed);
        let slot = (depth as usize).min(SLOTS - 1);
        let code = if usize::from(id) < PHASE_IDS { id } else { 0 };
        stack.slots[slot].store(code, Relaxed);
        compiler_fence(SeqCst);
        stack.depth.store(depth.wrapping_add(1), Relaxed);
        compiler_fence(SeqCst);
    });
}

#[inline(always)]
pub(crate) fn phase_end(id: u8) {
    if FLAGS.load(Relaxed) & PHASES != 0 {
        end_on(id);
    }
}

#[inline(always)]
fn end_on(id: u8) {
    STACK.with(|stack| {
        let depth = stack.depth.load(Relaxed);
        let top = depth as usize;
        let mismatched = depth == 0 || (top <= SLOTS && stack.slots[top - 1].load(Relaxed) != id);
        if mismatched {
            let block = BLOCK.with(Cell::get);
            // SAFETY: a non-null BLOCK points to a leaked, never freed block.
            if let Some(block) = unsafe { block.as_ref() } {
                let n = block.unbalanced.load(Relaxed);
                block.unbalanced.store(n + 1, Relaxed);
            }
            if depth == 0 {
                return;
            }
        }
        compiler_fence(SeqCst);
        stack.depth.store(depth - 1, Relaxed);
        compiler_fence(SeqCst);
    });
}

/// The calling thread's block, registered on its first event; `None` when off.
#[inline(always)]
fn this_block() -> Option<&'static Block> {
    let block = BLOCK.with(Cell::get);
    // SAFETY: a non-null BLOCK points to a leaked, never freed block.
    match unsafe { block.as_ref() } {
        Some(block) => Some(block),
        None => register(),
    }
}

#[cold]
#[inline(never)]
fn register() -> Option<&'static Block> {
    if FLAGS.load(Relaxed) == UNINIT {
        init();
    }
    if FLAGS.load(Relaxed) == 0 {
        return None;
    }
    let cpu = sys::thread_cpu_ns();
    let block = Box::into_raw(Box::new(Block {
        counts: [const { AtomicU64::new(0) }; COUNTERS],
        self_samples: [const { AtomicU64::new(0) }; PHASE_IDS],
        total_samples: [const { AtomicU64::new(0) }; PHASE_IDS],
        samples: AtomicU64::new(0),
        cpu_first_ns: cpu,
        cpu_last_ns: AtomicU64::new(cpu),
        unbalanced: AtomicU64::new(0),
        next: std::ptr::null(),
    }));
    {
        // A panic elsewhere while holding the lock leaves the list whole.
        let _guard = LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        // SAFETY: not yet published: this thread's alone.
        unsafe { (*block).next = HEAD.load(Relaxed) };
        // Release: a reader that sees the block sees it whole.
        HEAD.store(block, Release);
        THREADS.fetch_add(1, Relaxed);
    }
    BLOCK.with(|b| b.set(block));
    if FLAGS.load(Relaxed) & PHASES != 0 {
        start_timer();
    }
    // SAFETY: leaked, never freed.
    unsafe { block.as_ref() }
}

/// Starts the calling thread's CPU-time timer: SIGPROF to this thread every period.
fn start_timer() {
    let Some(config) = CONFIG.get() else { return };
    let mut event = sys::SigEvent {
        value: 0,
        signo: sys::SIGPROF,
        notify: sys::SIGEV_THREAD_ID,
        thread_id: sys::syscall(sys::SYS_GETTID) as c_int,
        pad: [0; 11],
    };
    let mut timer: *mut c_void = std::ptr::null_mut();
    let period = sys::Timespec {
        sec: (config.period_ns / 1_000_000_000) as i64,
        nsec: (config.period_ns % 1_000_000_000) as i64,
    };
    let spec = sys::ITimerSpec {
        interval: period,
        value: period,
    };
    // SAFETY: valid pointers to initialised structures; the timer is never deleted
    // (it dies with its thread's CPU clock).
    unsafe {
        if sys::timer_create(sys::CLOCK_THREAD_CPUTIME_ID, &mut event, &mut timer) == 0 {
            sys::timer_settime(timer, 0, &spec, std::ptr::null_mut());
        }
    }
}

/// Reads the environment once (any thread; the others wait).
#[cold]
fn init() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| FLAGS.store(configure(), Release));
}

fn configure() -> u8 {
    let Some(path) = std::env::var_os(crate::format::ENV_FILE).filter(|p| !p.is_empty()) else {
        return 0;
    };
    use std::os::unix::ffi::OsStrExt;
    let mut temp = path.as_bytes().to_vec();
    temp.extend_from_slice(b".tmp");
    let (Ok(path), Ok(temp)) = (CString::new(path.as_bytes()), CString::new(temp)) else {
        return 0;
    };
    let rate = std::env::var(crate::format::ENV_HZ)
        .ok()
        .and_then(|hz| hz.parse::<u64>().ok())
        .filter(|&hz| hz <= 100_000)
        .unwrap_or(1000);
    let config = Config {
        path,
        temp,
        pid: sys::getpid(),
        period_ns: 1_000_000_000u64.checked_div(rate).unwrap_or(0),
    };
    if CONFIG.set(config).is_err() {
        return 0;
    }
    let mut flags = COUNTS;
    if rate > 0 && install(sys::SIGPROF, on_sample, sys::SA_RESTART) {
        flags |= PHASES;
    }
    let stop = sys::SA_RESETHAND | sys::SA_NODEFER;
    install(sys::SIGINT, on_stop, stop);
    install(sys::SIGTERM, on_stop, stop);
    sys::atexit(at_exit);
    flags
}

/// Installs `handler` for `signal` unless the program handles it already.
fn install(signal: c_int, handler: extern "C" fn(c_int), flags: c_int) -> bool {
    let mut old = sys::SigAction {
        handler: 0,
        mask: [0; 16],
        flags: 0,
        restorer: 0,
    };
    let act = sys::SigAction {
        handler: handler as usize,
        mask: [0; 16],
        flags,
        restorer: 0,
    };
    // SAFETY: valid pointers; the handlers are async-signal-safe.
    unsafe {
        sys::sigaction(signal, std::ptr::null(), &mut old) == 0
            && old.handler == sys::SIG_DFL
            && sys::sigaction(signal, &act, std::ptr::null_mut()) == 0
    }
}

/// SIGPROF: one sample of this thread's phase stack.
extern "C" fn on_sample(_: c_int) {
    let errno = sys::__errno_location();
    // SAFETY: errno is this thread's; restored below.
    let saved = unsafe { *errno };
    let block = BLOCK.with(Cell::get);
    // SAFETY: a non-null BLOCK points to a leaked, never freed block.
    if let Some(block) = unsafe { block.as_ref() } {
        STACK.with(|stack| {
            let depth = stack.depth.load(Relaxed) as usize;
            compiler_fence(SeqCst);
            let n = depth.min(SLOTS);
            let phase = |level: usize| usize::from(stack.slots[level].load(Relaxed)) % PHASE_IDS;
            let leaf = if n == 0 { 0 } else { phase(n - 1) };
            bump(&block.self_samples[leaf]);
            let mut seen = 0u64;
            for level in 0..n {
                let id = phase(level);
                if seen >> id & 1 == 0 {
                    seen |= 1 << id;
                    bump(&block.total_samples[id]);
                }
            }
        });
        bump(&block.samples);
        block.cpu_last_ns.store(sys::thread_cpu_ns(), Relaxed);
    }
    // SAFETY: as above.
    unsafe { *errno = saved };
}

fn bump(cell: &AtomicU64) {
    cell.store(cell.load(Relaxed) + 1, Relaxed);
}

extern "C" fn at_exit() {
    write(None);
}

/// SIGINT, SIGTERM: write, then die of the signal (SA_RESETHAND and SA_NODEFER: the
/// default action is back and raise() delivers it now).
extern "C" fn on_stop(signal: c_int) {
    write(Some(signal as u32));
    sys::raise(signal);
}

pub(crate) fn flush() {
    if enabled() {
        write(None);
    }
}

/// Names a user id (the slot of its kind).
pub(crate) fn declare(counter: bool, index: usize, name: &str) {
    if !enabled() {
        return;
    }
    let names: &[Name] = if counter {
        &COUNTER_NAMES
    } else {
        &PHASE_NAMES_USER
    };
    let Some(slot) = names.get(index) else { return };
    let _guard = LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    // One line, printable: controls become '_'; cut at a character boundary.
    let mut length = 0;
    for c in name.trim().chars() {
        let c = if c.is_control() { '_' } else { c };
        let mut bytes = [0u8; 4];
        let bytes = c.encode_utf8(&mut bytes).as_bytes();
        if length + bytes.len() > NAME {
            break;
        }
        for (i, b) in bytes.iter().enumerate() {
            slot.bytes[length + i].store(*b, Relaxed);
        }
        length += bytes.len();
    }
    slot.length.store(length as u8, Release);
}

/// The fixed buffer the writer formats into (one writer: see [`WRITING`]).
struct Buffer {
    bytes: UnsafeCell<[u8; BUFFER]>,
    length: Cell<usize>,
}

// SAFETY: only the one writer that won WRITING touches it.
unsafe impl Sync for Buffer {}

static BUF: Buffer = Buffer {
    bytes: UnsafeCell::new([0; BUFFER]),
    length: Cell::new(0),
};

static WRITING: AtomicBool = AtomicBool::new(false);

impl Sink for &Buffer {
    fn text(&mut self, text: &str) {
        let at = self.length.get();
        let n = text.len().min(BUFFER - at);
        // SAFETY: the writer owns the buffer (WRITING); `at + n` is within it.
        unsafe {
            std::ptr::copy_nonoverlapping(text.as_ptr(), self.bytes.get().cast::<u8>().add(at), n)
        };
        self.length.set(at + n);
    }
}

/// A user id's name, or `counter K` / `phase K` for an undeclared one.
fn user_name<'a>(slot: &Name, kind: &str, index: usize, scratch: &'a mut [u8; 80]) -> &'a str {
    let length = usize::from(slot.length.load(Acquire)).min(NAME);
    let mut n = 0;
    if length > 0 {
        for (i, byte) in slot.bytes[..length].iter().enumerate() {
            scratch[i] = byte.load(Relaxed);
        }
        n = length;
    } else {
        for b in kind.bytes().chain(*b" ") {
            scratch[n] = b;
            n += 1;
        }
        if index >= 10 {
            scratch[n] = b'0' + (index / 10) as u8;
            n += 1;
        }
        scratch[n] = b'0' + (index % 10) as u8;
        n += 1;
    }
    std::str::from_utf8(&scratch[..n]).unwrap_or("?")
}

/// Sums the blocks and writes the file, once per process. Async-signal-safe: no lock,
/// no allocation.
fn write(signal: Option<u32>) {
    let Some(config) = CONFIG.get() else { return };
    let flags = FLAGS.load(Relaxed);
    if flags == 0 || flags == UNINIT || sys::getpid() != config.pid {
        return; // off, or a forked child
    }
    if WRITING.swap(true, AcqRel) {
        return;
    }
    let mut counts = [0u64; COUNTERS];
    let mut self_samples = [0u64; PHASE_IDS];
    let mut total_samples = [0u64; PHASE_IDS];
    let (mut samples, mut cpu, mut unbalanced) = (0u64, 0u64, 0u64);
    let mut block = HEAD.load(Acquire).cast_const();
    // SAFETY: blocks are leaked and never freed; `next` was set before publication.
    while let Some(b) = unsafe { block.as_ref() } {
        for (sum, c) in counts.iter_mut().zip(&b.counts) {
            *sum = sum.wrapping_add(c.load(Relaxed));
        }
        for i in 0..PHASE_IDS {
            self_samples[i] += b.self_samples[i].load(Relaxed);
            total_samples[i] += b.total_samples[i].load(Relaxed);
        }
        samples += b.samples.load(Relaxed);
        cpu += b.cpu_last_ns.load(Relaxed).saturating_sub(b.cpu_first_ns);
        unbalanced += b.unbalanced.load(Relaxed);
        block = b.next;
    }
    let phases = flags & PHASES != 0;
    let mut out = &BUF;
    out.length.set(0);
    Header {
        writer: "rust",
        pid: config.pid as u64,
        reason: signal.map_or(Reason::Exit, Reason::Signal),
        threads: THREADS.load(Relaxed),
        period_ns: if phases { config.period_ns } else { 0 },
        samples,
        cpu_ns: cpu,
        unbalanced,
    }
    .write(&mut out);
    for (key, value) in COUNTER_KEYS.iter().zip(counts) {
        line(&mut out, "counter", &[value], key);
    }
    let mut scratch = [0u8; 80];
    for (i, slot) in COUNTER_NAMES.iter().enumerate() {
        let value = counts[64 + i];
        if slot.length.load(Acquire) > 0 || value > 0 {
            let name = user_name(slot, "counter", i, &mut scratch);
            line(&mut out, "user_counter", &[value], name);
        }
    }
    line(&mut out, "outside", &[self_samples[0]], "");
    for (i, name) in PHASE_NAMES.iter().enumerate() {
        let id = i + 1;
        line(
            &mut out,
            "phase",
            &[self_samples[id], total_samples[id]],
            name,
        );
    }
    for (i, slot) in PHASE_NAMES_USER.iter().enumerate() {
        let id = 32 + i;
        if slot.length.load(Acquire) > 0 || total_samples[id] > 0 {
            let name = user_name(slot, "phase", i, &mut scratch);
            line(
                &mut out,
                "user_phase",
                &[self_samples[id], total_samples[id]],
                name,
            );
        }
    }
    out.text("end\n");
    let length = out.length.get();
    if length == BUFFER {
        return; // cannot happen at these sizes; never half a file
    }
    // SAFETY: the buffer is ours (WRITING) and holds `length` bytes; the paths are
    // NUL-terminated; open/write/close/rename/unlink are async-signal-safe.
    unsafe {
        let fd = sys::open(
            config.temp.as_ptr(),
            sys::O_WRONLY | sys::O_CREAT | sys::O_TRUNC | sys::O_CLOEXEC,
            0o644 as c_int,
        );
        if fd < 0 {
            return;
        }
        let start = BUF.bytes.get().cast::<u8>();
        let mut done = 0;
        while done < length {
            let n = sys::write(fd, start.add(done).cast(), length - done);
            if n < 0 && *sys::__errno_location() == sys::EINTR {
                continue;
            }
            if n <= 0 {
                break;
            }
            done += n as usize;
        }
        if sys::close(fd) == 0 && done == length {
            sys::rename(config.temp.as_ptr(), config.path.as_ptr());
        } else {
            sys::unlink(config.temp.as_ptr());
        }
    }
}
