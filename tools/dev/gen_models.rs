//! `gen-models`: writes the report's test models (test001–test008) and large synthetic meshes
//! for benchmarks, from `decimate_core::mesh::shapes`.
//!
//! ```text
//! gen-models assets DIR                      test001.wrl … test008.wrl into DIR
//! gen-models sphere RINGS SEGMENTS FILE      a bumpy sphere (.ply or .wrl by extension)
//! gen-models ribbon N FILE                   a strip of N vertices, every one on the border
//! gen-models fan N FILE                      a cone whose apex has N neighbours
//! gen-models polygon N FILE                  one convex N-gon in an IndexedFaceSet (.wrl)
//! gen-models star N FILE                     one star-shaped N-gon in an IndexedFaceSet (.wrl)
//! gen-models nesting N FILE                  a triangle under N nested Separators (.wrl)
//! gen-models subdivide IN OUT.ply LEVELS     every triangle of IN split 1→4 LEVELS times
//! ```
//!
//! ribbon … nesting are `tools/bench/scaling`'s inputs: each stresses one path that must stay
//! near-linear (long borders, huge fans, one giant polygon, deep scene graphs). `subdivide`
//! makes the big meshes of `tools/bench/tiles` and `tools/bench/memory` (the Stanford dragon:
//! 13.9M triangles at 2 levels, 55.8M at 3) as a binary PLY of positions and triangles only;
//! LEVELS 0 just converts IN to that form.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use decimate_core::io;
use decimate_core::mesh::{shapes, Model, Scene};

fn write(model: Model, path: &Path) -> Result<(), String> {
    let scene = Scene {
        models: vec![model],
    };
    let ply = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ply"));
    let result = if ply {
        io::write_ply(&scene, path)
    } else {
        io::write_vrml2(&scene, path)
    };
    result.map_err(|e| e.to_string())?;
    println!("wrote {}", path.display());
    Ok(())
}

/// A strip of `n` vertices in two rows along x, gently waved in z so that removals have
/// errors to rank: every vertex is on the border.
fn ribbon(n: u32) -> Model {
    let m = (n / 2).max(2);
    let mut model = Model {
        name: "ribbon".into(),
        ..Model::default()
    };
    for row in 0..2 {
        for i in 0..m {
            let x = i as f32 * 0.1;
            let z = 0.05 * (i as f32 * 0.37).sin() + 0.02 * (i as f32 * 1.7 + row as f32).sin();
            model.positions.push(glam::Vec3::new(x, row as f32, z));
        }
    }
    for i in 0..m - 1 {
        let (a, b, c, d) = (i, i + 1, m + i, m + i + 1);
        model.triangles.extend([[a, b, d], [a, d, c]]);
    }
    model
}

/// A low cone whose apex is joined to `n` rim vertices (a rim slightly waved in z).
fn fan(n: u32) -> Model {
    let n = n.max(3);
    let mut model = Model {
        name: "fan".into(),
        ..Model::default()
    };
    model.positions.push(glam::Vec3::new(0.0, 0.0, 0.2));
    for i in 0..n {
        let t = std::f32::consts::TAU * i as f32 / n as f32;
        let z = 0.01 * (i as f32 * 0.7).sin();
        model.positions.push(glam::Vec3::new(t.cos(), t.sin(), z));
    }
    for i in 0..n {
        model.triangles.push([0, 1 + i, 1 + (i + 1) % n]);
    }
    model
}

/// VRML 2.0 text of one IndexedFaceSet face over `n` corners on a circle (every other one
/// pulled in to `inner` of the radius: 1 gives a convex polygon).
fn polygon_vrml(n: u32, inner: f64) -> String {
    let mut s = String::from(
        "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [\n",
    );
    for i in 0..n {
        let t = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        let r = if i % 2 == 1 { inner } else { 1.0 };
        s += &format!("{} {} 0,\n", r * t.cos(), r * t.sin());
    }
    s += "] }\n coordIndex [\n";
    for i in 0..n {
        s += &format!("{i} ");
        if i % 16 == 15 {
            s.push('\n');
        }
    }
    s += "-1 ]\n} }\n";
    s
}

/// Inventor text of one triangle under `n` nested Separators.
fn nesting_iv(n: u32) -> String {
    let mut s = String::from("#Inventor V2.1 ascii\n");
    for _ in 0..n {
        s += "Separator {\n";
    }
    s += "Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\nIndexedFaceSet { coordIndex [ 0, 1, 2, -1 ] }\n";
    for _ in 0..n {
        s += "}\n";
    }
    s
}

fn write_text(text: &str, path: &Path) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// `model` with every triangle split 1→4 at its edges' midpoints: each edge's midpoint once
/// (edges sorted by their ends, numbered after the corners), then the triangles at the first,
/// second and third corners and the middle ones. One sort of the edges: O(n log n).
fn subdivide(model: &Model) -> Model {
    let key = |a: u32, b: u32| (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
    let mut edges: Vec<u64> = (model.triangles.iter())
        .flat_map(|&[a, b, c]| [key(a, b), key(b, c), key(c, a)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let n = model.positions.len() as u32;
    let mut positions = model.positions.clone();
    positions.extend(edges.iter().map(|&e| {
        let (a, b) = (
            model.positions[(e >> 32) as usize],
            model.positions[e as u32 as usize],
        );
        ((a.as_dvec3() + b.as_dvec3()) * 0.5).as_vec3()
    }));
    // Every key is in `edges`, so the search finds it.
    let mid = |a: u32, b: u32| n + edges.binary_search(&key(a, b)).unwrap_or(0) as u32;
    let split: Vec<[u32; 3]> = (model.triangles.iter())
        .map(|&[a, b, c]| [mid(a, b), mid(b, c), mid(c, a)])
        .collect();
    let mut triangles = Vec::with_capacity(4 * split.len());
    let corners = model.triangles.iter().zip(&split);
    triangles.extend(corners.clone().map(|(t, m)| [t[0], m[0], m[2]]));
    triangles.extend(corners.clone().map(|(t, m)| [m[0], t[1], m[1]]));
    triangles.extend(corners.map(|(t, m)| [m[2], m[1], t[2]]));
    triangles.extend(split);
    Model {
        name: model.name.clone(),
        transform: model.transform,
        positions,
        triangles,
        ..Model::default()
    }
}

/// `gen-models subdivide`: reads IN (any format `decimate` reads), splits every model's
/// triangles `levels` times and writes OUT, positions and triangles only.
fn subdivide_file(input: &Path, output: &Path, levels: u32) -> Result<(), String> {
    let scene = io::read_scene(input).map_err(|e| e.to_string())?.scene;
    let models = (scene.models.iter())
        .map(|m| {
            let mut m = Model {
                name: m.name.clone(),
                transform: m.transform,
                positions: m.positions.clone(),
                triangles: m.triangles.clone(),
                ..Model::default()
            };
            for _ in 0..levels {
                m = subdivide(&m);
            }
            m
        })
        .collect();
    io::write_ply(&Scene { models }, output).map_err(|e| e.to_string())?;
    println!("wrote {}", output.display());
    Ok(())
}

fn run(args: &[String]) -> Result<(), String> {
    let usage = "usage: gen-models assets DIR | gen-models sphere RINGS SEGMENTS FILE | \
                 gen-models ribbon|fan|polygon|star|nesting N FILE | \
                 gen-models subdivide IN OUT.ply LEVELS";
    let count = |s: &str| {
        s.parse::<u32>()
            .map_err(|_| format!("not a count: '{s}'\n{usage}"))
    };
    match args {
        [cmd, dir] if cmd == "assets" => {
            let dir = PathBuf::from(dir);
            std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            for model in shapes::all() {
                let path = dir.join(format!("{}.wrl", model.name));
                write(model, &path)?;
            }
            Ok(())
        }
        [cmd, rings, segments, file] if cmd == "sphere" => write(
            shapes::bumpy_sphere(count(rings)?, count(segments)?),
            Path::new(file),
        ),
        [cmd, input, output, levels] if cmd == "subdivide" => {
            subdivide_file(Path::new(input), Path::new(output), count(levels)?)
        }
        [cmd, n, file] => {
            let (n, path) = (count(n)?, Path::new(file));
            match cmd.as_str() {
                "ribbon" => write(ribbon(n), path),
                "fan" => write(fan(n), path),
                "polygon" => write_text(&polygon_vrml(n, 1.0), path),
                "star" => write_text(&polygon_vrml(n, 0.6), path),
                "nesting" => write_text(&nesting_iv(n), path),
                _ => Err(usage.to_string()),
            }
        }
        _ => Err(usage.to_string()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gen-models: {e}");
            ExitCode::from(2)
        }
    }
}
