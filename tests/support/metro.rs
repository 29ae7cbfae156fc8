//! Metro between two models in a test: 200,000 face samples a direction, the default seed.

use decimate_core::mesh::{Model, Scene};
use decimate_core::metro::{compare, Comparison, Options, Surface};

/// `a` against `b` in both directions.
pub fn compare_models(a: &Model, b: &Model) -> Comparison {
    let surface = |m: &Model| {
        Surface::from_scene(&Scene {
            models: vec![m.clone()],
        })
    };
    let options = Options {
        samples: Some(200_000),
        ..Options::default()
    };
    compare(&surface(a), &surface(b), &options).expect("comparable surfaces")
}
