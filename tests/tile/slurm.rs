//! The Slurm job script (tools/cluster/tile-slurm.sh) through a real single-node Slurm started by
//! the test (tools/cluster/slurm-local.sh: munged, slurmctld, slurmd under a temp folder): every
//! tile an array task, the merge a dependent job; the same mesh as the one-command run.
//! CI installs slurm-wlm and munge (.ci/run) and must run it; elsewhere it skips loudly
//! when they are missing.

use std::ffi::OsStr;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::{job_script, ok, one_command, s, sphere_ply};

const START: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tools/cluster/slurm-local.sh");
const JOBS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tools/cluster/tile-slurm.sh");

/// The local cluster's daemons, stopped when dropped: also when an assertion fails.
struct Cluster {
    dir: PathBuf,
}

impl Cluster {
    fn start(dir: &Path) -> Self {
        let o = run(Command::new("bash").args([START, "start", s(dir)]));
        let cluster = Self {
            dir: dir.to_path_buf(),
        };
        assert!(
            o.status.success(),
            "tools/cluster/slurm-local.sh start failed: {}\n{}",
            String::from_utf8_lossy(&o.stderr),
            cluster.logs()
        );
        cluster
    }

    fn conf(&self) -> PathBuf {
        self.dir.join("slurm.conf")
    }

    /// Runs tools/cluster/tile-slurm.sh in `cwd` on this cluster, with `decimate` as the binary its
    /// jobs run; WAIT=1: sbatch --wait on the merge job, which waits for the whole array.
    fn submit(
        &self,
        cwd: &Path,
        input: &Path,
        work: &Path,
        out: &Path,
        decimate: impl AsRef<OsStr>,
    ) -> Output {
        run(job_script(JOBS, input, work, out)
            .current_dir(cwd)
            .env("SLURM_CONF", self.conf())
            .env("DECIMATE", decimate)
            .env("WAIT", "1")
            .env_remove("SBATCH_OPTIONS"))
    }

    /// The daemons' last log lines, for a failure message.
    fn logs(&self) -> String {
        ["slurmctld.log", "slurmd.log", "munged.log"]
            .iter()
            .map(|f| {
                let text = std::fs::read_to_string(self.dir.join(f)).unwrap_or_default();
                let tail: Vec<&str> = text.lines().rev().take(8).collect();
                format!(
                    "--- {f}\n{}",
                    tail.into_iter().rev().collect::<Vec<_>>().join("\n")
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let o = run(Command::new("bash").args([START, "stop", s(&self.dir)]));
        if !o.status.success() {
            eprintln!(
                "tools/cluster/slurm-local.sh stop failed: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
    }
}

fn run(c: &mut Command) -> Output {
    c.output().expect("run bash")
}

/// Whether slurm-wlm and munge are installed; outside CI a loud skip when they are not.
fn slurm_installed() -> bool {
    let missing: Vec<&str> = ["munged", "slurmctld", "slurmd", "sbatch"]
        .into_iter()
        .filter(|tool| {
            !run(Command::new("sh").args(["-c", &format!("command -v {tool}")]))
                .status
                .success()
        })
        .collect();
    if missing.is_empty() {
        return true;
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "{} not installed: CI must install slurm-wlm and munge (.ci/run)",
        missing.join(", ")
    );
    eprintln!(
        "\n*** SKIPPED the Slurm test: {} not installed (run tools/setup --test) ***\n",
        missing.join(", ")
    );
    false
}

#[test]
fn slurm_job_array_equals_the_local_run() {
    if !slurm_installed() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    let cluster = Cluster::start(&tmp.path().join("slurm"));
    let work = tmp.path().join("work");
    let out = tmp.path().join("slurm.ply");
    let o = cluster.submit(
        tmp.path(),
        &input,
        &work,
        &out,
        env!("CARGO_BIN_EXE_decimate"),
    );
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        o.status.success(),
        "tools/cluster/tile-slurm.sh failed: {said}\n{}",
        cluster.logs()
    );
    assert!(said.contains("(4 tiles)"), "{said}");

    // Each array task found its tile through SLURM_ARRAY_TASK_ID and logged it.
    let logs: Vec<String> = std::fs::read_dir(&work)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            name.starts_with("slurm-") && !name.starts_with("slurm-merge-")
        })
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    assert_eq!(logs.len(), 4, "{logs:?}");
    for i in 0..4 {
        let line = format!("tile {i}: triangles");
        assert!(logs.iter().any(|l| l.contains(&line)), "{line}: {logs:?}");
    }
    let done = ok(&["tile", "status", s(&work)], &[]);
    assert!(String::from_utf8_lossy(&done.stdout).contains("4 of 4 tiles done"));

    let local = tmp.path().join("local.ply");
    one_command(&input, 4, &local);
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&local).unwrap());

    // A task that fails (tile 2's job exits 7): the merge is cancelled and the script says
    // so, exit 1; that one tile submitted again, then the merge, gives the same mesh.
    let failing = tmp.path().join("fails-on-tile-2.sh");
    std::fs::write(
        &failing,
        format!(
            "#!/bin/sh\n[ \"$2\" = run ] && [ \"$SLURM_ARRAY_TASK_ID\" = 2 ] && exit 7\n\
             exec '{}' \"$@\"\n",
            env!("CARGO_BIN_EXE_decimate")
        ),
    )
    .unwrap();
    std::fs::set_permissions(&failing, std::fs::Permissions::from_mode(0o755)).unwrap();
    let work = tmp.path().join("work2");
    let out = tmp.path().join("slurm2.ply");
    let o = cluster.submit(tmp.path(), &input, &work, &out, &failing);
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(
        said.contains("no merge: tiles failed") && said.contains("tile 2: pending"),
        "{said}"
    );
    assert!(!out.exists());
    let sbatch = |args: &[&str]| {
        let o = run(Command::new("sbatch")
            .args(args)
            .current_dir(tmp.path())
            .env("SLURM_CONF", cluster.conf()));
        assert!(
            o.status.success(),
            "sbatch {args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    };
    let bin = env!("CARGO_BIN_EXE_decimate");
    sbatch(&[
        "--wait",
        "--array=2",
        &format!("--wrap={bin} tile run {}", s(&work)),
    ]);
    sbatch(&[
        "--wait",
        &format!("--wrap={bin} tile merge {} -o {}", s(&work), s(&out)),
    ]);
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&local).unwrap());
    drop(cluster);
}
