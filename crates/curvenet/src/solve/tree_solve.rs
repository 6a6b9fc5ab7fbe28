//! Triangular solves with a supernodal factor for a few right-hand sides at once, split over
//! two threads along the elimination tree.
//!
//! The solves read the whole factor once per pass and are bound by memory bandwidth. faer's
//! own solve runs on one thread (its parallel mode splits the dense blocks, which are small);
//! here two independent subtrees of the elimination tree are solved concurrently, each thread
//! reading its share of `L` once, and the few supernodes above them (the first separators of a
//! nested dissection) sequentially. The dense work per supernode is done by [`kernels`]:
//! faer's general matrix products pack their operands and cost ~4× the bandwidth floor on
//! these thin (few-column) products.

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

/// Supernodes per thread and the ones above them.
#[derive(Debug, Default)]
pub(super) struct TreeSplit {
    /// Per thread: its subtrees as ranges of supernodes (postorder: contiguous).
    groups: [Vec<std::ops::Range<usize>>; 2],
    /// The remaining supernodes (ancestors of the groups), in increasing order.
    top: Vec<usize>,
    /// Per row of the factor: its slot among the top supernodes' rows, or `u32::MAX`.
    top_slot: Vec<u32>,
    top_rows: usize,
}

/// The split of `sym`'s elimination tree: descend from the roots through single children
/// and through any subtree holding over 60% of the remaining work, then share the subtrees
/// found between two threads (largest first to the lighter). `None` when the tree does not
/// split in two shares of at least 20% each (a chain, a tiny system).
pub(super) fn split(sym: &SymbolicSupernodalCholesky<u32>) -> Option<TreeSplit> {
    let ns = sym.n_supernodes();
    let begin = sym.supernode_begin();
    let vp = sym.col_ptr_for_val();
    let n = sym.nrows();
    if ns < 4 {
        return None;
    }
    // Parent: the supernode holding the first off-diagonal row.
    let mut parent = vec![usize::MAX; ns];
    for (s, p) in parent.iter_mut().enumerate() {
        if let Some(&r) = sym.supernode(s).pattern().iter().min() {
            let r = r as usize;
            let t = begin.partition_point(|&b| b as usize <= r) - 1;
            if t <= s {
                return None; // not a postorder: keep the sequential solve
            }
            *p = t;
        }
    }
    let mut work: Vec<usize> = (0..ns).map(|s| (vp[s + 1] - vp[s]) as usize).collect();
    let mut first = (0..ns).collect::<Vec<_>>();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); ns];
    for s in 0..ns {
        if parent[s] != usize::MAX {
            let p = parent[s];
            work[p] += work[s];
            first[p] = first[p].min(first[s]);
            children[p].push(s);
        }
    }
    let total: usize = (0..ns).filter(|&s| parent[s] == usize::MAX).map(|s| work[s]).sum();
    let mut candidates: Vec<usize> = (0..ns).filter(|&s| parent[s] == usize::MAX).collect();
    let mut top = Vec::new();
    loop {
        let sum: usize = candidates.iter().map(|&c| work[c]).sum();
        let (i, &heavy) = candidates.iter().enumerate().max_by_key(|(_, &c)| work[c])?;
        if candidates.len() == 1 || (work[heavy] * 10 > sum * 6 && !children[heavy].is_empty()) {
            candidates.swap_remove(i);
            top.push(heavy);
            candidates.extend_from_slice(&children[heavy]);
        } else {
            break;
        }
    }
    candidates.sort_by_key(|&c| std::cmp::Reverse(work[c]));
    let mut groups: [Vec<std::ops::Range<usize>>; 2] = [Vec::new(), Vec::new()];
    let mut load = [0usize; 2];
    for c in candidates {
        let g = if load[0] <= load[1] { 0 } else { 1 };
        load[g] += work[c];
        groups[g].push(first[c]..c + 1);
    }
    if load[0].min(load[1]) * 5 < total {
        return None;
    }
    for g in &mut groups {
        g.sort_by_key(|r| r.start);
    }
    top.sort_unstable();
    let mut top_slot = vec![u32::MAX; n];
    let mut top_rows = 0;
    for &s in &top {
        for r in begin[s] as usize..sym.supernode_end()[s] as usize {
            top_slot[r] = top_rows as u32;
            top_rows += 1;
        }
    }
    Some(TreeSplit { groups, top, top_slot, top_rows })
}

/// A raw view of the right-hand sides (row-major: row `r`'s `k` values contiguous, so that
/// a scattered row update touches one cache line) shared by the
/// two threads.
#[derive(Clone, Copy)]
struct Shared {
    ptr: *mut f64,
    k: usize,
}
// SAFETY: the threads write disjoint rows (their own subtrees'); rows of the top
// supernodes are written by the first thread only in the forward pass (the second one
// accumulates into its own buffer) and by neither in the backward pass.
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

impl Shared {
    /// # Safety
    /// Row `r` is not being written by another thread.
    unsafe fn at(self, r: usize, c: usize) -> *mut f64 {
        self.ptr.add(r * self.k + c)
    }
}

/// Where a forward update of a row outside the thread's subtrees goes.
enum Sink<'a> {
    /// Straight into `x`.
    Direct,
    /// Into a buffer (row-major, `top_rows` rows) indexed by the top slot.
    Buffer(&'a [u32], &'a mut [f64]),
}

/// The supernode's block of `L`: its first row, its pattern (the rows below its columns)
/// and its values, column-major with leading dimension `w + pattern.len()`.
fn block<'a>(sym: &'a SymbolicSupernodalCholesky<u32>, values: &'a [f64], s: usize) -> (usize, &'a [u32], &'a [f64]) {
    let node = sym.supernode(s);
    let vals = &values[sym.col_ptr_for_val()[s] as usize..sym.col_ptr_for_val()[s + 1] as usize];
    (node.start(), node.pattern(), vals)
}

/// `L y = b` for supernode `s` ([`crate::solve::kernels::forward`]): its own rows solved, the
/// products with its pattern rows subtracted from those rows or the sink.
///
/// # Safety
/// No other thread touches this supernode's rows or, with [`Sink::Direct`], the rows of
/// its pattern.
unsafe fn forward(
    sym: &SymbolicSupernodalCholesky<u32>,
    values: &[f64],
    s: usize,
    x: Shared,
    sink: &mut Sink<'_>,
    z: &mut Vec<f64>,
) {
    let (start, pattern, block) = block(sym, values, s);
    let (w, m, k) = (sym.supernode_end()[s] as usize - start, pattern.len(), x.k);
    let h = w + m;
    gather_own(z, x, start, w, h);
    prefetch_first(sym, values, s + 1, false);
    crate::solve::kernels::forward(block, w, h, k, z);
    put_back(z, x, start, w, h);
    // z's pattern rows hold −B x: added to the rows they belong to.
    for (idx, &r) in pattern.iter().enumerate() {
        let r = r as usize;
        let row: &mut [f64] = match sink {
            Sink::Buffer(slot, buf) if slot[r] != u32::MAX => {
                let t = slot[r] as usize;
                &mut buf[t * k..(t + 1) * k]
            }
            _ => std::slice::from_raw_parts_mut(x.at(r, 0), k),
        };
        for (c, v) in row.iter_mut().enumerate() {
            *v += z[c * h + w + idx];
        }
    }
}

/// `Lᵀ x = y` for supernode `s` ([`crate::solve::kernels::backward`]): its own rows and its
/// pattern's gathered, its own rows solved.
///
/// # Safety
/// As [`forward`]; the rows of the pattern are only read.
unsafe fn backward(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], s: usize, x: Shared, z: &mut Vec<f64>) {
    let (start, pattern, block) = block(sym, values, s);
    let (w, m, k) = (sym.supernode_end()[s] as usize - start, pattern.len(), x.k);
    let h = w + m;
    gather_own(z, x, start, w, h);
    for (idx, &r) in pattern.iter().enumerate() {
        let row = std::slice::from_raw_parts(x.at(r as usize, 0), k);
        for (c, &v) in row.iter().enumerate() {
            z[c * h + w + idx] = v;
        }
    }
    if s > 0 {
        prefetch_first(sym, values, s - 1, true);
    }
    crate::solve::kernels::backward(block, w, h, k, z);
    put_back(z, x, start, w, h);
}

/// Prefetches the columns supernode `s` uses first: its first four (forward) or its last
/// group of four (`last`, backward).
fn prefetch_first(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], s: usize, last: bool) {
    if s >= sym.n_supernodes() {
        return;
    }
    let (start, pattern, block) = block(sym, values, s);
    let w = sym.supernode_end()[s] as usize - start;
    let j = if last { w.saturating_sub(1) / 4 * 4 } else { 0 };
    crate::solve::kernels::prefetch(block, w + pattern.len(), j, w);
}

/// `z` (column-major `h × k`) ← the rows `start..start + w` of `x` on top, zeros below.
///
/// # Safety
/// Rows `start..start + w` of `x` are not being written by another thread.
unsafe fn gather_own(z: &mut Vec<f64>, x: Shared, start: usize, w: usize, h: usize) {
    let k = x.k;
    z.clear();
    z.resize(h * k, 0.0);
    let rows = std::slice::from_raw_parts(x.at(start, 0), w * k);
    for (j, row) in rows.chunks_exact(k).enumerate() {
        for (c, &v) in row.iter().enumerate() {
            z[c * h + j] = v;
        }
    }
}

/// The top `w` rows of `z` back into rows `start..start + w` of `x`.
///
/// # Safety
/// No other thread touches rows `start..start + w` of `x`.
unsafe fn put_back(z: &[f64], x: Shared, start: usize, w: usize, h: usize) {
    let k = x.k;
    let rows = std::slice::from_raw_parts_mut(x.at(start, 0), w * k);
    for (j, row) in rows.chunks_exact_mut(k).enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = z[c * h + j];
        }
    }
}

/// Solves `L Lᵀ x = b` in place (`x`: the permuted right-hand sides, row-major `n × k`).
pub(super) fn solve(sym: &SymbolicSupernodalCholesky<u32>, values: &[f64], split: &TreeSplit, x: &mut [f64], k: usize) {
    let shared = Shared { ptr: x.as_mut_ptr(), k };
    let rows = split.top_rows;
    let mut buf = vec![0.0; rows * k];
    // SAFETY (all blocks below): see `Shared`; the groups hold disjoint subtrees, whose
    // patterns reach only their own rows and the top supernodes' rows.
    rayon::join(
        || {
            let (shared, mut z) = (shared, Vec::new());
            for r in &split.groups[0] {
                for s in r.clone() {
                    unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut z) };
                }
            }
        },
        || {
            let (shared, mut z) = (shared, Vec::new());
            let mut sink = Sink::Buffer(&split.top_slot, &mut buf);
            for r in &split.groups[1] {
                for s in r.clone() {
                    unsafe { forward(sym, values, s, shared, &mut sink, &mut z) };
                }
            }
        },
    );
    let begin = sym.supernode_begin();
    let mut z = Vec::new();
    for &s in &split.top {
        for row in begin[s] as usize..sym.supernode_end()[s] as usize {
            let t = split.top_slot[row] as usize;
            for c in 0..k {
                unsafe { *shared.at(row, c) += buf[t * k + c] };
            }
        }
    }
    for &s in &split.top {
        unsafe { forward(sym, values, s, shared, &mut Sink::Direct, &mut z) };
    }
    for &s in split.top.iter().rev() {
        unsafe { backward(sym, values, s, shared, &mut z) };
    }
    rayon::join(
        || {
            let (shared, mut z) = (shared, Vec::new());
            for r in split.groups[0].iter().rev() {
                for s in r.clone().rev() {
                    unsafe { backward(sym, values, s, shared, &mut z) };
                }
            }
        },
        || {
            let (shared, mut z) = (shared, Vec::new());
            for r in split.groups[1].iter().rev() {
                for s in r.clone().rev() {
                    unsafe { backward(sym, values, s, shared, &mut z) };
                }
            }
        },
    );
}
