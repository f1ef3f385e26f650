/* rtprof.h: rtprof's probe. Exact counts and phase times from inside a ray tracer.
 *
 * One header, C99 and C++11, nothing to link. Linux with GCC or Clang; elsewhere every
 * macro compiles to nothing. docs/instrumenting.md in rtprof's repository is the
 * manual; in short:
 *
 *     #include "rtprof.h"            (before any system header in strict C99, see below)
 *
 *     RTPROF_COUNT(RTPROF_RAYS_PRIMARY, 1);          a standard counter
 *     RTPROF_PHASE_BEGIN(RTPROF_PHASE_SPHERE_TEST);  phases nest, END names the phase
 *     RTPROF_PHASE_END(RTPROF_PHASE_SPHERE_TEST);
 *     { RTPROF_PHASE(RTPROF_PHASE_SHADING); ... }    C++: ends with the scope
 *
 *     #define MY_REFITS RTPROF_USER_COUNTER(0)       user ids, 0..63 and 0..31
 *     RTPROF_DECLARE_COUNTER(MY_REFITS, "bvh refits");   names it in the output
 *
 * Off unless the environment names an output file (RTPROF_PROBE_FILE, which
 * `rtprof record` sets): every macro is then one load of a global flag and one
 * predictable branch. With RTPROF_DISABLE defined the macros are empty.
 *
 * When on: counters are per thread (each thread adds only to its own block, registered
 * once in a locked list; blocks outlive their threads), summed when the process exits
 * (atexit) or is stopped by SIGINT or SIGTERM (an async-signal-safe write, then the
 * signal's default action), and written to a temporary file renamed over the named
 * one. Phase times come from a per-thread CPU-time timer (CLOCK_THREAD_CPUTIME_ID,
 * RTPROF_PROBE_HZ per second, default 1000, 0 = no phases) whose SIGPROF handler reads
 * the interrupted thread's phase stack, as pbrt-v3's ProfilePhase does.
 *
 * Strict C99 (-std=c99) hides timer_create and sigaction: this header defines
 * _GNU_SOURCE, which only works before the first system header; otherwise build with
 * -D_GNU_SOURCE. GNU C and C++ modes need nothing.
 *
 * Part of rtprof (MIT OR Apache-2.0). The ids between the GENERATED markers are
 * written from rtprof's counter table by tests/probe_ids.rs; do not edit them.
 */
#ifndef RTPROF_H
#define RTPROF_H

#if !defined(RTPROF_DISABLE) && (!defined(__linux__) || !defined(__GNUC__))
#define RTPROF_DISABLE 1
#endif

#if !defined(RTPROF_DISABLE) && !defined(_GNU_SOURCE)
#define _GNU_SOURCE 1
#endif

/* The output format's first line; the Rust crate writes and reads the same. */
#define RTPROF_FORMAT "rtprof.probe 1"
/* The environment variables rtprof sets. */
#define RTPROF_ENV_FILE "RTPROF_PROBE_FILE"
#define RTPROF_ENV_HZ "RTPROF_PROBE_HZ"

/* BEGIN GENERATED: standard ids (tracer/tests/probe_ids.rs) */
/* The standard counters: rtprof's counter table, in its order. */
enum rtprof_counter {
    RTPROF_CALLS_PRIMARY_RAY_SETUP = 0, /* calls.primary_ray_setup */
    RTPROF_CALLS_TRACE = 1, /* calls.trace */
    RTPROF_CALLS_INTERSECT = 2, /* calls.intersect */
    RTPROF_CALLS_SHADE = 3, /* calls.shade */
    RTPROF_CALLS_COLOR_CONTRIBUTION = 4, /* calls.color_contribution */
    RTPROF_OPS_ADD = 5, /* ops.add */
    RTPROF_OPS_SUB = 6, /* ops.sub */
    RTPROF_OPS_CROSS = 7, /* ops.cross */
    RTPROF_OPS_DOT = 8, /* ops.dot */
    RTPROF_OPS_NORMALIZE = 9, /* ops.normalize */
    RTPROF_OPS_SCALE = 10, /* ops.scale */
    RTPROF_OPS_SQRT = 11, /* ops.sqrt */
    RTPROF_OPS_POW = 12, /* ops.pow */
    RTPROF_TESTS_SPHERE_TESTS = 13, /* tests.sphere.tests */
    RTPROF_TESTS_SPHERE_HITS = 14, /* tests.sphere.hits */
    RTPROF_TESTS_CYLINDER_TESTS = 15, /* tests.cylinder.tests */
    RTPROF_TESTS_CYLINDER_HITS = 16, /* tests.cylinder.hits */
    RTPROF_TESTS_CONE_TESTS = 17, /* tests.cone.tests */
    RTPROF_TESTS_CONE_HITS = 18, /* tests.cone.hits */
    RTPROF_TESTS_POLYGON_TESTS = 19, /* tests.polygon.tests */
    RTPROF_TESTS_POLYGON_HITS = 20, /* tests.polygon.hits */
    RTPROF_TESTS_PATCH_TESTS = 21, /* tests.patch.tests */
    RTPROF_TESTS_PATCH_HITS = 22, /* tests.patch.hits */
    RTPROF_TESTS_TRIANGLE_TESTS = 23, /* tests.triangle.tests */
    RTPROF_TESTS_TRIANGLE_HITS = 24, /* tests.triangle.hits */
    RTPROF_TESTS_PLANE_TESTS = 25, /* tests.plane.tests */
    RTPROF_TESTS_PLANE_HITS = 26, /* tests.plane.hits */
    RTPROF_RAYS_PRIMARY = 27, /* rays.primary */
    RTPROF_RAYS_PRIMARY_HIT = 28, /* rays.primary_hit */
    RTPROF_RAYS_SHADOW = 29, /* rays.shadow */
    RTPROF_RAYS_SHADOW_BLOCKED = 30, /* rays.shadow_blocked */
    RTPROF_RAYS_REFLECTION = 31, /* rays.reflection */
    RTPROF_RAYS_REFRACTION = 32, /* rays.refraction */
    RTPROF_ACCEL_NODES_VISITED = 33, /* accel.nodes_visited */
    RTPROF_ACCEL_LEAVES_VISITED = 34, /* accel.leaves_visited */
    RTPROF_ACCEL_LANES_ISSUED = 35, /* accel.lanes_issued */
    RTPROF_ACCEL_LANES_ACTIVE = 36, /* accel.lanes_active */
    RTPROF_STANDARD_COUNTERS = 37
};

/* The standard phases: rtprof's phases (0 is outside any phase). */
enum rtprof_phase {
    RTPROF_PHASE_CAMERA_RAY = 1, /* camera ray */
    RTPROF_PHASE_CLOSEST_HIT = 2, /* closest hit */
    RTPROF_PHASE_SHADOW_QUERY = 3, /* shadow query */
    RTPROF_PHASE_TRAVERSAL = 4, /* traversal */
    RTPROF_PHASE_SPHERE_TEST = 5, /* sphere test */
    RTPROF_PHASE_CYLINDER_TEST = 6, /* cylinder test */
    RTPROF_PHASE_CONE_TEST = 7, /* cone test */
    RTPROF_PHASE_POLYGON_TEST = 8, /* polygon test */
    RTPROF_PHASE_PATCH_TEST = 9, /* patch test */
    RTPROF_PHASE_SHADING = 10, /* shading */
    RTPROF_PHASE_SECONDARY_RAYS = 11, /* reflection/refraction set-up */
    RTPROF_PHASE_PIXEL_FILL = 12, /* pixel fill */
    RTPROF_PHASE_SAMPLE_ROW = 13, /* sample row */
    RTPROF_PHASE_TRIANGLE_TEST = 14, /* triangle test */
    RTPROF_STANDARD_PHASES = 14
};

/* Their names in the output, by id. */
#define RTPROF_I_COUNTER_KEYS \
    "calls.primary_ray_setup", \
    "calls.trace", \
    "calls.intersect", \
    "calls.shade", \
    "calls.color_contribution", \
    "ops.add", \
    "ops.sub", \
    "ops.cross", \
    "ops.dot", \
    "ops.normalize", \
    "ops.scale", \
    "ops.sqrt", \
    "ops.pow", \
    "tests.sphere.tests", \
    "tests.sphere.hits", \
    "tests.cylinder.tests", \
    "tests.cylinder.hits", \
    "tests.cone.tests", \
    "tests.cone.hits", \
    "tests.polygon.tests", \
    "tests.polygon.hits", \
    "tests.patch.tests", \
    "tests.patch.hits", \
    "tests.triangle.tests", \
    "tests.triangle.hits", \
    "tests.plane.tests", \
    "tests.plane.hits", \
    "rays.primary", \
    "rays.primary_hit", \
    "rays.shadow", \
    "rays.shadow_blocked", \
    "rays.reflection", \
    "rays.refraction", \
    "accel.nodes_visited", \
    "accel.leaves_visited", \
    "accel.lanes_issued", \
    "accel.lanes_active"
#define RTPROF_I_PHASE_NAMES \
    "camera ray", \
    "closest hit", \
    "shadow query", \
    "traversal", \
    "sphere test", \
    "cylinder test", \
    "cone test", \
    "polygon test", \
    "patch test", \
    "shading", \
    "reflection/refraction set-up", \
    "pixel fill", \
    "sample row", \
    "triangle test"
/* END GENERATED: standard ids */

/* User ids: counters 64..127, phases 32..63 (phase 0 is "outside any phase"). */
#define RTPROF_USER_COUNTERS 64
#define RTPROF_USER_PHASES 32
#define RTPROF_USER_COUNTER(k) (64 + (k))
#define RTPROF_USER_PHASE(k) (32 + (k))

#ifdef RTPROF_DISABLE

/* Compiled out: the arguments are named in sizeof, never evaluated, so that a variable
 * only counted raises no "unused" warning. */
#define RTPROF_COUNT(id, n) ((void)sizeof(id), (void)sizeof(n))
#define RTPROF_PHASE_BEGIN(id) ((void)sizeof(id))
#define RTPROF_PHASE_END(id) ((void)sizeof(id))
#define RTPROF_DECLARE_COUNTER(id, name) ((void)sizeof(id), (void)sizeof(name))
#define RTPROF_DECLARE_PHASE(id, name) ((void)sizeof(id), (void)sizeof(name))
#define RTPROF_FLUSH() ((void)0)
#define RTPROF_ENABLED() 0
#ifdef __cplusplus
#define RTPROF_PHASE(id) ((void)sizeof(id))
#endif

#else /* the probe compiled in */

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#if defined(__GLIBC__) && !defined(__USE_POSIX199309)
#error "rtprof.h: timer_create and sigaction are hidden; include rtprof.h before any system header or build with -D_GNU_SOURCE"
#endif

#define RTPROF_I_COUNTERS 128
#define RTPROF_I_PHASES 64
#define RTPROF_I_SLOTS 256
#define RTPROF_I_NAME 64
#define RTPROF_I_PATH 4000
#define RTPROF_I_BUF 32768
#define RTPROF_I_ON_COUNTS 1
#define RTPROF_I_ON_PHASES 2

#ifdef __cplusplus
extern "C" {
#endif

/* One thread's counts and phase samples. Allocated on the thread's first event and
 * never freed: a thread that ends before the process still counts. Only its thread
 * writes it (the counts with relaxed atomics, so that the exit's reads are defined;
 * the samples from the SIGPROF handler, which runs on that thread). */
struct rtprof_i_block {
    uint64_t counts[RTPROF_I_COUNTERS];
    uint64_t self[RTPROF_I_PHASES];  /* samples whose innermost phase is the index */
    uint64_t total[RTPROF_I_PHASES]; /* samples with the phase anywhere on the stack */
    uint64_t samples;
    uint64_t cpu_first_ns; /* the thread's CPU clock when it registered */
    uint64_t cpu_last_ns;  /* ... and at its last sample */
    uint64_t unbalanced;   /* phase ends that did not match the innermost phase */
    struct rtprof_i_block *next;
};

/* The calling thread's phase stack; read by the SIGPROF handler on the same thread. */
struct rtprof_i_stack {
    unsigned depth;
    unsigned char slots[RTPROF_I_SLOTS];
};

/* The process's state. Weak definitions: every translation unit that includes the
 * header defines them and the linker keeps one, so nothing needs to be linked. */
struct rtprof_i_state {
    int initialized;
    int lock;
    int writing;
    pid_t pid;
    uint64_t period_ns;
    uint64_t threads;
    struct rtprof_i_block *head;
    char path[RTPROF_I_PATH];
    char temp[RTPROF_I_PATH + 8];
    char counter_names[RTPROF_USER_COUNTERS][RTPROF_I_NAME];
    char phase_names[RTPROF_USER_PHASES][RTPROF_I_NAME];
    char buf[RTPROF_I_BUF];
};

__attribute__((weak)) int rtprof_i_flags;
__attribute__((weak)) struct rtprof_i_state rtprof_i_state;
__attribute__((weak)) __thread struct rtprof_i_block *rtprof_i_tls;
__attribute__((weak)) __thread struct rtprof_i_stack rtprof_i_stack;

#define RTPROF_I_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define RTPROF_I_LOAD(p) __atomic_load_n((p), __ATOMIC_RELAXED)
#define RTPROF_I_STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELAXED)
/* Orders stores against a signal handler on the same thread (no instruction). */
#define RTPROF_I_FENCE() __atomic_signal_fence(__ATOMIC_SEQ_CST)

static inline uint64_t rtprof_i_thread_cpu_ns(void) {
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0;
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Starts the calling thread's CPU-time timer: SIGPROF to this thread every period. */
static inline void rtprof_i_start_timer(void) {
    struct sigevent ev;
    struct itimerspec spec;
    timer_t timer;
    memset(&ev, 0, sizeof ev);
    ev.sigev_notify = SIGEV_THREAD_ID;
    ev.sigev_signo = SIGPROF;
#ifdef sigev_notify_thread_id
    ev.sigev_notify_thread_id = (pid_t)syscall(SYS_gettid);
#else
    ev._sigev_un._tid = (pid_t)syscall(SYS_gettid);
#endif
    if (timer_create(CLOCK_THREAD_CPUTIME_ID, &ev, &timer) != 0) return;
    spec.it_interval.tv_sec = (time_t)(rtprof_i_state.period_ns / 1000000000u);
    spec.it_interval.tv_nsec = (long)(rtprof_i_state.period_ns % 1000000000u);
    spec.it_value = spec.it_interval;
    timer_settime(timer, 0, &spec, NULL);
}

/* The calling thread's block, made and registered on its first event (kept out of
 * line: the hot paths only test for it). */
__attribute__((noinline, cold, unused)) static struct rtprof_i_block *rtprof_i_register(void) {
    struct rtprof_i_block *block = rtprof_i_tls;
    if (block) return block;
    block = (struct rtprof_i_block *)calloc(1, sizeof *block);
    if (!block) return NULL;
    block->cpu_first_ns = rtprof_i_thread_cpu_ns();
    block->cpu_last_ns = block->cpu_first_ns;
    while (__atomic_exchange_n(&rtprof_i_state.lock, 1, __ATOMIC_ACQUIRE)) {
    }
    block->next = rtprof_i_state.head;
    /* Release: a reader that sees the block (the exit, a signal) sees it whole. */
    __atomic_store_n(&rtprof_i_state.head, block, __ATOMIC_RELEASE);
    rtprof_i_state.threads++;
    __atomic_store_n(&rtprof_i_state.lock, 0, __ATOMIC_RELEASE);
    rtprof_i_tls = block;
    if (rtprof_i_flags & RTPROF_I_ON_PHASES) rtprof_i_start_timer();
    return block;
}

static inline void rtprof_i_count(int id, uint64_t n) {
    struct rtprof_i_block *block = rtprof_i_tls;
    if (RTPROF_I_UNLIKELY(!block)) block = rtprof_i_register();
    if (block && (unsigned)id < RTPROF_I_COUNTERS)
        RTPROF_I_STORE(&block->counts[id], RTPROF_I_LOAD(&block->counts[id]) + n);
}

static inline void rtprof_i_begin(int id) {
    unsigned depth;
    if (RTPROF_I_UNLIKELY(!rtprof_i_tls)) rtprof_i_register();
    depth = rtprof_i_stack.depth;
    /* Beyond the slots the deepest one is overwritten: the innermost phase stays
     * right on the way in. */
    rtprof_i_stack.slots[depth < RTPROF_I_SLOTS ? depth : RTPROF_I_SLOTS - 1] =
        (unsigned char)((unsigned)id < RTPROF_I_PHASES ? id : 0);
    RTPROF_I_FENCE();
    rtprof_i_stack.depth = depth + 1;
    RTPROF_I_FENCE();
}

static inline void rtprof_i_end(int id) {
    unsigned depth = rtprof_i_stack.depth;
    struct rtprof_i_block *block = rtprof_i_tls;
    if (depth == 0 ||
        (depth <= RTPROF_I_SLOTS && rtprof_i_stack.slots[depth - 1] != (unsigned char)id)) {
        if (block) RTPROF_I_STORE(&block->unbalanced, RTPROF_I_LOAD(&block->unbalanced) + 1);
        if (depth == 0) return;
    }
    RTPROF_I_FENCE();
    rtprof_i_stack.depth = depth - 1;
    RTPROF_I_FENCE();
}

/* SIGPROF: one sample of the interrupted thread's phase stack. */
static inline void rtprof_i_on_sample(int sig) {
    int saved = errno;
    struct rtprof_i_block *block = rtprof_i_tls;
    (void)sig;
    if (block) {
        unsigned depth = rtprof_i_stack.depth, n, i;
        uint64_t seen = 0;
        RTPROF_I_FENCE();
        n = depth < RTPROF_I_SLOTS ? depth : RTPROF_I_SLOTS;
        block->self[n ? rtprof_i_stack.slots[n - 1] % RTPROF_I_PHASES : 0]++;
        for (i = 0; i < n; i++) {
            unsigned id = rtprof_i_stack.slots[i] % RTPROF_I_PHASES;
            if (!((seen >> id) & 1u)) {
                seen |= (uint64_t)1 << id;
                block->total[id]++;
            }
        }
        block->samples++;
        block->cpu_last_ns = rtprof_i_thread_cpu_ns();
    }
    errno = saved;
}

/* Copies a user id's name (printable, one line, at most 63 bytes). */
static inline void rtprof_i_declare(char *slot, const char *name) {
    int i;
    if (!rtprof_i_flags || !name) return;
    while (__atomic_exchange_n(&rtprof_i_state.lock, 1, __ATOMIC_ACQUIRE)) {
    }
    for (i = 0; i < RTPROF_I_NAME - 1 && name[i]; i++)
        slot[i] = (name[i] < 0x20 && name[i] >= 0) || name[i] == 0x7f ? '_' : name[i];
    slot[i] = 0;
    __atomic_store_n(&rtprof_i_state.lock, 0, __ATOMIC_RELEASE);
}

static inline void rtprof_i_declare_counter(int id, const char *name) {
    if ((unsigned)(id - 64) < RTPROF_USER_COUNTERS)
        rtprof_i_declare(rtprof_i_state.counter_names[id - 64], name);
}

static inline void rtprof_i_declare_phase(int id, const char *name) {
    if ((unsigned)(id - 32) < RTPROF_USER_PHASES)
        rtprof_i_declare(rtprof_i_state.phase_names[id - 32], name);
}

/* The output, formatted without allocation or stdio (async-signal-safe). */
struct rtprof_i_out {
    char *at;
    char *end;
};

static inline void rtprof_i_text(struct rtprof_i_out *out, const char *text) {
    while (*text && out->at < out->end) *out->at++ = *text++;
}

static inline void rtprof_i_number(struct rtprof_i_out *out, uint64_t value) {
    char digits[24];
    int n = 0;
    do {
        digits[n++] = (char)('0' + value % 10);
        value /= 10;
    } while (value);
    while (n && out->at < out->end) *out->at++ = digits[--n];
}

/* "KIND VALUE... NAME\n" */
static inline void rtprof_i_line(struct rtprof_i_out *out, const char *kind, uint64_t a,
                                 int two, uint64_t b, const char *name) {
    rtprof_i_text(out, kind);
    rtprof_i_text(out, " ");
    rtprof_i_number(out, a);
    if (two) {
        rtprof_i_text(out, " ");
        rtprof_i_number(out, b);
    }
    if (name) {
        rtprof_i_text(out, " ");
        rtprof_i_text(out, name);
    }
    rtprof_i_text(out, "\n");
}

static inline const char *rtprof_i_counter_key(int id) {
    static const char *const keys[] = {RTPROF_I_COUNTER_KEYS};
    return (unsigned)id < sizeof keys / sizeof keys[0] ? keys[id] : NULL;
}

static inline const char *rtprof_i_phase_name(int id) {
    static const char *const names[] = {RTPROF_I_PHASE_NAMES};
    return id >= 1 && (unsigned)id <= sizeof names / sizeof names[0] ? names[id - 1] : NULL;
}

/* Sums every thread's block and writes the file (temporary file, then rename). Once
 * per process; `signal` is 0 at exit. Async-signal-safe: no lock, no allocation. */
static inline void rtprof_i_write(int signal) {
    static uint64_t counts[RTPROF_I_COUNTERS], self[RTPROF_I_PHASES], total[RTPROF_I_PHASES];
    struct rtprof_i_state *st = &rtprof_i_state;
    struct rtprof_i_out out;
    const struct rtprof_i_block *block;
    uint64_t samples = 0, cpu = 0, unbalanced = 0;
    char name[RTPROF_I_NAME + 16];
    int i, fd;
    if (!rtprof_i_flags || getpid() != st->pid) return; /* off, or a forked child */
    if (__atomic_exchange_n(&st->writing, 1, __ATOMIC_ACQ_REL)) return;
    for (block = __atomic_load_n(&st->head, __ATOMIC_ACQUIRE); block; block = block->next) {
        for (i = 0; i < RTPROF_I_COUNTERS; i++) counts[i] += RTPROF_I_LOAD(&block->counts[i]);
        for (i = 0; i < RTPROF_I_PHASES; i++) {
            self[i] += RTPROF_I_LOAD(&block->self[i]);
            total[i] += RTPROF_I_LOAD(&block->total[i]);
        }
        samples += RTPROF_I_LOAD(&block->samples);
        cpu += RTPROF_I_LOAD(&block->cpu_last_ns) - block->cpu_first_ns;
        unbalanced += RTPROF_I_LOAD(&block->unbalanced);
    }
    out.at = st->buf;
    out.end = st->buf + sizeof st->buf;
    rtprof_i_text(&out, RTPROF_FORMAT "\nwriter c\n");
    rtprof_i_line(&out, "pid", (uint64_t)st->pid, 0, 0, NULL);
    if (signal) rtprof_i_line(&out, "reason signal", (uint64_t)signal, 0, 0, NULL);
    else rtprof_i_text(&out, "reason exit\n");
    rtprof_i_line(&out, "threads", RTPROF_I_LOAD(&st->threads), 0, 0, NULL);
    rtprof_i_line(&out, "period_ns", (rtprof_i_flags & RTPROF_I_ON_PHASES) ? st->period_ns : 0,
                  0, 0, NULL);
    rtprof_i_line(&out, "samples", samples, 0, 0, NULL);
    rtprof_i_line(&out, "cpu_ns", cpu, 0, 0, NULL);
    rtprof_i_line(&out, "unbalanced", unbalanced, 0, 0, NULL);
    for (i = 0; rtprof_i_counter_key(i); i++)
        rtprof_i_line(&out, "counter", counts[i], 0, 0, rtprof_i_counter_key(i));
    for (i = 0; i < RTPROF_USER_COUNTERS; i++) {
        const char *declared = st->counter_names[i];
        if (!declared[0] && !counts[64 + i]) continue;
        if (!declared[0]) {
            struct rtprof_i_out n = {name, name + sizeof name - 1};
            rtprof_i_text(&n, "counter ");
            rtprof_i_number(&n, (uint64_t)i);
            *n.at = 0;
            declared = name;
        }
        rtprof_i_line(&out, "user_counter", counts[64 + i], 0, 0, declared);
    }
    rtprof_i_line(&out, "outside", self[0], 0, 0, NULL);
    for (i = 1; rtprof_i_phase_name(i); i++)
        rtprof_i_line(&out, "phase", self[i], 1, total[i], rtprof_i_phase_name(i));
    for (i = 0; i < RTPROF_USER_PHASES; i++) {
        const char *declared = st->phase_names[i];
        if (!declared[0] && !total[32 + i]) continue;
        if (!declared[0]) {
            struct rtprof_i_out n = {name, name + sizeof name - 1};
            rtprof_i_text(&n, "phase ");
            rtprof_i_number(&n, (uint64_t)i);
            *n.at = 0;
            declared = name;
        }
        rtprof_i_line(&out, "user_phase", self[32 + i], 1, total[32 + i], declared);
    }
    rtprof_i_text(&out, "end\n");
    if (out.at == out.end) return; /* cannot happen with the fixed sizes; never half a file */
    fd = open(st->temp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return;
    {
        const char *at = st->buf;
        while (at < out.at) {
            ssize_t n = write(fd, at, (size_t)(out.at - at));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            at += n;
        }
        if (close(fd) == 0 && at == out.at) rename(st->temp, st->path);
        else unlink(st->temp);
    }
}

static inline void rtprof_i_at_exit(void) { rtprof_i_write(0); }

/* SIGINT, SIGTERM: write, then die of the signal (installed with SA_RESETHAND and
 * SA_NODEFER, so the default action is back and raise() delivers it now). */
static inline void rtprof_i_on_stop(int sig) {
    int saved = errno;
    rtprof_i_write(sig);
    raise(sig);
    errno = saved;
}

/* Installs `handler` for `sig` unless the program already handles it. */
static inline int rtprof_i_install(int sig, void (*handler)(int), int flags) {
    struct sigaction old, act;
    if (sigaction(sig, NULL, &old) != 0 || old.sa_handler != SIG_DFL) return 0;
    memset(&act, 0, sizeof act);
    act.sa_handler = handler;
    act.sa_flags = flags;
    sigemptyset(&act.sa_mask);
    return sigaction(sig, &act, NULL) == 0;
}

/* Reads the environment once, before main. */
static inline void rtprof_i_init(void) {
    struct rtprof_i_state *st = &rtprof_i_state;
    const char *path, *hz;
    size_t length;
    uint64_t rate = 1000;
    int flags = RTPROF_I_ON_COUNTS;
    if (st->initialized) return;
    st->initialized = 1;
    path = getenv(RTPROF_ENV_FILE);
    if (!path || !*path) return;
    length = strlen(path);
    if (length >= RTPROF_I_PATH) {
        static const char message[] = "rtprof.h: " RTPROF_ENV_FILE " is too long; probe off\n";
        if (write(2, message, sizeof message - 1) < 0) { /* nothing more to do */ }
        return;
    }
    memcpy(st->path, path, length + 1);
    memcpy(st->temp, path, length);
    memcpy(st->temp + length, ".tmp", 5);
    hz = getenv(RTPROF_ENV_HZ);
    if (hz && *hz) {
        char *end;
        unsigned long value = strtoul(hz, &end, 10);
        rate = *end || value > 100000 ? 1000 : value;
    }
    st->pid = getpid();
    if (rate) {
        st->period_ns = 1000000000u / rate;
        if (rtprof_i_install(SIGPROF, rtprof_i_on_sample, SA_RESTART)) flags |= RTPROF_I_ON_PHASES;
    }
    rtprof_i_install(SIGINT, rtprof_i_on_stop, (int)(SA_RESETHAND | SA_NODEFER));
    rtprof_i_install(SIGTERM, rtprof_i_on_stop, (int)(SA_RESETHAND | SA_NODEFER));
    atexit(rtprof_i_at_exit);
    rtprof_i_flags = flags;
    rtprof_i_register(); /* the main thread, sampled from the start */
}

__attribute__((constructor)) static void rtprof_i_constructor(void) { rtprof_i_init(); }

/* Writes the file now (a program that ends by _exit or abort calls it first). */
static inline void rtprof_i_flush(void) { rtprof_i_write(0); }

#ifdef __cplusplus
} /* extern "C" */

/* A phase that ends with the enclosing scope (internal linkage, as the functions it
 * calls). */
namespace {
class rtprof_i_scope {
  public:
    explicit rtprof_i_scope(int id) : id_(id) {
        if (RTPROF_I_UNLIKELY(rtprof_i_flags & RTPROF_I_ON_PHASES)) rtprof_i_begin(id);
    }
    ~rtprof_i_scope() {
        if (RTPROF_I_UNLIKELY(rtprof_i_flags & RTPROF_I_ON_PHASES)) rtprof_i_end(id_);
    }
    rtprof_i_scope(const rtprof_i_scope &) = delete;
    rtprof_i_scope &operator=(const rtprof_i_scope &) = delete;

  private:
    int id_;
};
} // namespace
#define RTPROF_I_CAT2(a, b) a##b
#define RTPROF_I_CAT(a, b) RTPROF_I_CAT2(a, b)
#define RTPROF_PHASE(id) rtprof_i_scope RTPROF_I_CAT(rtprof_i_phase_, __LINE__)(id)
#endif

#define RTPROF_ENABLED() (rtprof_i_flags != 0)
#define RTPROF_COUNT(id, n)                                                                    \
    do {                                                                                       \
        if (RTPROF_I_UNLIKELY(rtprof_i_flags & RTPROF_I_ON_COUNTS))                            \
            rtprof_i_count((int)(id), (uint64_t)(n));                                          \
    } while (0)
#define RTPROF_PHASE_BEGIN(id)                                                                 \
    do {                                                                                       \
        if (RTPROF_I_UNLIKELY(rtprof_i_flags & RTPROF_I_ON_PHASES)) rtprof_i_begin((int)(id));  \
    } while (0)
#define RTPROF_PHASE_END(id)                                                                   \
    do {                                                                                       \
        if (RTPROF_I_UNLIKELY(rtprof_i_flags & RTPROF_I_ON_PHASES)) rtprof_i_end((int)(id));    \
    } while (0)
#define RTPROF_DECLARE_COUNTER(id, name) rtprof_i_declare_counter((int)(id), (name))
#define RTPROF_DECLARE_PHASE(id, name) rtprof_i_declare_phase((int)(id), (name))
#define RTPROF_FLUSH() rtprof_i_flush()

#endif /* RTPROF_DISABLE */
#endif /* RTPROF_H */
