//! The hexagonal lattice that fills the inside of a planar patch domain: points at spacing
//! `d` in rows `√3/2 d` apart (odd rows shifted by `d/2`), kept at least `0.6 d` from the
//! border, and the lattice's own equilateral triangles, which the triangulation takes as they
//! are ([`super::triangulate`] meshes only the band between them and the border).

use crate::geom::DVec2;

/// Points of a hexagonal lattice with their lattice coordinates.
pub(super) struct Lattice {
    /// The points, row by row, left to right.
    pub(super) points: Vec<DVec2>,
    /// Point index at `row * cols + col`, `u32::MAX` where there is none. Row `k` holds the
    /// points `x = x0 + (k odd ? d/2 : 0) + col·d`.
    grid: Vec<u32>,
    rows: usize,
    cols: usize,
}

/// The lattice's own triangles (each with its three corners in the lattice,
/// counter-clockwise), the outline of their union, and which points are inside it.
pub(super) struct LatticeTriangles {
    /// Counter-clockwise corners.
    pub(super) triangles: Vec<[u32; 3]>,
    /// Edges of exactly one triangle.
    pub(super) outline: Vec<[u32; 2]>,
    /// Per point: in some triangle and on no outline edge.
    pub(super) interior: Vec<bool>,
}

/// Triangles of the hexagonal lattice whose three corners are lattice points. Each triangle
/// lies inside the polygon the lattice was made for: its corners are at least `0.6 d` from the
/// border, more than the circumradius `d/√3`, so no border vertex lies in it and no border
/// edge crosses it.
pub(super) fn lattice_triangles(lat: &Lattice) -> LatticeTriangles {
    let m = lat.points.len();
    let at = |row: usize, col: isize| -> u32 {
        if row >= lat.rows || col < 0 || col as usize >= lat.cols {
            u32::MAX
        } else {
            lat.grid[row * lat.cols + col as usize]
        }
    };
    // Neighbours of (row, col) in row + 1: left and right (odd rows are shifted by d/2).
    let up = |row: usize, col: isize| if row % 2 == 0 { (col - 1, col) } else { (col, col + 1) };
    // Edge use counts per point and direction: 0 east, 1 up-left, 2 up-right.
    let mut uses = vec![0u8; 3 * m];
    let mut triangles = Vec::new();
    let mut in_triangle = vec![false; m];
    for row in 0..lat.rows.saturating_sub(1) {
        for col in 0..lat.cols as isize {
            let a = at(row, col);
            if a == u32::MAX {
                continue;
            }
            let (ul, ur) = up(row, col);
            let (above_l, above_r) = (at(row + 1, ul), at(row + 1, ur));
            // "Up" triangle: a, its east neighbour b, and the point above between them.
            let b = at(row, col + 1);
            if b != u32::MAX && above_r != u32::MAX {
                triangles.push([a, b, above_r]);
                uses[3 * a as usize] += 1; // a–b
                uses[3 * a as usize + 2] += 1; // a–apex
                uses[3 * b as usize + 1] += 1; // b–apex
            }
            // "Down" triangle: a and the two points above it.
            if above_l != u32::MAX && above_r != u32::MAX {
                triangles.push([a, above_r, above_l]);
                uses[3 * above_l as usize] += 1; // left–right above
                uses[3 * a as usize + 2] += 1; // a–right
                uses[3 * a as usize + 1] += 1; // a–left
            }
        }
    }
    for t in &triangles {
        for &v in t {
            in_triangle[v as usize] = true;
        }
    }
    let mut interior = in_triangle;
    let mut outline = Vec::new();
    for row in 0..lat.rows {
        for col in 0..lat.cols as isize {
            let a = at(row, col);
            if a == u32::MAX {
                continue;
            }
            let (ul, ur) = up(row, col);
            let ends = [at(row, col + 1), at(row + 1, ul), at(row + 1, ur)];
            for (dir, &b) in ends.iter().enumerate() {
                if b != u32::MAX && uses[3 * a as usize + dir] == 1 {
                    outline.push([a, b]);
                    interior[a as usize] = false;
                    interior[b as usize] = false;
                }
            }
        }
    }
    LatticeTriangles { triangles, outline, interior }
}

/// Points of the hexagonal lattice of side `d` inside the counter-clockwise polygon `poly`, at
/// least `0.6 d` from its border, aligned on the lower left corner of the polygon's bounding
/// box. The lattice is empty when the box is not wider and taller than `1.2 d` or would hold
/// more than about 4·10⁸ points.
pub(super) fn hex_lattice(poly: &[DVec2], d: f64) -> Lattice {
    let n = poly.len();
    let margin = 0.6 * d;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in poly {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let ext = hi - lo;
    let empty = Lattice { points: Vec::new(), grid: Vec::new(), rows: 0, cols: 0 };
    // (Comparisons with NaN are false: no lattice then either.)
    let wide = ext.x > 2.0 * margin && ext.y > 2.0 * margin;
    let positive = d > 0.0;
    if !wide || !positive || ext.x / d * ext.y / d > 4e8 {
        return empty;
    }
    let border = BorderGrid::new(poly, lo, ext, d);
    let row = 0.5 * 3f64.sqrt() * d;
    let mut out = Vec::new();
    let mut xs = Vec::new();
    let rows = (ext.y / row) as usize + 1;
    let cols = (ext.x / d) as usize + 2;
    let mut grid = vec![u32::MAX; (rows + 1) * cols];
    for k in 0..=rows {
        let y = lo.y + k as f64 * row + 0.5 * (ext.y - rows as f64 * row).max(0.0);
        // Even-odd crossings of the horizontal line with the border.
        xs.clear();
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            if (a.y > y) != (b.y > y) {
                xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        }
        xs.sort_by(f64::total_cmp);
        let shift = if k % 2 == 1 { 0.5 * d } else { 0.0 };
        for pair in xs.chunks(2) {
            let [x0, x1] = [pair[0], *pair.get(1).unwrap_or(&pair[0])];
            let start = ((x0 - lo.x - shift) / d).ceil().max(0.0) as usize;
            let mut col = start;
            let mut x = lo.x + shift + col as f64 * d;
            while x < x1 && col < cols {
                let p = DVec2::new(x, y);
                if x > x0 && !border.near(p, margin) {
                    grid[k * cols + col] = out.len() as u32;
                    out.push(p);
                }
                col += 1;
                x = lo.x + shift + col as f64 * d;
            }
        }
    }
    Lattice { points: out, grid, rows: rows + 1, cols }
}

/// The border edges of a polygon binned in a grid of square cells of side `d` over its
/// bounding box, to find the edges near a point.
struct BorderGrid<'a> {
    poly: &'a [DVec2],
    /// Lower corner of the bounding box.
    lo: DVec2,
    d: f64,
    nx: usize,
    ny: usize,
    /// Per cell (`x + nx·y`): the edges (from `poly[i]` to the next point) whose bounding box
    /// meets it.
    cells: Vec<Vec<u32>>,
}

impl<'a> BorderGrid<'a> {
    /// Bins the edges of `poly`, whose bounding box is `lo + [0, ext]`.
    fn new(poly: &'a [DVec2], lo: DVec2, ext: DVec2, d: f64) -> Self {
        let n = poly.len();
        // Border edges in a grid of cells of size d, to find the nearby ones.
        let (nx, ny) = ((ext.x / d) as usize + 1, (ext.y / d) as usize + 1);
        let mut grid: Vec<Vec<u32>> = vec![Vec::new(); nx * ny];
        for i in 0..n {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (cmin, cmax) = (a.min(b), a.max(b));
            let (x0, x1) = (((cmin.x - lo.x) / d) as usize, (((cmax.x - lo.x) / d) as usize).min(nx - 1));
            let (y0, y1) = (((cmin.y - lo.y) / d) as usize, (((cmax.y - lo.y) / d) as usize).min(ny - 1));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid[x + nx * y].push(i as u32);
                }
            }
        }
        BorderGrid { poly, lo, d, nx, ny, cells: grid }
    }

    /// The cell of `p` (clamped to the grid).
    fn cell(&self, p: DVec2) -> usize {
        let (lo, d, nx, ny) = (self.lo, self.d, self.nx, self.ny);
        (((p.x - lo.x) / d) as usize).min(nx - 1) + nx * (((p.y - lo.y) / d) as usize).min(ny - 1)
    }

    /// Whether `p` is closer than `margin` (at most `d`) to a border edge.
    fn near(&self, p: DVec2, margin: f64) -> bool {
        let (poly, n, nx, ny) = (self.poly, self.poly.len(), self.nx, self.ny);
        let c = self.cell(p);
        let (cx, cy) = (c % nx, c / nx);
        for y in cy.saturating_sub(1)..=(cy + 1).min(ny - 1) {
            for x in cx.saturating_sub(1)..=(cx + 1).min(nx - 1) {
                for &e in &self.cells[x + nx * y] {
                    let (a, b) = (poly[e as usize], poly[(e as usize + 1) % n]);
                    let ab = b - a;
                    let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                    if p.distance(a + ab * t) < margin {
                        return true;
                    }
                }
            }
        }
        false
    }
}

#[cfg(test)]
#[path = "tests/lattice.rs"]
mod tests;
