//! The Slurm job script the cluster docs show is the repository's file
//! (docs/slurm/invlight.sbatch), and it starts invlight as the docs say: through
//! `srun --mpi=pmix` (a stock Slurm does not use PMIx unless asked), or by Open MPI's
//! `mpirun` inside the allocation where the site has no PMIx. The launchers are stand-ins
//! that print what they were asked to run; Slurm itself is not needed.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn script() -> String {
    std::fs::read_to_string(repo().join("docs/slurm/invlight.sbatch")).unwrap()
}

#[test]
fn the_documented_job_script_is_the_repository_s() {
    let docs = std::fs::read_to_string(repo().join("docs/cluster.md")).unwrap();
    let block = format!("```sh\n{}```", script());
    assert!(
        docs.contains(&block),
        "docs/cluster.md must show docs/slurm/invlight.sbatch as it is"
    );
}

/// Runs the job script with `launcher` (`srun` or `mpirun`) replaced by a stand-in in
/// `dir` that prints its arguments, as Slurm would start it in `dir`.
fn submitted(dir: &Path, launch: Option<&str>) -> String {
    for launcher in ["srun", "mpirun"] {
        let fake = dir.join(launcher);
        std::fs::write(&fake, format!("#!/bin/sh\necho {launcher} \"$@\"\n")).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let path = format!(
        "{}:{}",
        dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut cmd = Command::new("bash");
    cmd.arg(repo().join("docs/slurm/invlight.sbatch"))
        .args(["office.xml", "run"])
        .env("PATH", path)
        .env("SLURM_SUBMIT_DIR", dir)
        .env("SLURM_CPUS_PER_TASK", "3")
        .env_remove("INVLIGHT_LAUNCH");
    if let Some(l) = launch {
        cmd.env("INVLIGHT_LAUNCH", l);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_job_script_starts_the_ranks_by_pmix_or_by_mpirun() {
    let dir = tempfile::tempdir().unwrap();
    let args = "target/release/invlight solve office.xml -o run --threads 3 --resume\n";
    assert_eq!(
        submitted(dir.path(), None),
        format!("srun --mpi=pmix --cpu-bind=none {args}")
    );
    assert_eq!(
        submitted(dir.path(), Some("mpirun")),
        format!("mpirun --bind-to none {args}")
    );
}
