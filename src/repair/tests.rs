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
    let (r, prov) = repair(&mut p, &only(|o| o.weld_vertices = true));
    assert_eq!(r.welded_vertices, 2);
    assert_eq!(p.positions.len(), 5);
    assert_eq!(faces(&p), [vec![0, 1, 2], vec![0, 2, 3]]);
    assert_eq!(prov.vertex_source, [0, 1, 2, 5, 6]);
    assert!(Mesh::from_buffers(&p).is_ok());
}

#[test]
fn weld_respects_classes() {
    let mut p = soup(&[SQUARE[0], SQUARE[0], SQUARE[1], SQUARE[2]], &[&[0, 2, 3]]);
    let (r, _) = repair_with(&mut p, &only(|o| o.weld_vertices = true), &[0, 1, 0, 0]);
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
    let (r, prov) = repair(&mut p, &only(|o| o.drop_degenerate_faces = true));
    // 0 1 1 2 0 -> 0 1 2; 0 2 2 -> two corners; 0 2 3 2 pinches at 2.
    assert_eq!((r.collapsed_corners, r.degenerate_faces), (2, 3));
    assert_eq!(faces(&p), [vec![0, 1, 2], vec![0, 2, 3]]);
    assert_eq!(prov.face_source, [0, 3]);
    assert_eq!(prov.corner_source, [0, 2, 3, 12, 13, 14]);
}

#[test]
fn duplicate_faces_go_in_either_orientation() {
    let mut p = soup(&SQUARE, &[&[0, 1, 2], &[1, 2, 0], &[2, 1, 0], &[0, 2, 3]]);
    let (r, prov) = repair(&mut p, &only(|o| o.drop_duplicate_faces = true));
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
    let (r, prov) = repair(&mut p, &only(|o| o.orient_faces = true));
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
    let (r, _) = repair(&mut p, &only(|o| o.orient_faces = true));
    assert_eq!(r.orientation_conflicts, 1);
    let (r, _) = repair(&mut p, &RepairOptions::all());
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
    let (r, prov) = repair(&mut p, &only(|o| o.split_nonmanifold_edges = true));
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
    let (r, prov) = repair(&mut p, &only(|o| o.split_nonmanifold_vertices = true));
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
    let (r, _) = repair(&mut p, &RepairOptions::all());
    assert!(r.is_clean(), "{r}");
    assert_eq!(Mesh::from_buffers(&p).unwrap().hole_count(), 1);
}

#[test]
fn unreferenced_vertices_go() {
    let mut p = soup(&[SQUARE[0], [9.0; 3], SQUARE[1], SQUARE[2]], &[&[0, 2, 3]]);
    let (r, prov) = repair(&mut p, &only(|o| o.drop_unreferenced_vertices = true));
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
    let (r, _) = repair(&mut p, &RepairOptions::none());
    assert!(r.is_clean());
    assert_eq!(p, before);
}
