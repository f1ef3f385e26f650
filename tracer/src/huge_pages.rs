//! Large, randomly read arrays (a BVH over a million primitives and the primitives
//! themselves) backed by 2 MiB pages
//! where the system allows it. A ray's walk touches lines scattered over tens of
//! megabytes; with 4 KiB pages nearly every one of those reads also misses the
//! translation cache (a few thousand entries cover only a few megabytes), which is
//! most of the extra time per ray on large scenes. Linux gives huge pages to memory
//! advised with `MADV_HUGEPAGE` before it is first touched (the usual
//! `transparent_hugepage` setting is `madvise`); elsewhere, or when refused, nothing
//! changes but the speed.

/// Below this many bytes a vector stays on ordinary pages (a huge page would be mostly
/// empty, and small trees fit the caches anyway).
const THRESHOLD: usize = 4 << 20;

/// An empty vector with room for `capacity` elements, its pages advised to be huge.
pub(crate) fn vec_with_capacity<T>(capacity: usize) -> Vec<T> {
    let v = Vec::with_capacity(capacity);
    advise(&v);
    v
}

/// `v` moved into memory advised to be huge, if it is large enough for that to matter
/// (one copy, at load time).
pub(crate) fn rehoused<T>(v: Vec<T>) -> Vec<T> {
    if v.len() * std::mem::size_of::<T>() < THRESHOLD {
        return v;
    }
    let mut moved = vec_with_capacity(v.len());
    moved.extend(v);
    moved
}

#[cfg(target_os = "linux")]
fn advise<T>(v: &Vec<T>) {
    const HUGE: usize = 2 << 20;
    let bytes = v.capacity() * std::mem::size_of::<T>();
    if bytes < THRESHOLD {
        return;
    }
    // Only the whole huge pages inside the allocation.
    let start = (v.as_ptr() as usize).next_multiple_of(HUGE);
    let end = (v.as_ptr() as usize + bytes) / HUGE * HUGE;
    if end > start {
        // SAFETY: madvise only changes how the kernel backs these pages, which lie
        // inside this vector's own allocation; a failure leaves them as they were.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise<T>(_: &Vec<T>) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rehousing_keeps_every_element_in_order() {
        let small: Vec<u32> = (0..1000).collect();
        let ptr = small.as_ptr();
        let kept = rehoused(small);
        assert_eq!(kept.as_ptr(), ptr, "small vectors are not moved");
        let large: Vec<u64> = (0..(THRESHOLD as u64 / 8 + 12_345)).collect();
        let moved = rehoused(large.clone());
        assert_eq!(moved, large);
        let empty: Vec<[f32; 16]> = vec_with_capacity(THRESHOLD);
        assert!(empty.is_empty() && empty.capacity() >= THRESHOLD);
    }
}
