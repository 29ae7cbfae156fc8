//! The error of a decimated level against its original — the one figure the viewer calls
//! "max distance to the input", in its captions, its heat-map legend and `shot --measure`'s
//! summary: metro's symmetric maximum (Hausdorff) distance, with its mean, in model units and
//! in percent of the original's bounding-box diagonal. Measured on request (`d` in the viewer, `--measure` in
//! `shot`): it samples both surfaces, which takes about as long as decimating them.

use decimate_core::decimate::Cancel;
use decimate_core::mesh::Scene;
use decimate_core::metro::{compare_cancellable, Options, Surface};

/// Metro's distance between an original and one of its levels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelError {
    pub mean: f64,
    /// The Hausdorff distance.
    pub max: f64,
    /// The original's bounding-box diagonal.
    pub diagonal: f64,
}

impl LevelError {
    /// Measures `level` against `original` with metro's default sampling (fixed seed: the
    /// same scenes give the same numbers); an error names the surface with no triangles.
    pub fn measure(original: &Scene, level: &Scene) -> Result<Self, String> {
        Self::measure_cancellable(original, level, &Cancel::default())
    }

    /// [`Self::measure`], stopping soon after `cancel` is requested (then an error saying so).
    pub fn measure_cancellable(
        original: &Scene,
        level: &Scene,
        cancel: &Cancel,
    ) -> Result<Self, String> {
        let (a, b) = rayon::join(
            || Surface::from_scene(original),
            || Surface::from_scene(level),
        );
        let c = compare_cancellable(&a, &b, &Options::default(), cancel).map_err(|e| {
            let e = e.to_string();
            e.replace("surface A", "the original")
                .replace("surface B", "the level shown")
        })?;
        let s = c.symmetric();
        Ok(Self {
            mean: s.mean,
            max: s.max,
            diagonal: c.diagonal,
        })
    }

    /// "max distance to the input: 0.011 model units (0.48 % of the diagonal), mean 0.0012".
    pub fn words(&self) -> String {
        let percent = |x: f64| {
            if self.diagonal > 0.0 {
                100.0 * x / self.diagonal
            } else {
                0.0
            }
        };
        format!(
            "max distance to the input: {} model units ({:.2} % of the diagonal), mean {}",
            significant(self.max),
            percent(self.max),
            significant(self.mean),
        )
    }
}

/// `x` with about three significant digits, in plain notation from 0.001 to 99 999.
fn significant(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&magnitude) {
        format!("{x:.2e}")
    } else {
        let decimals = (2 - magnitude.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use decimate_core::mesh::shapes;

    #[test]
    fn a_level_is_as_far_as_metro_says_and_the_words_say_so() {
        let original = Scene {
            models: vec![shapes::uv_sphere(24, 48)],
        };
        let same = LevelError::measure(&original, &original).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((same.mean, same.max), (0.0, 0.0));
        // The unit sphere moved 0.01 along x: every point is 0.01 from the other surface
        // or less, and the farthest ones (the sides facing the move) nearly exactly that.
        let mut moved = original.clone();
        for p in &mut moved.models[0].positions {
            p.x += 0.01;
        }
        let e = LevelError::measure(&original, &moved).unwrap_or_else(|e| panic!("{e}"));
        assert!((e.max - 0.01).abs() < 5e-4, "{e:?}");
        assert!(e.mean > 0.002 && e.mean < e.max, "{e:?}");
        assert!((e.diagonal - 12f64.sqrt()).abs() < 0.01, "{e:?}");
        let words = LevelError {
            mean: 0.00123,
            max: 0.0456,
            diagonal: 3.0,
        }
        .words();
        assert_eq!(
            words,
            "max distance to the input: 0.0456 model units (1.52 % of the diagonal), mean 0.00123"
        );
        let empty = Scene { models: vec![] };
        let e = LevelError::measure(&original, &empty).unwrap_err();
        assert!(e.contains("the level shown"), "{e}");
    }

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(1234.6), "1235");
        assert_eq!(significant(12.345), "12.3");
        assert_eq!(significant(0.012345), "0.0123");
        assert_eq!(significant(0.00001234), "1.23e-5");
    }
}
