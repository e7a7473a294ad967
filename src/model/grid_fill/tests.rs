use super::*;
use crate::attr::{Conserved, FaceAttr, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, next_random};
use crate::shapes::{self, GridFaces};
use crate::Error;

/// An `n × n` grid with corner UVs from the linear field (plus `shift` on
/// faces right of x = n / 2), a material per column of quads and a
/// conserved mass of 1 a face; the quads inside `[lo, hi]²` removed into
/// one hole.
fn holed_grid(
    n: usize,
    lo: f64,
    hi: f64,
    shift: f64,
) -> (Mesh, FaceKey, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let mut m = shapes::grid(n, n, GridFaces::Quads);
    let uv = m.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = m.add_face_attr::<u32>("material").unwrap();
    let mass = m
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    let mut inside = Vec::new();
    for f in m.faces().collect::<Vec<_>>() {
        let ps: Vec<V3> = m
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| m.position(v).unwrap())
            .collect();
        let x = ps.iter().map(|p| p[0]).sum::<f64>() / 4.0;
        let right = x > n as f64 / 2.0;
        for h in m.face(f).unwrap().halfedges().collect::<Vec<_>>() {
            let p = m.halfedge(h).unwrap().origin().position().unwrap();
            let [u, v] = field(p);
            m.set_attr(&uv, h, [if right { u + shift } else { u }, v])
                .unwrap();
        }
        m.set_attr(&material, f, x as u32).unwrap();
        m.set_attr(&mass, f, 1.0).unwrap();
        if ps
            .iter()
            .all(|p| (lo..=hi).contains(&p[0]) && (lo..=hi).contains(&p[1]))
        {
            inside.push(f);
        }
    }
    let mut hole = None;
    for f in inside {
        hole = m.remove_face(f).unwrap().first().copied().or(hole);
    }
    (m, hole.unwrap(), uv, material)
}

fn mass_total(m: &Mesh) -> f64 {
    m.faces()
        .filter_map(|f| m.attr_value("mass", f).unwrap())
        .map(|x| x.as_f64().unwrap())
        .sum()
}

#[test]
fn a_four_by_four_hole_comes_back_as_sixteen_quads_on_the_field() {
    let (mut m, hole, uv, material) = holed_grid(6, 1.0, 5.0, 0.0);
    assert_eq!((m.face_count(), m.face(hole).unwrap().degree()), (20, 16));
    let made = m.grid_fill(hole, &GridFillOptions::default()).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (made.faces.len(), made.vertices.len(), made.edges.len()),
        (16, 9, 24)
    );
    assert_eq!(made.span, 4);
    assert_eq!(made.faces[0], hole);
    assert_eq!(
        (m.face_count(), m.hole_count(), m.euler_characteristic()),
        (36, 1, 1)
    );
    // The inner vertices on the grid's points; every corner on the field.
    for &v in &made.vertices {
        let p = m.position(v).unwrap();
        assert!(p.iter().all(|x| (x - x.round()).abs() < 1e-12), "{p:?}");
    }
    for h in m
        .halfedges()
        .filter(|&h| !m.halfedge(h).unwrap().is_boundary())
    {
        let p = m.halfedge(h).unwrap().origin().position().unwrap();
        let got = *m.attr(&uv, h).unwrap().unwrap();
        let want = field(p);
        assert!(
            (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12,
            "{p:?}"
        );
    }
    // Each quad takes the material of the rim face nearest it (its
    // column's x, clamped to the rim's columns 0 and 5 at the sides).
    for &f in &made.faces {
        let x = m
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| m.position(v).unwrap()[0])
            .sum::<f64>()
            / 4.0;
        let got = *m.attr(&material, f).unwrap().unwrap();
        assert!(got == x as u32 || got == 0 || got == 5, "{got} at {x}");
    }
    assert_eq!(mass_total(&m), 20.0);
}

#[test]
fn spans_counts_and_small_holes() {
    for (span, faces) in [(Some(2), 12), (Some(1), 7), (Some(7), 7), (None, 16)] {
        let (mut m, hole, _, _) = holed_grid(6, 1.0, 5.0, 0.0);
        let made = m
            .grid_fill(
                hole,
                &GridFillOptions {
                    span,
                    offset: Some(3),
                },
            )
            .unwrap();
        m.validate().unwrap();
        assert_eq!(made.faces.len(), faces);
        assert_eq!(m.euler_characteristic(), 1);
    }
    // A quad hole: one quad, nothing new inside.
    let (mut m, hole, _, _) = holed_grid(3, 1.0, 2.0, 0.0);
    let made = m.grid_fill(hole, &GridFillOptions::default()).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (made.faces.len(), made.vertices.len(), made.edges.len()),
        (1, 0, 0)
    );
    // A 2 × 1 hole: two quads.
    let (mut m, hole, _, _) = holed_grid(4, 1.0, 3.0, 0.0);
    let (mut m2, hole2) = {
        let mut g = shapes::grid(4, 3, GridFaces::Quads);
        let fs: Vec<FaceKey> = g.faces().collect();
        g.remove_face(fs[5]).unwrap();
        let h = g.remove_face(fs[6]).unwrap()[0];
        (g, h)
    };
    assert_eq!(m2.face(hole2).unwrap().degree(), 6);
    let made = m2.grid_fill(hole2, &GridFillOptions::default()).unwrap();
    m2.validate().unwrap();
    assert_eq!(made.faces.len(), 2);
    assert_eq!(
        m.grid_fill(hole, &GridFillOptions::default())
            .unwrap()
            .faces
            .len(),
        4
    );
}

#[test]
fn a_seam_on_the_rim_stays_on_each_side() {
    let (mut m, hole, uv, _) = holed_grid(6, 1.0, 5.0, 10.0);
    let made = m.grid_fill(hole, &GridFillOptions::default()).unwrap();
    m.validate().unwrap();
    // A corner at a rim vertex copies the face across its rim edge: the
    // left island's values left of x = 3, the right island's right of it.
    for &f in &made.faces {
        for h in m.face(f).unwrap().halfedges() {
            let view = m.halfedge(h).unwrap();
            let p = view.origin().position().unwrap();
            // Only corners at the rim's vertices.
            if [1.0, 5.0].iter().all(|&r| p[0] != r && p[1] != r) {
                continue;
            }
            let got = *m.attr(&uv, h).unwrap().unwrap();
            let want = field(p);
            let shift = got[0] - want[0];
            assert!(shift.abs() < 1e-12 || (shift - 10.0).abs() < 1e-12, "{p:?}");
            if p[0] < 3.0 {
                assert!(shift.abs() < 1e-12, "{p:?}");
            }
            if p[0] > 3.0 {
                assert!((shift - 10.0).abs() < 1e-12, "{p:?}");
            }
        }
    }
}

#[test]
fn refusals_change_nothing_and_a_fill_is_one_undo_step() {
    let (mut m, hole, _, _) = holed_grid(6, 1.0, 5.0, 0.0);
    m.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&m);
    let face = m.faces().next().unwrap();
    let n16 = |span| GridFillOptions {
        span: Some(span),
        offset: None,
    };
    for (h, o, want) in [
        (face, GridFillOptions::default(), Refusal::NotHole),
        (
            hole,
            n16(0),
            Refusal::Parameter("span must be in 1..n/2 for a hole of n edges"),
        ),
        (
            hole,
            n16(8),
            Refusal::Parameter("span must be in 1..n/2 for a hole of n edges"),
        ),
        (
            hole,
            GridFillOptions {
                span: None,
                offset: Some(16),
            },
            Refusal::Parameter("offset must be below the hole's edge count"),
        ),
    ] {
        let err = m.grid_fill(h, &o).unwrap_err();
        assert_eq!(m.check_grid_fill(h, &o).unwrap_err(), err);
        assert!(matches!(err, Error::Refused { reason, .. } if reason == want));
        assert_eq!(fingerprint(&m), before);
    }
    // An odd hole: a triangle out of an icosphere.
    let mut t = shapes::icosphere(1);
    let odd = t.remove_face(t.faces().next().unwrap()).unwrap()[0];
    let tb = fingerprint(&t);
    assert!(matches!(
        t.grid_fill(odd, &GridFillOptions::default()),
        Err(Error::Refused {
            reason: Refusal::Parameter(_),
            ..
        })
    ));
    assert_eq!(fingerprint(&t), tb);
    let undo = m.history().undo_len();
    m.grid_fill(hole, &GridFillOptions::default()).unwrap();
    assert_eq!(m.history().undo_len(), undo + 1);
    assert!(m.undo());
    assert_eq!(fingerprint(&m), before);
}

#[test]
fn random_holes_fill_and_validate_or_change_nothing() {
    let mut seed = 0x5851_f42d_4c95_7f2du64;
    for mesh in mixed_meshes() {
        for _ in 0..30 {
            let mut m = mesh.clone();
            let faces: Vec<FaceKey> = m.faces().collect();
            for _ in 0..1 + next_random(&mut seed) % 4 {
                let f = faces[next_random(&mut seed) as usize % faces.len()];
                if m.face(f).is_ok() {
                    let _ = m.remove_face(f);
                }
            }
            let holes: Vec<FaceKey> = m.holes().collect();
            let hole = holes[next_random(&mut seed) as usize % holes.len()];
            let span = match next_random(&mut seed) % 3 {
                0 => None,
                _ => Some(next_random(&mut seed) as usize % 6),
            };
            let o = GridFillOptions { span, offset: None };
            let before = fingerprint(&m);
            let (f0, chi) = (m.face_count(), m.euler_characteristic());
            match m.grid_fill(hole, &o) {
                Ok(made) => {
                    m.validate().unwrap();
                    assert_eq!(m.face_count(), f0 + made.faces.len());
                    assert_eq!(m.euler_characteristic(), chi + 1);
                }
                Err(Error::Refused { .. }) => assert_eq!(fingerprint(&m), before),
                Err(e) => panic!("{e:?}"),
            }
        }
    }
}
