//! Printing a Metro [`Comparison`] (Cignoni, Rocchini, Scopigno, "Metro: measuring error on
//! simplified surfaces", Computer Graphics Forum 17(2), 1998): a table for people and JSON for
//! scripts.
//!
//! Owns the output formats (the folded-triangle count only when it was measured). Both are deterministic: the same comparison prints the same bytes
//! (timings are not part of either; the binary prints them on standard error).

use std::fmt::Write as _;

use super::{Comparison, DirectionStats, SurfaceInfo};

/// A human-readable report; `names` are the two inputs as the user gave them.
pub fn table(c: &Comparison, names: [&str; 2]) -> String {
    let mut s = String::new();
    surfaces_table(&mut s, c, names);
    distances_table(&mut s, c);
    hausdorff_lines(&mut s, c);
    if let Some(f) = &c.folds {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "folded triangles of B over A: {} ({:.4} % of B's area); degenerate: {}",
            f.triangles,
            100.0 * f.area_fraction,
            f.degenerate
        );
        let _ = writeln!(
            s,
            "   {} triangles checked with {} samples",
            f.checked, f.samples
        );
        if let Some(p) = f.largest_at {
            let _ = writeln!(
                s,
                "   the largest at ({}, {}, {})",
                num(p.x),
                num(p.y),
                num(p.z)
            );
        }
    }
    s
}

/// The two surfaces, the diagonal and the samples taken.
fn surfaces_table(s: &mut String, c: &Comparison, names: [&str; 2]) {
    for (label, name, info) in [("A", names[0], &c.a), ("B", names[1], &c.b)] {
        let _ = writeln!(s, "{label}: {name}");
        let _ = writeln!(
            s,
            "   {} triangles, {} vertices, {} {}, area {}, {}",
            info.triangles,
            info.vertices,
            info.components,
            if info.components == 1 {
                "piece"
            } else {
                "pieces"
            },
            num(info.area),
            volume_text(info)
        );
        if info.skipped_triangles > 0 {
            let _ = writeln!(
                s,
                "   {} degenerate triangles ignored",
                info.skipped_triangles
            );
        }
    }
    let _ = writeln!(
        s,
        "bounding-box diagonal of A: {} (relative errors are fractions of it)",
        num(c.diagonal)
    );
    let _ = writeln!(
        s,
        "samples (face + edge + vertex): A->B {}, B->A {}; seed {}",
        sample_text(&c.a_to_b),
        sample_text(&c.b_to_a),
        c.seed
    );
}

/// The distances both ways and symmetric: max, mean and RMS with their share of the
/// diagonal.
fn distances_table(s: &mut String, c: &Comparison) {
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:<11} {:>26} {:>26} {:>26}",
        "distance", "max", "mean", "RMS"
    );
    let row = |s: &mut String, label: &str, max: f64, mean: f64, rms: f64| {
        let cell = |v: f64| format!("{} ({:.4} %)", num(v), 100.0 * c.relative(v));
        let _ = writeln!(
            s,
            "{label:<11} {:>26} {:>26} {:>26}",
            cell(max),
            cell(mean),
            cell(rms)
        );
    };
    row(s, "A->B", c.a_to_b.max, c.a_to_b.mean, c.a_to_b.rms);
    row(s, "B->A", c.b_to_a.max, c.b_to_a.mean, c.b_to_a.rms);
    let sym = c.symmetric();
    row(s, "symmetric", sym.max, sym.mean, sym.rms);
    let _ = writeln!(s);
}

/// The Hausdorff distance and where it is reached.
fn hausdorff_lines(s: &mut String, c: &Comparison) {
    let _ = writeln!(
        s,
        "Hausdorff distance: {} ({:.4} % of the diagonal)",
        num(c.hausdorff()),
        100.0 * c.relative(c.hausdorff())
    );
    let farthest = if c.a_to_b.max >= c.b_to_a.max {
        ("A", c.a_to_b.max_at)
    } else {
        ("B", c.b_to_a.max_at)
    };
    let _ = writeln!(
        s,
        "   reached at the sample of {} at ({}, {}, {})",
        farthest.0,
        num(farthest.1.x),
        num(farthest.1.y),
        num(farthest.1.z)
    );
}

fn num(v: f64) -> String {
    format!("{v:.6e}")
}

fn sample_text(d: &DirectionStats) -> String {
    format!(
        "{} + {} + {}",
        d.face_samples, d.edge_samples, d.vertex_samples
    )
}

fn volume_text(info: &SurfaceInfo) -> String {
    match info.volume {
        Some(v) => format!("volume {} (closed)", num(v)),
        None if info.nonmanifold_edges > 0 => format!(
            "no volume (open: {} boundary, {} non-manifold edges)",
            info.boundary_edges, info.nonmanifold_edges
        ),
        None if info.boundary_edges > 0 => {
            format!("no volume (open: {} boundary edges)", info.boundary_edges)
        }
        None => "no volume (inconsistently oriented)".to_string(),
    }
}

/// A JSON object with every number of the comparison.
pub fn json(c: &Comparison, names: [&str; 2]) -> String {
    let mut s = String::from("{\n");
    for (key, name, info) in [("a", names[0], &c.a), ("b", names[1], &c.b)] {
        json_surface(&mut s, key, name, info);
    }
    let _ = writeln!(s, "  \"diagonal\": {},", float(c.diagonal));
    let _ = writeln!(s, "  \"seed\": {},", c.seed);
    for (key, d) in [("a_to_b", &c.a_to_b), ("b_to_a", &c.b_to_a)] {
        json_direction(&mut s, c, key, d);
    }
    json_symmetric(&mut s, c);
    if let Some(f) = &c.folds {
        json_folds(&mut s, f);
    }
    let _ = writeln!(s, "  \"hausdorff\": {},", float(c.hausdorff()));
    let _ = writeln!(
        s,
        "  \"hausdorff_relative\": {}",
        float(c.relative(c.hausdorff()))
    );
    s.push_str("}\n");
    s
}

/// One surface's member of [`json`]: its file and what was counted on it.
fn json_surface(s: &mut String, key: &str, name: &str, info: &SurfaceInfo) {
    let _ = writeln!(
        s,
        "  \"{key}\": {{\"file\": {}, \"triangles\": {}, \"vertices\": {}, \"area\": {}, \
         \"volume\": {}, \"closed\": {}, \"boundary_edges\": {}, \"nonmanifold_edges\": {}, \
         \"components\": {}, \"skipped_triangles\": {}, \"bbox_min\": {}, \"bbox_max\": {}}},",
        string(name),
        info.triangles,
        info.vertices,
        float(info.area),
        info.volume.map_or("null".to_string(), float),
        info.volume.is_some(),
        info.boundary_edges,
        info.nonmanifold_edges,
        info.components,
        info.skipped_triangles,
        vec3(info.bbox_min.to_array()),
        vec3(info.bbox_max.to_array()),
    );
}

/// One direction's member of [`json`]: its samples and distances.
fn json_direction(s: &mut String, c: &Comparison, key: &str, d: &DirectionStats) {
    let _ = writeln!(
        s,
        "  \"{key}\": {{\"face_samples\": {}, \"edge_samples\": {}, \"vertex_samples\": {}, \
         \"max\": {}, \"mean\": {}, \"rms\": {}, \"max_relative\": {}, \"mean_relative\": {}, \
         \"rms_relative\": {}, \"max_at\": {}}},",
        d.face_samples,
        d.edge_samples,
        d.vertex_samples,
        float(d.max),
        float(d.mean),
        float(d.rms),
        float(c.relative(d.max)),
        float(c.relative(d.mean)),
        float(c.relative(d.rms)),
        vec3(d.max_at.to_array()),
    );
}

/// The symmetric distances' member of [`json`].
fn json_symmetric(s: &mut String, c: &Comparison) {
    let sym = c.symmetric();
    let _ = writeln!(
        s,
        "  \"symmetric\": {{\"max\": {}, \"mean\": {}, \"rms\": {}, \"max_relative\": {}, \
         \"mean_relative\": {}, \"rms_relative\": {}}},",
        float(sym.max),
        float(sym.mean),
        float(sym.rms),
        float(c.relative(sym.max)),
        float(c.relative(sym.mean)),
        float(c.relative(sym.rms)),
    );
}

/// The folded triangles' member of [`json`] (`metro --folds`).
fn json_folds(s: &mut String, f: &super::folds::Folds) {
    let _ = writeln!(
        s,
        "  \"folded\": {{\"triangles\": {}, \"area\": {}, \"area_fraction\": {}, \
         \"degenerate\": {}, \"checked\": {}, \"samples\": {}, \"largest_at\": {}}},",
        f.triangles,
        float(f.area),
        float(f.area_fraction),
        f.degenerate,
        f.checked,
        f.samples,
        f.largest_at
            .map_or("null".to_string(), |p| vec3(p.to_array())),
    );
}

/// A JSON number (shortest round-trip form) or `null` when not finite.
fn float(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        "null".to_string()
    }
}

fn vec3(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", float(v[0]), float(v[1]), float(v[2]))
}

/// A JSON string literal.
fn string(v: &str) -> String {
    let mut s = String::with_capacity(v.len() + 2);
    s.push('"');
    for ch in v.chars() {
        match ch {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if u32::from(c) < 0x20 => {
                let _ = write!(s, "\\u{:04x}", u32::from(c));
            }
            c => s.push(c),
        }
    }
    s.push('"');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_literals() {
        assert_eq!(string("a\"b\\c\nd\u{1}"), "\"a\\\"b\\\\c\\nd\\u0001\"");
        assert_eq!(float(0.25), "2.5e-1");
        assert_eq!(float(f64::NAN), "null");
    }
}
