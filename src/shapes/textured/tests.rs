//! Textured primitives: validity, counts, orientation, the UV layout
//! (range, islands, seams, area, no flipped face) and the materials.

use super::*;
use crate::attr::{HalfedgeAttr, Incompatible, Interpolate};
use crate::keys::{EdgeKey, FaceKey};
use crate::shapes::{self, MAX_SEGMENTS};

/// What a textured shape must measure.
struct Expect {
    vef: (usize, usize, usize),
    chi: i64,
    holes: usize,
    islands: usize,
    seams: usize,
    /// The total UV area.
    area: f64,
}

fn uv_column(mesh: &Mesh) -> HalfedgeAttr<[f64; 2]> {
    mesh.attr_handle(UV).unwrap()
}

/// The UV of every corner of `f`, in order.
fn face_uvs(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>, f: FaceKey) -> Vec<[f64; 2]> {
    let face = mesh.face(f).unwrap();
    face.halfedges()
        .map(|h| *mesh.attr(uv, h).unwrap().expect("every corner has a UV"))
        .collect()
}

fn cross2(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Six times the enclosed volume (fan-triangulated faces).
fn volume6(mesh: &Mesh) -> f64 {
    let mut v = 0.0;
    for f in mesh.faces() {
        let p: Vec<_> = mesh
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| mesh.position(v).unwrap())
            .collect();
        for k in 1..p.len() - 1 {
            v += crate::vec3::dot(p[0], crate::vec3::cross(p[k], p[k + 1]));
        }
    }
    v
}

/// Whether the edge's two faces give its ends different UVs.
fn is_seam(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>, e: EdgeKey) -> bool {
    let h = mesh.edge(e).unwrap().halfedge(0);
    let t = h.twin();
    if h.face().is_hole() || t.face().is_hole() {
        return false;
    }
    let at = |h: crate::HalfedgeKey| *mesh.attr(uv, h).unwrap().unwrap();
    at(h.key()) != at(t.next().key()) || at(h.next().key()) != at(t.key())
}

/// Islands (faces joined across edges that are not seams) and seams.
fn islands_and_seams(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>) -> (usize, usize) {
    let faces: Vec<FaceKey> = mesh.faces().collect();
    let index = |f: FaceKey| faces.iter().position(|&g| g == f).unwrap();
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut seams = 0;
    for e in mesh.edges() {
        let [Some(a), Some(b)] = mesh.edge(e).unwrap().faces() else {
            continue;
        };
        if mesh.face(a).unwrap().is_hole() || mesh.face(b).unwrap().is_hole() {
            continue;
        }
        if is_seam(mesh, uv, e) {
            seams += 1;
        } else {
            let (ra, rb) = (root(&mut parent, index(a)), root(&mut parent, index(b)));
            parent[ra] = rb;
        }
    }
    let islands = (0..faces.len())
        .filter(|&i| root(&mut parent, i) == i)
        .count();
    (islands, seams)
}

/// Every check of a textured shape; returns the mesh for more.
fn check(mesh: Mesh, want: Expect) -> Mesh {
    mesh.validate().unwrap();
    let vef = (mesh.vertex_count(), mesh.edge_count(), mesh.face_count());
    assert_eq!(vef, want.vef);
    assert_eq!(mesh.euler_characteristic(), want.chi);
    assert_eq!(mesh.hole_count(), want.holes);
    if want.holes == 0 {
        assert!(mesh.is_closed());
        assert!(volume6(&mesh) > 0.0, "faces must point outwards");
    }
    let uv = uv_column(&mesh);
    let mut area = 0.0;
    for f in mesh.faces() {
        let c = face_uvs(&mesh, &uv, f);
        assert!(c.iter().flatten().all(|x| (0.0..=1.0).contains(x)), "{c:?}");
        for k in 1..c.len() - 1 {
            let a = cross2(c[0], c[k], c[k + 1]);
            assert!(a > 1e-12, "flipped or empty UV triangle {c:?}");
            area += 0.5 * a;
        }
    }
    for h in mesh
        .holes()
        .flat_map(|f| mesh.face(f).unwrap().halfedges().collect::<Vec<_>>())
    {
        assert_eq!(mesh.attr(&uv, h).unwrap(), None, "hole corners have no UV");
    }
    assert!(
        (area - want.area).abs() < 1e-9,
        "UV area {area}, expected {}",
        want.area
    );
    assert_eq!(islands_and_seams(&mesh, &uv), (want.islands, want.seams));
    mesh
}

/// The area of a regular n-gon of circumradius `r`.
fn ngon_area(n: usize, r: f64) -> f64 {
    0.5 * n as f64 * r * r * (2.0 * std::f64::consts::PI / n as f64).sin()
}

/// How many faces carry each material id 0, 1, 2.
fn material_counts(mesh: &Mesh) -> [usize; 3] {
    let m = mesh
        .attr_handle::<FaceKey, u32, Incompatible>(MATERIAL)
        .unwrap();
    let mut out = [0; 3];
    for f in mesh.faces() {
        out[*mesh.attr(&m, f).unwrap().unwrap() as usize] += 1;
    }
    out
}

fn with_materials() -> ShapeOptions {
    ShapeOptions {
        materials: true,
        ..ShapeOptions::default()
    }
}

#[test]
fn box_is_a_cross_of_one_island() {
    let b = box_mesh([2.0, 3.0, 0.5], &with_materials()).unwrap();
    let want = Expect {
        vef: (8, 12, 6),
        chi: 2,
        holes: 0,
        islands: 1,
        seams: 7,
        area: 0.375,
    };
    let b = check(b, want);
    assert_eq!(material_counts(&b), [4, 1, 1]);
    // The extent is the size, centred on the origin.
    let xs: Vec<_> = b.vertices().map(|v| b.position(v).unwrap()).collect();
    assert!(xs
        .iter()
        .all(|p| p[0].abs() == 1.0 && p[1].abs() == 1.5 && p[2].abs() == 0.25));
    // The top's normal is +z and its material TOP.
    let m = b
        .attr_handle::<FaceKey, u32, Incompatible>(MATERIAL)
        .unwrap();
    for f in b.faces() {
        let z: Vec<_> = b
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| b.position(v).unwrap()[2])
            .collect();
        let top = z.iter().all(|&z| z > 0.0);
        assert_eq!(top, b.attr(&m, f).unwrap() == Some(&TOP));
    }
}

#[test]
fn cylinders_capped_and_open() {
    for s in [3, 4, 7, 32] {
        let caps = 2.0 * ngon_area(s, 0.24);
        let want = Expect {
            vef: (2 * s, 3 * s, s + 2),
            chi: 2,
            holes: 0,
            islands: 3,
            seams: 2 * s + 1,
            area: 0.5 + caps,
        };
        let c = check(cylinder(0.7, 1.5, s, &with_materials()).unwrap(), want);
        assert_eq!(material_counts(&c), [s, 1, 1]);
        let open = ShapeOptions {
            caps: false,
            ..with_materials()
        };
        let want = Expect {
            vef: (2 * s, 3 * s, s),
            chi: 0,
            holes: 2,
            islands: 1,
            seams: 1,
            area: 1.0,
        };
        let c = check(cylinder(0.7, 1.5, s, &open).unwrap(), want);
        assert_eq!(material_counts(&c), [s, 0, 0]);
    }
}

#[test]
fn cones_to_a_point_either_way_and_frustums() {
    let s = 10;
    let disk = ngon_area(s, 0.24);
    for radii in [[1.0, 0.0], [0.0, 2.0]] {
        let want = Expect {
            vef: (s + 1, 2 * s, s + 1),
            chi: 2,
            holes: 0,
            islands: 2,
            seams: s,
            area: 2.0 * disk,
        };
        let c = check(
            cone(radii[0], radii[1], 1.0, s, &with_materials()).unwrap(),
            want,
        );
        let end = if radii[0] > 0.0 { [s, 1, 0] } else { [s, 0, 1] };
        assert_eq!(material_counts(&c), end);
        let open = ShapeOptions {
            caps: false,
            ..ShapeOptions::default()
        };
        let want = Expect {
            vef: (s + 1, 2 * s, s),
            chi: 1,
            holes: 1,
            islands: 1,
            seams: 0,
            area: ngon_area(s, 0.5),
        };
        check(cone(radii[0], radii[1], 1.0, s, &open).unwrap(), want);
    }
    let want = Expect {
        vef: (2 * s, 3 * s, s + 2),
        chi: 2,
        holes: 0,
        islands: 3,
        seams: 2 * s + 1,
        area: 0.5 + 2.0 * disk,
    };
    check(
        cone(1.0, 0.25, 2.0, s, &ShapeOptions::default()).unwrap(),
        want,
    );
}

#[test]
fn grid_is_the_unit_square() {
    for (c, r) in [(1, 1), (3, 2), (5, 7)] {
        let e = c * (r + 1) + r * (c + 1);
        let want = Expect {
            vef: ((c + 1) * (r + 1), e, c * r),
            chi: 1,
            holes: 1,
            islands: 1,
            seams: 0,
            area: 1.0,
        };
        let g = check(
            textured_grid([4.0, 2.0], c, r, &with_materials()).unwrap(),
            want,
        );
        assert_eq!(material_counts(&g), [c * r, 0, 0]);
        for v in g.vertices() {
            let p = g.position(v).unwrap();
            assert!(p[0].abs() <= 2.0 && p[1].abs() <= 1.0 && p[2] == 0.0);
        }
        // Faces look up: the area vector's z of each face is positive.
        let (p, _) = g.to_polygons();
        for f in p.faces() {
            let z: f64 = (0..f.len())
                .map(|k| {
                    let (a, b) = (
                        p.positions[f[k] as usize],
                        p.positions[f[(k + 1) % f.len()] as usize],
                    );
                    a[0] * b[1] - a[1] * b[0]
                })
                .sum();
            assert!(z > 0.0);
        }
    }
}

#[test]
fn uv_sphere_seam_and_poles() {
    for (s, r) in [(3, 2), (4, 3), (7, 5), (16, 8)] {
        let want = Expect {
            vef: (s * (r - 1) + 2, s * (2 * r - 1), s * r),
            chi: 2,
            holes: 0,
            // Two rings: the pole fans meet on the equator only, each
            // pair of triangles an island of its own.
            islands: if r == 2 { s } else { 1 },
            seams: r - 2 + 2 * s,
            area: (r - 1) as f64 / r as f64,
        };
        let m = check(
            textured_uv_sphere(1.5, s, r, &ShapeOptions::default()).unwrap(),
            want,
        );
        // The same sphere as the untextured one, scaled.
        let plain = shapes::uv_sphere(s, r);
        for (a, b) in m.vertices().zip(plain.vertices()) {
            let (p, q) = (m.position(a).unwrap(), plain.position(b).unwrap());
            assert!((0..3).all(|k| (p[k] - 1.5 * q[k]).abs() < 1e-12));
        }
    }
}

#[test]
fn icosphere_net_of_one_island() {
    let tri = 3f64.sqrt() / 121.0; // a net triangle of side 2/11
    for n in 0..=3u32 {
        let k = 4usize.pow(n);
        let want = Expect {
            vef: (10 * k + 2, 30 * k, 20 * k),
            chi: 2,
            holes: 0,
            islands: 1,
            seams: 11 << n,
            area: 20.0 * tri,
        };
        let m = check(
            textured_icosphere(2.0, n, &ShapeOptions::default()).unwrap(),
            want,
        );
        for v in m.vertices() {
            let p = m.position(v).unwrap();
            assert!((crate::vec3::dot(p, p).sqrt() - 2.0).abs() < 1e-12);
        }
    }
}

#[test]
fn torus_is_the_unit_square_once() {
    for (big, small) in [(3, 3), (4, 5), (12, 6), (7, 8)] {
        let want = Expect {
            vef: (big * small, 2 * big * small, big * small),
            chi: 0,
            holes: 0,
            islands: 1,
            seams: big + small,
            area: 1.0,
        };
        check(
            textured_torus(2.0, 0.5, big, small, &ShapeOptions::default()).unwrap(),
            want,
        );
    }
    // The seams are on the −x side and inside the ring, as Blender's.
    let t = textured_torus(2.0, 0.5, 8, 8, &ShapeOptions::default()).unwrap();
    let uv = uv_column(&t);
    for e in t.edges().filter(|&e| is_seam(&t, &uv, e)) {
        let h = t.edge(e).unwrap().halfedge(0);
        let (p, q) = (h.origin().position().unwrap(), h.dest().position().unwrap());
        let inside = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1]).sqrt() < 1.6;
        assert!(
            (p[0] < -1.4 && q[0] < -1.4) || (inside(p) && inside(q)),
            "{p:?} {q:?}"
        );
    }
}

#[test]
fn options_leave_columns_out() {
    let bare = ShapeOptions {
        uv: false,
        ..ShapeOptions::default()
    };
    let b = box_mesh([1.0; 3], &bare).unwrap();
    assert!(b
        .attr_handle::<crate::HalfedgeKey, [f64; 2], Interpolate>(UV)
        .is_err());
    assert!(b
        .attr_handle::<FaceKey, u32, Incompatible>(MATERIAL)
        .is_err());
    let s = textured_uv_sphere(1.0, 6, 4, &with_materials()).unwrap();
    assert_eq!(material_counts(&s), [24, 0, 0]);
}

#[test]
fn invalid_parameters_are_errors() {
    let o = ShapeOptions::default();
    let unsuitable = |r: Result<Mesh>| matches!(r, Err(crate::Error::Unsuitable { key: None, .. }));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(unsuitable(box_mesh([1.0, bad, 1.0], &o)));
        assert!(unsuitable(cylinder(bad, 1.0, 8, &o)));
        assert!(unsuitable(cylinder(1.0, bad, 8, &o)));
        assert!(unsuitable(textured_grid([bad, 1.0], 2, 2, &o)));
        assert!(unsuitable(textured_uv_sphere(bad, 8, 4, &o)));
        assert!(unsuitable(textured_icosphere(bad, 1, &o)));
        assert!(unsuitable(textured_torus(1.0, bad, 8, 4, &o)));
    }
    assert!(unsuitable(cone(0.0, 0.0, 1.0, 8, &o)));
    assert!(unsuitable(cone(-1.0, 1.0, 1.0, 8, &o)));
    for n in [0, 2, MAX_SEGMENTS + 1, usize::MAX] {
        assert!(unsuitable(cylinder(1.0, 1.0, n, &o)));
        assert!(unsuitable(textured_uv_sphere(1.0, n, 4, &o)));
        assert!(unsuitable(textured_torus(1.0, 0.5, 8, n, &o)));
    }
    assert!(unsuitable(textured_grid([1.0; 2], 0, 1, &o)));
    assert!(unsuitable(textured_grid([1.0; 2], 1, usize::MAX, &o)));
    assert!(unsuitable(textured_uv_sphere(1.0, 8, 1, &o)));
    assert!(unsuitable(textured_icosphere(1.0, u32::MAX, &o)));
    // Finite sizes whose positions overflow.
    assert!(unsuitable(textured_torus(f64::MAX, f64::MAX, 8, 4, &o)));
    let e = cylinder(1.0, 1.0, 0, &o).unwrap_err().to_string();
    assert!(e.contains("segments") && e.contains("cylinder"), "{e}");
}

/// A generator's first step: the textured cylinder's top extruded keeps
/// its material and its UVs on the new top; the new walls take the
/// material of the face they were made from (BMesh's rule), the top's.
#[test]
fn extruding_a_textured_cap_keeps_its_columns() {
    let mut c = cylinder(1.0, 1.0, 8, &with_materials()).unwrap();
    let m = c
        .attr_handle::<FaceKey, u32, Incompatible>(MATERIAL)
        .unwrap();
    let uv = uv_column(&c);
    let top = c
        .faces()
        .find(|&f| c.attr(&m, f).unwrap() == Some(&TOP))
        .unwrap();
    let before = face_uvs(&c, &uv, top);
    let opts = crate::model::ExtrudeOptions {
        distance: 0.5,
        ..Default::default()
    };
    let out = c.extrude_faces(&[top], &opts).unwrap();
    c.validate().unwrap();
    assert_eq!(out.top, vec![top]);
    assert_eq!(face_uvs(&c, &uv, top), before);
    assert_eq!(material_counts(&c), [8, 1, 1 + 8]);
}
