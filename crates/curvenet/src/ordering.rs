//! Fill-reducing orderings for the sparse Cholesky factorisation.
//!
//! [`nested_dissection`] is George's automatic nested dissection by level structures (A.
//! George, *Nested dissection of a regular finite element mesh*, SIAM J. Numer. Anal. 1973;
//! George & Liu, *Computer Solution of Large Sparse Positive Definite Systems*, 1981, ch. 8):
//! breadth-first levels from a pseudo-peripheral vertex, the middle level as separator, both
//! halves ordered recursively and the separator last. On the meshes of this crate (2-manifolds
//! of quasi-uniform triangles) the levels are curves of about √n vertices, so the factor has
//! O(n log n) entries — fewer than minimum degree gives at large n — and the ordering itself
//! costs a few breadth-first searches per level of the recursion. It works on the pattern of
//! the matrix actually factored (the two-ring stencil of `Ls M⁻¹ Ls`), so every level is a true
//! separator of that matrix.

use crate::sparse::Csc;

/// Subsets at most this large are not split further but ordered by minimum degree (measured:
/// large leaves give the least fill; the dissection matters at the top levels).
const LEAF: usize = 500;

/// Moves separator vertices that touch only one side into that side (the smaller side first,
/// to keep the halves balanced). Uses `stamp` as side marks: `id + 1` for A, `id + 2` for B.
fn thin_separator(
    q: &Csc,
    mut a: Vec<u32>,
    mut b: Vec<u32>,
    s: Vec<u32>,
    stamp: &mut [u32],
    id: u32,
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let (ma, mb) = (id.wrapping_add(1), id.wrapping_add(2));
    for &v in &a {
        stamp[v as usize] = ma;
    }
    for &v in &b {
        stamp[v as usize] = mb;
    }
    let mut rest = Vec::with_capacity(s.len());
    // First into the smaller side, then into the other.
    let (first, second) = if a.len() <= b.len() { ((ma, mb), (mb, ma)) } else { ((mb, ma), (ma, mb)) };
    let mut pending = s;
    for (into, other) in [first, second] {
        rest.clear();
        for &v in &pending {
            let touches_other = q.col(v as usize).0.iter().any(|&w| stamp[w as usize] == other);
            if touches_other {
                rest.push(v);
            } else {
                stamp[v as usize] = into;
                if into == ma {
                    a.push(v)
                } else {
                    b.push(v)
                }
            }
        }
        std::mem::swap(&mut pending, &mut rest);
    }
    for &v in a.iter().chain(&b) {
        stamp[v as usize] = 0;
    }
    (a, b, pending)
}

/// The symmetric pattern `P ∪ Pᵀ` of `q` without the diagonal (values unused).
fn symmetric_pattern(q: &Csc) -> Csc {
    let n = q.ncols;
    let mut deg = vec![0usize; n];
    for j in 0..n {
        for &i in q.col(j).0 {
            if i as usize != j {
                deg[j] += 1;
                deg[i as usize] += 1;
            }
        }
    }
    let mut col_ptr = vec![0usize; n + 1];
    for j in 0..n {
        col_ptr[j + 1] = col_ptr[j] + deg[j];
    }
    let mut fill = col_ptr.clone();
    let mut rows = vec![0u32; col_ptr[n]];
    for j in 0..n {
        for &i in q.col(j).0 {
            let iu = i as usize;
            if iu != j {
                rows[fill[j]] = i;
                fill[j] += 1;
                rows[fill[iu]] = j as u32;
                fill[iu] += 1;
            }
        }
    }
    // Sort and deduplicate each column (a full input lists every edge twice).
    let mut out =
        Csc { nrows: n, ncols: n, col_ptr: vec![0], row_idx: Vec::with_capacity(rows.len() / 2), values: Vec::new() };
    for j in 0..n {
        let col = &mut rows[col_ptr[j]..col_ptr[j + 1]];
        col.sort_unstable();
        let mut last = u32::MAX;
        for &r in col.iter() {
            if r != last {
                out.row_idx.push(r);
                last = r;
            }
        }
        out.col_ptr.push(out.row_idx.len());
    }
    out.values = vec![0.0; out.row_idx.len()];
    out
}

/// Approximate minimum degree order (faer's AMD) of the subgraph of `q` induced by `set`;
/// `local` is scratch of size `q.ncols`, all `u32::MAX`, and is left so.
fn amd_order(q: &Csc, set: &[u32], local: &mut [u32]) -> Vec<u32> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    for (k, &v) in set.iter().enumerate() {
        local[v as usize] = k as u32;
    }
    let m = set.len();
    let mut col_ptr = Vec::with_capacity(m + 1);
    let mut rows = Vec::new();
    col_ptr.push(0u32);
    for &v in set {
        let (r, _) = q.col(v as usize);
        let start = rows.len();
        for &w in r {
            let l = local[w as usize];
            if l != u32::MAX {
                rows.push(l);
            }
        }
        rows[start..].sort_unstable();
        col_ptr.push(rows.len() as u32);
    }
    for &v in set {
        local[v as usize] = u32::MAX;
    }
    let nnz = rows.len();
    let (mut perm, mut inv) = (vec![0u32; m], vec![0u32; m]);
    let ok = (|| {
        let sym = faer::sparse::SymbolicSparseColMat::new_checked(m, m, col_ptr, None, rows);
        let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_scratch::<u32>(m, nnz)).ok()?;
        faer::sparse::linalg::amd::order(&mut perm, &mut inv, sym.as_ref(), Default::default(), MemStack::new(&mut mem))
            .ok()
    })();
    match ok {
        Some(_) => perm.iter().map(|&k| set[k as usize]).collect(),
        None => set.to_vec(),
    }
}

/// An elimination order of the symmetric pattern of `q` (the diagonal is ignored): `order[k]`
/// is the index eliminated `k`-th.
pub fn nested_dissection(q: &Csc) -> Vec<u32> {
    nested_dissection_with_leaves(q, LEAF)
}

/// [`nested_dissection`] stopping at subsets of at most `leaf` vertices, which are ordered by
/// minimum degree.
pub fn nested_dissection_with_leaves(q: &Csc, leaf: usize) -> Vec<u32> {
    // Both triangles of the pattern (the input may hold only the lower one).
    let q = &symmetric_pattern(q);
    let n = q.ncols;
    let mut local = vec![u32::MAX; n];
    let mut reversed: Vec<u32> = Vec::with_capacity(n);
    // Membership stamp per vertex and BFS level (u32::MAX: unvisited in the current search).
    let mut stamp = vec![0u32; n];
    let mut level = vec![u32::MAX; n];
    let mut queue: Vec<u32> = Vec::with_capacity(n);
    let mut next_stamp = 1u32;
    let mut stack: Vec<Vec<u32>> = vec![(0..n as u32).collect()];
    while let Some(set) = stack.pop() {
        if set.len() <= leaf {
            let order = if set.len() > 3 { amd_order(q, &set, &mut local) } else { set };
            reversed.extend(order.iter().rev());
            continue;
        }
        let id = next_stamp;
        next_stamp = next_stamp.wrapping_add(1).max(1);
        for &v in &set {
            stamp[v as usize] = id;
        }
        // Breadth-first search within the set; returns the visit order (levels in `level`).
        let bfs = |start: u32, level: &mut [u32], queue: &mut Vec<u32>| {
            queue.clear();
            queue.push(start);
            level[start as usize] = 0;
            let mut head = 0;
            while head < queue.len() {
                let v = queue[head] as usize;
                head += 1;
                let (rows, _) = q.col(v);
                for &w in rows {
                    let wu = w as usize;
                    if stamp[wu] == id && level[wu] == u32::MAX {
                        level[wu] = level[v] + 1;
                        queue.push(w);
                    }
                }
            }
        };
        let reset = |level: &mut [u32], queue: &[u32]| {
            for &v in queue {
                level[v as usize] = u32::MAX;
            }
        };
        bfs(set[0], &mut level, &mut queue);
        if queue.len() < set.len() {
            // Disconnected: the reached component and the rest are ordered separately.
            let reached: Vec<u32> = queue.clone();
            reset(&mut level, &queue);
            for &v in &reached {
                stamp[v as usize] = 0;
            }
            let rest: Vec<u32> = set.iter().copied().filter(|&v| stamp[v as usize] == id).collect();
            stack.push(reached);
            stack.push(rest);
            continue;
        }
        // Pseudo-peripheral start: the last vertex reached, twice.
        let mut start = *queue.last().unwrap_or(&set[0]);
        for _ in 0..2 {
            reset(&mut level, &queue);
            bfs(start, &mut level, &mut queue);
            start = *queue.last().unwrap_or(&start);
        }
        // A level separates the lower levels from the higher ones (a Q-edge joins adjacent
        // levels only): the smallest level with at least 35% of the set on each side.
        let depth = level[queue[queue.len() - 1] as usize] as usize;
        let mut count = vec![0usize; depth + 1];
        for &v in &queue {
            count[level[v as usize] as usize] += 1;
        }
        let lo = set.len() * 35 / 100;
        let (mut below, mut best, mut sep) = (0usize, usize::MAX, None);
        for (l, &c) in count.iter().enumerate() {
            let above = set.len() - below - c;
            if below >= lo && above >= lo && c < best {
                best = c;
                sep = Some(l);
            }
            below += c;
        }
        let sep = sep.unwrap_or_else(|| {
            // No balanced level: the median one.
            let mut acc = 0;
            count
                .iter()
                .position(|&c| {
                    acc += c;
                    acc > set.len() / 2
                })
                .unwrap_or(depth)
        }) as u32;
        let (mut a, mut b, mut s) = (Vec::new(), Vec::new(), Vec::new());
        for &v in &queue {
            match level[v as usize].cmp(&sep) {
                std::cmp::Ordering::Less => a.push(v),
                std::cmp::Ordering::Greater => b.push(v),
                std::cmp::Ordering::Equal => s.push(v),
            }
        }
        reset(&mut level, &queue);
        // Thin the separator: a vertex with no neighbour on one side can join that side
        // (the level of a two-ring stencil is wider than it needs to be).
        let (a, b, s) = thin_separator(q, a, b, s, &mut stamp, id);
        reversed.extend(s.iter().rev());
        if !b.is_empty() {
            stack.push(b);
        }
        if !a.is_empty() {
            stack.push(a);
        }
    }
    reversed.reverse();
    reversed
}

#[cfg(test)]
#[path = "tests/ordering.rs"]
mod tests;
