//! A flat and a curved grid cut by one seam, through the binary as OBJ: an exact mapping
//! where nothing bends, the outline held by `--keep-border`, the seam closed on a curved
//! surface, and a model that is all seams.

use std::process::Command;

use super::{
    check_layout, check_obj_seam, decimate, distinct_positions, grid_obj, read_obj, seam_vertices,
    welded_edges, Obj,
};

#[test]
fn a_flat_textured_grid_keeps_an_exact_mapping_and_its_seam() {
    let n = 32;
    // 33 × 33 points, the 33 on the seam twice: 1122 vertices.
    let obj = grid_obj(n, |x, y| [x, y, 0.0]);
    for algorithm in ["schroeder", "qem"] {
        let out = decimate(
            &format!("flat-{algorithm}"),
            &obj,
            &["-a", algorithm, "--keep-vertices", "300"],
        );
        assert_eq!(distinct_positions(&out.positions), 300, "{algorithm}");
        check_layout(&out);
        // Flat: no vertex leaves its edge, so each pair is its island's map of the position.
        for (p, uv) in out.positions.iter().zip(&out.texcoords) {
            let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
            assert!(
                (uv[0] - shift - p[0]).abs() < 1e-5 && (uv[1] - p[1]).abs() < 1e-5,
                "{algorithm}: vertex at {p:?} maps to {uv:?}"
            );
        }
        check_obj_seam(&out, n, algorithm);
    }
}

#[test]
fn keep_border_holds_the_outline_but_a_seam_still_simplifies() {
    // The seam down x = 0.5 is two borders in the file (its sides are split by their
    // texture pairs) but none on screen: --keep-border pins the grid's outline, 4 × 32
    // edges on 128 points, and leaves the seam to simplify (its 31 inner points a side).
    let n = 32;
    let obj = grid_obj(n, |x, y| [x, y, 0.1 * (6.0 * x).sin() * (5.0 * y).cos()]);
    let on_outline = |p: &[f32; 3]| p[0] == 0.0 || p[0] == 1.0 || p[1] == 0.0 || p[1] == 1.0;
    let outline = |out: &Obj| {
        let mut points: Vec<[u32; 3]> = (out.positions.iter())
            .filter(|p| on_outline(p))
            .map(|p| p.map(|x| (x + 0.0).to_bits())) // -0 as 0
            .collect();
        points.sort_unstable();
        points.dedup();
        points
    };
    let before = outline(&read_obj(&obj));
    assert_eq!(before.len(), 4 * n);
    for algorithm in ["schroeder", "qem"] {
        let out = decimate(
            &format!("keep-border-{algorithm}"),
            &obj,
            &["-a", algorithm, "-p", "90", "--keep-border"],
        );
        check_layout(&out);
        assert_eq!(outline(&out), before, "{algorithm}: the outline moved");
        // Inside the outline 90 % of everything else went, and the seam with it.
        let inside = out.positions.iter().filter(|p| !on_outline(p)).count();
        assert!(
            inside < 300,
            "{algorithm}: {inside} vertices inside the outline"
        );
        let [left, right] = seam_vertices(&out);
        assert!(
            left == right && left < n / 2,
            "{algorithm}: seam sides of {left} and {right} points"
        );
        check_obj_seam(&out, n, algorithm);
    }
}

#[test]
fn a_curved_textured_surface_stays_closed_along_its_seam() {
    // The larger grid (23k vertices) is collapsed in regions on all cores: a seam collapse
    // there needs both sides in one region.
    for n in [48, 150] {
        curved_surface_stays_closed_along_its_seam(n);
    }
}

fn curved_surface_stays_closed_along_its_seam(n: usize) {
    let obj = grid_obj(n, |x, y| [x, y, 0.2 * (3.0 * x).sin() * (2.0 * y).cos()]);
    for algorithm in ["schroeder", "qem"] {
        let out = decimate(
            &format!("curved-{n}-{algorithm}"),
            &obj,
            &["-a", algorithm, "-p", "80"],
        );
        // 80 % of the points go: exactly, a seam's two sides one point.
        let points = (n + 1) * (n + 1);
        assert_eq!(
            distinct_positions(&out.positions),
            points - (0.8 * points as f64).round() as usize,
            "{algorithm}"
        );
        check_layout(&out);
        // Weld by position: every edge inside the unit square has two triangles, so the
        // seam's two sides still meet along their whole length.
        let edges = welded_edges(&out);
        // Boundary vertices slide along the rim (qem: within its constraint planes); an edge
        // along the rim has both ends near the same side of the square.
        let sides = |v: usize| {
            let p = out.positions[v];
            [p[0], p[0] - 1.0, p[1], p[1] - 1.0].map(|c| c.abs() < 1e-3)
        };
        for (&(a, b), &count) in &edges {
            let (sa, sb) = (sides(a), sides(b));
            let on_rim = (0..4).any(|k| sa[k] && sb[k]);
            let at = [a, b].map(|v| out.positions[v]);
            assert_eq!(
                count,
                if on_rim { 1 } else { 2 },
                "{algorithm}: edge {at:?}"
            );
        }
        check_obj_seam(&out, n, algorithm);
        // The mapping still follows the surface: each pair within one input square of its
        // island's map of the vertex's (x, y).
        let worst = out
            .positions
            .iter()
            .zip(&out.texcoords)
            .map(|(p, uv)| {
                let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
                (uv[0] - shift - p[0]).abs().max((uv[1] - p[1]).abs())
            })
            .fold(0.0f32, f32::max);
        eprintln!("{algorithm}: worst texture shift {worst}");
        assert!(
            worst < 1.0 / n as f32,
            "{algorithm}: texture shifted by {worst}"
        );
    }
}

#[test]
fn a_model_all_seams_says_why_it_stops() {
    // Every triangle of a 4 × 4 grid has texture coordinates of its own: every point is on
    // a seam, so nothing may go, and the summary says why.
    let mut obj = String::new();
    for j in 0..=4 {
        for i in 0..=4 {
            obj += &format!("v {} {} 0\n", i as f32 / 4.0, j as f32 / 4.0);
        }
    }
    let mut k = 0;
    for j in 0..4 {
        for i in 0..4 {
            let a = j * 5 + i + 1;
            for tri in [[a, a + 1, a + 6], [a, a + 6, a + 5]] {
                for _ in tri {
                    obj += &format!("vt {} 0\n", k as f32 * 0.01);
                    k += 1;
                }
                obj += &format!(
                    "f {}/{} {}/{} {}/{}\n",
                    tri[0],
                    k - 2,
                    tri[1],
                    k - 1,
                    tri[2],
                    k
                );
            }
        }
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("in.obj"), obj).unwrap();
    for algorithm in ["schroeder", "qem"] {
        let run = Command::new(env!("CARGO_BIN_EXE_decimate"))
            .arg(dir.path().join("in.obj"))
            .args(["nogui", "-a", algorithm, "-p", "50", "-o"])
            .arg(dir.path().join("out.obj"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{stderr}");
        // 96 corners, each a vertex, at 25 points; all but the two corners of the square
        // that only one triangle touches are on a seam. The two corners at the diagonals' ends have two
        // sides each: pairs that both algorithms would take away together, not pinned (none
        // can go: a lone triangle loses no corner).
        let expected = "fully decimated (90 vertices are pinned on texture seams or borders)";
        assert!(
            stderr.contains("vertices 25 -> 25")
                && stderr.contains("(96 -> 96 vertices with texture-seam copies)")
                && stderr.contains(expected),
            "{algorithm}: {stderr}"
        );
    }
}
