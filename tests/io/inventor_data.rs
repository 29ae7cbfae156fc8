//! Real Open Inventor models from Debian's `inventor-data` (binary ones converted with
//! `ivcat` from `inventor-clients` at test time): each parses without error, has triangles,
//! and finite, plausible bounds. CI installs both packages; without them this test fails and
//! says how to install them.

use decimate_core::io::read_scene;
use glam::Vec3;
use std::path::Path;

use crate::support::inventor::{ascii_copy, install_hint, MODELS};

/// (file under MODELS, fewest models expected, fewest triangles expected)
const CASES: &[(&str, usize, usize)] = &[
    ("simple/indexedFaceSet.iv", 2, 24),
    ("simple/quadMesh.iv", 2, 64),
    ("simple/triangleStripSet.iv", 2, 36),
    ("simple/faceSet.iv", 1, 12),
    ("household/mug.iv", 1, 3450),
    ("chess/knight.iv", 1, 419),
    ("vehicles/f16.iv", 22, 4428),
    ("robots/robotcop.iv", 90, 11222),
    ("buildings/windmill.iv", 6, 70),
    ("CyberHeads/josie.iv", 1, 3042),
];

#[test]
fn real_inventor_models_parse_with_triangles_and_plausible_bounds() {
    assert!(
        Path::new(MODELS).is_dir(),
        "{MODELS} is missing; {}",
        install_hint()
    );
    let dir = std::env::temp_dir().join(format!("decimate-inventor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for &(name, min_models, min_triangles) in CASES {
        let src = Path::new(MODELS).join(name);
        assert!(
            src.is_file(),
            "{} is missing; {}",
            src.display(),
            install_hint()
        );
        let path = ascii_copy(&src, &dir);
        let outcome = read_scene(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let s = &outcome.scene;
        println!(
            "{name}: {} models, {} vertices, {} triangles, warnings {:?}",
            s.models.len(),
            s.vertex_count(),
            s.triangle_count(),
            outcome.warnings
        );
        assert!(
            s.models.len() >= min_models,
            "{name}: {} models",
            s.models.len()
        );
        assert!(
            s.triangle_count() >= min_triangles,
            "{name}: {} triangles",
            s.triangle_count()
        );
        let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        for m in &s.models {
            assert!(!m.triangles.is_empty(), "{name}: model {} is empty", m.name);
            assert!(m.transform.is_finite(), "{name}: {} transform", m.name);
            for &p in &m.positions {
                let w = m.transform.transform_point3(p);
                assert!(w.is_finite(), "{name}: {w}");
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        let size = (hi - lo).max_element();
        assert!(
            size > 1e-3 && size < 1e5,
            "{name}: implausible size {size} ({lo} .. {hi})"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
