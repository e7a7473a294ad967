//! The random operator stream shared by the model tests (`ops_model.rs`)
//! and the journal tests (`journal.rs`): one enum of every topological
//! operator with the numbers that pick its elements, one weighted
//! generator, and one function that turns an op into the elements it acts
//! on in the mesh as it is.

use meshloom::{EdgeKey, FaceKey, HalfedgeKey, Mesh, VertexKey};
use quickcheck::{Arbitrary, Gen};

/// One operator of a random stream. The numbers pick elements (modulo how
/// many there are) when the op runs, so a stream applies to any mesh.
#[derive(Clone, Debug)]
pub enum TopoOp {
    SplitEdge(usize, u8),
    SplitFace(usize, usize, usize),
    Poke(usize),
    Collapse(usize),
    CollapseAt(usize, u8),
    Flip(usize),
    RemoveEdge(usize),
    MergeFaces(usize, usize),
    RemoveVertex(usize),
    RemoveFace(usize),
    FillHole(usize),
    Triangulate(usize),
    TriangulateAll,
    Compact,
    Extrude(usize),
    SplitVertex(usize, usize, usize),
    CutOpen(usize, usize),
    CutLoop(usize),
}

impl Arbitrary for TopoOp {
    fn arbitrary(g: &mut Gen) -> TopoOp {
        let i = usize::arbitrary(g);
        let j = usize::arbitrary(g);
        let k = usize::arbitrary(g);
        let t = u8::arbitrary(g) % 11;
        // Weighted so that meshes both grow and shrink.
        match u8::arbitrary(g) % 28 {
            0..=2 => TopoOp::SplitEdge(i, t),
            3..=4 => TopoOp::SplitFace(i, j, k),
            5..=6 => TopoOp::Poke(i),
            7..=10 => TopoOp::Collapse(i),
            11 => TopoOp::CollapseAt(i, t),
            12..=14 => TopoOp::Flip(i),
            15..=16 => TopoOp::RemoveEdge(i),
            17 => TopoOp::MergeFaces(i, j),
            18 => TopoOp::RemoveVertex(i),
            19 => TopoOp::RemoveFace(i),
            20 => TopoOp::FillHole(i),
            21 => TopoOp::Triangulate(i),
            22 => TopoOp::TriangulateAll,
            23 => TopoOp::Extrude(i),
            24 => TopoOp::SplitVertex(i, j, k),
            25 => TopoOp::CutOpen(i, j),
            26 => TopoOp::CutLoop(i),
            _ => TopoOp::Compact,
        }
    }
}

/// The `i`-th item (modulo `count`) of an iterator of `count` items.
pub fn nth<T>(mut it: impl Iterator<Item = T>, count: usize, i: usize) -> Option<T> {
    if count == 0 {
        None
    } else {
        it.nth(i % count)
    }
}

/// The elements an op acts on, picked in the mesh as it is.
#[derive(Clone, Debug)]
pub enum Target {
    /// An edge and a parameter in 0..=1.
    Edge(EdgeKey, f64),
    /// A face and two of its vertices.
    FaceCorners(FaceKey, VertexKey, VertexKey),
    /// A face (or hole).
    Face(FaceKey),
    /// A half-edge and a parameter in 0..=1.
    Halfedge(HalfedgeKey, f64),
    /// Two faces.
    Faces(FaceKey, FaceKey),
    /// A vertex.
    Vertex(VertexKey),
    /// Two outgoing half-edges of one vertex.
    Outgoing(HalfedgeKey, HalfedgeKey),
    /// A path of vertices (a loop when it ends where it starts).
    Path(Vec<VertexKey>),
    /// The whole mesh.
    Mesh,
}

/// What `op` acts on in `m`; `None` when there is nothing to pick.
pub fn pick(m: &Mesh, op: &TopoOp) -> Option<Target> {
    Some(match *op {
        TopoOp::SplitEdge(i, t) => {
            Target::Edge(nth(m.edges(), m.edge_count(), i)?, f64::from(t) / 10.0)
        }
        TopoOp::Flip(i) | TopoOp::RemoveEdge(i) => {
            Target::Edge(nth(m.edges(), m.edge_count(), i)?, 0.0)
        }
        TopoOp::SplitFace(i, j, k) => {
            let f = nth(m.faces(), m.face_count(), i)?;
            let c: Vec<_> = m.face(f).unwrap().vertices().collect();
            Target::FaceCorners(f, c[j % c.len()], c[k % c.len()])
        }
        TopoOp::Poke(i) => Target::Face(nth(
            m.faces_and_holes(),
            m.face_count() + m.hole_count(),
            i,
        )?),
        TopoOp::RemoveFace(i) | TopoOp::Triangulate(i) | TopoOp::Extrude(i) => {
            Target::Face(nth(m.faces(), m.face_count(), i)?)
        }
        TopoOp::FillHole(i) => Target::Face(nth(m.holes(), m.hole_count(), i)?),
        TopoOp::Collapse(i) => Target::Halfedge(nth(m.halfedges(), m.halfedge_count(), i)?, 1.0),
        TopoOp::CollapseAt(i, t) => Target::Halfedge(
            nth(m.halfedges(), m.halfedge_count(), i)?,
            f64::from(t) / 10.0,
        ),
        TopoOp::MergeFaces(i, j) => {
            let f = nth(m.faces(), m.face_count(), i)?;
            let ns: Vec<_> = m.face(f).unwrap().neighbors().collect();
            let g = if ns.is_empty() { f } else { ns[j % ns.len()] };
            Target::Faces(f, g)
        }
        TopoOp::RemoveVertex(i) => Target::Vertex(nth(m.vertices(), m.vertex_count(), i)?),
        TopoOp::SplitVertex(i, j, k) => {
            let v = nth(m.vertices(), m.vertex_count(), i)?;
            let outs: Vec<_> = m.vertex(v).unwrap().outgoing().collect();
            Target::Outgoing(outs[j % outs.len()], outs[k % outs.len()])
        }
        TopoOp::CutOpen(i, j) => {
            let v = nth(m.vertices(), m.vertex_count(), i)?;
            // A walk of up to four steps that never meets a vertex twice.
            let mut path = vec![v];
            let mut salt = j;
            for _ in 0..4 {
                let last = *path.last().unwrap();
                let ns: Vec<_> = m
                    .vertex(last)
                    .unwrap()
                    .neighbors()
                    .filter(|n| !path.contains(n))
                    .collect();
                if ns.is_empty() {
                    break;
                }
                path.push(ns[salt % ns.len()]);
                salt /= 7;
            }
            Target::Path(path)
        }
        TopoOp::CutLoop(i) => {
            let v = nth(m.vertices(), m.vertex_count(), i)?;
            let mut ring: Vec<_> = m.vertex(v).unwrap().neighbors().collect();
            ring.push(ring[0]);
            Target::Path(ring)
        }
        TopoOp::TriangulateAll | TopoOp::Compact => Target::Mesh,
    })
}

/// Run `op` on `m` with no checks of its own: `None` when there was
/// nothing to pick, else whether the operator succeeded (a refused one
/// must change nothing; the callers check that).
pub fn apply(m: &mut Mesh, op: &TopoOp) -> Option<bool> {
    let target = pick(m, op)?;
    Some(match (op, target) {
        (TopoOp::SplitEdge(..), Target::Edge(e, t)) => m.split_edge(e, t).is_ok(),
        (TopoOp::Flip(_), Target::Edge(e, _)) => m.flip_edge(e).is_ok(),
        (TopoOp::RemoveEdge(i), Target::Edge(e, _)) => {
            if i % 3 == 0 {
                m.remove_edge_allowing_bridge(e).is_ok()
            } else {
                m.remove_edge(e).is_ok()
            }
        }
        (TopoOp::SplitFace(i, ..), Target::FaceCorners(f, a, b)) => {
            if i % 3 == 0 {
                // The same cut by its two vertices (the face is found).
                m.insert_edge(a, b).is_ok()
            } else {
                m.split_face(f, a, b).is_ok()
            }
        }
        (TopoOp::Poke(_), Target::Face(f)) => m.poke_face(f).is_ok(),
        (TopoOp::RemoveFace(_), Target::Face(f)) => m.remove_face(f).is_ok(),
        (TopoOp::Triangulate(_), Target::Face(f)) => m.triangulate(f).is_ok(),
        (TopoOp::Extrude(_), Target::Face(f)) => m.extrude_face(f, 0.5).is_ok(),
        (TopoOp::FillHole(i), Target::Face(h)) => {
            if i % 2 == 0 {
                m.fill_hole(h).is_ok()
            } else {
                m.fill_hole_triangulated(h).is_ok()
            }
        }
        (TopoOp::Collapse(_), Target::Halfedge(h, _)) => m.collapse_edge(h).is_ok(),
        (TopoOp::CollapseAt(i, _), Target::Halfedge(h, t)) => {
            if i % 2 == 0 {
                m.collapse_edge_at(h, t).is_ok()
            } else {
                // To a point off the edge: its position is given.
                let view = m.halfedge(h).unwrap();
                let a = view.origin().position();
                let b = view.dest().position();
                match (a, b) {
                    (Some(a), Some(b)) => {
                        let p = [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]) + 0.25);
                        m.collapse_edge_to(h, p).is_ok()
                    }
                    _ => m.collapse_edge_at(h, t).is_ok(),
                }
            }
        }
        (TopoOp::MergeFaces(..), Target::Faces(f, g)) => m.merge_faces(f, g).is_ok(),
        (TopoOp::RemoveVertex(_), Target::Vertex(v)) => m.remove_vertex(v).is_ok(),
        (TopoOp::SplitVertex(..), Target::Outgoing(a, b)) => m.split_vertex(a, b).is_ok(),
        (TopoOp::CutOpen(..) | TopoOp::CutLoop(_), Target::Path(p)) => m.cut_path(&p).is_ok(),
        (TopoOp::TriangulateAll, _) => {
            m.triangulate_all();
            true
        }
        (TopoOp::Compact, _) => {
            m.compact();
            true
        }
        (op, t) => unreachable!("{op:?} picked {t:?}"),
    })
}
