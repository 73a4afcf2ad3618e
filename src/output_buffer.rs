//! Allocation of the large output buffers that are handed to NumPy.
//!
//! A knit writes 80-90 bytes per triangle into freshly allocated memory (positions, colours,
//! corner vertices, corner edges, edges): 170 MB for 10,000 stitches at default quality.
//! Fresh memory arrives from the kernel one 4 KiB page per fault, and measured on a 2-core
//! machine the faults cost more than the geometry itself (about 45% of a knit's time was in
//! the kernel). Asking for transparent huge pages on these buffers makes it one fault per
//! 2 MiB. It is advice only: where the kernel offers no huge pages (or on other systems) the
//! buffers are ordinary memory, and the results are identical either way.

/// A zero-filled `Vec` of `len` elements, its pages not yet touched, with huge pages
/// requested where the OS offers them.
///
/// `vec![zero; len]` of a primitive becomes `calloc`, which for a large block maps fresh
/// (already zero) pages without writing them, so the advice is given before the first touch.
pub fn zeroed<T: Copy + Default + PartialEq>(len: usize) -> Vec<T> {
    debug_assert!(T::default() == T::default());
    let v = vec![T::default(); len];
    advise_huge_pages(v.as_ptr().cast(), std::mem::size_of_val(v.as_slice()));
    v
}

/// Smallest buffer worth advising: below a few huge pages there is nothing to gain.
const MIN_ADVISED_BYTES: usize = 4 << 20;

#[cfg(target_os = "linux")]
fn advise_huge_pages(ptr: *const u8, bytes: usize) {
    if bytes < MIN_ADVISED_BYTES {
        return;
    }
    // SAFETY: sysconf has no preconditions.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    let page = if page > 0 { page as usize } else { 4096 };
    let start = (ptr as usize).div_ceil(page) * page;
    let end = (ptr as usize + bytes) / page * page;
    if end > start {
        // SAFETY: [start, end) lies inside the allocation we own and is page-aligned.
        // MADV_HUGEPAGE only changes how the kernel backs the range; it never changes its
        // contents, and failure (EINVAL where THP is compiled out) is harmless.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages(_ptr: *const u8, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zeroed_buffers_are_zero_at_every_size() {
        for len in [0usize, 1, 1000, (8 << 20) / 4 + 3] {
            let v: Vec<f32> = zeroed(len);
            assert_eq!(v.len(), len);
            assert!(v.iter().all(|&x| x == 0.0));
            let w: Vec<i32> = zeroed(len);
            assert!(w.iter().all(|&x| x == 0));
        }
    }
}
