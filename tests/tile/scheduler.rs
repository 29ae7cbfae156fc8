//! The GNU parallel job script (tools/cluster/tile-parallel.sh) run for real: every tile a separate
//! `decimate tile run` process started by `parallel`, then merged; the same mesh as the
//! one-command run. CI installs `parallel` (.ci/run).

use crate::common::{job_script, one_command, sphere_ply};

#[test]
fn gnu_parallel_job_array_equals_the_local_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    let work = tmp.path().join("work");
    let out = tmp.path().join("parallel.ply");
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tools/cluster/tile-parallel.sh"
    );
    let o = job_script(script, &input, &work, &out)
        .env("DECIMATE", env!("CARGO_BIN_EXE_decimate"))
        .env("JOBS", "2")
        .output()
        .expect("run bash");
    assert!(
        o.status.success(),
        "tools/cluster/tile-parallel.sh failed (is GNU parallel installed?): {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let log = String::from_utf8_lossy(&o.stdout);
    for i in 0..4 {
        assert!(log.contains(&format!("tile {i}: triangles")), "{log}");
    }
    let local = tmp.path().join("local.ply");
    one_command(&input, 4, &local);
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&local).unwrap());
}
