//! Golden screenshots on lavapipe, one per draw mode, of a 10×10-segment cube (test004's
//! shape) built in code, plus what a user would notice: the model fills a sensible part of
//! the picture, the corners show the background, each mode looks different — except smooth
//! and flat shading of a cube, which must look the same (its edges are creases), while on a
//! sphere they must not.

use crate::support::shot::*;

const MODES: [&str; 8] = [
    "triangles",
    "triangles,flat",
    "triangles,unlit",
    "edges",
    "triangles,edges",
    "points",
    "triangles,normals",
    "triangles,vertex-normals",
];

#[test]
fn every_draw_mode_matches_its_golden() {
    let scene = cube(10);
    for mode in MODES {
        let image = render(&scene, 1, modes(mode), None);
        assert_background_corners(&image);
        let covered = coverage(&image, 0, 0, WIDTH, HEIGHT);
        // Filled modes cover the cube's silhouette; lines and points leave gaps between them.
        let least = if mode.starts_with("triangles") {
            0.2
        } else {
            0.05
        };
        assert!(
            (least..0.8).contains(&covered),
            "{mode}: the model covers {:.0} % of the picture",
            covered * 100.0
        );
        assert_matches_golden(&format!("cube10_{}", mode.replace(',', "_")), &image);
    }
}

#[test]
fn each_mode_looks_different_from_the_others() {
    let scene = cube(10);
    let images: Vec<_> = MODES
        .iter()
        .map(|m| render(&scene, 1, modes(m), None))
        .collect();
    for i in 0..MODES.len() {
        for j in i + 1..MODES.len() {
            let d = different_fraction(&images[i], &images[j], CHANNEL_TOLERANCE);
            if (MODES[i], MODES[j]) == ("triangles", "triangles,flat") {
                // Smooth shading keeps creases sharp: a cube's faces stay flat.
                assert!(
                    d < 0.005,
                    "a smooth-shaded cube looks rounded ({:.2} % differ from flat)",
                    d * 100.0
                );
                continue;
            }
            assert!(
                d > 0.01,
                "{} and {} look alike ({:.2} % differ)",
                MODES[i],
                MODES[j],
                d * 100.0
            );
        }
    }
}

#[test]
fn smooth_and_flat_shading_differ_on_a_sphere() {
    // A coarse sphere, compared closely: facets differ by a few levels of grey.
    let scene = sphere(6, 12, glam::Mat4::IDENTITY);
    let smooth = render(&scene, 1, modes("triangles"), None);
    let flat = render(&scene, 1, modes("triangles,flat"), None);
    let d = different_fraction(&smooth, &flat, 4);
    assert!(
        d > 0.05,
        "smooth and flat spheres look alike ({:.2} % differ)",
        d * 100.0
    );
}

#[test]
fn edges_alone_show_the_background_between_them() {
    let scene = cube(10);
    let solid = render(&scene, 1, modes("triangles"), None);
    let wire = render(&scene, 1, modes("edges"), None);
    // At the centre the solid cube is opaque; the wireframe lets the background through.
    let solid_centre = coverage(&solid, 140, 100, 180, 140);
    let wire_centre = coverage(&wire, 140, 100, 180, 140);
    assert!(solid_centre > 0.99, "solid centre covered {solid_centre}");
    assert!(wire_centre < 0.6, "wireframe centre covered {wire_centre}");
}

/// A floor: a 20 × 20 grid of quads in y = 0, seen from the default view's slight height,
/// so its triangles lie at a grazing angle to the eye.
fn floor() -> decimate_core::mesh::Scene {
    let n = 20u32;
    let mut m = decimate_core::mesh::Model {
        diffuse: [0.6, 0.6, 0.6],
        ..Default::default()
    };
    for j in 0..=n {
        for i in 0..=n {
            m.positions.push(glam::Vec3::new(i as f32, 0.0, j as f32));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            m.triangles.push([v, v + n + 2, v + 1]);
            m.triangles.push([v, v + n + 1, v + n + 2]);
        }
    }
    decimate_core::mesh::Scene { models: vec![m] }
}

#[test]
fn edges_over_a_grazing_surface_are_unbroken() {
    // Every edge of a floor is on its visible surface: drawn over the triangles, each must
    // show as fully as drawn alone — a surface poking through the lines would dash them.
    let scene = floor();
    let alone = render(&scene, 1, modes("edges"), None);
    let over = render(&scene, 1, modes("triangles,edges"), None);
    let (light, dark) = ([217, 224, 242, 255], [13, 13, 20, 255]);
    let (mut drawn, mut kept) = (0usize, 0usize);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            if close(pixel(&alone, x, y), light, 40) {
                drawn += 1;
                kept += usize::from(close(pixel(&over, x, y), dark, 40));
            }
        }
    }
    assert!(drawn > 2000, "only {drawn} edge pixels drawn alone");
    let share = kept as f64 / drawn as f64;
    assert!(
        share > 0.97,
        "{:.1} % of the edge pixels show over the surface",
        share * 100.0
    );
    assert_matches_golden("floor_triangles_edges", &over);
}

/// A UV sphere split along the meridian facing the camera as a texture seam splits it: the
/// vertices there have a second copy, used by the faces on one side, with u = 1 instead of 0.
fn seamed_sphere() -> (decimate_core::mesh::Scene, decimate_core::mesh::Scene) {
    let (rings, segments) = (16u32, 32u32);
    let mut whole = decimate_core::mesh::shapes::uv_sphere(rings, segments);
    whole.diffuse = [0.45, 0.65, 0.85];
    let n = whole.positions.len() as u32;
    let column = |v: u32| (v != 0 && v != n - 1).then(|| (v - 1) % segments);
    // The meridian at phi = 270°, which faces +z, the default view's side.
    let seam = segments * 3 / 4;
    let uv = |v: u32| {
        let p = whole.positions[v as usize];
        let u = column(v).map_or(0.5, |s| s as f32 / segments as f32);
        [u, 0.5 + 0.5 * p.y]
    };
    let mut split = whole.clone();
    split.texcoords = Some((0..n).map(uv).collect());
    let mut copy = std::collections::HashMap::new();
    for v in (0..n).filter(|&v| column(v) == Some(seam)) {
        copy.insert(v, split.positions.len() as u32);
        split.positions.push(whole.positions[v as usize]);
        if let Some(t) = &mut split.texcoords {
            t.push([1.0, uv(v)[1]]);
        }
    }
    for t in &mut split.triangles {
        if t.iter().any(|&v| column(v) == Some(seam - 1)) {
            for v in t.iter_mut() {
                *v = copy.get(v).copied().unwrap_or(*v);
            }
        }
    }
    let scene = |m| decimate_core::mesh::Scene { models: vec![m] };
    (scene(whole), scene(split))
}

#[test]
fn a_texture_seam_does_not_show_in_the_shading() {
    // Texture off: the seamed sphere must look exactly like the whole one, smooth or flat.
    let (whole, seamed) = seamed_sphere();
    assert_eq!(
        seamed.models[0].positions.len(),
        whole.models[0].positions.len() + 15
    );
    for mode in ["triangles,untextured", "triangles,untextured,flat"] {
        let a = render(&whole, 1, modes(mode), None);
        let b = render(&seamed, 1, modes(mode), None);
        let differ = different_fraction(&a, &b, 3);
        assert!(
            differ < 0.0005,
            "{mode}: {:.2} % of the pixels show the seam",
            differ * 100.0
        );
    }
    let image = render(&seamed, 1, modes("triangles,untextured"), None);
    assert_matches_golden("sphere_seamed_smooth", &image);
}
