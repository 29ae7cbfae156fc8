//! The `metro` command line (Metro, Cignoni–Rocchini–Scopigno 1998): usage, and clear
//! failures that name the file at fault.

use std::process::Command;

fn metro(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_metro"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn help_prints_usage_and_succeeds() {
    let (code, out, _) = metro(&["--help"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("usage: metro [options] A B"));
    assert!(out.contains("--samples N"));
}

#[test]
fn wrong_usage_exits_2() {
    let (code, _, err) = metro(&["only-one.wrl"]);
    assert_eq!(code, 2);
    assert!(err.contains("expected two files, got 1"), "{err}");
    let (code, _, err) = metro(&["a.wrl", "b.wrl", "--samples", "many"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("'many' is not a positive whole number"),
        "{err}"
    );
}

#[test]
fn unreadable_file_is_named() {
    let dir = std::env::temp_dir().join(format!("metro-cli-{}", std::process::id()));
    let missing = dir.join("no-such-mesh.wrl");
    let path = missing.to_string_lossy().into_owned();
    let (code, out, err) = metro(&[&path, &path]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.starts_with("metro: "), "{err}");
    assert!(err.contains("no-such-mesh.wrl"), "{err}");
}
