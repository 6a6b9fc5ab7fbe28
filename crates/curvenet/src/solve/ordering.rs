//! Fill-reducing orderings for the sparse Cholesky factorisation.
//!
//! [`nested_dissection`] is George's automatic nested dissection by level structures (A.
//! George, *Nested dissection of a regular finite element mesh*, SIAM J. Numer. Anal. 1973;
//! George & Liu, *Computer Solution of Large Sparse Positive Definite Systems*, 1981, ch. 8):
//! breadth-first levels from a pseudo-peripheral vertex, a middle level as separator, both
//! halves ordered recursively and the separator last; small subsets are ordered by minimum
//! degree. On the meshes of this crate (2-manifolds of quasi-uniform triangles) the levels are
//! curves of about √n vertices, so the factor has O(n log n) entries — fewer than minimum
//! degree gives at large n. It works on the pattern of the matrix actually factored (the
//! two-ring stencil of `Ls M⁻¹ Ls`), so every level is a true separator of that matrix.
//!
//! [`nested_dissection_in_parts`] adds what the surfacing systems know: their unknowns fall in
//! patches that touch only across the curves. Two patches' free vertices are coupled through
//! the curve vertices between them, which are not unknowns, so one layer of free vertices
//! along a curve separates the two-ring stencil where a cut across a patch needs two layers.
//! The dissection groups whole patches while that is cheaper (measured on the 100k sphere: a
//! factor with 21% fewer non-zeros than minimum degree's, 9% more than METIS's).
//!
//! The two halves of the first splits are ordered on two threads.

use crate::solve::sparse::Csc;

/// Subsets at most this large are not split further but ordered by minimum degree (measured
/// on the sphere at 100k and 1M unknowns: 150 gives 3% less fill than 500).
const LEAF: usize = 150;

/// The smallest share of a set (percent) on either side of a level separator.
const LEVEL_BALANCE: usize = 25;

/// The smallest share of a set (percent) on either side of a split along part borders.
const PART_BALANCE: usize = 20;

/// Sets at least this large have their two halves ordered in parallel (down to
/// [`PARALLEL_DEPTH`] levels).
const PARALLEL_SET: usize = 40_000;
const PARALLEL_DEPTH: u32 = 2;

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
    nested_dissection_with_leaves(q, None, LEAF)
}

/// [`nested_dissection`] of a system whose unknowns are grouped in parts that touch each other
/// only along thin borders: `parts[i]` is the part of unknown `i` (see the module
/// documentation). `parts` of the wrong length are ignored.
pub fn nested_dissection_in_parts(q: &Csc, parts: &[u32]) -> Vec<u32> {
    nested_dissection_with_leaves(q, Some(parts), LEAF)
}

/// [`nested_dissection`] (or [`nested_dissection_in_parts`] with `parts`) stopping at subsets
/// of at most `leaf` vertices, which are ordered by minimum degree.
pub fn nested_dissection_with_leaves(q: &Csc, parts: Option<&[u32]>, leaf: usize) -> Vec<u32> {
    // Both triangles of the pattern (the input may hold only the lower one).
    let g = symmetric_pattern(q);
    let parts = parts.filter(|p| p.len() == q.ncols);
    let part_count = parts.map_or(0, |p| p.iter().max().map_or(0, |m| *m as usize + 1));
    let d = Dissection { g: &g, parts, part_count, leaf: leaf.max(1) };
    d.order((0..q.ncols as u32).collect(), PARALLEL_DEPTH)
}

/// A partition of a vertex set: the two sides and the separator between them.
struct Split {
    a: Vec<u32>,
    b: Vec<u32>,
    s: Vec<u32>,
}

/// Per-thread scratch (vertex arrays sized `g.ncols`, part arrays sized by the part count).
struct Scratch {
    /// Membership stamps: a set's vertices carry its id (see [`thin_separator`]).
    stamp: Vec<u32>,
    next_stamp: u32,
    /// Breadth-first levels (`u32::MAX`: unvisited).
    level: Vec<u32>,
    queue: Vec<u32>,
    /// Local indices for [`amd_order`] (`u32::MAX` outside).
    local: Vec<u32>,
    /// Local index of each part in the current set (`u32::MAX`: absent).
    part_local: Vec<u32>,
}

impl Scratch {
    fn new(n: usize, part_count: usize) -> Self {
        Scratch {
            stamp: vec![0; n],
            next_stamp: 1,
            level: vec![u32::MAX; n],
            queue: Vec::with_capacity(n),
            local: vec![u32::MAX; n],
            part_local: vec![u32::MAX; part_count],
        }
    }

    /// A fresh stamp value with `k` consecutive values reserved.
    fn stamp_id(&mut self, k: u32) -> u32 {
        if self.next_stamp > u32::MAX - 8 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.next_stamp = 1;
        }
        let id = self.next_stamp;
        self.next_stamp += k;
        id
    }
}

/// The separator size scaled by the imbalance of the sides (a ratio cut, 1× at an even split):
/// a small separator that leaves most of the set on one side only postpones the work.
fn ratio_cost(separator: usize, a: usize, b: usize) -> f64 {
    let (a, b) = (a.max(1) as f64, b.max(1) as f64);
    separator as f64 * (a + b) * (a + b) / (4.0 * a * b)
}

/// The graph being dissected and the options.
struct Dissection<'a> {
    /// Symmetric pattern without diagonal.
    g: &'a Csc,
    parts: Option<&'a [u32]>,
    part_count: usize,
    leaf: usize,
}

impl Dissection<'_> {
    /// The elimination order of `set`: its halves in parallel while large, then sequentially.
    fn order(&self, set: Vec<u32>, par_depth: u32) -> Vec<u32> {
        if par_depth == 0 || set.len() < PARALLEL_SET {
            return self.order_sequential(set);
        }
        let mut sc = Scratch::new(self.g.ncols, self.part_count);
        let Split { a, b, s } = self.split(&set, &mut sc);
        drop(sc);
        let (mut oa, ob) = rayon::join(|| self.order(a, par_depth - 1), || self.order(b, par_depth - 1));
        oa.extend(ob);
        oa.extend(s);
        oa
    }

    fn order_sequential(&self, set: Vec<u32>) -> Vec<u32> {
        let mut sc = Scratch::new(self.g.ncols, self.part_count);
        // Built backwards: a set's separator, then its halves (B's order, then A's).
        let mut reversed: Vec<u32> = Vec::with_capacity(set.len());
        let mut stack: Vec<Vec<u32>> = vec![set];
        while let Some(set) = stack.pop() {
            if set.len() <= self.leaf {
                let order = if set.len() > 3 { amd_order(self.g, &set, &mut sc.local) } else { set };
                reversed.extend(order.iter().rev());
                continue;
            }
            let Split { a, b, s } = self.split(&set, &mut sc);
            reversed.extend(s.iter().rev());
            if !a.is_empty() {
                stack.push(a);
            }
            if !b.is_empty() {
                stack.push(b);
            }
        }
        reversed.reverse();
        reversed
    }

    /// Splits `set`: into its connected components (reached from the first vertex, and the
    /// rest; no separator) or, when connected, by the cheaper of a level separator and a split
    /// along part borders, both thinned.
    fn split(&self, set: &[u32], sc: &mut Scratch) -> Split {
        let g = self.g;
        let id = sc.stamp_id(1);
        for &v in set {
            sc.stamp[v as usize] = id;
        }
        bfs(g, set[0], id, sc);
        if sc.queue.len() < set.len() {
            let a: Vec<u32> = sc.queue.clone();
            let b: Vec<u32> = set.iter().copied().filter(|&v| sc.level[v as usize] == u32::MAX).collect();
            reset_levels(sc);
            return Split { a, b, s: Vec::new() };
        }
        let by_levels = split_by_levels(g, set, id, sc);
        let by_parts = self.parts.and_then(|p| {
            for &v in set {
                sc.stamp[v as usize] = id;
            }
            split_by_parts(g, set, p, id, sc)
        });
        let mut thin = |sp: Split| {
            let t = sc.stamp_id(3);
            let (a, b, s) = thin_separator(g, sp.a, sp.b, sp.s, &mut sc.stamp, t);
            Split { a, b, s }
        };
        let by_levels = thin(by_levels);
        match by_parts.map(thin) {
            Some(sp)
                if ratio_cost(sp.s.len(), sp.a.len(), sp.b.len())
                    <= ratio_cost(by_levels.s.len(), by_levels.a.len(), by_levels.b.len()) =>
            {
                sp
            }
            _ => by_levels,
        }
    }
}

/// Breadth-first search from `start` over the vertices stamped `id`: visit order in
/// `sc.queue`, levels in `sc.level` (to be reset with [`reset_levels`]).
fn bfs(g: &Csc, start: u32, id: u32, sc: &mut Scratch) {
    let Scratch { stamp, level, queue, .. } = sc;
    queue.clear();
    queue.push(start);
    level[start as usize] = 0;
    let mut head = 0;
    while head < queue.len() {
        let v = queue[head] as usize;
        head += 1;
        let next = level[v] + 1;
        for &w in g.col(v).0 {
            let wu = w as usize;
            if stamp[wu] == id && level[wu] == u32::MAX {
                level[wu] = next;
                queue.push(w);
            }
        }
    }
}

fn reset_levels(sc: &mut Scratch) {
    for &v in &sc.queue {
        sc.level[v as usize] = u32::MAX;
    }
}

/// The split of a connected `set` (stamped `id`, with a breadth-first search from any of its
/// vertices in `sc`) at one level of a search from a pseudo-peripheral vertex (the last one
/// that search reached): the level of least [`ratio_cost`] with at least [`LEVEL_BALANCE`]
/// percent of the set on each side (a `g`-edge joins adjacent levels only). One search for the
/// start, not the usual iteration to a fixed eccentricity: 0.5% more fill, 15% faster.
fn split_by_levels(g: &Csc, set: &[u32], id: u32, sc: &mut Scratch) -> Split {
    let start = sc.queue[sc.queue.len() - 1];
    reset_levels(sc);
    bfs(g, start, id, sc);
    let depth = sc.level[sc.queue[sc.queue.len() - 1] as usize] as usize;
    let mut count = vec![0usize; depth + 1];
    for &v in &sc.queue {
        count[sc.level[v as usize] as usize] += 1;
    }
    let lo = set.len() * LEVEL_BALANCE / 100;
    let (mut below, mut best, mut sep) = (0usize, f64::INFINITY, None);
    for (l, &c) in count.iter().enumerate() {
        let above = set.len() - below - c;
        let cost = ratio_cost(c, below, above);
        if below >= lo && above >= lo && cost < best {
            best = cost;
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
    for &v in &sc.queue {
        match sc.level[v as usize].cmp(&sep) {
            std::cmp::Ordering::Less => a.push(v),
            std::cmp::Ordering::Greater => b.push(v),
            std::cmp::Ordering::Equal => s.push(v),
        }
    }
    reset_levels(sc);
    Split { a, b, s }
}

/// The split of a connected `set` (stamped `id`) along part borders: the parts present are
/// grouped in two by greedy growth over the part adjacency from several seeds (each side at
/// least [`PART_BALANCE`] percent of the set, least [`ratio_cost`]), and the separator is the
/// layer of vertices on one side that touch the other. `None` when the set lies in one part or
/// no grouping is balanced enough.
fn split_by_parts(g: &Csc, set: &[u32], parts: &[u32], id: u32, sc: &mut Scratch) -> Option<Split> {
    // Local part indices.
    let mut part_local = std::mem::take(&mut sc.part_local);
    let mut present: Vec<u32> = Vec::new();
    for &v in set {
        let p = parts[v as usize] as usize;
        if part_local[p] == u32::MAX {
            part_local[p] = present.len() as u32;
            present.push(p as u32);
        }
    }
    let result = (|| {
        let k = present.len();
        if k < 2 {
            return None;
        }
        let lp = |v: u32| part_local[parts[v as usize] as usize] as usize;
        let mut weight = vec![0usize; k];
        // (p, r) once per vertex of part p with a neighbour in part r.
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut seen: Vec<usize> = Vec::new();
        for &v in set {
            let p = lp(v);
            weight[p] += 1;
            seen.clear();
            for &w in g.col(v as usize).0 {
                if sc.stamp[w as usize] == id {
                    let r = lp(w);
                    if r != p && !seen.contains(&r) {
                        seen.push(r);
                        pairs.push((p as u32, r as u32));
                    }
                }
            }
        }
        pairs.sort_unstable();
        // border[(p, r)] as adjacency lists: (r, |p→r|, |r→p|).
        let mut count: Vec<((u32, u32), usize)> = Vec::new();
        for &pr in &pairs {
            match count.last_mut() {
                Some((last, c)) if *last == pr => *c += 1,
                _ => count.push((pr, 1)),
            }
        }
        let lookup = |p: u32, r: u32| count.binary_search_by(|(pr, _)| pr.cmp(&(p, r))).map_or(0, |i| count[i].1);
        let mut adj: Vec<Vec<(usize, usize, usize)>> = vec![Vec::new(); k];
        for &((p, r), c) in &count {
            adj[p as usize].push((r as usize, c, lookup(r, p)));
        }
        let total = set.len();
        let (lo, hi) = (total * PART_BALANCE / 100, total - total * PART_BALANCE / 100);
        // Seeds: every part when there are few, else a spread of them.
        let step = (k / 16).max(1);
        let mut best: Option<(f64, Vec<bool>, bool)> = None;
        for seed in (0..k).step_by(step) {
            let mut in_a = vec![false; k];
            // gain[x]: change of the border (both ways) when x joins A; frontier: touches A.
            let mut gain: Vec<i64> = (0..k).map(|x| adj[x].iter().map(|&(_, c, b)| (c + b) as i64).sum()).collect();
            let mut frontier = vec![false; k];
            let (mut w_a, mut out_a, mut out_b) = (0usize, 0usize, 0usize);
            let mut next = Some(seed);
            while let Some(x) = next {
                in_a[x] = true;
                w_a += weight[x];
                for &(r, c, back) in &adj[x] {
                    if in_a[r] {
                        out_a -= back;
                        out_b -= c;
                    } else {
                        out_a += c;
                        out_b += back;
                        gain[r] -= 2 * (c + back) as i64;
                        frontier[r] = true;
                    }
                }
                if w_a >= lo && w_a <= hi {
                    let cost = ratio_cost(out_a.min(out_b), w_a, total - w_a);
                    if best.as_ref().is_none_or(|(c, _, _)| cost < *c) {
                        best = Some((cost, in_a.clone(), out_a <= out_b));
                    }
                }
                if w_a >= hi {
                    break;
                }
                next = (0..k).filter(|&x| frontier[x] && !in_a[x]).min_by_key(|&x| gain[x]);
            }
        }
        let (_, in_a, sep_in_a) = best?;
        // The side whose border is smaller gives its border layer as separator; the other
        // side keeps all its vertices (stamped `keep`).
        let keep = sc.stamp_id(1);
        for &v in set {
            if in_a[lp(v)] != sep_in_a {
                sc.stamp[v as usize] = keep;
            }
        }
        let (mut a, mut b, mut s) = (Vec::new(), Vec::new(), Vec::new());
        for &v in set {
            if sc.stamp[v as usize] == keep {
                b.push(v);
            } else if g.col(v as usize).0.iter().any(|&w| sc.stamp[w as usize] == keep) {
                s.push(v);
            } else {
                a.push(v);
            }
        }
        Some(Split { a, b, s })
    })();
    for p in present {
        part_local[p as usize] = u32::MAX;
    }
    sc.part_local = part_local;
    result
}

#[cfg(test)]
#[path = "tests/ordering.rs"]
mod tests;
