//! Triangle meshes for granular walls (`fix mesh/surface`): vertices merged from a
//! triangle soup (an STL file), degenerate triangles found, and the topology that lets a
//! sphere touching a shared edge or corner feel one contact — each edge knows its
//! triangles, each triangle its edges — and the closest point of a triangle to a point,
//! with the feature (face, edge or corner) it lies on.

use glam::DVec3;

use crate::error::{Error, Result};

/// Where on a triangle a closest point lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Feature {
    /// Inside triangle `t`.
    Face(u32),
    /// On edge `e` (between its corners).
    Edge(u32),
    /// At vertex `v`.
    Vertex(u32),
}

/// A triangle mesh with merged vertices and edge topology.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub verts: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise about [`TriMesh::normals`].
    pub tris: Vec<[u32; 3]>,
    /// Unit normal of each triangle (right-hand rule on its corners).
    pub normals: Vec<DVec3>,
    /// Edges as vertex pairs (lower index first), each once.
    pub edges: Vec<[u32; 2]>,
    /// The edges of each triangle: edge `k` joins corners `k` and `(k + 1) % 3`.
    pub tri_edges: Vec<[u32; 3]>,
    /// Triangles of each edge: `edge_tris[edge_first[e]..edge_first[e + 1]]`.
    pub edge_tris: Vec<u32>,
    /// Offsets into `edge_tris`, one per edge plus one.
    pub edge_first: Vec<u32>,
    /// The distance within which corners merge (`fix mesh/surface ... precision`, 1e-8
    /// by default); LIGGGHTS also widens each face by it for contacts (see
    /// `wall::mesh`).
    pub precision: f64,
}

/// What [`TriMesh::from_triangles`] found and did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshReport {
    /// Triangles read.
    pub read: usize,
    /// Vertices after merging.
    pub vertices: usize,
    /// Degenerate triangles (zero area, or two corners merged), by index in the input.
    pub degenerate: Vec<usize>,
    /// Triangles dropped as duplicates of an earlier one (same three vertices).
    pub duplicates: Vec<usize>,
    /// Edges shared by more than two triangles.
    pub non_manifold_edges: usize,
}

impl TriMesh {
    /// Builds a mesh from a triangle soup: corners closer than `merge_tol` become one
    /// vertex. Degenerate triangles are an error unless `drop_bad` (LIGGGHTS' `heal
    /// auto_remove_duplicates`), which drops them and duplicated triangles; the report
    /// lists what was found either way.
    pub fn from_triangles(
        soup: &[[DVec3; 3]],
        merge_tol: f64,
        drop_bad: bool,
    ) -> Result<(Self, MeshReport)> {
        let mut report = MeshReport {
            read: soup.len(),
            ..Default::default()
        };
        if soup.is_empty() {
            return Err(Error::Invalid {
                what: "mesh",
                reason: "has no triangles".into(),
            });
        }
        for (k, t) in soup.iter().enumerate() {
            if !t.iter().all(|p| p.is_finite()) {
                return Err(Error::Invalid {
                    what: "mesh",
                    reason: format!(
                        "triangle {} has a corner that is not a finite number",
                        k + 1
                    ),
                });
            }
        }
        // Merge corners: sort them along x, then compare within the tolerance.
        let corners: Vec<DVec3> = soup.iter().flatten().copied().collect();
        let mut order: Vec<u32> = (0..corners.len() as u32).collect();
        order.sort_by(|&a, &b| corners[a as usize].x.total_cmp(&corners[b as usize].x));
        let mut vid = vec![u32::MAX; corners.len()];
        let mut verts: Vec<DVec3> = Vec::new();
        let tol2 = merge_tol * merge_tol;
        for (s, &c) in order.iter().enumerate() {
            if vid[c as usize] != u32::MAX {
                continue;
            }
            let p = corners[c as usize];
            let id = verts.len() as u32;
            verts.push(p);
            vid[c as usize] = id;
            for &o in &order[s + 1..] {
                let q = corners[o as usize];
                if q.x - p.x > merge_tol {
                    break;
                }
                if vid[o as usize] == u32::MAX && (q - p).length_squared() <= tol2 {
                    vid[o as usize] = id;
                }
            }
        }
        // Number the vertices in order of first use, so the mesh does not depend on the
        // sort.
        let mut renum = vec![u32::MAX; verts.len()];
        let mut used = Vec::with_capacity(verts.len());
        for &v in &vid {
            if renum[v as usize] == u32::MAX {
                renum[v as usize] = used.len() as u32;
                used.push(verts[v as usize]);
            }
        }
        let mut tris = Vec::with_capacity(soup.len());
        let mut normals = Vec::with_capacity(soup.len());
        let mut seen = std::collections::HashSet::new();
        let scale = bbox_diagonal(&used).max(f64::MIN_POSITIVE);
        for (k, t) in soup.iter().enumerate() {
            let ids = [0, 1, 2].map(|c| renum[vid[3 * k + c] as usize]);
            let cross = (t[1] - t[0]).cross(t[2] - t[0]);
            let degenerate = ids[0] == ids[1]
                || ids[1] == ids[2]
                || ids[0] == ids[2]
                || cross.length() <= 1e-12 * scale * scale;
            if degenerate {
                report.degenerate.push(k);
                continue;
            }
            let mut key = ids;
            key.sort_unstable();
            if !seen.insert(key) {
                report.duplicates.push(k);
                continue;
            }
            tris.push(ids);
            normals.push(cross.normalize());
        }
        if !drop_bad && !report.degenerate.is_empty() {
            let list: Vec<String> = report
                .degenerate
                .iter()
                .take(5)
                .map(|k| (k + 1).to_string())
                .collect();
            return Err(Error::Invalid {
                what: "mesh",
                reason: format!(
                    "{} degenerate triangle(s) (zero area or two corners closer than the merge tolerance), e.g. number {}; 'heal auto_remove_duplicates' drops them",
                    report.degenerate.len(),
                    list.join(", ")
                ),
            });
        }
        if !drop_bad && !report.duplicates.is_empty() {
            return Err(Error::Invalid {
                what: "mesh",
                reason: format!(
                    "{} triangle(s) repeat an earlier one (e.g. number {}); 'heal auto_remove_duplicates' drops them",
                    report.duplicates.len(),
                    report.duplicates[0] + 1
                ),
            });
        }
        if tris.is_empty() {
            return Err(Error::Invalid {
                what: "mesh",
                reason: "has no triangle left after dropping the degenerate ones".into(),
            });
        }
        // Drop vertices no triangle uses any more.
        let mut keep = vec![u32::MAX; used.len()];
        let mut verts = Vec::with_capacity(used.len());
        for t in &mut tris {
            for v in t.iter_mut() {
                if keep[*v as usize] == u32::MAX {
                    keep[*v as usize] = verts.len() as u32;
                    verts.push(used[*v as usize]);
                }
                *v = keep[*v as usize];
            }
        }
        report.vertices = verts.len();
        let mut mesh = TriMesh {
            verts,
            tris,
            normals,
            precision: merge_tol,
            ..Default::default()
        };
        mesh.build_edges();
        report.non_manifold_edges = (0..mesh.edges.len())
            .filter(|&e| mesh.edge_first[e + 1] - mesh.edge_first[e] > 2)
            .count();
        Ok((mesh, report))
    }

    /// Fills the edge tables from the triangles.
    fn build_edges(&mut self) {
        let mut all: Vec<([u32; 2], u32, u8)> = Vec::with_capacity(3 * self.tris.len());
        for (t, tri) in self.tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                all.push(([a.min(b), a.max(b)], t as u32, k as u8));
            }
        }
        all.sort_unstable();
        self.edges.clear();
        self.edge_tris.clear();
        self.edge_first.clear();
        self.tri_edges = vec![[0; 3]; self.tris.len()];
        for (key, t, k) in all {
            if self.edges.last() != Some(&key) {
                self.edges.push(key);
                self.edge_first.push(self.edge_tris.len() as u32);
            }
            self.edge_tris.push(t);
            self.tri_edges[t as usize][k as usize] = self.edges.len() as u32 - 1;
        }
        self.edge_first.push(self.edge_tris.len() as u32);
    }

    /// The triangles that share edge `e`.
    pub fn triangles_of_edge(&self, e: u32) -> &[u32] {
        let e = e as usize;
        &self.edge_tris[self.edge_first[e] as usize..self.edge_first[e + 1] as usize]
    }

    /// Per triangle, how many triangles share an edge with it (an edge shared by `k`
    /// triangles counts `k − 1` for each): LIGGGHTS' `nneighs`.
    pub fn neighbour_counts(&self) -> Vec<u32> {
        self.tri_edges
            .iter()
            .map(|es| {
                es.iter()
                    .map(|&e| self.triangles_of_edge(e).len() as u32 - 1)
                    .sum()
            })
            .collect()
    }

    /// Per triangle, its active edges as LIGGGHTS 3.8 counts them (`dump mesh/vtk
    /// aedges`): each active edge ([`TriMesh::edge_is_active`]) counts once, for the
    /// last of its triangles. Measured on LIGGGHTS 3.8: a flat square 2 2, a ridge or a
    /// valley 2 3, a tetrahedron 0 1 2 3, a flat fan 1 each, and every triangle of the
    /// tutorials' meshes (1616 of the chute).
    pub fn active_edge_counts(&self, coplanar_cos: f64) -> Vec<u32> {
        let mut count = vec![0; self.tris.len()];
        for e in 0..self.edges.len() as u32 {
            if self.edge_is_active(e, coplanar_cos) {
                let last = *self.triangles_of_edge(e).iter().max().expect("a triangle");
                count[last as usize] += 1;
            }
        }
        count
    }

    /// Whether edge `e` is active as LIGGGHTS 3.8 counts it: an edge of one triangle
    /// is; an edge whose triangles all lie within the angle of `coplanar_cos` of the
    /// first is not (one flat surface); any other shared edge is.
    pub fn edge_is_active(&self, e: u32, coplanar_cos: f64) -> bool {
        let ts = self.triangles_of_edge(e);
        let n0 = self.normals[ts[0] as usize];
        let flat = ts.len() > 1
            && ts[1..]
                .iter()
                .all(|&t| n0.dot(self.normals[t as usize]).abs() >= coplanar_cos);
        !flat
    }

    /// Per triangle, its active corners as LIGGGHTS 3.8 counts them (`dump mesh/vtk
    /// acorners`): each active corner counts once, for the last of its triangles. A
    /// corner is active when an active edge ([`TriMesh::edge_is_active`]) meets there
    /// and none of them runs on in a straight line, within the angle of `coplanar_cos`,
    /// into another edge that meets there (active or not): inside a flat surface, on a
    /// straight boundary or on a straight crease it is not. Measured on LIGGGHTS 3.8:
    /// a square 1 3, a tetrahedron 0 0 1 3, a flat fan 0 1 1 1 1 2, a 2 × 2 grid flat
    /// and folded along its middle, a boundary kinked by 0.25° (straight) and 0.26° (a
    /// corner), a cube, an open box, and every triangle of the tutorials' meshGran
    /// hopper (92) and chute_wear chute (1616).
    pub fn active_corner_counts(&self, coplanar_cos: f64) -> Vec<u32> {
        let mut count = vec![0; self.tris.len()];
        for t in self.corner_owners(coplanar_cos).into_iter().flatten() {
            count[t as usize] += 1;
        }
        count
    }

    /// The triangle that holds each active edge ([`TriMesh::edge_is_active`]) in
    /// LIGGGHTS 3.8, the last of its triangles, or `None` for an inactive edge: a sphere
    /// whose nearest point on a triangle lies on an edge touches that edge only through
    /// its holder.
    pub fn edge_owners(&self, coplanar_cos: f64) -> Vec<Option<u32>> {
        (0..self.edges.len() as u32)
            .map(|e| {
                self.edge_is_active(e, coplanar_cos)
                    .then(|| *self.triangles_of_edge(e).iter().max().expect("a triangle"))
            })
            .collect()
    }

    /// The triangle that holds each active corner (see
    /// [`TriMesh::active_corner_counts`]) in LIGGGHTS 3.8, the last of its triangles, or
    /// `None` for an inactive corner (or a vertex of no triangle).
    pub fn corner_owners(&self, coplanar_cos: f64) -> Vec<Option<u32>> {
        let nv = self.verts.len();
        // The edges at each vertex: (unit direction away from it, active).
        let mut at: Vec<Vec<(DVec3, bool)>> = vec![Vec::new(); nv];
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            let active = self.edge_is_active(e as u32, coplanar_cos);
            let d = (self.verts[b as usize] - self.verts[a as usize]).normalize();
            at[a as usize].push((d, active));
            at[b as usize].push((-d, active));
        }
        let mut last = vec![None::<usize>; nv];
        for (t, tri) in self.tris.iter().enumerate() {
            for &v in tri {
                last[v as usize] = Some(t);
            }
        }
        at.iter()
            .enumerate()
            .map(|(v, edges)| {
                let straight_on = |(i, &(d, _)): (usize, &(DVec3, bool))| {
                    edges
                        .iter()
                        .enumerate()
                        .any(|(j, &(d2, _))| j != i && -d.dot(d2) >= coplanar_cos)
                };
                let mut active = edges.iter().enumerate().filter(|(_, &(_, a))| a);
                let corner = active.clone().next().is_some() && !active.any(straight_on);
                last[v].filter(|_| corner).map(|t| t as u32)
            })
            .collect()
    }

    /// The corners of triangle `t`.
    #[inline]
    pub fn corners(&self, t: u32) -> [DVec3; 3] {
        self.tris[t as usize].map(|v| self.verts[v as usize])
    }

    /// Applies `f` to every vertex and recomputes the normals (scale, move, rotate).
    pub fn transform(&mut self, f: impl Fn(DVec3) -> DVec3) {
        for v in &mut self.verts {
            *v = f(*v);
        }
        for (t, n) in self.normals.iter_mut().enumerate() {
            let [a, b, c] = self.tris[t].map(|v| self.verts[v as usize]);
            *n = (b - a).cross(c - a).normalize();
        }
    }

    /// The closest point of triangle `t` to `p`, and the feature it lies on.
    #[inline]
    pub fn closest_point(&self, t: u32, p: DVec3) -> (DVec3, Feature) {
        let tri = self.tris[t as usize];
        let [a, b, c] = tri.map(|v| self.verts[v as usize]);
        let e = self.tri_edges[t as usize];
        // Voronoi regions of the triangle (Ericson, Real-Time Collision Detection 5.1.5).
        let ab = b - a;
        let ac = c - a;
        let ap = p - a;
        let d1 = ab.dot(ap);
        let d2 = ac.dot(ap);
        if d1 <= 0.0 && d2 <= 0.0 {
            return (a, Feature::Vertex(tri[0]));
        }
        let bp = p - b;
        let d3 = ab.dot(bp);
        let d4 = ac.dot(bp);
        if d3 >= 0.0 && d4 <= d3 {
            return (b, Feature::Vertex(tri[1]));
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            let v = d1 / (d1 - d3);
            return (a + v * ab, Feature::Edge(e[0]));
        }
        let cp = p - c;
        let d5 = ab.dot(cp);
        let d6 = ac.dot(cp);
        if d6 >= 0.0 && d5 <= d6 {
            return (c, Feature::Vertex(tri[2]));
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            let w = d2 / (d2 - d6);
            return (a + w * ac, Feature::Edge(e[2]));
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            return (b + w * (c - b), Feature::Edge(e[1]));
        }
        // Inside the face: the projection onto the plane.
        let n = self.normals[t as usize];
        (p - (p - a).dot(n) * n, Feature::Face(t))
    }

    /// Smallest and largest corner of the whole mesh.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.verts.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &v| (lo.min(v), hi.max(v)),
        )
    }
}

fn bbox_diagonal(v: &[DVec3]) -> f64 {
    let (lo, hi) = v.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if v.is_empty() {
        0.0
    } else {
        (hi - lo).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Active edges and neighbour counts of small meshes, as LIGGGHTS 3.8 wrote them
    /// (`dump mesh/vtk aedges nneighs`, curvature at its default).
    #[test]
    fn active_edges_and_neighbours_as_liggghts() {
        let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let mesh = |soup: &[[DVec3; 3]]| TriMesh::from_triangles(soup, 1e-8, false).unwrap().0;
        let cos = 1.0 - 1e-5;
        let square = mesh(&[
            [v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.)],
            [v(0., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)],
        ]);
        assert_eq!(square.active_edge_counts(cos), [2, 2]);
        assert_eq!(square.neighbour_counts(), [1, 1]);
        for z in [0.5, -0.5, 0.0175] {
            // A ridge, a valley, and a 1° bend: the shared edge counts for the second.
            let ridge = mesh(&[
                [v(0., 0., 0.), v(1., 0., 0.), v(0.5, 1., z)],
                [v(1., 0., 0.), v(0., 0., 0.), v(0.5, -1., z)],
            ]);
            assert_eq!(ridge.active_edge_counts(cos), [2, 3], "z = {z}");
        }
        // A 0.1° bend is flat.
        let bend = mesh(&[
            [v(0., 0., 0.), v(1., 0., 0.), v(0.5, 1., 0.00175)],
            [v(1., 0., 0.), v(0., 0., 0.), v(0.5, -1., 0.00175)],
        ]);
        assert_eq!(bend.active_edge_counts(cos), [2, 2]);
        let tet = mesh(&[
            [v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)],
            [v(0., 0., 0.), v(0., 0., 1.), v(1., 0., 0.)],
            [v(0., 0., 0.), v(0., 1., 0.), v(0., 0., 1.)],
            [v(1., 0., 0.), v(0., 0., 1.), v(0., 1., 0.)],
        ]);
        assert_eq!(tet.active_edge_counts(cos), [0, 1, 2, 3]);
        assert_eq!(tet.neighbour_counts(), [3, 3, 3, 3]);
        let one = mesh(&[[v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)]]);
        assert_eq!(one.active_edge_counts(cos), [3]);
        assert_eq!(one.neighbour_counts(), [0]);
        // A flat fan of six about the origin: only the rim.
        let p = |k: usize| {
            let a = std::f64::consts::TAU * k as f64 / 6.0;
            v(a.cos(), a.sin(), 0.0)
        };
        let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [v(0., 0., 0.), p(k), p(k + 1)]).collect();
        let fan = mesh(&fan);
        assert_eq!(fan.active_edge_counts(cos), [1; 6]);
        assert_eq!(fan.neighbour_counts(), [2; 6]);
        // Raised 1 cm at the centre (0.57°): the spokes count, each for the later one.
        let cone: Vec<[DVec3; 3]> = (0..6).map(|k| [v(0., 0., 0.01), p(k), p(k + 1)]).collect();
        assert_eq!(mesh(&cone).active_edge_counts(cos), [1, 2, 2, 2, 2, 3]);
    }

    /// Active corners of small meshes, as LIGGGHTS 3.8 wrote them (`dump mesh/vtk
    /// acorners`, curvature at its default).
    #[test]
    fn active_corners_as_liggghts() {
        let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let mesh = |soup: &[[DVec3; 3]]| TriMesh::from_triangles(soup, 1e-8, false).unwrap().0;
        let cos = 1.0 - 1e-5;
        let quad = |a, b, c, d| [[a, b, c], [a, c, d]];
        let square = mesh(&quad(
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(1., 1., 0.),
            v(0., 1., 0.),
        ));
        assert_eq!(square.active_corner_counts(cos), [1, 3]);
        for z in [0.5, -0.5] {
            let ridge = mesh(&[
                [v(0., 0., 0.), v(1., 0., 0.), v(0.5, 1., z)],
                [v(1., 0., 0.), v(0., 0., 0.), v(0.5, -1., z)],
            ]);
            assert_eq!(ridge.active_corner_counts(cos), [1, 3], "z = {z}");
        }
        let tet = mesh(&[
            [v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)],
            [v(0., 0., 0.), v(0., 0., 1.), v(1., 0., 0.)],
            [v(0., 0., 0.), v(0., 1., 0.), v(0., 0., 1.)],
            [v(1., 0., 0.), v(0., 0., 1.), v(0., 1., 0.)],
        ]);
        assert_eq!(tet.active_corner_counts(cos), [0, 0, 1, 3]);
        let one = mesh(&[[v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)]]);
        assert_eq!(one.active_corner_counts(cos), [3]);
        // A flat fan: its centre is inside a flat surface; raised, it is a corner.
        let p = |k: usize| {
            let a = std::f64::consts::TAU * k as f64 / 6.0;
            v(a.cos(), a.sin(), 0.0)
        };
        let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [v(0., 0., 0.), p(k), p(k + 1)]).collect();
        assert_eq!(mesh(&fan).active_corner_counts(cos), [0, 1, 1, 1, 1, 2]);
        let cone: Vec<[DVec3; 3]> = (0..6).map(|k| [v(0., 0., 0.01), p(k), p(k + 1)]).collect();
        assert_eq!(mesh(&cone).active_corner_counts(cos), [0, 1, 1, 1, 1, 3]);
        // A 2 × 2 grid, flat and folded along x = 1: the points halfway along its
        // straight sides and on the straight fold are not corners.
        let grid = |fold: f64| {
            let z = |x: f64| if x <= 1.0 { 0.0 } else { fold * (x - 1.0) };
            let mut g = Vec::new();
            for i in 0..2 {
                for j in 0..2 {
                    let (x, y) = (i as f64, j as f64);
                    g.extend(quad(
                        v(x, y, z(x)),
                        v(x + 1., y, z(x + 1.)),
                        v(x + 1., y + 1., z(x + 1.)),
                        v(x, y + 1., z(x)),
                    ));
                }
            }
            mesh(&g)
        };
        assert_eq!(
            grid(0.0).active_corner_counts(cos),
            [0, 1, 0, 1, 1, 0, 0, 1]
        );
        assert_eq!(
            grid(0.3).active_corner_counts(cos),
            [0, 1, 0, 1, 1, 1, 0, 2]
        );
        // A boundary kinked in its plane: straight below the curvature angle (0.256°).
        for (deg, want) in [
            (0.1, [0, 2, 2]),
            (0.25, [0, 2, 2]),
            (0.26, [0, 2, 3]),
            (1.0, [0, 2, 3]),
        ] {
            let t: f64 = f64::to_radians(deg);
            let mut soup =
                quad(v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)).to_vec();
            soup.push([v(1., 0., 0.), v(1. + t.cos(), -t.sin(), 0.), v(1., 1., 0.)]);
            assert_eq!(mesh(&soup).active_corner_counts(cos), want, "{deg}°");
        }
        // A cube and the same box without its lid.
        let c: Vec<DVec3> = (0..8)
            .map(|k| v((k / 4) as f64, (k / 2 % 2) as f64, (k % 2) as f64))
            .collect();
        let faces = [
            [0, 2, 6, 4],
            [1, 5, 7, 3],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 1, 3, 2],
            [4, 6, 7, 5],
        ];
        let boxed = |skip: usize| {
            let soup: Vec<[DVec3; 3]> = faces
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != skip)
                .flat_map(|(_, f)| quad(c[f[0]], c[f[1]], c[f[2]], c[f[3]]))
                .collect();
            mesh(&soup)
        };
        assert_eq!(
            boxed(usize::MAX).active_corner_counts(cos),
            [0, 0, 0, 0, 0, 0, 0, 0, 1, 3, 1, 3]
        );
        assert_eq!(
            boxed(1).active_corner_counts(cos),
            [0, 0, 0, 0, 0, 0, 1, 3, 1, 3]
        );
    }

    fn square() -> Vec<[DVec3; 3]> {
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        vec![
            [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
            [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        ]
    }

    /// Two triangles of a unit square share 4 vertices and one of 5 edges.
    #[test]
    fn square_topology() {
        let (m, r) = TriMesh::from_triangles(&square(), 1e-9, false).unwrap();
        assert_eq!(r.vertices, 4);
        assert_eq!(m.edges.len(), 5);
        let shared: Vec<usize> = (0..5)
            .filter(|&e| m.triangles_of_edge(e as u32).len() == 2)
            .collect();
        assert_eq!(shared.len(), 1);
        assert_eq!(m.normals[0], DVec3::Z);
        assert_eq!(r.non_manifold_edges, 0);
    }

    /// Closest points: inside the face, on an edge, at a corner.
    #[test]
    fn closest_point_features() {
        let (m, _) = TriMesh::from_triangles(&square(), 1e-9, false).unwrap();
        let (q, f) = m.closest_point(0, DVec3::new(0.7, 0.2, 0.5));
        assert_eq!(f, Feature::Face(0));
        assert!((q - DVec3::new(0.7, 0.2, 0.0)).length() < 1e-15);
        let (q, f) = m.closest_point(0, DVec3::new(0.5, -0.3, 0.5));
        assert!(matches!(f, Feature::Edge(_)));
        assert!((q - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-15);
        let (q, f) = m.closest_point(0, DVec3::new(1.5, -0.3, 0.5));
        assert!(matches!(f, Feature::Vertex(_)));
        assert!((q - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-15);
        // The diagonal: the same edge seen from both triangles.
        let (_, f0) = m.closest_point(0, DVec3::new(0.3, 0.6, 0.2));
        let (_, f1) = m.closest_point(1, DVec3::new(0.6, 0.3, 0.2));
        assert!(matches!(f0, Feature::Edge(_)));
        assert_eq!(f0, f1);
    }

    /// Corners within the tolerance merge; a degenerate triangle is an error unless
    /// dropped, and a repeated triangle too.
    #[test]
    fn merging_and_healing() {
        let mut s = square();
        s[1][0] += DVec3::splat(1e-12);
        let (m, _) = TriMesh::from_triangles(&s, 1e-9, false).unwrap();
        assert_eq!(m.verts.len(), 4);
        let mut bad = square();
        let p = DVec3::new(2.0, 2.0, 0.0);
        bad.push([p, p, DVec3::new(3.0, 2.0, 0.0)]);
        assert!(TriMesh::from_triangles(&bad, 1e-9, false).is_err());
        let (m, r) = TriMesh::from_triangles(&bad, 1e-9, true).unwrap();
        assert_eq!(r.degenerate, vec![2]);
        assert_eq!(m.tris.len(), 2);
        assert_eq!(m.verts.len(), 4);
        let mut dup = square();
        dup.push(dup[0]);
        assert!(TriMesh::from_triangles(&dup, 1e-9, false).is_err());
        let (_, r) = TriMesh::from_triangles(&dup, 1e-9, true).unwrap();
        assert_eq!(r.duplicates, vec![2]);
    }
}
