//! The values options take: numbers, lists, sizes, error bounds, draw modes; each error
//! names the option.

use decimate_core::decimate::{ErrorBound, Target};
use decimate_core::mesh::repair::Tolerance;
use decimate_viewer::render::draw::DrawOptions;

use super::CliError;

/// A count of at least one.
pub(super) fn positive(name: &str, s: &str) -> Result<usize, CliError> {
    match number::<usize>(name, s)? {
        0 => Err(CliError(format!("{name}: expected at least 1, got 0"))),
        n => Ok(n),
    }
}

/// A size in bytes, with an optional K, M, G or T suffix (powers of 1024), read as the
/// readers' limits read theirs (`io::file_limits::parse_size`).
pub(super) fn bytes(name: &str, s: &str) -> Result<u64, CliError> {
    decimate_core::io::file_limits::parse_size(s).ok_or_else(|| {
        CliError(format!(
            "{name}: expected a positive size such as 2G or 512M, got '{s}'"
        ))
    })
}

pub(super) fn set_target(slot: &mut Option<Target>, t: Target) -> Result<(), CliError> {
    if slot.is_some() {
        return Err(CliError(
            "give only one of -p, -v, --keep-vertices, --keep-triangles".into(),
        ));
    }
    *slot = Some(t);
    Ok(())
}

pub(super) fn number<T: std::str::FromStr>(name: &str, s: &str) -> Result<T, CliError> {
    s.trim()
        .parse()
        .map_err(|_| CliError(format!("{name}: expected a number, got '{s}'")))
}

/// `R,G,B` (each 0 to 255) or `#rrggbb`, as RGB from 0 to 1.
pub(super) fn colour(name: &str, s: &str) -> Result<[f32; 3], CliError> {
    let bad = || {
        CliError(format!(
            "{name}: expected R,G,B (0-255 each) or #rrggbb, got '{s}'"
        ))
    };
    let channels: Vec<u8> = match s.strip_prefix('#') {
        Some(hex) if hex.len() == 6 && hex.is_ascii() => (0..3)
            .map(|i| u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).map_err(|_| bad()))
            .collect::<Result<_, _>>()?,
        Some(_) => return Err(bad()),
        None => numbers::<u8>(name, s).map_err(|_| bad())?,
    };
    match channels[..] {
        [r, g, b] => Ok([r, g, b].map(|c| f32::from(c) / 255.0)),
        _ => Err(bad()),
    }
}

/// A comma-separated list of numbers (`60,80,90`), at least one.
pub(super) fn numbers<T: std::str::FromStr>(name: &str, s: &str) -> Result<Vec<T>, CliError> {
    s.split(',').map(|item| number(name, item)).collect()
}

pub(super) fn error_bound(s: &str) -> Result<ErrorBound, CliError> {
    let (digits, percent) = match s.strip_suffix('%') {
        Some(d) => (d, true),
        None => (s, false),
    };
    let e: f64 = number("--max-error", digits)?;
    if !e.is_finite() || e < 0.0 {
        return Err(CliError(format!(
            "--max-error: expected a non-negative number, got '{s}'"
        )));
    }
    Ok(if percent {
        ErrorBound::DiagonalFraction(e / 100.0)
    } else {
        ErrorBound::Absolute(e)
    })
}

pub(super) fn tolerance(s: &str) -> Result<Tolerance, CliError> {
    let (digits, percent) = match s.strip_suffix('%') {
        Some(d) => (d, true),
        None => (s, false),
    };
    let e: f64 = number("--weld-tolerance", digits)?;
    if !e.is_finite() || e < 0.0 {
        return Err(CliError(format!(
            "--weld-tolerance: expected a non-negative number, got '{s}'"
        )));
    }
    Ok(if percent {
        Tolerance::DiagonalFraction(e / 100.0)
    } else {
        Tolerance::Absolute(e)
    })
}

pub(super) fn size(s: &str) -> Result<(u32, u32), CliError> {
    let bad = || CliError(format!("--size: expected WxH such as 800x600, got '{s}'"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.parse().map_err(|_| bad())?;
    let h: u32 = h.parse().map_err(|_| bad())?;
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(CliError(format!(
            "--size: each side must be 1 to 8192 pixels, got '{s}'"
        )));
    }
    Ok((w, h))
}

/// The draw toggles of a `--mode` list (the viewer's toggles, shading words meaning "off").
pub fn draw_modes(s: &str) -> Result<DrawOptions, CliError> {
    let mut m = DrawOptions {
        triangles: false,
        ..DrawOptions::default()
    };
    for word in s.split(',').map(str::trim).filter(|w| !w.is_empty()) {
        match word {
            "triangles" | "solid" => m.triangles = true,
            "edges" => m.edges = true,
            "points" => m.points = true,
            "normals" => m.face_normals = true,
            "vertex-normals" => m.vertex_normals = true,
            "flat" => m.smooth = false,
            "unlit" => m.lighting = false,
            "untextured" => m.textures = false,
            "error" => m.error_map = true,
            other => {
                return Err(CliError(format!(
                    "--mode: unknown mode '{other}' (expected triangles, edges, points, \
                     normals, vertex-normals, flat, unlit, untextured, error)"
                )))
            }
        }
    }
    // Shading words alone still mean "draw the triangles".
    if !(m.edges || m.points) {
        m.triangles = true;
    }
    Ok(m)
}
