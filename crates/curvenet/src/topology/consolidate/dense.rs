//! The strokes as dense polylines: every input edge cut into pieces no longer than `h` (a
//! quarter of the gap), the points on the input polyline itself (linear, so that a junction
//! found on a dense stroke lies on the curve as written), in one spatial hash. Input samples
//! closer than `h / 8` along to the point before them are left out, so that a query's ball
//! holds a bounded number of points whatever the input's sampling (a 500k-sample loop made the
//! overdraw stage scan every sample within its band: 4.7 s of a 9 s run).
//!
//! The stages of consolidation work on *pieces*: lists of dense points in order along a
//! stroke. A stroke starts as one piece; overdraw removes stretches of it (splitting it), jitter
//! trimming and gap closing cut its ends back.

use crate::geom::{grid_cell, DVec3, GridCell};
use crate::network::Curve;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A multiply–xor hash of grid cells (three `i64`s): the hash's lookups are most of
/// consolidation's time, and std's SipHash (built against collision attacks a grid of our own
/// points does not face) made the overdraw stage 1.9× slower (measured on 27k dense points,
/// 52 → 28 ms; docs/performance.md).
#[derive(Default)]
pub(super) struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }

    fn write_i64(&mut self, x: i64) {
        self.write_u64(x as u64);
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

/// Input samples closer than this many `h` along to the point before them are not dense points.
pub(super) const FINEST: f64 = 0.125;

type Grid = HashMap<GridCell, Vec<u32>, BuildHasherDefault<CellHasher>>;

/// A position's bits (an exact key).
fn bits(p: DVec3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// The sample positions that are samples of two curves or more.
fn shared_samples(curves: &[Curve]) -> HashSet<[u64; 3], BuildHasherDefault<CellHasher>> {
    let samples = curves.iter().map(|c| c.points.len()).sum();
    let mut first: HashMap<[u64; 3], usize, BuildHasherDefault<CellHasher>> =
        HashMap::with_capacity_and_hasher(samples, Default::default());
    let mut out = HashSet::default();
    for (c, curve) in curves.iter().enumerate() {
        for &p in &curve.points {
            let owner = *first.entry(bits(p)).or_insert(c);
            if owner != c {
                out.insert(bits(p));
            }
        }
    }
    out
}

/// The dense points of every curve of a network, and the hash that finds them.
pub(super) struct Dense {
    /// Positions (moved by the averaging of overdrawn stretches).
    pub(super) pos: Vec<DVec3>,
    /// Normals (zero where the curve has none).
    pub(super) nrm: Vec<DVec3>,
    /// Unit tangents (along the curve's sample order).
    pub(super) tan: Vec<DVec3>,
    /// Arc length from the curve's first sample.
    pub(super) arc: Vec<f64>,
    /// The curve of each point.
    pub(super) curve: Vec<u32>,
    /// The point is one of the input samples (not a point inserted on an edge).
    pub(super) sample: Vec<bool>,
    /// Per curve: its points are `range.0..range.1`.
    pub(super) ranges: Vec<(usize, usize)>,
    /// Per curve: it is closed, and its length.
    pub(super) closed: Vec<bool>,
    pub(super) length: Vec<f64>,
    /// The largest distance between two consecutive points.
    pub(super) h: f64,
    /// Cell side of the hash.
    cell: f64,
    grid: Grid,
}

impl Dense {
    /// The dense points of `curves`, at most `h` apart along them, hashed in cells of side
    /// `cell`.
    pub(super) fn new(curves: &[Curve], h: f64, cell: f64) -> Self {
        let mut d = Dense {
            pos: Vec::new(),
            nrm: Vec::new(),
            tan: Vec::new(),
            arc: Vec::new(),
            curve: Vec::new(),
            sample: Vec::new(),
            ranges: Vec::new(),
            closed: Vec::new(),
            length: Vec::new(),
            h,
            cell,
            grid: Grid::default(),
        };
        // At most every sample and a point every `h` between them (the caller bounds the
        // latter): reserved at once rather than grown by copying.
        let samples: usize = curves.iter().map(|c| c.points.len()).sum();
        let between =
            curves.iter().map(|c| c.points.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>()).sum::<f64>() / h;
        let room = samples + (between.ceil() as usize).min(16 * samples + 1_000_000);
        for v in [&mut d.pos, &mut d.nrm] {
            v.reserve(room);
        }
        d.arc.reserve(room);
        d.curve.reserve(room);
        d.sample.reserve(room);
        let mut shared: Option<HashSet<[u64; 3], BuildHasherDefault<CellHasher>>> = None;
        for (c, curve) in curves.iter().enumerate() {
            let start = d.pos.len();
            let p = &curve.points;
            let n = p.len();
            let edges = if curve.closed { n } else { n - 1 };
            let mut arc = 0.0;
            // The arc length of the last point pushed: an input sample closer than `h / 8` along
            // to it is left out (a stroke sampled far more finely than the gap would otherwise
            // put thousands of points in every query's ball).
            let mut last = f64::NEG_INFINITY;
            for i in 0..edges {
                let (a, b) = (p[i], p[(i + 1) % n]);
                let normal = |s: f64| {
                    if curve.has_normals() {
                        curve.mean_normal(i).lerp(curve.mean_normal((i + 1) % n), s).normalize_or_zero()
                    } else {
                        DVec3::ZERO
                    }
                };
                let len = a.distance(b);
                let pieces = ((len / h).ceil() as usize).max(1);
                for k in 0..pieces {
                    let s = k as f64 / pieces as f64;
                    // (A vertex shared with another curve is always kept: overdraw tells a
                    // neatened graph's shallow junction by it.)
                    if k == 0
                        && arc - last < FINEST * h
                        && !shared.get_or_insert_with(|| shared_samples(curves)).contains(&bits(a))
                    {
                        continue;
                    }
                    last = arc + s * len;
                    d.pos.push(a.lerp(b, s));
                    d.nrm.push(normal(s));
                    d.arc.push(arc + s * len);
                    d.curve.push(c as u32);
                    d.sample.push(k == 0);
                }
                arc += len;
            }
            if !curve.closed {
                d.pos.push(p[n - 1]);
                d.nrm.push(if curve.has_normals() {
                    curve.mean_normal(n - 1).normalize_or_zero()
                } else {
                    DVec3::ZERO
                });
                d.arc.push(arc);
                d.curve.push(c as u32);
                d.sample.push(true);
            }
            d.ranges.push((start, d.pos.len()));
            d.closed.push(curve.closed);
            d.length.push(arc);
        }
        d.tan = (0..d.pos.len()).map(|i| d.tangent_at(i)).collect();
        for (i, &p) in d.pos.iter().enumerate() {
            d.grid.entry(grid_cell(p, cell)).or_default().push(i as u32);
        }
        // A sample left out lengthens the step over it (by at most `h / 8`).
        let longest =
            (0..d.pos.len()).filter_map(|i| d.next(i).map(|j| d.pos[i].distance(d.pos[j]))).fold(0.0, f64::max);
        d.h = d.h.max(longest);
        d
    }

    /// The point after `i` on its curve (wrapping on a closed curve), if any.
    pub(super) fn next(&self, i: usize) -> Option<usize> {
        let (s, e) = self.ranges[self.curve[i] as usize];
        if i + 1 < e {
            Some(i + 1)
        } else if self.closed[self.curve[i] as usize] {
            Some(s)
        } else {
            None
        }
    }

    /// The point before `i` on its curve (wrapping on a closed curve), if any.
    pub(super) fn prev(&self, i: usize) -> Option<usize> {
        let (s, e) = self.ranges[self.curve[i] as usize];
        if i > s {
            Some(i - 1)
        } else if self.closed[self.curve[i] as usize] {
            Some(e - 1)
        } else {
            None
        }
    }

    fn tangent_at(&self, i: usize) -> DVec3 {
        let a = self.prev(i).map_or(self.pos[i], |j| self.pos[j]);
        let b = self.next(i).map_or(self.pos[i], |j| self.pos[j]);
        (b - a).normalize_or_zero()
    }

    /// Distance along their curve between points `i` and `j` (the shorter way on a loop).
    pub(super) fn along(&self, i: usize, j: usize) -> f64 {
        let c = self.curve[i] as usize;
        let d = (self.arc[i] - self.arc[j]).abs();
        if self.closed[c] {
            d.min(self.length[c] - d)
        } else {
            d
        }
    }

    /// Calls `f(j)` for every dense point `j` within `r` of `p` (the cells the ball's box
    /// meets: 8 for a radius of half the cell).
    pub(super) fn near(&self, p: DVec3, r: f64, mut f: impl FnMut(usize)) {
        let (lo, hi) = (grid_cell(p - DVec3::splat(r), self.cell), grid_cell(p + DVec3::splat(r), self.cell));
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for z in lo.2..=hi.2 {
                    if let Some(list) = self.grid.get(&(x, y, z)) {
                        for &j in list {
                            if self.pos[j as usize].distance_squared(p) <= r * r {
                                f(j as usize);
                            }
                        }
                    }
                }
            }
        }
    }

    /// Recomputes the tangents and the hash (after positions moved).
    pub(super) fn retangent(&mut self) {
        self.tan = (0..self.pos.len()).map(|i| self.tangent_at(i)).collect();
        self.grid.clear();
        for (i, &p) in self.pos.iter().enumerate() {
            self.grid.entry(grid_cell(p, self.cell)).or_default().push(i as u32);
        }
    }
}
