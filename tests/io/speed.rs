//! Read-speed check, ignored by default (it needs big files and a release build):
//! `DECIMATE_SPEED_FILES=a.wrl:b.ply cargo test --release --test io speed:: -- --ignored
//! --nocapture`
//! prints the time to read each file. Without the variable it builds a 1M-triangle VRML 2.0
//! grid in memory and requires it to parse within a generous bound.

use decimate_core::io::{parse_bytes, read_scene};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

#[test]
#[ignore = "timing; run in release with --ignored"]
fn read_speed() {
    if let Ok(list) = std::env::var("DECIMATE_SPEED_FILES") {
        for f in list.split(':') {
            let t = Instant::now();
            let s = read_scene(Path::new(f))
                .unwrap_or_else(|e| panic!("{e}"))
                .scene;
            println!(
                "{f}: {} vertices, {} triangles in {:.3} s",
                s.vertex_count(),
                s.triangle_count(),
                t.elapsed().as_secs_f64()
            );
        }
        return;
    }
    let (nu, nv) = (1001u32, 501u32);
    let mut src = String::from(
        "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [\n",
    );
    for j in 0..nv {
        for i in 0..nu {
            let _ = writeln!(
                src,
                "{} {} {},",
                i as f32 * 0.01,
                j as f32 * 0.01,
                ((i * j) % 97) as f32 * 0.001
            );
        }
    }
    src.push_str("] }\n coordIndex [\n");
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            let a = j * nu + i;
            let _ = writeln!(
                src,
                "{a} {} {} -1 {a} {} {} -1",
                a + 1,
                a + nu + 1,
                a + nu + 1,
                a + nu
            );
        }
    }
    src.push_str("] } }\n");
    let t = Instant::now();
    let s = parse_bytes(src.into_bytes(), Path::new("grid.wrl"))
        .unwrap()
        .scene;
    let secs = t.elapsed().as_secs_f64();
    println!("grid.wrl: {} triangles in {secs:.3} s", s.triangle_count());
    assert_eq!(s.triangle_count(), 1_000_000);
    assert!(secs < 5.0, "1M triangles took {secs:.2} s");
}
