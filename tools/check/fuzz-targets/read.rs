//! One reader under libFuzzer: the bytes are read as a file named `FUZZ_FILE_NAME` (its
//! extension picks the reader, e.g. `x.ply`), and a scene that reads is decimated by both
//! algorithms and written as PLY to memory. A panic, an overflow (checked in this build),
//! a hang or an allocation over libFuzzer's `-rss_limit_mb`/`-malloc_limit_mb` is a crash.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::io;
use libfuzzer_sys::fuzz_target;

fn name() -> &'static PathBuf {
    static NAME: OnceLock<PathBuf> = OnceLock::new();
    NAME.get_or_init(|| {
        PathBuf::from(std::env::var("FUZZ_FILE_NAME").unwrap_or_else(|_| "input.ply".into()))
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(outcome) = io::parse_bytes(data.to_vec(), name()) else {
        return;
    };
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        let mut scene = outcome.scene.clone();
        let params = Params {
            target: Target::RemovePercent(50.0),
            algorithm,
            ..Params::default()
        };
        simplify_scene(&mut scene, &params, &mut |_| {});
        let mut out = Vec::new();
        let _ = io::ply::write_ply_to(&mut out, &scene);
    }
});
