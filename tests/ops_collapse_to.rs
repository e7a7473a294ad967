//! `collapse_edge_to` and the corner (wedge) rule shared by every collapse.

use meshloom::attr::HalfedgeAttr;
use meshloom::{Error, HalfedgeKey, Mesh, VertexKey};

/// A grid of `n × n` unit squares cut into triangles, with a corner column
/// `uv` = (x, y) / n, plus 10 on u for faces right of x = `seam` (two
/// islands: a UV seam along the line x = seam).
fn seamed_grid(n: u32, seam: f64) -> (Mesh, HalfedgeAttr<[f64; 2]>) {
    let mut p = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            p.push([f64::from(x), f64::from(y), 0.0]);
        }
    }
    let mut faces = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let v = y * (n + 1) + x;
            faces.push([v, v + 1, v + n + 2]);
            faces.push([v, v + n + 2, v + n + 1]);
        }
    }
    let mut mesh = Mesh::from_polygons(&p, &faces).unwrap();
    let uv: HalfedgeAttr<[f64; 2]> = mesh.add_halfedge_attr("uv").unwrap();
    let fs: Vec<_> = mesh.faces().collect();
    for f in fs {
        let c = mesh.face_centroid(f).unwrap();
        let hs: Vec<_> = mesh.face(f).unwrap().halfedges().collect();
        for h in hs {
            let q = mesh
                .position(mesh.halfedge(h).unwrap().origin().key())
                .unwrap();
            let shift = if c[0] > seam { 10.0 } else { 0.0 };
            let value = [q[0] / f64::from(n) + shift, q[1] / f64::from(n)];
            mesh.set_attr(&uv, h, value).unwrap();
        }
    }
    (mesh, uv)
}

fn vertex_at(mesh: &Mesh, q: [f64; 2]) -> VertexKey {
    mesh.vertices()
        .find(|&v| {
            let p = mesh.position(v).unwrap();
            (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9
        })
        .unwrap()
}

fn seam_edges(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>) -> usize {
    mesh.edges()
        .filter(|&e| {
            let ev = mesh.edge(e).unwrap();
            let (h, t) = (ev.halfedge(0), ev.halfedge(1));
            if h.face().is_hole() || t.face().is_hole() {
                return false;
            }
            // Corner at origin(h) in face(h) against the corner at the same
            // vertex in face(t) (= next(t)), and the same at dest(h).
            let get = |k: HalfedgeKey| *mesh.attr(uv, k).unwrap().unwrap();
            get(h.key()) != get(t.next().key()) || get(h.next().key()) != get(t.key())
        })
        .count()
}

#[test]
fn position_is_exact_and_vertex_columns_use_the_projection() {
    let mut mesh = meshloom::shapes::icosahedron();
    let w = mesh.add_vertex_attr::<f64>("w").unwrap();
    let vs: Vec<_> = mesh.vertices().collect();
    for (i, &v) in vs.iter().enumerate() {
        mesh.set_attr(&w, v, i as f64).unwrap();
    }
    let h = mesh.halfedges().next().unwrap();
    let (a, b) = (
        mesh.halfedge(h).unwrap().origin().key(),
        mesh.halfedge(h).unwrap().dest().key(),
    );
    let (pa, pb) = (mesh.position(a).unwrap(), mesh.position(b).unwrap());
    let (wa, wb) = (
        *mesh.attr(&w, a).unwrap().unwrap(),
        *mesh.attr(&w, b).unwrap().unwrap(),
    );
    // A quarter of the way from a, then lifted off the edge along a normal.
    let d: Vec<f64> = (0..3).map(|i| pb[i] - pa[i]).collect();
    let off = [d[1], -d[0], 0.0];
    let p: [f64; 3] = std::array::from_fn(|i| pa[i] + 0.25 * d[i] + 0.3 * off[i]);
    let kept = mesh.collapse_edge_to(h, p).unwrap();
    assert_eq!(kept, b);
    assert_eq!(mesh.position(b).unwrap(), p);
    let got = *mesh.attr(&w, b).unwrap().unwrap();
    assert!((got - (0.75 * wa + 0.25 * wb)).abs() < 1e-12, "{got}");
    mesh.validate().unwrap();
}

#[test]
fn refused_collapses_change_nothing() {
    let mut mesh = meshloom::shapes::icosahedron();
    let h = mesh.halfedges().next().unwrap();
    let before = format!("{mesh:?}");
    for bad in [[f64::NAN, 0.0, 0.0], [0.0, f64::INFINITY, 0.0]] {
        assert!(matches!(
            mesh.check_collapse_edge_to(h, bad),
            Err(Error::NonFinitePosition { .. })
        ));
        assert!(matches!(
            mesh.collapse_edge_to(h, bad),
            Err(Error::NonFinitePosition { .. })
        ));
    }
    assert_eq!(format!("{mesh:?}"), before);
    // A stale key.
    mesh.collapse_edge(h).unwrap();
    assert!(matches!(
        mesh.collapse_edge_to(h, [0.0; 3]),
        Err(Error::StaleKey(_))
    ));
}

#[test]
fn corners_across_a_plain_edge_interpolate_together() {
    let (mut mesh, uv) = seamed_grid(6, 100.0); // no seam
    let a = vertex_at(&mesh, [2.0, 2.0]);
    let b = vertex_at(&mesh, [3.0, 2.0]);
    let h = mesh.find_halfedge(a, b).unwrap().unwrap();
    mesh.collapse_edge_to(h, [2.5, 2.0, 0.7]).unwrap();
    let hs: Vec<_> = mesh.vertex(b).unwrap().outgoing().collect();
    for h in hs {
        let v = *mesh.attr(&uv, h).unwrap().unwrap();
        assert!((v[0] - 2.5 / 6.0).abs() < 1e-12 && (v[1] - 2.0 / 6.0).abs() < 1e-12);
    }
    assert_eq!(seam_edges(&mesh, &uv), 0);
    mesh.validate().unwrap();
}

#[test]
fn collapse_edge_moves_corner_values_with_the_vertex() {
    // t = 1: b stays; a's corners take b's value (they used to keep a's).
    let (mut mesh, uv) = seamed_grid(6, 100.0);
    let a = vertex_at(&mesh, [2.0, 2.0]);
    let b = vertex_at(&mesh, [2.0, 3.0]);
    let h = mesh.find_halfedge(a, b).unwrap().unwrap();
    mesh.collapse_edge(h).unwrap();
    let hs: Vec<_> = mesh.vertex(b).unwrap().outgoing().collect();
    for h in hs {
        assert_eq!(*mesh.attr(&uv, h).unwrap().unwrap(), [2.0 / 6.0, 3.0 / 6.0]);
    }
}

#[test]
fn a_seam_along_the_edge_stays_a_seam() {
    let (mut mesh, uv) = seamed_grid(6, 3.0);
    let seams = seam_edges(&mesh, &uv);
    assert_eq!(seams, 6);
    // The vertical edge (3,2) -> (3,3) lies on the seam.
    let a = vertex_at(&mesh, [3.0, 2.0]);
    let b = vertex_at(&mesh, [3.0, 3.0]);
    let h = mesh.find_halfedge(a, b).unwrap().unwrap();
    mesh.collapse_edge_at(h, 0.5).unwrap();
    assert_eq!(seam_edges(&mesh, &uv), seams - 1);
    // Each side interpolated its own values: u is 0.5 left, 10.5 right.
    let hs: Vec<_> = mesh.vertex(b).unwrap().outgoing().collect();
    let mut sides = [0, 0];
    for h in hs {
        if mesh.halfedge(h).unwrap().face().is_hole() {
            continue;
        }
        let v = *mesh.attr(&uv, h).unwrap().unwrap();
        assert!((v[1] - 2.5 / 6.0).abs() < 1e-12);
        if (v[0] - 0.5).abs() < 1e-12 {
            sides[0] += 1;
        } else {
            assert!((v[0] - 10.5).abs() < 1e-12, "{v:?}");
            sides[1] += 1;
        }
    }
    assert!(sides[0] > 0 && sides[1] > 0);
    mesh.validate().unwrap();
}

#[test]
fn a_seam_at_one_end_keeps_the_other_wedge() {
    // a is next to the seam (x = 2), b on it (x = 3): a's corners join the
    // left wedge of b; b's right wedge keeps its values.
    let (mut mesh, uv) = seamed_grid(6, 3.0);
    let a = vertex_at(&mesh, [2.0, 2.0]);
    let b = vertex_at(&mesh, [3.0, 2.0]);
    let h = mesh.find_halfedge(a, b).unwrap().unwrap();
    mesh.collapse_edge(h).unwrap();
    let hs: Vec<_> = mesh.vertex(b).unwrap().outgoing().collect();
    for h in hs {
        if mesh.halfedge(h).unwrap().face().is_hole() {
            continue;
        }
        let v = *mesh.attr(&uv, h).unwrap().unwrap();
        assert!(v == [0.5, 2.0 / 6.0] || v == [10.5, 2.0 / 6.0], "{v:?}");
    }
    assert_eq!(seam_edges(&mesh, &uv), 6);
    mesh.validate().unwrap();
}
