//! The order-k Laplacian system with Cauchy constraints, assembled row by row by the recursion
//! of \[A11\] Appendix A, Algorithm 2 (`buildEqn`).
//!
//! Unknowns are the [`Role::Free`] vertices. Row `r` is `Δᵏ(v_r) = 0` with the recursive
//! Laplacian of \[A11\] eq. 1, `Δᵏ(u) = (1/A_u) Σᵢ wᵢ (Δᵏ⁻¹(u) − Δᵏ⁻¹(vᵢ))`, `Δ⁰(u) = u`. At a
//! Cauchy vertex `u` reached from the vertex `v` the micro-Laplacian of \[A11\] eq. 2 replaces it:
//! `Δᵏ(u_v) = 2wΔᵏ⁻¹(u_v) − wΔᵏ⁻¹(v) − wΔᵏ⁻¹(g₁)`, and along the line of ghost vertices
//! `g₀ = u, g₁, …, g_{k−1}` (the `gNum` of Algorithm 2) `Δᵏ(g_m) = 2wΔᵏ⁻¹(g_m) − wΔᵏ⁻¹(g_{m−1}) −
//! wΔᵏ⁻¹(g_{m+1})`. Positions of constraint and ghost vertices go to the right-hand side, which is
//! kept split (eq. 5): `b = l + Σ_j m_j g_j`, `l` from the fixed vertices, `m_j` per ghost.
//!
//! **Micro-Laplacian weight.** \[A11\] sets `w = 1` (§4.3). With the free vertices' Laplacian scaled
//! by the inverse area, that makes the micro term vanish relative to the others as the mesh is
//! refined (`O(h²)`), so the tangent condition fades into a natural boundary condition. We use
//! the 1D Laplacian of the hinge instead, `w = 1/|u − v|²` (the micro geometry's edge length is
//! that of the edge `u v`), which keeps the terms consistent and makes the 1-manifold case
//! converge to the cubic Hermite curve (\[A11\] Fig. 12; `tests/cauchy.rs`). [`MicroWeight`]
//! selects either.
//!
//! **Solver.** The micro-Laplacians make the matrix non-symmetric for `k ≥ 3` (and the rows are
//! not area-weighted), so it is factored by faer's sparse LU with partial pivoting (\[A11\] used
//! SuperLU, also an LU), once, and reused for every right-hand side (3 coordinates, or one per
//! ghost vertex for the basis of [`super::reduce`]).

use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::operators::Operators;
use crate::solve::lu::{Lu, LuError};
use crate::solve::Factorization;
use faer::Mat;
use rayon::prelude::*;
use std::collections::HashMap;

/// What a vertex is in the system (\[A11\] §5: Cauchy, smooth position, inactive constraints).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Role {
    /// An unknown (also the vertices of inactive constraints: they ride on the surface).
    #[default]
    Free,
    /// A smooth position constraint: fixed position, its Laplacian from its own one-ring.
    Position,
    /// A Cauchy constraint: fixed position, one micro-Laplacian per neighbour with ghost
    /// vertices that set the surface's tangent plane (and higher derivatives).
    Cauchy,
}

/// The weight `w` of the micro-Laplacian (\[A11\] eq. 2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MicroWeight {
    /// `w = 1/|u − v|²`: the hinge's 1D Laplacian, consistent under refinement (default).
    #[default]
    Consistent,
    /// `w = 1`, as printed in \[A11\] §4.3.
    Unit,
}

/// The discrete domain: one-ring weights and vertex areas from a fixed initial domain (\[A11\]
/// §3: "cotangent weights are computed in a fixed initial domain and held constant").
#[derive(Clone, Debug, Default)]
pub struct Stencil {
    /// Per vertex: `(neighbour, wᵢ)` with the cotangent weight `wᵢ` (unscaled).
    pub neighbours: Vec<Vec<(u32, f64)>>,
    /// Vertex areas `A_u`.
    pub area: Vec<f64>,
    /// Domain positions (for the edge lengths of the micro-Laplacian).
    pub positions: Vec<DVec3>,
    /// Domain lengths of edges `(u, v)` that override `positions` (curve networks: the planar
    /// domain of the patch the edge lies in).
    pub edge_lengths: HashMap<(u32, u32), f64>,
}

impl Stencil {
    /// From the cotangent operators: `wᵢ = (Ls)_{uvᵢ}`, `A_u = M_uu`.
    pub fn from_operators(ops: &Operators, domain_positions: Vec<DVec3>) -> Self {
        let n = ops.ls.ncols;
        let neighbours = (0..n)
            .map(|j| {
                let (rows, vals) = ops.ls.col(j);
                rows.iter().zip(vals).filter(|(&i, _)| i as usize != j).map(|(&i, &w)| (i, w)).collect()
            })
            .collect();
        Stencil { neighbours, area: ops.mass.clone(), positions: domain_positions, edge_lengths: HashMap::new() }
    }

    /// A polyline with parameters `t` (increasing): the 1-manifold case of \[A11\] Fig. 12,
    /// `wᵢ = 1/|t_u − t_v|`, `A_u` = half the adjacent lengths.
    pub fn polyline(t: &[f64]) -> Self {
        let n = t.len();
        let mut neighbours = vec![Vec::new(); n];
        let mut area = vec![0.0; n];
        for i in 0..n.saturating_sub(1) {
            let h = t[i + 1] - t[i];
            neighbours[i].push((i as u32 + 1, 1.0 / h));
            neighbours[i + 1].push((i as u32, 1.0 / h));
            area[i] += 0.5 * h;
            area[i + 1] += 0.5 * h;
        }
        Stencil {
            neighbours,
            area,
            positions: t.iter().map(|&x| DVec3::new(x, 0.0, 0.0)).collect(),
            edge_lengths: HashMap::new(),
        }
    }

    /// Number of vertices of the domain.
    pub fn num_vertices(&self) -> usize {
        self.area.len()
    }
}

/// A ghost vertex: number `number` (1 ..= k−1) on the line from the Cauchy vertex `vertex` away
/// from its neighbour `source` (\[A11\] Fig. 3, Algorithm 2's `gNum`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ghost {
    /// The Cauchy vertex.
    pub vertex: u32,
    /// The neighbour the ghost line leads away from.
    pub source: u32,
    /// Position on the line, 1 ..= k−1.
    pub number: u32,
}

/// The assembled system `A x = l + Σ_j m_j g_j` (\[A11\] eq. 1, 2, 5), not yet factored.
#[derive(Clone, Debug)]
pub struct System {
    /// The Laplacian order `k`.
    pub order: usize,
    /// Vertex of each unknown.
    pub free: Vec<u32>,
    /// Unknown of each vertex (`u32::MAX` for constraints).
    pub column: Vec<u32>,
    /// `A` as triplets (row, column, value), `#free × #free`.
    pub a: Vec<(u32, u32, f64)>,
    /// `l`: per row, `(constraint vertex, coefficient)` — the row's right-hand side is
    /// `Σ coefficient · position`.
    pub fixed: Vec<Vec<(u32, f64)>>,
    /// `m`: per row, `(ghost index, coefficient)`.
    pub ghost_terms: Vec<Vec<(u32, f64)>>,
    /// The ghost vertices, indexed as in `ghost_terms`.
    pub ghosts: Vec<Ghost>,
    /// First ghost index of each (Cauchy vertex, source) pair; ghost `m` is at `first + m − 1`.
    pub ghost_index: HashMap<(u32, u32), u32>,
}

struct RowAcc {
    a: Vec<(u32, f64)>,
    fixed: Vec<(u32, f64)>,
    ghost: Vec<(u32, f64)>,
}

struct Ctx<'a> {
    stencil: &'a Stencil,
    roles: &'a [Role],
    column: &'a [u32],
    ghost_index: &'a HashMap<(u32, u32), u32>,
    micro: MicroWeight,
}

impl Ctx<'_> {
    fn micro_weight(&self, u: u32, v: u32) -> f64 {
        match self.micro {
            MicroWeight::Unit => 1.0,
            MicroWeight::Consistent => {
                let len = match self.stencil.edge_lengths.get(&(u, v)) {
                    Some(&l) => l,
                    None => self.stencil.positions[u as usize].distance(self.stencil.positions[v as usize]),
                };
                1.0 / (len * len)
            }
        }
    }

    /// \[A11\] Algorithm 2, `buildEqn(M, r, v, o, wt, sV, gNum)`: adds `wt · Δᵒ(v)` (seen from
    /// `source` when `v` is a Cauchy vertex; ghost `g_num` of its line) to the row.
    fn build(&self, acc: &mut RowAcc, v: u32, o: usize, wt: f64, source: u32, g_num: u32) {
        let vi = v as usize;
        match self.roles[vi] {
            Role::Cauchy => {
                if o == 0 {
                    // setRHS(r, v, gNum, sV, −wt): the constraint's or the ghost's position.
                    if g_num == 0 {
                        acc.fixed.push((v, -wt));
                    } else {
                        let first = self.ghost_index[&(v, source)];
                        acc.ghost.push((first + g_num - 1, -wt));
                    }
                } else {
                    // [A11] eq. 2 (and its continuation along the ghost line).
                    let w = self.micro_weight(v, source);
                    self.build(acc, v, o - 1, 2.0 * w * wt, source, g_num);
                    self.build(acc, v, o - 1, -w * wt, source, g_num + 1);
                    if g_num == 0 {
                        self.build(acc, source, o - 1, -w * wt, v, 0);
                    } else {
                        self.build(acc, v, o - 1, -w * wt, source, g_num - 1);
                    }
                }
            }
            role => {
                if o == 0 {
                    if role == Role::Free {
                        acc.a.push((self.column[vi], wt));
                    } else {
                        acc.fixed.push((v, -wt));
                    }
                } else {
                    // [A11] eq. 1: Δᵒ(v) = (1/A_v) Σᵢ wᵢ (Δᵒ⁻¹(v) − Δᵒ⁻¹(nᵢ)).
                    // The self terms of the sum are gathered in one call (same expansion as
                    // Algorithm 2's per-neighbour calls, fewer branches).
                    let wt = wt / self.stencil.area[vi];
                    let total: f64 = self.stencil.neighbours[vi].iter().map(|e| e.1).sum();
                    self.build(acc, v, o - 1, wt * total, u32::MAX, 0);
                    for &(n, w) in &self.stencil.neighbours[vi] {
                        self.build(acc, n, o - 1, -wt * w, v, 0);
                    }
                }
            }
        }
    }
}

/// Sums the entries of equal keys (sorts by key).
fn merge(mut v: Vec<(u32, f64)>) -> Vec<(u32, f64)> {
    v.sort_unstable_by_key(|e| e.0);
    let mut out: Vec<(u32, f64)> = Vec::with_capacity(v.len());
    for (k, x) in v {
        match out.last_mut() {
            Some(last) if last.0 == k => last.1 += x,
            _ => out.push((k, x)),
        }
    }
    out
}

impl System {
    /// Assembles `Δᵏ x = 0` on the free vertices (\[A11\] Algorithm 1: one `buildEqn` per row).
    pub fn build(stencil: &Stencil, roles: &[Role], order: usize, micro: MicroWeight) -> Result<Self> {
        let n = stencil.num_vertices();
        if roles.len() != n {
            return Err(Error::usage(format!("{} roles for {n} vertices", roles.len())));
        }
        if !(1..=3).contains(&order) {
            return Err(Error::usage(format!("Laplacian order {order} is not 1, 2 or 3")));
        }
        if let Some(i) = stencil.area.iter().position(|a| !(*a > 0.0)) {
            return Err(Error::numerical(format!("vertex {i} has zero area: degenerate triangles around it")));
        }
        let mut column = vec![u32::MAX; n];
        let mut free = Vec::new();
        for (i, r) in roles.iter().enumerate() {
            if *r == Role::Free {
                column[i] = free.len() as u32;
                free.push(i as u32);
            }
        }
        if free.is_empty() {
            return Err(Error::input("every vertex is constrained: nothing to solve (the mesh has no free vertex)"));
        }
        // Ghost lines exist for each Cauchy vertex and each neighbour that expands its one-ring
        // (free or position vertices), numbers 1 ..= k−1.
        let mut ghosts = Vec::new();
        let mut ghost_index = HashMap::new();
        if order >= 2 {
            for u in 0..n {
                if roles[u] != Role::Cauchy {
                    continue;
                }
                for &(v, _) in &stencil.neighbours[u] {
                    if roles[v as usize] == Role::Cauchy {
                        continue;
                    }
                    ghost_index.insert((u as u32, v), ghosts.len() as u32);
                    for m in 1..order as u32 {
                        ghosts.push(Ghost { vertex: u as u32, source: v, number: m });
                    }
                }
            }
        }
        let ctx = Ctx { stencil, roles, column: &column, ghost_index: &ghost_index, micro };
        let rows: Vec<RowAcc> = free
            .par_iter()
            .map(|&v| {
                let mut acc = RowAcc { a: Vec::new(), fixed: Vec::new(), ghost: Vec::new() };
                ctx.build(&mut acc, v, order, 1.0, u32::MAX, 0);
                RowAcc { a: merge(acc.a), fixed: merge(acc.fixed), ghost: merge(acc.ghost) }
            })
            .collect();
        let mut a = Vec::new();
        let mut fixed = Vec::with_capacity(rows.len());
        let mut ghost_terms = Vec::with_capacity(rows.len());
        for (r, row) in rows.into_iter().enumerate() {
            a.extend(row.a.into_iter().map(|(c, x)| (r as u32, c, x)));
            fixed.push(row.fixed);
            ghost_terms.push(row.ghost);
        }
        Ok(System { order, free, column, a, fixed, ghost_terms, ghosts, ghost_index })
    }

    /// Number of unknowns (free vertices).
    pub fn num_free(&self) -> usize {
        self.free.len()
    }

    /// The right-hand side `l + Σ_j m_j g_j` (`#free × 3`) for constraint positions
    /// `positions` (read at the constraint vertices) and ghost positions `ghosts`.
    pub fn rhs(&self, positions: &[DVec3], ghosts: &[DVec3]) -> Mat<f64> {
        let mut b = Mat::<f64>::zeros(self.num_free(), 3);
        for r in 0..self.num_free() {
            let mut s = DVec3::ZERO;
            for &(v, c) in &self.fixed[r] {
                s += c * positions[v as usize];
            }
            for &(g, c) in &self.ghost_terms[r] {
                s += c * ghosts[g as usize];
            }
            b[(r, 0)] = s.x;
            b[(r, 1)] = s.y;
            b[(r, 2)] = s.z;
        }
        b
    }

    /// Factors `A` (sparse LU with partial pivoting, [`crate::solve::Lu`]; see the module docs).
    pub fn factor(&self) -> Result<Factored> {
        let lu = Lu::factor(self.num_free(), &self.a).map_err(|e| match e {
            LuError::Assembly(e) => Error::numerical(format!("Cauchy system assembly: {e}")),
            LuError::Singular(e) => Error::numerical(format!(
                "the order-{} Cauchy system is singular ({e}): is every patch constrained?",
                self.order
            )),
        })?;
        Ok(Factored { lu })
    }

    /// Factors and solves once; returns all vertex positions (constraints keep `positions`).
    pub fn solve(&self, positions: &[DVec3], ghosts: &[DVec3]) -> Result<Vec<DVec3>> {
        let f = self.factor()?;
        let mut b = self.rhs(positions, ghosts);
        f.solve_in_place(&mut b);
        let out = self.scatter(&b, positions);
        crate::methods::check_finite(&out, "Cauchy solve")?;
        Ok(out)
    }

    /// Solves with ghost lines `g_m = u + m·offset` (one offset per ghost, \[A11\] eq. 3), then
    /// `updates` re-solves with centred ghosts (ours; `docs/cauchy.md`): `g₁ = v + 2e` turns the
    /// tangent condition into a central difference (`(g₁ − v)/2 = e`: second order instead of
    /// first) and `g₂ = 3g₁ − 3u + v` continues the parabola through `v, u, g₁`, with `v` from
    /// the previous solve — a fixed-point iteration on the right-hand side only (same
    /// factorisation), under-relaxed by ½ for `k = 2` where the plain update oscillates.
    pub fn solve_with_updates(
        &self,
        f: &Factored,
        positions: &[DVec3],
        offsets: &[DVec3],
        updates: usize,
    ) -> Result<Vec<DVec3>> {
        let mut ghosts: Vec<DVec3> =
            self.ghosts.iter().zip(offsets).map(|(g, &o)| positions[g.vertex as usize] + g.number as f64 * o).collect();
        let mut b = self.rhs(positions, &ghosts);
        f.solve_in_place(&mut b);
        let mut out = self.scatter(&b, positions);
        for _ in 0..updates {
            for (i, g) in self.ghosts.iter().enumerate() {
                let (u, v) = (out[g.vertex as usize], out[g.source as usize]);
                let g1 = v + 2.0 * offsets[i];
                let target = if g.number == 1 { g1 } else { 3.0 * g1 - 3.0 * u + v };
                ghosts[i] = if self.order == 2 { 0.5 * (ghosts[i] + target) } else { target };
            }
            let mut b = self.rhs(positions, &ghosts);
            f.solve_in_place(&mut b);
            out = self.scatter(&b, positions);
        }
        crate::methods::check_finite(&out, "Cauchy solve")?;
        Ok(out)
    }

    /// Vertex positions from the solution `x` (`#free × 3`).
    pub fn scatter(&self, x: &Mat<f64>, positions: &[DVec3]) -> Vec<DVec3> {
        let mut out = positions.to_vec();
        for (r, &v) in self.free.iter().enumerate() {
            out[v as usize] = DVec3::new(x[(r, 0)], x[(r, 1)], x[(r, 2)]);
        }
        out
    }
}

/// A factored system: solve many right-hand sides.
pub struct Factored {
    lu: Lu,
}

impl Factored {
    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.lu.dim()
    }

    /// Solves `A X = B` in place for every column of `b`.
    pub fn solve_in_place(&self, b: &mut Mat<f64>) {
        self.lu.solve_in_place(b.as_mut());
    }
}
