//! Per-vertex colours under quadric edge collapse: a smooth colour field and a sharp jump
//! on a sphere kept at 952 triangles, each output vertex (and each output triangle's
//! centre) compared with the input's colour at the nearest point of the input surface,
//! found here by brute force. The bars are VTK's `vtkQuadricDecimation` (attribute error
//! metric and volume preservation on) on the same spheres, measured the same way.

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::mesh::{shapes, Attribute, Model, Scene};
use glam::{DVec3, Vec3};

/// The sphere: `shapes::uv_sphere(80, 120)`, 18960 triangles.
fn sphere(colour: impl Fn(Vec3) -> [f32; 3]) -> Model {
    let mut m = shapes::uv_sphere(80, 120);
    m.colors = Some(Attribute::PerVertex(
        m.positions.iter().map(|&p| colour(p)).collect(),
    ));
    m
}

/// A smooth field: red and green trade places along waves over the sphere.
fn smooth(p: Vec3) -> [f32; 3] {
    let f = 0.5 + 0.5 * (3.0 * p.x).sin() * (2.0 * p.y + p.z).cos();
    [f, 1.0 - f, 0.5 * f]
}

/// A jump: one colour above z = 0.3, another below.
fn jump(p: Vec3) -> [f32; 3] {
    let f = if p.z > 0.3 { 1.0 } else { 0.0 };
    [f, 0.2 + 0.5 * f, 1.0 - f]
}

fn qem_to_952(model: Model) -> Model {
    let mut scene = Scene {
        models: vec![model],
    };
    let params = Params {
        target: Target::KeepTriangles(952),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

/// The point of triangle `t` nearest `p` as barycentric weights (Ericson, "Real-Time
/// Collision Detection", 5.1.5), with its squared distance.
fn nearest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> ([f64; 3], f64) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    let (va, vb, vc) = (d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2);
    let w = if d1 <= 0.0 && d2 <= 0.0 {
        [1.0, 0.0, 0.0]
    } else if d3 >= 0.0 && d4 <= d3 {
        [0.0, 1.0, 0.0]
    } else if d6 >= 0.0 && d5 <= d6 {
        [0.0, 0.0, 1.0]
    } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        [1.0 - t, t, 0.0]
    } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        [1.0 - t, 0.0, t]
    } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        [0.0, 1.0 - t, t]
    } else {
        let s = va + vb + vc;
        [va / s, vb / s, vc / s]
    };
    let q = a * w[0] + b * w[1] + c * w[2];
    (w, (q - p).length_squared())
}

fn vertex_colours(m: &Model) -> &[[f32; 3]] {
    match &m.colors {
        Some(Attribute::PerVertex(c)) => c,
        other => panic!("{}: colours not per vertex: {other:?}", m.name),
    }
}

/// The input's colour at the point of its surface nearest `p`.
fn colour_near(input: &Model, p: DVec3) -> DVec3 {
    let colours = vertex_colours(input);
    let mut best = (f64::INFINITY, DVec3::ZERO);
    for tri in &input.triangles {
        let corners = tri.map(|v| input.positions[v as usize].as_dvec3());
        let (w, d2) = nearest_on_triangle(p, corners);
        if d2 < best.0 {
            let c = |i: usize| Vec3::from(colours[tri[i] as usize]).as_dvec3();
            best = (d2, c(0) * w[0] + c(1) * w[1] + c(2) * w[2]);
        }
    }
    best.1
}

/// Mean and max colour error (RGB distance) over the output's vertices, and over its
/// triangles' centres (colours interpolated there), against the input's.
fn colour_errors(input: &Model, output: &Model) -> ([f64; 2], [f64; 2]) {
    let colours = vertex_colours(output);
    let colour = |v: u32| Vec3::from(colours[v as usize]).as_dvec3();
    let position = |v: u32| output.positions[v as usize].as_dvec3();
    let at_vertices: Vec<f64> = (0..output.positions.len() as u32)
        .map(|v| (colour(v) - colour_near(input, position(v))).length())
        .collect();
    let at_centres: Vec<f64> = (output.triangles.iter())
        .map(|t| {
            let p = t.iter().map(|&v| position(v)).sum::<DVec3>() / 3.0;
            let c = t.iter().map(|&v| colour(v)).sum::<DVec3>() / 3.0;
            (c - colour_near(input, p)).length()
        })
        .collect();
    let summary = |e: &[f64]| {
        let mean = e.iter().sum::<f64>() / e.len() as f64;
        [mean, e.iter().copied().fold(0.0, f64::max)]
    };
    (summary(&at_vertices), summary(&at_centres))
}

/// Decimates `input` and checks its colour errors against VTK's (`[mean, max]` at the
/// vertices, then at the triangles' centres).
fn assert_colours_within(input: Model, vtk_vertices: [f64; 2], vtk_centres: [f64; 2]) {
    let output = qem_to_952(input.clone());
    assert_eq!(output.triangles.len(), 952);
    let (vertices, centres) = colour_errors(&input, &output);
    println!("vertices {vertices:?} centres {centres:?}");
    for (what, ours, vtk) in [
        ("vertices", vertices, vtk_vertices),
        ("centres", centres, vtk_centres),
    ] {
        assert!(
            ours[0] <= vtk[0] && ours[1] <= vtk[1],
            "colour error at the {what}: mean {} max {} against VTK's {} {}",
            ours[0],
            ours[1],
            vtk[0],
            vtk[1]
        );
    }
}

// VTK 9 (python3-vtk9), vtkQuadricDecimation with AttributeErrorMetricOn and
// VolumePreservationOn, target reduction to 952 triangles, on the same sphere and colours,
// measured as here (2026-12-07): smooth 0.00408 / 0.0157 at the vertices, 0.00521 / 0.0199
// at the centres; jump 0.00188 / 0.234 and 0.00237 / 0.201.

#[test]
fn a_smooth_colour_field_stays_as_close_as_vtk_keeps_it() {
    assert_colours_within(sphere(smooth), [0.00408, 0.0157], [0.00521, 0.0199]);
}

#[test]
fn a_colour_jump_stays_as_sharp_as_vtk_keeps_it() {
    assert_colours_within(sphere(jump), [0.00188, 0.234], [0.00237, 0.201]);
}
