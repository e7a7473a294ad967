//! Each policy on a tiny soup, alone and with the others.

use super::*;
use crate::mesh::Mesh;

fn soup(positions: &[[f64; 3]], faces: &[&[u32]]) -> Polygons {
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    for f in faces {
        indices.extend_from_slice(f);
        offsets.push(indices.len() as u32);
    }
    Polygons {
        positions: positions.to_vec(),
        offsets,
        indices,
    }
}

fn only(policy: impl Fn(&mut RepairOptions)) -> RepairOptions {
    let mut o = RepairOptions::none();
    policy(&mut o);
    o
}

fn faces(p: &Polygons) -> Vec<Vec<u32>> {
    p.faces().map(|f| f.to_vec()).collect()
}

const SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

#[test]
fn weld_merges_bit_identical_positions_only() {
    // Two triangles of a square, the diagonal's ends given twice; a third
    // copy of vertex 0 differs in the sign of zero and stays.
    let mut p = soup(
        &[
            SQUARE[0],
            SQUARE[1],
            SQUARE[2],
            SQUARE[0],
            SQUARE[2],
            SQUARE[3],
            [-0.0, 0.0, 0.0],
        ],
        &[&[0, 1, 2], &[3, 4, 5]],
    );
    let (r, prov) = repair(&mut p, &only(|o| o.weld_vertices = true)).unwrap();
    assert_eq!(r.welded_vertices, 2);
    assert_eq!(p.positions.len(), 5);
    assert_eq!(faces(&p), [vec![0, 1, 2], vec![0, 2, 3]]);
    assert_eq!(prov.vertex_source, [0, 1, 2, 5, 6]);
    assert!(Mesh::from_buffers(&p).is_ok());
}

#[test]
fn weld_respects_classes() {
    let mut p = soup(&[SQUARE[0], SQUARE[0], SQUARE[1], SQUARE[2]], &[&[0, 2, 3]]);
    let (r, _) = repair_with(&mut p, &only(|o| o.weld_vertices = true), &[0, 1, 0, 0]).unwrap();
    assert_eq!(r.welded_vertices, 0);
}

#[test]
fn degenerate_faces_collapse_or_go() {
    let mut p = soup(
        &SQUARE,
        &[
            &[0, 1, 1, 2, 0],
            &[0, 2, 2],
            &[0, 2, 3, 2],
            &[0, 2, 3],
            &[1, 1],
        ],
    );
    let (r, prov) = repair(&mut p, &only(|o| o.drop_degenerate_faces = true)).unwrap();
    // 0 1 1 2 0 -> 0 1 2; 0 2 2 -> two corners; 0 2 3 2 pinches at 2.
    assert_eq!((r.collapsed_corners, r.degenerate_faces), (2, 3));
    assert_eq!(faces(&p), [vec![0, 1, 2], vec![0, 2, 3]]);
    assert_eq!(prov.face_source, [0, 3]);
    assert_eq!(prov.corner_source, [0, 2, 3, 12, 13, 14]);
}

#[test]
fn duplicate_faces_go_in_either_orientation() {
    let mut p = soup(&SQUARE, &[&[0, 1, 2], &[1, 2, 0], &[2, 1, 0], &[0, 2, 3]]);
    let (r, prov) = repair(&mut p, &only(|o| o.drop_duplicate_faces = true)).unwrap();
    assert_eq!(r.duplicate_faces, 2);
    assert_eq!(prov.face_source, [0, 3]);
}

#[test]
fn orientation_follows_the_majority_per_component() {
    // Tetrahedron with one face flipped; a separate triangle untouched.
    let mut p = soup(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [5.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [5.0, 1.0, 0.0],
        ],
        &[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[2, 3, 0], &[4, 5, 6]],
    );
    assert!(Mesh::from_buffers(&p).is_err());
    let (r, prov) = repair(&mut p, &only(|o| o.orient_faces = true)).unwrap();
    assert_eq!((r.flipped_faces, r.orientation_conflicts), (1, 0));
    // The flipped face keeps its first corner.
    assert_eq!(p.face(3), Some(&[2, 0, 3][..]));
    assert_eq!(&prov.corner_source[9..12], [9, 11, 10]);
    let m = Mesh::from_buffers(&p).unwrap();
    assert!(m.hole_count() == 1 && m.euler_characteristic() == 3);
}

#[test]
fn a_moebius_band_keeps_one_conflict() {
    // Three quads closing into a band with a half twist.
    let pos: Vec<[f64; 3]> = (0..6).map(|i| [i as f64, (i % 2) as f64, 0.0]).collect();
    let mut p = soup(&pos, &[&[0, 1, 3, 2], &[2, 3, 5, 4], &[4, 5, 0, 1]]);
    let (r, _) = repair(&mut p, &only(|o| o.orient_faces = true)).unwrap();
    assert_eq!(r.orientation_conflicts, 1);
    let (r, _) = repair(&mut p, &RepairOptions::all()).unwrap();
    assert_eq!(r.nonmanifold_edges, 1);
    Mesh::from_buffers(&p).unwrap().validate().unwrap();
}

#[test]
fn a_fin_on_an_edge_gets_its_own_vertices() {
    // Three triangles on edge 0-1: two opposite ones keep it.
    let mut p = soup(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -1.0, 0.0],
            [0.5, 0.0, 1.0],
        ],
        &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]],
    );
    let (r, prov) = repair(&mut p, &only(|o| o.split_nonmanifold_edges = true)).unwrap();
    assert_eq!((r.nonmanifold_edges, r.added_vertices), (1, 2));
    assert_eq!(p.face(2), Some(&[5, 6, 4][..]));
    assert_eq!(prov.vertex_source[5..], [0, 1]);
    let m = Mesh::from_buffers(&p).unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (7, 8, 3)
    );
}

#[test]
fn two_cones_touching_at_a_tip_are_split() {
    // Two closed tetrahedra sharing vertex 0: two closed fans there.
    let mut p = soup(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, -1.0],
        ],
        &[
            &[0, 2, 1],
            &[0, 1, 3],
            &[1, 2, 3],
            &[2, 0, 3],
            &[0, 4, 5],
            &[0, 6, 4],
            &[4, 6, 5],
            &[5, 6, 0],
        ],
    );
    assert!(Mesh::from_buffers(&p).is_err());
    let (r, prov) = repair(&mut p, &only(|o| o.split_nonmanifold_vertices = true)).unwrap();
    assert_eq!((r.nonmanifold_vertices, r.added_vertices), (1, 1));
    assert_eq!(prov.vertex_source[7], 0);
    let m = Mesh::from_buffers(&p).unwrap();
    assert_eq!(
        (m.vertex_count(), m.face_count(), m.euler_characteristic()),
        (8, 8, 4)
    );
}

#[test]
fn a_bowtie_of_open_fans_is_left_alone() {
    let mut p = soup(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-1.0, -1.0, 0.0],
        ],
        &[&[0, 1, 2], &[0, 3, 4]],
    );
    let (r, _) = repair(&mut p, &RepairOptions::all()).unwrap();
    assert!(r.is_clean(), "{r}");
    assert_eq!(Mesh::from_buffers(&p).unwrap().hole_count(), 1);
}

#[test]
fn unreferenced_vertices_go() {
    let mut p = soup(&[SQUARE[0], [9.0; 3], SQUARE[1], SQUARE[2]], &[&[0, 2, 3]]);
    let (r, prov) = repair(&mut p, &only(|o| o.drop_unreferenced_vertices = true)).unwrap();
    assert_eq!(r.unreferenced_vertices, 1);
    assert_eq!(faces(&p), [vec![0, 1, 2]]);
    assert_eq!(prov.vertex_source, [0, 2, 3]);
}

#[test]
fn the_report_reads_well() {
    let r = RepairReport {
        welded_vertices: 3,
        flipped_faces: 1,
        ..Default::default()
    };
    assert_eq!(r.to_string(), "vertices welded: 3\nfaces flipped: 1");
    assert_eq!(RepairReport::default().to_string(), "no repairs needed");
}

#[test]
fn nothing_happens_without_policies() {
    let mut p = soup(&SQUARE, &[&[0, 1, 2], &[0, 1, 2]]);
    let before = p.clone();
    let (r, _) = repair(&mut p, &RepairOptions::none()).unwrap();
    assert!(r.is_clean());
    assert_eq!(p, before);
}

/// Issue 10, defect 3: malformed polygons give the builder's error, the
/// polygons untouched, where repair used to panic.
#[test]
fn malformed_polygons_give_the_builders_errors() {
    let tri = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let cases = [
        // An index past the positions.
        Polygons {
            positions: tri.clone(),
            offsets: vec![0, 3],
            indices: vec![0, 1, 3],
        },
        // Offsets past the indices.
        Polygons {
            positions: tri.clone(),
            offsets: vec![0, 5],
            indices: vec![0, 1, 2],
        },
        // Offsets that decrease.
        Polygons {
            positions: tri.clone(),
            offsets: vec![0, 3, 2, 3],
            indices: vec![0, 1, 2],
        },
        // Offsets that do not start at 0.
        Polygons {
            positions: tri.clone(),
            offsets: vec![1, 3],
            indices: vec![0, 1, 2],
        },
        // A NaN position of a used vertex.
        Polygons {
            positions: vec![[0.0; 3], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]],
            offsets: vec![0, 3],
            indices: vec![0, 1, 2],
        },
        // A huge index with positions.
        Polygons {
            positions: tri.clone(),
            offsets: vec![0, 3],
            indices: vec![0, 1, u32::MAX],
        },
    ];
    for p in cases {
        let expected = Mesh::from_buffers(&p).unwrap_err();
        for options in [RepairOptions::all(), RepairOptions::none()] {
            let mut q = p.clone();
            let got = repair(&mut q, &options).unwrap_err();
            // Debug text: NaN != NaN under PartialEq.
            assert_eq!(format!("{got:?}"), format!("{expected:?}"));
            assert_eq!(format!("{q:?}"), format!("{p:?}"), "the polygons changed");
        }
    }
}

#[test]
fn a_huge_index_in_a_topology_only_soup_costs_nothing() {
    // Three indices claiming 2^32 vertices: renumbered, not allocated.
    let p = Polygons {
        positions: Vec::new(),
        offsets: vec![0, 3],
        indices: vec![0, 1, u32::MAX],
    };
    let mut q = p.clone();
    let (r, prov) = repair(&mut q, &RepairOptions::all()).unwrap();
    assert_eq!(r.unreferenced_vertices, u32::MAX as usize + 1 - 3);
    assert_eq!(q.indices, [0, 1, 2]);
    assert_eq!(prov.vertex_source, [0, 1, u32::MAX]);
    // Keeping the unreferenced ones would list four billion: refused.
    let mut q = p.clone();
    let keep = only(|o| o.orient_faces = true);
    let e = repair(&mut q, &keep).unwrap_err();
    assert!(
        matches!(e, crate::Error::Build(crate::BuildError::TooLarge { .. })),
        "{e}"
    );
    assert_eq!(q, p);
    // A few unreferenced ones are kept, numbering and all.
    let mut q = Polygons {
        positions: Vec::new(),
        offsets: vec![0, 3, 6],
        indices: vec![0, 1, 5, 0, 1, 5],
    };
    let (r, prov) = repair(&mut q, &only(|o| o.drop_duplicate_faces = true)).unwrap();
    assert_eq!(r.duplicate_faces, 1);
    assert_eq!(q.indices, [0, 1, 5]);
    assert_eq!(prov.vertex_source, [0, 1, 2, 3, 4, 5]);
}

#[test]
fn a_valid_mesh_is_left_alone_even_where_a_policy_would_act() {
    // Two triangles with one vertex set in opposite orientations: a closed
    // "pillow", a valid mesh; the duplicate policy must not drop one.
    let mut p = soup(&SQUARE[..3], &[&[0, 1, 2], &[0, 2, 1]]);
    let before = p.clone();
    let (r, _) = repair(&mut p, &RepairOptions::all()).unwrap();
    assert!(r.is_clean(), "{r}");
    assert_eq!(p, before);
}

#[test]
fn welding_that_would_pinch_a_closed_mesh_is_refused() {
    // Two tetrahedra whose apexes are distinct vertices at one position:
    // welding them would make a vertex with two closed fans.
    let mut p = soup(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 2.0],
            [0.0, 1.0, 2.0],
            [0.0, 0.0, 2.0],
        ],
        &[
            &[0, 2, 1],
            &[0, 1, 3],
            &[1, 2, 3],
            &[2, 0, 3],
            &[4, 5, 6],
            &[4, 6, 7],
            &[4, 7, 5],
            &[5, 7, 6],
        ],
    );
    let before = p.clone();
    let weld = RepairOptions {
        weld_vertices: true,
        ..RepairOptions::all()
    };
    let (r, _) = repair(&mut p, &weld).unwrap();
    assert_eq!((r.welded_vertices, r.weld_refused), (0, 1), "{r}");
    assert_eq!(p, before);
    let m = Mesh::from_buffers(&p).unwrap();
    assert_eq!((m.stats().components, m.hole_count()), (2, 0));
}

/// Found by fuzzing (fuzz/corpus/repair/crash-weld-after-degenerate): a
/// degenerate face kept a weld apart in the first pass; dropping it let a
/// second repair weld. Passes until nothing changes make repair idempotent.
#[test]
fn a_weld_freed_by_a_later_policy_happens_in_the_same_repair() {
    let mut p = Polygons {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, 5.0],
            [0.0, 0.0, 0.0],
        ],
        offsets: vec![0, 1, 1, 2, 2, 2, 3, 5, 6, 10, 13],
        indices: vec![0, 1, 0, 0, 2, 0, 0, 1, 2, 3, 1, 4, 2],
    };
    let weld = RepairOptions {
        weld_vertices: true,
        ..RepairOptions::all()
    };
    let (first, _) = repair(&mut p, &weld).unwrap();
    assert_eq!(first.welded_vertices, 1, "{first}");
    let after = p.clone();
    let (second, _) = repair(&mut p, &weld).unwrap();
    assert!(second.is_clean(), "{second}");
    assert_eq!(p, after);
    Mesh::from_buffers(&p).unwrap().validate().unwrap();
}

/// Found by fuzzing: a NaN position is refused as malformed even where
/// the builder first names a defect that repair would fix.
#[test]
fn a_nan_position_is_refused_before_repairable_defects() {
    let p = Polygons {
        positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [f64::NAN, 1.0, 0.0]],
        offsets: vec![0, 3],
        indices: vec![0, 2, 2],
    };
    assert!(matches!(
        Mesh::from_buffers(&p),
        Err(crate::Error::Build(
            crate::BuildError::RepeatedVertex { .. }
        ))
    ));
    let mut q = p.clone();
    let e = repair(&mut q, &RepairOptions::all()).unwrap_err();
    assert!(matches!(
        e,
        crate::Error::Build(crate::BuildError::NonFinitePosition { vertex: 2, .. })
    ));
}
