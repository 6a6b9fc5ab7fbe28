//! Exact closest points on triangles and segments, and point-to-mesh distance queries over a
//! bounding volume hierarchy: the measurements of [`crate::metrics`] and the pipeline's check
//! that the surface passes near the strokes it was given.

use crate::geom::DVec3;

/// Closest point to `p` on the triangle `abc` (Ericson, *Real-Time Collision Detection*,
/// §5.1.5).
pub fn closest_point_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Closest point to `p` on the segment `ab`.
pub fn closest_point_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let d = b - a;
    let l2 = d.length_squared();
    if l2 == 0.0 {
        return a;
    }
    a + d * ((p - a).dot(d) / l2).clamp(0.0, 1.0)
}

/// Exact point-to-mesh distance queries over a bounding volume hierarchy of the triangles
/// (median splits along the longest axis, leaves of up to 4 triangles).
pub struct MeshDistance<'a> {
    positions: &'a [DVec3],
    faces: &'a [[u32; 3]],
    nodes: Vec<BvhNode>,
    order: Vec<u32>,
}

struct BvhNode {
    bounds: crate::geom::Aabb,
    /// Leaf: range of `order` (`count > 0`); inner node: its two children.
    start: u32,
    count: u32,
    children: [u32; 2],
}

fn box_distance_sq(b: &crate::geom::Aabb, p: DVec3) -> f64 {
    let d = (b.min - p).max(p - b.max).max(DVec3::ZERO);
    d.length_squared()
}

impl<'a> MeshDistance<'a> {
    /// A closest-point structure over the triangles `faces` of `positions` (a bounding-box tree).
    pub fn new(positions: &'a [DVec3], faces: &'a [[u32; 3]]) -> Self {
        let tri_box = |f: &[u32; 3]| crate::geom::Aabb::of(f.iter().map(|&i| positions[i as usize]));
        let boxes: Vec<crate::geom::Aabb> = faces.iter().map(tri_box).collect();
        let centers: Vec<DVec3> = boxes.iter().map(|b| b.center()).collect();
        let mut me = MeshDistance { positions, faces, nodes: Vec::new(), order: (0..faces.len() as u32).collect() };
        if !faces.is_empty() {
            me.build(0, faces.len(), &boxes, &centers);
        }
        me
    }

    fn build(&mut self, start: usize, end: usize, boxes: &[crate::geom::Aabb], centers: &[DVec3]) -> u32 {
        let mut bounds = crate::geom::Aabb::empty();
        for &t in &self.order[start..end] {
            bounds.extend(boxes[t as usize].min);
            bounds.extend(boxes[t as usize].max);
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(BvhNode { bounds, start: start as u32, count: (end - start) as u32, children: [0; 2] });
        if end - start <= 4 {
            return id;
        }
        let ext = bounds.max - bounds.min;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let mid = (start + end) / 2;
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            centers[a as usize][axis].total_cmp(&centers[b as usize][axis])
        });
        let left = self.build(start, mid, boxes, centers);
        let right = self.build(mid, end, boxes, centers);
        let node = &mut self.nodes[id as usize];
        node.count = 0;
        node.children = [left, right];
        id
    }

    /// Distance from `p` to the mesh, the closest point and the index of its face.
    pub fn closest_face(&self, p: DVec3) -> (f64, DVec3, usize) {
        self.closest_face_where(p, |_| true)
    }

    /// [`MeshDistance::closest_face`] among the faces `f` with `keep(f)` (infinite distance and
    /// face `usize::MAX` when there is none).
    pub fn closest_face_where(&self, p: DVec3, keep: impl Fn(usize) -> bool) -> (f64, DVec3, usize) {
        let mut best = (f64::INFINITY, p, usize::MAX);
        if self.nodes.is_empty() {
            return best;
        }
        let mut stack = vec![0u32];
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id as usize];
            if box_distance_sq(&node.bounds, p) >= best.0 * best.0 {
                continue;
            }
            if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    if !keep(t as usize) {
                        continue;
                    }
                    let f = self.faces[t as usize];
                    let [a, b, c] = f.map(|i| self.positions[i as usize]);
                    // A "triangle" whose last two corners agree is a segment (polyline queries).
                    let q = if f[1] == f[2] {
                        closest_point_on_segment(p, a, b)
                    } else {
                        closest_point_on_triangle(p, a, b, c)
                    };
                    let d = p.distance(q);
                    if d < best.0 {
                        best = (d, q, t as usize);
                    }
                }
            } else {
                // Visit the nearer child first.
                let [l, r] = node.children;
                let (dl, dr) = (
                    box_distance_sq(&self.nodes[l as usize].bounds, p),
                    box_distance_sq(&self.nodes[r as usize].bounds, p),
                );
                if dl <= dr {
                    stack.push(r);
                    stack.push(l);
                } else {
                    stack.push(l);
                    stack.push(r);
                }
            }
        }
        best
    }

    /// Distance from `p` to the mesh and the closest point.
    pub fn closest(&self, p: DVec3) -> (f64, DVec3) {
        let (d, q, _) = self.closest_face(p);
        (d, q)
    }
}
