//! Renderer tests: coverage, colours, errors.

use super::*;
use meshloom::shapes;

fn small(view: View) -> RenderOptions {
    RenderOptions {
        width: 80,
        height: 60,
        view,
        ..RenderOptions::default()
    }
}

#[test]
fn cube_covers_the_middle_not_the_corners() {
    for view in [
        View::Iso,
        View::Front,
        View::Top,
        View::Direction([-1.0, -2.0, 0.5]),
    ] {
        let o = small(view);
        let img = render(&shapes::cube(), &o).unwrap();
        let bg = o.colors.background;
        assert_ne!(img.pixel(40, 30), Some(bg), "{view}");
        for (x, y) in [(0, 0), (79, 0), (0, 59), (79, 59)] {
            assert_eq!(img.pixel(x, y), Some(bg), "{view} corner {x},{y}");
        }
    }
}

#[test]
fn front_view_of_cube_is_one_flat_square() {
    // Seen along z the cube is a square filling the height minus margins;
    // every pixel inside has the same colour under flat shading.
    let o = RenderOptions {
        shading: Shading::Flat,
        supersample: 1,
        ..small(View::Front)
    };
    let img = render(&shapes::cube(), &o).unwrap();
    let centre = img.pixel(40, 30).unwrap();
    for (x, y) in [(25, 15), (54, 15), (25, 44), (54, 44)] {
        assert_eq!(img.pixel(x, y), Some(centre), "{x},{y}");
    }
    assert_eq!(img.pixel(10, 30), Some(o.colors.background));
}

#[test]
fn open_mesh_shows_boundary_colour() {
    // A cube without its top: the rim is boundary.
    let p: Vec<[f64; 3]> = (0..8u32)
        .map(|i| {
            [
                f64::from(i & 1),
                f64::from((i >> 1) & 1),
                f64::from((i >> 2) & 1),
            ]
        })
        .collect();
    let faces = [
        [0u32, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mesh = Mesh::from_polygons(&p, &faces).unwrap();
    let with = RenderOptions {
        boundary: true,
        ..small(View::Iso)
    };
    let red = with.colors.boundary;
    let img = render(&mesh, &with).unwrap();
    let count = |img: &Image| img.as_rgb().chunks(3).filter(|c| *c == red).count();
    assert!(count(&img) > 20, "boundary pixels: {}", count(&img));
    let without = render(&mesh, &small(View::Iso)).unwrap();
    assert_eq!(count(&without), 0);
    // The inside is seen through the opening: back colour appears.
    let brownish = img
        .as_rgb()
        .chunks(3)
        .filter(|c| u16::from(c[0]) > u16::from(c[2]) + 40)
        .count();
    assert!(brownish > 20);
}

#[test]
fn wireframe_draws_lines_in_the_wire_colour() {
    let o = RenderOptions {
        wireframe: true,
        ..small(View::Iso)
    };
    let wire = o.colors.wire;
    let near_wire = |img: &Image| {
        img.as_rgb()
            .chunks(3)
            .filter(|c| c.iter().zip(wire).all(|(&a, b)| a.abs_diff(b) < 16))
            .count()
    };
    let img = render(&shapes::icosahedron(), &o).unwrap();
    assert!(near_wire(&img) > 50, "wire pixels: {}", near_wire(&img));
    let plain = render(&shapes::icosahedron(), &small(View::Iso)).unwrap();
    assert_eq!(near_wire(&plain), 0);
}

#[test]
fn non_convex_polygon_leaves_its_notch_empty() {
    // An L-shape in the z = 0 plane: the notch at the top right stays
    // background.
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&p, &[[2u32, 3, 4, 5, 0, 1]]).unwrap();
    let o = RenderOptions {
        width: 100,
        height: 100,
        supersample: 1,
        ..small(View::Front)
    };
    let img = render(&mesh, &o).unwrap();
    let bg = o.colors.background;
    assert_ne!(img.pixel(25, 75), Some(bg)); // lower left square
    assert_ne!(img.pixel(75, 75), Some(bg)); // lower right square
    assert_ne!(img.pixel(25, 25), Some(bg)); // upper left square
    assert_eq!(img.pixel(75, 25), Some(bg)); // the notch
}

#[test]
fn empty_and_topology_only_meshes_are_errors() {
    let o = RenderOptions::default();
    assert!(matches!(render(&Mesh::new(), &o), Err(RenderError::Empty)));
    let topo = Mesh::from_faces(3, &[[0u32, 1, 2]]).unwrap();
    let err = render(&topo, &o).unwrap_err();
    assert!(matches!(err, RenderError::NoPositions));
    assert!(err.to_string().contains("positions"));
}

#[test]
fn bad_options_are_errors() {
    let cube = shapes::cube();
    let zero = RenderOptions {
        width: 0,
        ..RenderOptions::default()
    };
    assert!(matches!(
        render(&cube, &zero),
        Err(RenderError::Size { .. })
    ));
    let degenerate = RenderOptions {
        view: View::Direction([0.0, 0.0, 0.0]),
        ..RenderOptions::default()
    };
    assert!(matches!(
        render(&cube, &degenerate),
        Err(RenderError::View { .. })
    ));
}

#[test]
fn flat_mesh_seen_edge_on_does_not_panic() {
    let square = Mesh::from_polygons(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        &[[0u32, 1, 2, 3]],
    )
    .unwrap();
    let img = render(&square, &small(View::Right)).unwrap();
    assert_eq!(img.width(), 80);
}

#[test]
fn png_round_trip_has_the_right_size() {
    let img = render(&shapes::tetrahedron(), &small(View::Iso)).unwrap();
    let mut bytes = Vec::new();
    img.encode_png(&mut bytes).unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    assert_eq!((info.width, info.height), (80, 60));
}

#[test]
fn view_names_round_trip() {
    for name in VIEW_NAMES {
        let v: View = name.parse().unwrap();
        assert_eq!(v.to_string(), name);
    }
}

#[test]
fn diverging_map_runs_blue_white_red() {
    assert_eq!(diverging(0.0), [242.0, 242.0, 242.0]);
    assert_eq!(diverging(f64::NAN), diverging(0.0));
    assert_eq!(diverging(-1.0), [59.0, 76.0, 192.0]);
    assert_eq!(diverging(-7.0), diverging(-1.0)); // saturates
    assert_eq!(diverging(1.0), [180.0, 4.0, 38.0]);
    let half = diverging(0.5);
    assert!(half[0] > half[2] && half[0] < 242.0);
}

#[test]
fn curvature_range_ignores_the_top_two_percent() {
    // 98 values of 1 and two wild ones: the range is 1, not 1000.
    let values =
        (0..98)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .chain([1000.0, -1000.0, f64::NAN]);
    assert_eq!(symmetric_range(values), 1.0);
    assert_eq!(symmetric_range([0.0, 0.0].into_iter()), 1.0);
    assert_eq!(symmetric_range(std::iter::empty()), 1.0);
}

#[test]
fn a_sphere_in_curvature_colours_is_red() {
    // Convex everywhere (H > 0): the middle pixel is red, not the plain
    // blue-grey; the background stays.
    let mesh = shapes::icosphere(3);
    let o = RenderOptions {
        coloring: Coloring::Curvature,
        ..small(View::Front)
    };
    let img = render(&mesh, &o).unwrap();
    let [r, g, b] = img.pixel(40, 30).unwrap();
    assert!(r > g && r > b, "{:?}", [r, g, b]);
    assert_eq!(img.pixel(0, 0), Some(o.colors.background));
    let plain = render(&mesh, &small(View::Front)).unwrap();
    let [r, _, b] = plain.pixel(40, 30).unwrap();
    assert!(b > r);
}
