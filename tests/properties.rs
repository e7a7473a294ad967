//! quickcheck properties of building and circulating.
//!
//! Soups are valid by construction: faces of random shapes (or random
//! subsets of them), bowtie fans, several pieces side by side, then vertices
//! renumbered, faces reordered, every face started at a random corner and a
//! few unused vertices added. Everything checked against the soup is counted
//! here, independently of the library.

use std::collections::{HashMap, HashSet};

use meshloom::shapes::{self, GridFaces};
use meshloom::traverse::Bfs;
use meshloom::{Error, Mesh, Polygons, VertexKey};
use quickcheck::{Arbitrary, Gen, QuickCheck, TestResult};

const TESTS: u64 = 300;

fn between(g: &mut Gen, lo: usize, hi: usize) -> usize {
    lo + usize::arbitrary(g) % (hi - lo + 1)
}

/// A valid polygon soup over `n` vertices.
#[derive(Clone, Debug)]
struct Soup {
    n: usize,
    faces: Vec<Vec<u32>>,
}

fn piece(g: &mut Gen) -> (Polygons, bool) {
    let grid_faces = *g.choose(&[GridFaces::Quads, GridFaces::Triangles]).unwrap();
    let p = match between(g, 0, 10) {
        0 => shapes::tetrahedron_polygons(),
        1 => shapes::cube_polygons(),
        2 => shapes::octahedron_polygons(),
        3 => shapes::icosphere_polygons(between(g, 0, 1) as u32),
        4 => shapes::uv_sphere_polygons(between(g, 3, 6), between(g, 2, 5)),
        5 => shapes::torus_polygons(between(g, 3, 6), between(g, 3, 5), 1.0, 0.25),
        6 | 7 => shapes::grid_polygons(between(g, 1, 5), between(g, 1, 5), grid_faces),
        8 => shapes::disk_polygons(between(g, 3, 9)),
        _ => return (bowtie(g), true),
    };
    (p, false)
}

/// Open triangle fans meeting at vertex 0 only.
fn bowtie(g: &mut Gen) -> Polygons {
    let mut p = Polygons {
        positions: vec![[0.0; 3]],
        offsets: vec![0],
        indices: vec![],
    };
    for _ in 0..between(g, 2, 4) {
        let m = between(g, 1, 4) as u32;
        let first = p.positions.len() as u32;
        p.positions.extend((0..=m).map(|_| [0.0; 3]));
        for k in 0..m {
            p.indices.extend_from_slice(&[0, first + k, first + k + 1]);
            p.offsets.push(p.indices.len() as u32);
        }
    }
    p
}

impl Arbitrary for Soup {
    fn arbitrary(g: &mut Gen) -> Soup {
        let mut faces: Vec<Vec<u32>> = Vec::new();
        let mut n = 0u32;
        for _ in 0..between(g, 1, 3) {
            let (p, is_bowtie) = piece(g);
            // Sometimes drop faces: a subset of a valid surface is valid.
            let drop = if is_bowtie {
                0
            } else {
                *g.choose(&[0, 0, 20, 50]).unwrap()
            };
            let before = faces.len();
            for f in p.faces() {
                if drop == 0 || between(g, 1, 100) > drop {
                    faces.push(f.iter().map(|&i| i + n).collect());
                }
            }
            if faces.len() == before {
                faces.push(p.face(0).unwrap_or(&[]).iter().map(|&i| i + n).collect());
            }
            n += p.positions.len() as u32;
        }
        // A few unused vertices, then renumber, reorder, rotate.
        let n = n as usize + between(g, 0, 3);
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            order.swap(i, between(g, 0, i));
        }
        for i in (1..faces.len()).rev() {
            faces.swap(i, between(g, 0, i));
        }
        for f in &mut faces {
            let r = between(g, 0, f.len() - 1);
            f.rotate_left(r);
            for i in f.iter_mut() {
                *i = order[*i as usize];
            }
        }
        Soup { n, faces }
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Soup>> {
        // Dropping faces keeps a soup valid.
        let me = self.clone();
        let k = self.faces.len();
        Box::new((0..k.min(16)).filter(move |_| k > 1).map(move |i| {
            let mut s = me.clone();
            s.faces.remove(i * k / k.min(16));
            s
        }))
    }
}

/// The list rotated to start at its smallest entry.
fn canonical(f: &[u32]) -> Vec<u32> {
    let k = (0..f.len()).min_by_key(|&i| f[i]).unwrap_or(0);
    let mut v = f.to_vec();
    v.rotate_left(k);
    v
}

/// Independent counts: referenced vertices, undirected edges, boundary
/// edges (used by one face), and boundary loops when no vertex has two
/// boundary edges leaving it.
struct Counts {
    vertices: usize,
    edges: usize,
    boundary_edges: usize,
    loops: Option<usize>,
}

fn count(soup: &Soup) -> Counts {
    let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
    let mut used = HashSet::new();
    for f in &soup.faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            used.insert(a);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let directed: HashSet<(u32, u32)> = soup
        .faces
        .iter()
        .flat_map(|f| (0..f.len()).map(move |k| (f[k], f[(k + 1) % f.len()])))
        .collect();
    // Boundary half-edges run b -> a for a face side a -> b with no twin.
    let mut hole_next: HashMap<u32, u32> = HashMap::new();
    let mut unique = true;
    for &(a, b) in &directed {
        if !directed.contains(&(b, a)) {
            unique &= hole_next.insert(b, a).is_none();
        }
    }
    let loops = unique.then(|| {
        let mut seen = HashSet::new();
        let mut loops = 0;
        for &start in hole_next.keys() {
            if seen.insert(start) {
                loops += 1;
                let mut v = hole_next[&start];
                while seen.insert(v) {
                    v = hole_next[&v];
                }
            }
        }
        loops
    });
    Counts {
        vertices: used.len(),
        edges: uses.len(),
        boundary_edges: uses.values().filter(|&&u| u == 1).count(),
        loops,
    }
}

fn build_matches_soup(soup: Soup) -> TestResult {
    let built = match Mesh::build(None, soup.n, &soup.faces) {
        Ok(b) => b,
        Err(e) => return TestResult::error(format!("valid soup refused: {e}")),
    };
    let mesh = &built.mesh;
    if let Err(e) = mesh.validate() {
        return TestResult::error(format!("built mesh invalid: {e}"));
    }
    let c = count(&soup);
    assert_eq!(mesh.vertex_count(), c.vertices);
    assert_eq!(mesh.edge_count(), c.edges);
    assert_eq!(mesh.face_count(), soup.faces.len());
    assert_eq!(built.unreferenced, soup.n - c.vertices);
    assert_eq!(
        mesh.euler_characteristic(),
        c.vertices as i64 - c.edges as i64 + soup.faces.len() as i64
    );
    let boundary = mesh
        .edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .count();
    assert_eq!(boundary, c.boundary_edges);
    let hole_sides: usize = mesh.holes().map(|h| mesh.face(h).unwrap().degree()).sum();
    assert_eq!(hole_sides, c.boundary_edges);
    if let Some(loops) = c.loops {
        assert_eq!(mesh.hole_count(), loops);
    }

    // to_polygons gives back every input face, up to rotation.
    let input_of: HashMap<VertexKey, u32> = built
        .vertices
        .iter()
        .enumerate()
        .filter_map(|(i, k)| k.map(|k| (k, i as u32)))
        .collect();
    let (poly, maps) = mesh.to_polygons();
    assert_eq!(poly.face_count(), soup.faces.len());
    for (i, f) in soup.faces.iter().enumerate() {
        let j = maps
            .face_index(built.faces[i])
            .expect("every face exported");
        let back: Vec<u32> = poly
            .face(j)
            .expect("face j exists")
            .iter()
            .map(|&k| input_of[&maps.vertices[k as usize]])
            .collect();
        assert_eq!(canonical(&back), canonical(f), "face {i}");
    }
    // Building the exported buffers again gives the same buffers.
    let again = Mesh::from_buffers(&poly).unwrap();
    assert_eq!(again.to_polygons().0, poly);

    // Vertex neighbourhoods agree with the soup's edges.
    let mut adjacent: HashMap<u32, HashSet<u32>> = HashMap::new();
    for f in &soup.faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            adjacent.entry(a).or_default().insert(b);
            adjacent.entry(b).or_default().insert(a);
        }
    }
    for v in mesh.vertices() {
        let around: HashSet<u32> = mesh
            .vertex(v)
            .unwrap()
            .neighbors()
            .map(|w| input_of[&w])
            .collect();
        assert_eq!(around, adjacent[&input_of[&v]]);
    }
    check_circulators(mesh);
    TestResult::passed()
}

/// Every circulator visits each element once, and the views agree.
fn check_circulators(mesh: &Mesh) {
    let e2 = 2 * mesh.edge_count();
    let mut in_ring: HashMap<_, usize> = HashMap::new();
    let mut degrees = 0;
    for v in mesh.vertices() {
        let vv = mesh.vertex(v).unwrap();
        let out: Vec<_> = vv.outgoing().collect();
        let inc: Vec<_> = vv.incoming().collect();
        let nbr: Vec<_> = vv.neighbors().collect();
        let edges: Vec<_> = vv.edges().collect();
        assert_eq!(out.len(), vv.degree());
        assert_eq!(out.iter().collect::<HashSet<_>>().len(), out.len());
        assert_eq!(nbr.iter().collect::<HashSet<_>>().len(), nbr.len());
        let mut faces = Vec::new();
        for (i, &h) in out.iter().enumerate() {
            let hv = mesh.halfedge(h).unwrap();
            assert_eq!(hv.origin().key(), v);
            assert_eq!(inc[i], hv.twin().key());
            assert_eq!(nbr[i], hv.dest().key());
            assert_eq!(edges[i], h.edge_key());
            if !hv.face().is_hole() {
                faces.push(hv.face().key());
            }
            // Clockwise order: the next outgoing is twin(h).next.
            assert_eq!(out[(i + 1) % out.len()], hv.rotate_cw().key());
            *in_ring.entry(h).or_default() += 1;
        }
        assert_eq!(vv.faces().collect::<Vec<_>>(), faces);
        assert_eq!(
            vv.is_boundary(),
            out.iter().any(|&h| mesh.halfedge(h).unwrap().is_boundary())
        );
        assert_eq!(vv.halfedge().key(), out[0]);
        degrees += out.len();
    }
    assert_eq!(degrees, e2);
    assert_eq!(in_ring.len(), e2);

    let mut in_loop: HashMap<_, usize> = HashMap::new();
    let mut sides = 0;
    for f in mesh.faces_and_holes() {
        let fv = mesh.face(f).unwrap();
        let hs: Vec<_> = fv.halfedges().collect();
        let vs: Vec<_> = fv.vertices().collect();
        let es: Vec<_> = fv.edges().collect();
        assert_eq!(hs.len(), fv.degree());
        assert_eq!(hs[0], fv.halfedge().key());
        let mut across = Vec::new();
        for (i, &h) in hs.iter().enumerate() {
            let hv = mesh.halfedge(h).unwrap();
            assert_eq!(hv.face().key(), f);
            assert_eq!(vs[i], hv.origin().key());
            assert_eq!(es[i], h.edge_key());
            assert_eq!(hv.next().key(), hs[(i + 1) % hs.len()]);
            if !hv.twin().face().is_hole() {
                across.push(hv.twin().face().key());
            }
            *in_loop.entry(h).or_default() += 1;
        }
        assert_eq!(fv.neighbors().collect::<Vec<_>>(), across);
        if !fv.is_hole() {
            assert!(hs.len() >= 3);
            assert_eq!(vs.iter().collect::<HashSet<_>>().len(), vs.len());
        }
        sides += hs.len();
    }
    assert_eq!(sides, e2);
    assert_eq!(in_loop.len(), e2);
    assert!(in_loop.values().chain(in_ring.values()).all(|&n| n == 1));

    let mut all = 0;
    for h in mesh.halfedges() {
        let hv = mesh.halfedge(h).unwrap();
        assert_eq!(hv.next().prev().key(), h);
        assert_eq!(hv.prev().next().key(), h);
        assert_eq!(hv.twin().twin().key(), h);
        assert_eq!(hv.rotate_cw().rotate_ccw().key(), h);
        assert_eq!(hv.next().origin().key(), hv.dest().key());
        assert_eq!(
            mesh.find_halfedge(hv.origin().key(), hv.dest().key())
                .unwrap(),
            Some(h)
        );
        assert_eq!(in_ring.get(&h), Some(&1));
        all += 1;
    }
    assert_eq!(all, e2);
    for e in mesh.edges() {
        let ev = mesh.edge(e).unwrap();
        let (h0, h1) = (ev.halfedge(0), ev.halfedge(1));
        assert_eq!(h0.twin().key(), h1.key());
        assert_eq!(ev.vertices(), [h0.origin().key(), h1.origin().key()]);
        assert!(ev.faces().iter().any(Option::is_some), "dangling edge");
        assert_eq!(ev.is_boundary(), ev.faces().iter().any(Option::is_none));
    }
}

#[test]
fn soups_build_validate_and_round_trip() {
    QuickCheck::new()
        .tests(TESTS)
        .quickcheck(build_matches_soup as fn(Soup) -> TestResult);
}

#[test]
fn buffers_and_face_lists_build_the_same_mesh() {
    fn prop(soup: Soup) -> bool {
        let mut p = Polygons {
            positions: vec![],
            offsets: vec![0],
            indices: vec![],
        };
        for f in &soup.faces {
            p.indices.extend_from_slice(f);
            p.offsets.push(p.indices.len() as u32);
        }
        let a = Mesh::from_buffers(&p).unwrap();
        let b = Mesh::from_faces(soup.n, &soup.faces).unwrap();
        a.to_polygons().0 == b.to_polygons().0
    }
    QuickCheck::new()
        .tests(TESTS / 2)
        .quickcheck(prop as fn(Soup) -> bool);
}

#[test]
fn bowtie_soups_build_with_one_ring_per_vertex() {
    fn prop(fans: Vec<u8>) -> TestResult {
        let fans: Vec<u32> = fans.iter().take(5).map(|&m| 1 + u32::from(m % 4)).collect();
        if fans.len() < 2 {
            return TestResult::discard();
        }
        let mut faces = Vec::new();
        let mut next = 1u32;
        for &m in &fans {
            for k in 0..m {
                faces.push([0, next + k, next + k + 1]);
            }
            next += m + 1;
        }
        let mesh = Mesh::from_faces(next as usize, &faces).unwrap();
        mesh.validate().unwrap();
        let centre = mesh.vertices().next().unwrap();
        let cv = mesh.vertex(centre).unwrap();
        let total: u32 = fans.iter().sum();
        assert_eq!(cv.degree() as u32, total + fans.len() as u32);
        assert_eq!(cv.faces().count() as u32, total);
        assert!(cv.is_boundary());
        // All the fans' boundaries pass the centre: one hole through it.
        assert_eq!(mesh.hole_count(), 1);
        let hole = mesh.holes().next().unwrap();
        let through = mesh
            .face(hole)
            .unwrap()
            .vertices()
            .filter(|&v| v == centre)
            .count();
        assert_eq!(through, fans.len());
        check_circulators(&mesh);
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(TESTS)
        .quickcheck(prop as fn(Vec<u8>) -> TestResult);
}

/// Random face lists, mostly invalid: the builder answers with a typed
/// error or a valid mesh whose counts match the input, and never panics.
#[test]
fn arbitrary_face_lists_never_panic() {
    fn prop(n: u8, raw: Vec<Vec<u8>>) -> bool {
        let n = usize::from(n % 12) + 1;
        let faces: Vec<Vec<i32>> = raw
            .iter()
            .take(12)
            .map(|f| f.iter().take(6).map(|&i| i32::from(i % 14) - 1).collect())
            .collect();
        match Mesh::from_faces(n, &faces) {
            Ok(mesh) => {
                mesh.validate().unwrap();
                let soup = Soup {
                    n,
                    faces: faces
                        .iter()
                        .map(|f| f.iter().map(|&i| i as u32).collect())
                        .collect(),
                };
                let c = count(&soup);
                check_circulators(&mesh);
                mesh.vertex_count() == c.vertices
                    && mesh.edge_count() == c.edges
                    && mesh.face_count() == faces.len()
            }
            Err(Error::Build(_)) => true,
            Err(e) => panic!("unexpected error kind {e:?}"),
        }
    }
    QuickCheck::new()
        .tests(2000)
        .quickcheck(prop as fn(u8, Vec<Vec<u8>>) -> bool);
}

/// Pairs of triangles on few vertices: most such soups are valid, so this
/// reaches the builder's harder cases (bowties, closed fans, pinches).
#[test]
fn dense_small_soups_build_or_refuse_cleanly() {
    fn prop(raw: Vec<(u8, u8, u8)>) -> bool {
        let mut faces: Vec<[u32; 3]> = raw
            .iter()
            .take(6)
            .map(|&(a, b, c)| {
                // Three distinct corners out of seven.
                let a = u32::from(a % 7);
                let b = (a + 1 + u32::from(b % 6)) % 7;
                let rest: Vec<u32> = (0..7).filter(|&v| v != a && v != b).collect();
                [a, b, rest[usize::from(c % 5)]]
            })
            .collect();
        // Turn a triangle over if it repeats a side's direction, so most
        // soups are orientable and the builder's later stages are reached.
        let mut directed = HashSet::new();
        for f in &mut faces {
            if (0..3).any(|k| directed.contains(&(f[k], f[(k + 1) % 3]))) {
                f.swap(1, 2);
            }
            directed.extend((0..3).map(|k| (f[k], f[(k + 1) % 3])));
        }
        match Mesh::from_faces(7, &faces) {
            Ok(mesh) => {
                mesh.validate().unwrap();
                check_circulators(&mesh);
                let soup = Soup {
                    n: 7,
                    faces: faces.iter().map(|f| f.to_vec()).collect(),
                };
                let c = count(&soup);
                mesh.edge_count() == c.edges && mesh.vertex_count() == c.vertices
            }
            Err(Error::Build(_)) => true,
            Err(e) => panic!("unexpected error kind {e:?}"),
        }
    }
    QuickCheck::new()
        .tests(3000)
        .quickcheck(prop as fn(Vec<(u8, u8, u8)>) -> bool);
}

/// Walks, components and unit-cost paths agree with a breadth-first search
/// and a component count done here on the soup's own edges.
#[test]
fn traversals_match_an_independent_search() {
    fn prop(soup: Soup) -> bool {
        let built = Mesh::build(None, soup.n, &soup.faces).unwrap();
        let mesh = &built.mesh;
        let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); soup.n];
        for f in &soup.faces {
            for k in 0..f.len() {
                let (a, b) = (f[k] as usize, f[(k + 1) % f.len()] as usize);
                adjacent[a].push(b);
                adjacent[b].push(a);
            }
        }
        let distances = |s: usize| {
            let mut d = vec![usize::MAX; soup.n];
            d[s] = 0;
            let mut queue = std::collections::VecDeque::from([s]);
            while let Some(u) = queue.pop_front() {
                for &w in &adjacent[u] {
                    if d[w] == usize::MAX {
                        d[w] = d[u] + 1;
                        queue.push_back(w);
                    }
                }
            }
            d
        };
        let used: Vec<usize> = (0..soup.n).filter(|&i| !adjacent[i].is_empty()).collect();
        // Components: label by repeated searches.
        let mut label = vec![usize::MAX; soup.n];
        let mut pieces = 0;
        for &i in &used {
            if label[i] == usize::MAX {
                for (j, &d) in distances(i).iter().enumerate() {
                    if d != usize::MAX {
                        label[j] = pieces;
                    }
                }
                pieces += 1;
            }
        }
        let parts = mesh.components();
        let mut ok = parts.count() == pieces;
        for &a in used.iter().take(3) {
            let d = distances(a);
            let key = |i: usize| built.vertices[i].unwrap();
            let mut bfs = Bfs::new(mesh, key(a)).unwrap();
            let mut visited = 0;
            let mut last = 0;
            while let Some((v, depth)) = bfs.next_with_depth(mesh) {
                let i = built.vertices.iter().position(|&k| k == Some(v)).unwrap();
                ok &= d[i] == depth && depth >= last;
                last = depth;
                visited += 1;
            }
            ok &= visited == used.iter().filter(|&&i| d[i] != usize::MAX).count();
            for &b in used.iter().step_by(5) {
                let path = mesh.shortest_path(key(a), key(b), |_| 1.0).unwrap();
                ok &= match path {
                    Some(p) => p.cost == d[b] as f64 && p.halfedges.len() == d[b],
                    None => d[b] == usize::MAX,
                };
                ok &=
                    (parts.of_vertex(key(a)) == parts.of_vertex(key(b))) == (label[a] == label[b]);
            }
        }
        ok
    }
    QuickCheck::new()
        .tests(TESTS)
        .quickcheck(prop as fn(Soup) -> bool);
}

#[cfg(feature = "quickcheck")]
mod arbitrary_meshes {
    use super::*;
    use meshloom::arbitrary::ArbitraryMesh;

    #[test]
    fn arbitrary_meshes_are_valid_and_circulate() {
        fn prop(m: ArbitraryMesh) -> bool {
            let mesh = &m.0;
            mesh.validate().unwrap();
            check_circulators(mesh);
            let (poly, _) = mesh.to_polygons();
            let again = Mesh::from_buffers(&poly).unwrap();
            again.to_polygons().0 == poly
                && again.euler_characteristic() == mesh.euler_characteristic()
                && again.hole_count() == mesh.hole_count()
                && mesh.has_positions()
        }
        QuickCheck::new()
            .tests(TESTS)
            .quickcheck(prop as fn(ArbitraryMesh) -> bool);
    }

    #[test]
    fn components_and_walks_cover_arbitrary_meshes() {
        fn prop(m: ArbitraryMesh) -> bool {
            let mesh = &m.0;
            let parts = mesh.components();
            let total: usize = parts.vertex_counts().iter().sum();
            let mut ok = total == mesh.vertex_count();
            for v in mesh.vertices().take(3) {
                let walked = mesh.bfs_vertices(v).unwrap().count();
                ok &= walked == parts.vertex_counts()[parts.of_vertex(v).unwrap()];
                ok &= mesh.dfs_vertices(v).unwrap().count() == walked;
                // Every vertex of the component is reachable at finite cost.
                for w in parts.vertices(parts.of_vertex(v).unwrap()).take(5) {
                    ok &= mesh.shortest_path(v, w, |_| 1.0).unwrap().is_some();
                }
            }
            ok
        }
        QuickCheck::new()
            .tests(TESTS)
            .quickcheck(prop as fn(ArbitraryMesh) -> bool);
    }
}

#[test]
fn soup_loop_counter_counts_loops() {
    // The independent loop count itself, on known cases.
    let square = Soup {
        n: 4,
        faces: vec![vec![0, 1, 2, 3]],
    };
    assert_eq!(count(&square).loops, Some(1));
    let annulus: Vec<Vec<u32>> = (0..4u32)
        .map(|k| vec![k, (k + 1) % 4, 4 + (k + 1) % 4, 4 + k])
        .collect();
    let ring = Soup {
        n: 8,
        faces: annulus,
    };
    assert_eq!(count(&ring).loops, Some(2));
    assert_eq!(Mesh::from_faces(8, &ring.faces).unwrap().hole_count(), 2);
}
