//! Malformed compact buffers are refused with an error, never a panic.

use meshloom::{BuildError, Error, Mesh, Polygons};

fn buffers(offsets: &[u32], indices: &[u32]) -> Polygons {
    Polygons {
        positions: vec![],
        offsets: offsets.to_vec(),
        indices: indices.to_vec(),
    }
}

#[test]
fn indices_without_offsets_are_refused() {
    // Regression: this used to panic inside the builder (build.rs, hole
    // linking) because corners belonging to no face were paired.
    let r = Mesh::from_buffers(&buffers(&[], &[0, 1, 2]));
    assert!(matches!(r, Err(Error::Build(_))), "{r:?}");
}

#[test]
fn malformed_offsets_are_refused() {
    for (offsets, indices) in [
        (&[1u32, 3][..], &[0u32, 1, 2][..]),
        (&[0, 3, 2], &[0, 1, 2]),
        (&[0, 2], &[0, 1, 2]),
        (&[0], &[0, 1, 2]),
        (&[0, 4], &[0, 1, 2]),
    ] {
        let r = Mesh::from_buffers(&buffers(offsets, indices));
        assert!(matches!(r, Err(Error::Build(_))), "{offsets:?}: {r:?}");
    }
    assert!(Mesh::from_buffers(&buffers(&[], &[])).unwrap().is_empty());
    assert!(Mesh::from_buffers(&buffers(&[0], &[])).unwrap().is_empty());
}

#[test]
fn random_buffers_never_panic() {
    fn prop(offsets: Vec<u8>, indices: Vec<u8>) -> bool {
        let offsets: Vec<u32> = offsets.iter().take(8).map(|&o| u32::from(o % 16)).collect();
        let indices: Vec<u32> = indices.iter().take(16).map(|&i| u32::from(i % 8)).collect();
        match Mesh::from_buffers(&buffers(&offsets, &indices)) {
            Ok(m) => m.validate().is_ok(),
            Err(Error::Build(_)) => true,
            Err(_) => false,
        }
    }
    quickcheck::QuickCheck::new()
        .tests(3000)
        .quickcheck(prop as fn(Vec<u8>, Vec<u8>) -> bool);
}

fn three_indices(last: u32) -> Polygons {
    buffers(&[0, 3], &[0, 1, last])
}

/// Issue 10, defect 2: a topology-only triangle whose third index is huge
/// made the builder allocate memory proportional to the index (16 GiB for
/// `u32::MAX`, 8 GiB for 2^31) or run a loop of that length (`u32::MAX -
/// 1`). The vertex count of topology-only buffers is one past the largest
/// index, the unused vertices are dropped, and building is linear in the
/// corners: a triangle, at once, in a few hundred bytes.
#[test]
fn huge_topology_only_index_builds_in_linear_memory() {
    for last in [u32::MAX, u32::MAX - 1, 1 << 31, 3] {
        let m = Mesh::from_buffers(&three_indices(last)).unwrap();
        assert_eq!((m.vertex_count(), m.face_count()), (3, 1), "{last}");
        assert!(m.heap_bytes() < 4096, "{last}: {}", m.heap_bytes());
        let (back, _) = m.to_polygons();
        assert_eq!(back.indices, [0, 1, 2]);
    }
}

/// `build_buffers` returns a key per input vertex: for such an input that
/// map would be proportional to the index, so it is refused; a gap of a
/// few unused vertices is fine.
#[test]
fn huge_topology_only_index_refuses_the_key_map() {
    for last in [u32::MAX, u32::MAX - 1, 1 << 31, 70] {
        let r = Mesh::build_buffers(&three_indices(last));
        assert!(
            matches!(r, Err(Error::Build(BuildError::TooLarge { .. }))),
            "{last}: {r:?}"
        );
    }
    // Up to 2 * 3 + 64 = 70 input vertices for three corners.
    let b = Mesh::build_buffers(&three_indices(69)).unwrap();
    assert_eq!(
        (b.mesh.vertex_count(), b.unreferenced, b.vertices.len()),
        (3, 67, 70)
    );
    let b = Mesh::build_buffers(&buffers(&[0, 3, 6], &[0, 1, 3, 3, 1, 4])).unwrap();
    assert_eq!((b.mesh.vertex_count(), b.unreferenced), (4, 1));
    assert_eq!(b.vertices[2], None);
}

/// With positions the same index is past the vertex count: a typed error
/// naming the face.
#[test]
fn huge_index_past_the_positions_is_out_of_range() {
    for last in [u32::MAX, u32::MAX - 1, 1 << 31, 3] {
        let mut p = three_indices(last);
        p.positions = vec![[0.0; 3]; 3];
        let expected = BuildError::IndexOutOfRange {
            face: 0,
            index: i64::from(last),
            vertex_count: 3,
        };
        assert_eq!(Mesh::from_buffers(&p).unwrap_err(), Error::Build(expected));
    }
}

/// A caller may claim billions of vertices and use three: building stays
/// linear in the corners (it used to allocate by the largest index).
#[test]
fn a_huge_vertex_count_with_three_used_builds_small() {
    let big = (1usize << 31) - 1;
    let m = Mesh::from_faces(big, &[[0u32, 1, big as u32 - 1]]).unwrap();
    assert_eq!((m.vertex_count(), m.face_count()), (3, 1));
    assert!(m.heap_bytes() < 4096, "{}", m.heap_bytes());
    let r = Mesh::from_faces(1usize << 31, &[[0u32, 1, 2]]);
    assert!(
        matches!(r, Err(Error::Build(BuildError::TooLarge { .. }))),
        "{r:?}"
    );
}
