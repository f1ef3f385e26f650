//! Render phases and the per-thread phase stack, read by a sampling profiler.
//!
//! A native profile credits an inlined sphere test to whichever function the optimizer
//! put it in; a phase is a name the source gives to a piece of the work, so it stays
//! right whatever the compiler inlines (as pbrt-v4's `ProfilerScope` and Mitsuba 3's
//! `ProfilerPhase` do). The renderer marks its work through
//! [`Counter::enter_phase`](super::Counter::enter_phase), which the
//! [`Phased`](super::Phased) counter turns into entries on a stack of the calling
//! thread ([`enter_phase`]); [`phase_stack_key`] reads that stack from a signal handler
//! on the same thread.
//!
//! Phases are of two sorts. The scopes ([`Phase::is_scope`]: sample row, shading,
//! reflection/refraction set-up, pixel fill) nest to any depth (a reflection ray is
//! shaded inside the set-up of the hit that spawned it) and are pushed on a stack. The
//! work phases run hundreds of times per ray and contain no scope, so each has a fixed
//! cell on top of the stack instead, in nesting order: camera ray and the two queries,
//! then traversal, then the primitive tests. Entering one is one store to its cell,
//! leaving it one store of 0; a push is one load and two stores, a pop one store. The
//! stack a profiler sees is the pushed scopes, outermost first, then the set cells.
//!
//! The stack is a `thread_local!` with a `const` initializer and no destructor, so
//! reaching it is an offset from the thread pointer: no lazy initialization, no
//! registration, nothing a signal handler could interrupt half done. Its cells are
//! relaxed atomics (plain loads and stores on every target) ordered by compiler
//! fences: a push writes the phase into its slot before it raises the depth, a pop
//! lowers the depth, and the work between them cannot be moved outside by the
//! compiler. A handler that interrupts the thread anywhere therefore sees the slots
//! below the depth and the set cells holding the phases the thread is in.
//!
//! Key encoding (the contract with the sampler): 4 bits per phase, the outermost phase
//! in the lowest nibble, 0 ends the stack. A stack deeper than 16 keeps its outermost
//! 15 phases and its innermost phase in the 16th nibble, so the self time of a sample
//! still goes to the phase the thread was running. The stack records up to 255 scopes;
//! beyond that a push overwrites the deepest slot (the innermost scope stays right on
//! the way in, and may name a scope already left on the way back out above level 255;
//! the deepest real nesting, a ray tree of the default limit's 64 levels, is about 130).

use std::sync::atomic::{AtomicU8, Ordering, compiler_fence};

/// A phase of the render: a function identity of the phase view of a profile.
///
/// The values are the 4-bit codes of [`phase_stack_key`] (0 means "no phase").
#[repr(u8)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Phase {
    /// Eye-ray generation (and the camera's set-up before the loop).
    CameraRay = 1,
    /// A closest-hit query of the intersector (eye, reflection and refraction rays).
    ClosestHit = 2,
    /// An occlusion query of the intersector (a shadow ray).
    ShadowQuery = 3,
    /// A BVH's node work: box tests and the stack walk. A brute-force loop, with or
    /// without SIMD lanes, has no traversal: its tests sit right under the query.
    Traversal = 4,
    /// Sphere tests (one primitive, or a SIMD chunk of spheres).
    SphereTest = 5,
    /// Cylinder tests (one primitive, or a SIMD chunk of cylinders).
    CylinderTest = 6,
    /// Cone tests.
    ConeTest = 7,
    /// Polygon tests (plane and outline).
    PolygonTest = 8,
    /// Polygon-patch tests (plane and outline).
    PatchTest = 9,
    /// Shading of a hit: hit body, lights and shadow-ray set-up (the shadow queries and
    /// the secondary rays nest inside).
    Shading = 10,
    /// Reflection and refraction: the mirror and Snell directions, the ray origins and
    /// the weighting of what they bring back (the traced rays nest inside).
    SecondaryRays = 11,
    /// Framebuffer work after tracing: gathering the rows, the `pixel-avg`
    /// checkerboard fill, the SPD corner averaging.
    PixelFill = 12,
    /// One sample row of the parallel loop (a worker's root phase): the loop itself,
    /// storing the row's samples, the progress call.
    SampleRow = 13,
    /// Triangle tests (a SIMD pack of the triangles of polygons and patches, in the
    /// wide BVH).
    TriangleTest = 14,
}

impl Phase {
    /// Every phase, by value.
    pub const ALL: [Phase; 14] = [
        Phase::CameraRay,
        Phase::ClosestHit,
        Phase::ShadowQuery,
        Phase::Traversal,
        Phase::SphereTest,
        Phase::CylinderTest,
        Phase::ConeTest,
        Phase::PolygonTest,
        Phase::PatchTest,
        Phase::Shading,
        Phase::SecondaryRays,
        Phase::PixelFill,
        Phase::SampleRow,
        Phase::TriangleTest,
    ];

    /// The short readable name, used as a function identity in profiles (never
    /// contains `;`, the separator of folded stacks).
    pub fn name(self) -> &'static str {
        match self {
            Phase::CameraRay => "camera ray",
            Phase::ClosestHit => "closest hit",
            Phase::ShadowQuery => "shadow query",
            Phase::Traversal => "traversal",
            Phase::SphereTest => "sphere test",
            Phase::CylinderTest => "cylinder test",
            Phase::ConeTest => "cone test",
            Phase::PolygonTest => "polygon test",
            Phase::PatchTest => "patch test",
            Phase::TriangleTest => "triangle test",
            Phase::Shading => "shading",
            Phase::SecondaryRays => "reflection/refraction set-up",
            Phase::PixelFill => "pixel fill",
            Phase::SampleRow => "sample row",
        }
    }

    /// What the phase covers, in a few words (the probe's documentation of its standard
    /// phase ids, docs/instrumenting.md, is made from it).
    pub fn description(self) -> &'static str {
        match self {
            Phase::CameraRay => "eye-ray generation (and the camera's set-up)",
            Phase::ClosestHit => "a closest-hit query: eye, reflection and refraction rays",
            Phase::ShadowQuery => "an occlusion query: a shadow ray",
            Phase::Traversal => {
                "an acceleration structure's node work: box tests and the stack walk"
            }
            Phase::SphereTest => "sphere tests (one, or a loop or SIMD chunk of them)",
            Phase::CylinderTest => "cylinder tests",
            Phase::ConeTest => "cone tests",
            Phase::PolygonTest => "polygon tests (plane and outline)",
            Phase::PatchTest => "polygon-patch tests (plane and outline)",
            Phase::TriangleTest => "triangle tests",
            Phase::Shading => {
                "shading a hit: its surface, lights and shadow-ray set-up (shadow queries and secondary rays nest inside)"
            }
            Phase::SecondaryRays => {
                "reflection and refraction set-up: directions, origins, weights (the traced rays nest inside)"
            }
            Phase::PixelFill => {
                "framebuffer work after tracing: gathering rows, filling, averaging"
            }
            Phase::SampleRow => "one row of samples of the parallel loop (a worker's root phase)",
        }
    }

    /// Whether this is one primitive kind's intersection test (a leaf of the stack:
    /// tests contain no other phase, so the tests' self times add up).
    pub const fn is_primitive_test(self) -> bool {
        matches!(self.cell(), Some(2))
    }

    /// The phase named `name` ([`Phase::name`]).
    pub fn from_name(name: &str) -> Option<Phase> {
        Phase::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Whether this is a scope, pushed on the stack and free to contain any phase;
    /// the others are work phases, each in its fixed cell (see the module doc).
    #[inline(always)]
    pub const fn is_scope(self) -> bool {
        self.cell().is_none()
    }

    /// The cell of a work phase, in nesting order: camera ray and the queries, then
    /// traversal, then the tests. A work phase contains only phases of later cells.
    #[inline(always)]
    const fn cell(self) -> Option<usize> {
        match self {
            Phase::CameraRay | Phase::ClosestHit | Phase::ShadowQuery => Some(0),
            Phase::Traversal => Some(1),
            Phase::SphereTest
            | Phase::CylinderTest
            | Phase::ConeTest
            | Phase::PolygonTest
            | Phase::PatchTest
            | Phase::TriangleTest => Some(2),
            Phase::Shading | Phase::SecondaryRays | Phase::PixelFill | Phase::SampleRow => None,
        }
    }

    /// The phase of a 4-bit code, `None` for 0 and unused codes.
    pub fn from_code(code: u8) -> Option<Phase> {
        Phase::ALL.into_iter().find(|p| *p as u8 == code)
    }
}

/// Slots of the stack; a `u8` depth indexes them without a bounds check.
const SLOTS: usize = 256;

/// Cells of the work phases.
const CELLS: usize = 3;

/// Phases in a key: 16 nibbles of a `u64`.
const KEY_PHASES: usize = 16;

/// One thread's phase stack. No `Drop`, const-initialized: see the module doc.
struct PhaseStack {
    /// The scopes, outermost first, below `depth`.
    slots: [AtomicU8; SLOTS],
    depth: AtomicU8,
    /// The work phases running on top of the scopes (0 where none).
    cells: [AtomicU8; CELLS],
}

thread_local! {
    static STACK: PhaseStack = const {
        PhaseStack {
            slots: [const { AtomicU8::new(0) }; SLOTS],
            depth: AtomicU8::new(0),
            cells: [const { AtomicU8::new(0) }; CELLS],
        }
    };
}

/// What a phase's end puts back.
#[derive(Debug)]
enum Restore {
    /// The depth before a scope's push.
    Depth(u8),
    /// The cell a work phase set, back to 0.
    Cell(usize),
}

/// Ends a phase when dropped (so also when its work unwinds).
#[must_use = "the phase ends when the guard is dropped"]
#[derive(Debug)]
pub struct PhaseGuard {
    restore: Restore,
}

impl Drop for PhaseGuard {
    #[inline(always)]
    fn drop(&mut self) {
        compiler_fence(Ordering::SeqCst);
        STACK.with(|stack| match self.restore {
            Restore::Depth(depth) => stack.depth.store(depth, Ordering::Relaxed),
            Restore::Cell(cell) => stack.cells[cell].store(0, Ordering::Relaxed),
        });
        compiler_fence(Ordering::SeqCst);
    }
}

/// Starts `phase` on the calling thread's phase stack until the guard is dropped: a
/// store to its cell for a work phase, a push for a scope. `phase` is a constant at
/// every call site, so the choice costs nothing. With debug assertions it checks the
/// nesting rule (no scope inside a work phase, work phases in cell order).
#[inline(always)]
pub fn enter_phase(phase: Phase) -> PhaseGuard {
    let restore = STACK.with(|stack| {
        if let Some(cell) = phase.cell() {
            debug_assert!(
                stack.cells[cell..]
                    .iter()
                    .all(|c| c.load(Ordering::Relaxed) == 0),
                "{phase:?} entered inside a work phase of its cell or a later one"
            );
            stack.cells[cell].store(phase as u8, Ordering::Relaxed);
            return Restore::Cell(cell);
        }
        debug_assert!(
            stack.cells.iter().all(|c| c.load(Ordering::Relaxed) == 0),
            "scope {phase:?} entered inside a work phase"
        );
        let saved = stack.depth.load(Ordering::Relaxed);
        // At 255 levels the depth stays and the deepest slot is overwritten; a u8
        // index is always in bounds (no check in the hot loop).
        let slot = saved.min(254);
        stack.slots[usize::from(slot)].store(phase as u8, Ordering::Relaxed);
        compiler_fence(Ordering::SeqCst);
        stack.depth.store(slot + 1, Ordering::Relaxed);
        Restore::Depth(saved)
    });
    compiler_fence(Ordering::SeqCst);
    PhaseGuard { restore }
}

/// Runs `f` in `phase` on the calling thread's phase stack ([`enter_phase`] around
/// `f`).
#[inline(always)]
pub fn with_phase<R>(phase: Phase, f: impl FnOnce() -> R) -> R {
    let _phase = enter_phase(phase);
    f()
}

/// The calling thread's phase stack encoded in a `u64` (0 = empty; see the module doc
/// for the encoding). Async-signal-safe: it reads a const-initialized thread-local
/// without a destructor with plain loads, allocates nothing and takes no lock.
#[inline]
pub fn phase_stack_key() -> u64 {
    STACK.with(|stack| {
        let depth = usize::from(stack.depth.load(Ordering::Relaxed));
        compiler_fence(Ordering::SeqCst);
        // The stack as read: the scopes below the depth, then the set cells.
        let mut work = [0u8; CELLS];
        let mut set = 0;
        for cell in &stack.cells {
            let code = cell.load(Ordering::Relaxed);
            if code != 0 {
                work[set] = code;
                set += 1;
            }
        }
        let levels = depth + set;
        let phase_at = |level: usize| {
            if level < depth {
                stack.slots[level].load(Ordering::Relaxed)
            } else {
                work[level - depth]
            }
        };
        let mut key = 0u64;
        for nibble in 0..levels.min(KEY_PHASES) {
            // The 16th nibble is the innermost phase, whatever the depth (at 16
            // levels it is the 16th either way).
            let level = if nibble == KEY_PHASES - 1 {
                levels - 1
            } else {
                nibble
            };
            key |= u64::from(phase_at(level) & 0xF) << (4 * nibble);
        }
        key
    })
}

/// The phases of a key, outermost first (a key deeper than 16 phases gives its
/// outermost 15 and its leaf). Unknown codes are skipped; a 0 nibble ends the stack.
pub fn phases_of(key: u64) -> Vec<Phase> {
    (0..KEY_PHASES)
        .map(|level| ((key >> (4 * level)) & 0xF) as u8)
        .take_while(|&code| code != 0)
        .filter_map(Phase::from_code)
        .collect()
}

/// The phase names of a key, outermost first (what the sampler recorded).
pub fn phase_names(key: u64) -> Vec<&'static str> {
    phases_of(key).into_iter().map(Phase::name).collect()
}

/// The number of phases the calling thread is in (not capped at 16; at most 255
/// scopes and the work phases).
pub fn phase_depth() -> usize {
    STACK.with(|stack| {
        let depth = usize::from(stack.depth.load(Ordering::Relaxed));
        depth
            + stack
                .cells
                .iter()
                .filter(|c| c.load(Ordering::Relaxed) != 0)
                .count()
    })
}

/// Exact calls per render of the phases the counters determine, by phase: camera ray
/// (eye rays), closest hit (`calls.trace`: one query per traced ray), shadow query
/// (shadow rays), shading (`calls.shade`) and each kind's test (its tests; a SIMD chunk
/// or a brute-force loop enters its phase once for many tests, so the calls are the
/// tests, and a phase's time per call is its time per test). Traversal, the set-up of
/// secondary rays, pixel fill and sample rows have no exact count.
pub fn phase_calls(counts: &super::Counts) -> Vec<(Phase, u64)> {
    let t = &counts.tests;
    vec![
        (Phase::CameraRay, counts.rays.primary),
        (Phase::ClosestHit, counts.calls.trace),
        (Phase::ShadowQuery, counts.rays.shadow),
        (Phase::SphereTest, t.sphere.tests),
        (Phase::CylinderTest, t.cylinder.tests),
        (Phase::ConeTest, t.cone.tests),
        (Phase::PolygonTest, t.polygon.tests),
        (Phase::PatchTest, t.patch.tests),
        (Phase::TriangleTest, t.triangle.tests),
        (Phase::Shading, counts.calls.shade),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `f` inside `phases`, outermost first.
    fn nested<R>(phases: &[Phase], f: impl FnOnce() -> R) -> R {
        match phases.split_first() {
            None => f(),
            Some((&outer, rest)) => with_phase(outer, || nested(rest, f)),
        }
    }

    #[test]
    fn codes_are_four_bit_distinct_and_names_are_folded_stack_safe() {
        let mut seen = std::collections::BTreeSet::new();
        for (i, phase) in Phase::ALL.into_iter().enumerate() {
            let code = phase as u8;
            assert!((1..=15).contains(&code), "{phase:?}");
            assert_eq!(usize::from(code), i + 1, "ALL is in value order");
            assert!(seen.insert(phase.name()), "duplicate name {}", phase.name());
            assert!(!phase.name().contains(';') && !phase.name().is_empty());
            assert_eq!(Phase::from_code(code), Some(phase));
        }
        assert_eq!(Phase::from_code(0), None);
        assert_eq!(Phase::from_code(15), None);
    }

    #[test]
    fn key_of_a_shallow_stack_has_the_outermost_phase_in_the_lowest_nibble() {
        assert_eq!(phase_stack_key(), 0);
        let key = nested(
            &[Phase::ClosestHit, Phase::Traversal, Phase::SphereTest],
            phase_stack_key,
        );
        // Hand-encoded: 2 | 4 << 4 | 5 << 8.
        assert_eq!(key, 0x542);
        assert_eq!(
            phase_names(key),
            ["closest hit", "traversal", "sphere test"]
        );
        assert_eq!(phase_stack_key(), 0, "the stack is empty again");
        assert_eq!(phase_names(0), Vec::<&str>::new());
    }

    #[test]
    fn a_stack_deeper_than_sixteen_keeps_the_outermost_fifteen_and_the_leaf() {
        // Shading > set-up, 10 times over (20 levels), then a shadow query's test.
        let mut phases = Vec::new();
        for _ in 0..10 {
            phases.extend([Phase::Shading, Phase::SecondaryRays]);
        }
        phases.extend([Phase::ShadowQuery, Phase::Traversal, Phase::ConeTest]);
        let (key, depth) = nested(&phases, || (phase_stack_key(), phase_depth()));
        assert_eq!(depth, 23);
        let mut want: Vec<Phase> = phases[..15].to_vec();
        want.push(Phase::ConeTest);
        assert_eq!(phases_of(key), want);
        assert_eq!(key >> 60, Phase::ConeTest as u64, "leaf in the top nibble");

        // Exactly 16 levels: the 16th nibble is the 16th phase, which is the leaf.
        let sixteen = &phases[..16];
        let key = nested(sixteen, phase_stack_key);
        assert_eq!(phases_of(key), sixteen);

        // Leaving the leaf shows the leaf of the level above again.
        let key = nested(&phases[..18], || {
            with_phase(Phase::PatchTest, || ());
            phase_stack_key()
        });
        assert_eq!(phases_of(key).last(), Some(&phases[17]));
        assert_eq!(phase_depth(), 0);
    }

    #[test]
    fn work_phases_sit_on_top_of_the_pushed_scopes() {
        let work: Vec<Phase> = Phase::ALL.into_iter().filter(|p| !p.is_scope()).collect();
        assert_eq!(work.len(), 10, "{work:?}");
        let (inside, after) = with_phase(Phase::ShadowQuery, || {
            let inside = with_phase(Phase::CylinderTest, || (phase_stack_key(), phase_depth()));
            (inside, (phase_stack_key(), phase_depth()))
        });
        // Hand-encoded: shadow query (3), then cylinder test (6).
        assert_eq!(inside, (0x63, 2));
        assert_eq!(after, (0x3, 1), "leaving the test clears the leaf");
        // A test at exactly 15 pushed levels is the 16th nibble; at 20, it replaces
        // the 16th.
        for pushed in [15, 20] {
            let phases = vec![Phase::SecondaryRays; pushed];
            let key = nested(&phases, || with_phase(Phase::PatchTest, phase_stack_key));
            assert_eq!(key >> 60, Phase::PatchTest as u64, "{pushed}");
            assert_eq!(phases_of(key).len(), 16);
        }
    }

    #[test]
    fn the_cells_follow_the_scopes_in_nesting_order() {
        let key = nested(
            &[
                Phase::SampleRow,
                Phase::Shading,
                Phase::SecondaryRays,
                Phase::ClosestHit,
                Phase::Traversal,
                Phase::PolygonTest,
            ],
            phase_stack_key,
        );
        // Hand-encoded: 13, 10, 11, 2, 4, 8 from the lowest nibble up.
        assert_eq!(key, 0x84_2B_AD);
        // Leaving the traversal (and its test) leaves the query on top.
        let key = with_phase(Phase::ShadowQuery, || {
            with_phase(Phase::Traversal, || with_phase(Phase::SphereTest, || ()));
            phase_stack_key()
        });
        assert_eq!(phase_names(key), ["shadow query"]);
        // A test straight under a query (brute force) skips the traversal cell.
        let key = with_phase(Phase::ClosestHit, || {
            with_phase(Phase::CylinderTest, phase_stack_key)
        });
        assert_eq!(phase_names(key), ["closest hit", "cylinder test"]);
    }

    #[cfg(debug_assertions)]
    #[test]
    #[should_panic(expected = "scope Shading entered inside a work phase")]
    fn a_scope_inside_a_work_phase_breaks_the_nesting_rule() {
        with_phase(Phase::ClosestHit, || with_phase(Phase::Shading, || ()));
    }

    #[cfg(debug_assertions)]
    #[test]
    #[should_panic(expected = "ClosestHit entered inside a work phase")]
    fn a_query_inside_a_traversal_breaks_the_nesting_rule() {
        with_phase(Phase::Traversal, || with_phase(Phase::ClosestHit, || ()));
    }

    #[test]
    fn the_stack_is_restored_when_the_work_unwinds() {
        let caught = std::panic::catch_unwind(|| {
            with_phase(Phase::Shading, || {
                with_phase(Phase::SphereTest, || std::panic::resume_unwind(Box::new(7)))
            })
        });
        assert!(caught.is_err());
        assert_eq!(phase_depth(), 0);
        assert_eq!(phase_stack_key(), 0);
    }

    #[test]
    fn beyond_the_slots_the_depth_saturates_and_unwinds_to_zero() {
        let phases = vec![Phase::Shading; 300];
        let (key, depth) = nested(&phases, || {
            with_phase(Phase::PolygonTest, || (phase_stack_key(), phase_depth()))
        });
        // 255 scopes and the test's cell.
        assert_eq!(depth, 256);
        assert_eq!(phases_of(key).last(), Some(&Phase::PolygonTest));
        assert_eq!(phases_of(key)[..15], [Phase::Shading; 15]);
        // A push beyond 255 levels overwrites the deepest slot: it is the leaf there.
        let key = nested(&phases, || {
            with_phase(Phase::PixelFill, || (phase_stack_key(), phase_depth()))
        });
        assert_eq!(key.1, 255);
        assert_eq!(phases_of(key.0).last(), Some(&Phase::PixelFill));
        assert_eq!(phase_depth(), 0);
    }

    #[test]
    fn each_thread_has_its_own_stack() {
        with_phase(Phase::PixelFill, || {
            let other = std::thread::spawn(phase_stack_key).join().unwrap_or(1);
            assert_eq!(other, 0);
            assert_eq!(phase_stack_key(), u64::from(Phase::PixelFill as u8));
        });
    }
}
