//! One timed library call for `tools/bench/percore`: reads a mesh file once, then times
//! `api::simplify` alone (the mesh already in memory, no file I/O in the timing) keeping
//! PERCENT of its triangles, on THREADS threads of a pool of the call's own
//! (`api::with_threads`; 0: rayon's global pool as `RAYON_NUM_THREADS` sets it).
//!
//! `cargo run --release -p decimate-core --example bench_percore -- IN PERCENT THREADS`
//! prints one line: seconds, triangles out, the process's peak resident memory in KiB, and
//! the CPU seconds the process spent in the call (all threads; on a busy machine a steadier
//! measure than the clock).

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use decimate_core::api::{read_scene, simplify, with_threads, Algorithm, Params, Target};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, percent, threads] = args.as_slice() else {
        eprintln!("usage: bench_percore IN PERCENT THREADS");
        return ExitCode::from(2);
    };
    let (Ok(percent), Ok(threads)) = (percent.parse::<f64>(), threads.parse::<usize>()) else {
        eprintln!("bench_percore: PERCENT and THREADS must be numbers");
        return ExitCode::from(2);
    };
    let scene = match read_scene(Path::new(input)) {
        Ok(outcome) => outcome.scene,
        Err(e) => {
            eprintln!("bench_percore: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for m in &scene.models {
        let base = positions.len() as u32;
        positions.extend(m.positions.iter().map(|p| p.to_array()));
        indices.extend(m.triangles.iter().flatten().map(|&i| i + base));
    }
    drop(scene);
    let keep = (indices.len() as f64 / 3.0 * percent / 100.0).round() as usize;
    let params = Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let cpu_start = cpu_seconds();
    let start = Instant::now();
    let call = || simplify(&positions, &indices, &params);
    let result = if threads == 0 {
        call()
    } else {
        with_threads(threads, call)
    };
    let seconds = start.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu_start;
    match result {
        Ok((mesh, _)) => {
            let kept = mesh.indices.len() / 3;
            println!("{seconds:.4} {kept} {} {cpu:.4}", peak_kib());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bench_percore: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The process's peak resident memory (Linux's `VmHWM`), in KiB; 0 where it is not known.
fn peak_kib() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

/// The CPU time this process has spent so far, all its threads together, in seconds.
fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a pointer to a live local.
    let ok = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) } == 0;
    if ok {
        t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
    } else {
        0.0
    }
}
