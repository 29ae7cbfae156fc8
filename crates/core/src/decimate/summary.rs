//! What a decimation run prints: the per-model table of counts and errors, and the column of
//! counts that level rebuilding (`batch`) prints in the same layout.

use super::{ModelReport, Report};

/// A model's line of a summary up to its counts, (before, after) each; decimation and
/// level rebuilding print the same columns.
pub fn counts_column(name: &str, vertices: (usize, usize), triangles: (usize, usize)) -> String {
    format!(
        "{name:<24} vertices {:>9} -> {:<9} triangles {:>9} -> {:<9}",
        vertices.0, vertices.1, triangles.0, triangles.1
    )
}

impl Report {
    /// The per-model table printed after a run.
    pub fn summary(&self) -> String {
        let report = self;
        let mut s = String::new();
        let (mut vb, mut tb, mut va, mut ta) = (0, 0, 0, 0);
        let mut instances = 0;
        for m in &report.models {
            let state = state(report, m);
            s += &counts_column(
                &m.name,
                (m.vertices_before, m.vertices_after),
                (m.triangles_before, m.triangles_after),
            );
            s += &format!(" max error {:.4e}{state}\n", m.max_error);
            if m.instance_of.is_some() {
                instances += 1;
                continue;
            }
            vb += m.vertices_before;
            tb += m.triangles_before;
            va += m.vertices_after;
            ta += m.triangles_after;
        }
        let removed = report.vertices_removed();
        let rate = if report.seconds > 0.0 {
            removed as f64 / report.seconds
        } else {
            0.0
        };
        let counted = match instances {
            0 => String::new(),
            n => format!(" (each mesh once: {n} more instances not counted)"),
        };
        s += &format!(
            "total{counted}: vertices {vb} -> {va}, triangles {tb} -> {ta}; removed {removed} \
             vertices in {:.3} s ({:.0} vertices/s)\n",
            report.seconds, rate
        );
        if !report.models.is_empty() && report.fully_decimated() {
            s += "the model is fully decimated: no further vertex can be removed\n";
        }
        s
    }
}

/// What model `m`'s line of `report`'s summary says after its counts and error.
fn state(report: &Report, m: &ModelReport) -> String {
    let mut state = if let Some(j) = m.instance_of {
        let source = report.models.get(j).map_or("", |s| s.name.as_str());
        format!("  instance of {source}: the same mesh, decimated once, counted once")
    } else if m.copied {
        "  copied through unchanged (skinned or morph targets)".to_string()
    } else if m.dropped {
        "  dropped (fewer than 4 vertices left)".to_string()
    } else if m.fully_decimated {
        let mut held = Vec::new();
        if m.pinned > 0 {
            held.push(format!(
                "{} vertices are pinned on texture seams or borders",
                m.pinned
            ));
        }
        if m.non_manifold_kept > 0 {
            held.push(format!(
                "{} vertices on non-manifold edges of the input hold it back",
                m.non_manifold_kept
            ));
        }
        if m.closed_kept > 0 {
            held.push(format!(
                "{} vertices are kept so that a closed part does not turn inside out \
                 or flat",
                m.closed_kept
            ));
        }
        if held.is_empty() {
            "  fully decimated".to_string()
        } else {
            format!("  fully decimated ({})", held.join("; "))
        }
    } else {
        String::new()
    };
    let sheets = &m.hanging_sheets;
    if sheets.sheets > 0 {
        let plural = |n: usize, one: &str| format!("{n} {one}{}", if n == 1 { "" } else { "s" });
        state += &format!(
            "  ({} hanging on non-manifold edges, smaller than the result's triangles, \
             removed: {}, {} among them)",
            plural(sheets.sheets, "sheet"),
            plural(sheets.triangles, "triangle"),
            plural(sheets.pockets, "closed pocket")
        );
    }
    if m.seam_copies_before + m.seam_copies_after > 0 {
        state += &format!(
            "  ({} -> {} vertices with texture-seam copies)",
            m.vertices_before + m.seam_copies_before,
            m.vertices_after + m.seam_copies_after
        );
    }
    if m.feature_angle_deg > report.feature_angle_deg {
        state += &format!(
            "  (feature angle relaxed to {:.0} deg to reach the target)",
            m.feature_angle_deg
        );
    }
    state
}
