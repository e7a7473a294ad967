//! Malformed compact buffers are refused with an error, never a panic.

use meshloom::{Error, Mesh, Polygons};

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
