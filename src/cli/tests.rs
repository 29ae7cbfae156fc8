//! The command line's parse, option by option, and the usage text it prints.

use super::*;
use decimate_core::decimate::{Algorithm, ErrorBound};
use decimate_viewer::render::draw::DrawOptions;

fn run(args: &[&str]) -> Args {
    match parse(args.iter().copied()) {
        Ok(Command::Run(a)) => *a,
        other => panic!("expected a run, got {other:?}"),
    }
}

#[test]
fn original_typical_usages() {
    let a = run(&["model.wrl"]);
    assert_eq!(a.action, Action::Gui);
    let a = run(&["model.wrl", "nogui", "-p", "100", "-o", "output.wrl"]);
    assert_eq!(a.action, Action::NoGui);
    assert_eq!(a.params.target, Target::RemovePercent(100.0));
    assert_eq!(a.output, PathBuf::from("output.wrl"));
    let a = run(&["model.wrl", "nogui", "-v", "50"]);
    assert_eq!(a.params.target, Target::RemoveVertices(50));
    assert_eq!(a.output, PathBuf::from("out.wrl"));
}

#[test]
fn algorithm_is_schroeder_unless_qem_is_asked() {
    let a = run(&["model.wrl", "nogui", "-p", "90"]);
    assert_eq!(a.params.algorithm, Algorithm::Schroeder);
    let a = run(&["model.wrl", "nogui", "-a", "qem", "-p", "90"]);
    assert_eq!(a.params.algorithm, Algorithm::Qem);
    let a = run(&["model.wrl", "nogui", "--algorithm", "schroeder", "-p", "90"]);
    assert_eq!(a.params.algorithm, Algorithm::Schroeder);
    let e = parse(["model.wrl", "nogui", "-a", "lindstrom", "-p", "9"]);
    assert_eq!(
        e,
        Err(CliError(
            "-a: unknown algorithm 'lindstrom' (expected schroeder or qem)".into()
        ))
    );
    assert!(usage().contains("-a, --algorithm A"));
}

#[test]
fn progressive_selects_qem_and_refuses_schroeder() {
    let a = run(&["m.wrl", "nogui", "-p", "90", "--progressive", "m.pm"]);
    assert_eq!(a.progressive, Some(PathBuf::from("m.pm")));
    assert_eq!(a.params.algorithm, Algorithm::Qem);
    assert_eq!(a.output, PathBuf::from("out.wrl"));
    let a = run(&[
        "m.wrl",
        "nogui",
        "-a",
        "qem",
        "--progressive",
        "x",
        "-p",
        "9",
    ]);
    assert_eq!(a.progressive, Some(PathBuf::from("x")));
    assert_eq!(a.params.algorithm, Algorithm::Qem);
    assert_eq!(run(&["m.wrl", "nogui", "-p", "9"]).progressive, None);
    for order in [
        ["-a", "schroeder", "--progressive", "m.pm"],
        ["--progressive", "m.pm", "-a", "schroeder"],
    ] {
        let mut args = vec!["m.wrl", "nogui", "-p", "50"];
        args.extend(order);
        let e = parse(args).unwrap_err();
        assert!(
            e.0.contains("records no vertex splits") && e.0.contains("-a qem"),
            "{e}"
        );
    }
    assert!(usage().contains("  --progressive FILE    also write the collapses"));
    assert!(usage().contains("(implies -a qem)"));
}

#[test]
fn progressive_needs_nogui_a_value_and_its_own_file() {
    let e = parse(["m.wrl", "nogui", "-p", "9", "--progressive"]).unwrap_err();
    assert!(e.0.contains("--progressive needs a value"), "{e}");
    let e = parse(["m.wrl", "shot", "--progressive", "m.pm"]).unwrap_err();
    assert!(e.0.contains("option of nogui"), "{e}");
    let e = parse(["m.wrl", "--progressive", "m.pm"]).unwrap_err();
    assert!(e.0.contains("option of nogui"), "{e}");
    let e = parse(["m.wrl", "nogui", "-p", "9", "--progressive", "out.wrl"]).unwrap_err();
    assert!(e.0.contains("also the -o file"), "{e}");
    let e = parse([
        "m.wrl",
        "nogui",
        "-p",
        "9",
        "-o",
        "a.pm",
        "--progressive",
        "a.pm",
    ]);
    assert!(e.is_err());
}

#[test]
fn tile_steps_parse_and_a_file_named_tile_still_opens() {
    assert_eq!(
        parse(["tile", "run", "w"]),
        Ok(Command::Tile(TileCommand::Run {
            dir: PathBuf::from("w"),
            index: None
        }))
    );
    assert_eq!(
        parse([
            "tile",
            "plan",
            "in.ply",
            "--work",
            "w",
            "--tile-triangles",
            "5",
            "-p",
            "90"
        ]),
        Ok(Command::Tile(TileCommand::Plan {
            input: PathBuf::from("in.ply"),
            dir: PathBuf::from("w"),
            count: TileCount::TrianglesEach(5),
            target: Target::RemovePercent(90.0),
        }))
    );
    assert_eq!(
        parse(["tile", "merge", "w", "-o", "o.ply", "--memory", "512M"]),
        Ok(Command::Tile(TileCommand::Merge {
            dir: PathBuf::from("w"),
            output: PathBuf::from("o.ply"),
            target: None,
            memory: Some(512 << 20),
        }))
    );
    assert_eq!(run(&["tile"]).input, PathBuf::from("tile"));
    assert_eq!(run(&["tile", "nogui", "-p", "9"]).action, Action::NoGui);
    let a = run(&[
        "m.ply", "nogui", "-p", "9", "--tiles", "auto", "--memory", "1.5G",
    ]);
    assert_eq!((a.tiles, a.memory), (Some(Tiles::Auto), Some(3 << 29)));
    assert_eq!(
        run(&["m.ply", "nogui", "-p", "9", "--tiles", "7"]).tiles,
        Some(Tiles::Count(7))
    );
}

#[test]
fn help_and_version() {
    assert_eq!(parse(["-h"]), Ok(Command::Help));
    assert_eq!(parse(["x.wrl", "--help"]), Ok(Command::Help));
    assert_eq!(parse(["--version"]), Ok(Command::Version));
}

#[test]
fn nogui_without_target_is_an_error() {
    let e = parse(["m.wrl", "nogui"]).unwrap_err();
    assert!(e.0.contains("needs a target"), "{e}");
}

#[test]
fn bad_values_are_named() {
    assert!(parse(["m.wrl", "nogui", "-p", "abc"])
        .unwrap_err()
        .0
        .contains("-p"));
    assert!(parse(["m.wrl", "nogui", "-p", "140"])
        .unwrap_err()
        .0
        .contains("between 0 and 100"));
    assert!(parse(["m.wrl", "nogui", "-p"])
        .unwrap_err()
        .0
        .contains("needs a value"));
    assert!(parse(["m.wrl", "fly"])
        .unwrap_err()
        .0
        .contains("unknown action"));
    assert!(parse(["m.wrl", "nogui", "-p", "5", "-v", "3"])
        .unwrap_err()
        .0
        .contains("only one"));
    assert!(parse(["m.wrl", "--frobnicate"])
        .unwrap_err()
        .0
        .contains("--frobnicate"));
    assert!(parse(Vec::<String>::new())
        .unwrap_err()
        .0
        .contains("no filename"));
}

#[test]
fn error_bounds_and_shot_options() {
    let a = run(&["m.wrl", "nogui", "-p", "90", "--keep-features"]);
    assert!(a.params.keep_features && !a.params.keep_border);
    let a = run(&["m.wrl", "nogui", "-p", "90", "--keep-border"]);
    assert!(a.params.keep_border && !a.params.keep_features);
    let a = run(&["m.wrl", "nogui", "--max-error", "0.5%"]);
    assert_eq!(a.params.target, Target::ErrorOnly);
    assert_eq!(
        a.params.max_error,
        Some(ErrorBound::DiagonalFraction(0.005))
    );
    let a = run(&[
        "m.wrl",
        "shot",
        "--size",
        "640x480",
        "--viewports",
        "4",
        "--mode",
        "edges,flat",
    ]);
    assert_eq!(
        (a.shot.width, a.shot.height, a.shot.viewports),
        (640, 480, 4)
    );
    assert!(a.shot.modes.edges && !a.shot.modes.smooth && !a.shot.modes.triangles);
    assert!(a.shot.modes.lighting && a.shot.modes.textures);
    assert_eq!(run(&["m.wrl", "shot"]).shot.modes, DrawOptions::default());
    assert_eq!(a.output, PathBuf::from("shot.png"));
    assert!(parse(["m.wrl", "shot", "--viewports", "5"]).is_err());
    assert_eq!(a.shot.labels, None);
    let a = run(&["m.wrl", "shot", "--no-labels"]);
    assert_eq!(a.shot.labels, Some(false));
    assert!(!a.shot.measure);
    assert!(
        run(&["m.wrl", "shot", "-p", "60,80", "--measure"])
            .shot
            .measure
    );
    for (args, says) in [
        (
            &["m.wrl", "nogui", "-p", "50", "--measure"][..],
            "an option of shot",
        ),
        (&["m.wrl", "shot", "--measure"][..], "needs a target"),
        (
            &["m.wrl", "shot", "-p", "5", "--measure", "--no-labels"][..],
            "--no-labels",
        ),
    ] {
        let e = parse(args.iter().copied()).map(|_| ()).unwrap_err();
        assert!(e.0.contains(says), "{args:?}: {}", e.0);
    }
    let a = run(&["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "0.1%"]);
    assert_eq!(a.weld_tolerance, Some(Tolerance::DiagonalFraction(0.001)));
    let a = run(&["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "0.25"]);
    assert_eq!(a.weld_tolerance, Some(Tolerance::Absolute(0.25)));
    assert_eq!(run(&["m.wrl", "nogui", "-p", "50"]).weld_tolerance, None);
    assert!(parse(["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "-1"]).is_err());
    assert!(parse(["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "x%"]).is_err());
    assert!(parse(["m.wrl", "shot", "--size", "0x10"]).is_err());
}

#[test]
fn msaa_and_the_error_map_are_options_of_the_viewer_and_shot() {
    assert_eq!(run(&["m.wrl", "shot"]).shot.msaa, 4);
    assert_eq!(run(&["m.wrl", "shot", "--msaa", "1"]).shot.msaa, 1);
    assert_eq!(run(&["m.wrl", "--msaa", "8"]).shot.msaa, 8);
    match parse(["m.wrl", "shot", "--msaa", "3"]) {
        Err(e) => assert!(e.0.contains("--msaa") && e.0.contains('3'), "{}", e.0),
        Ok(_) => panic!("--msaa 3 was accepted"),
    }
    assert!(parse(["m.wrl", "shot", "--msaa", "x"]).is_err());
    let a = run(&["m.wrl", "shot", "--mode", "error"]);
    assert!(a.shot.modes.error_map && a.shot.modes.triangles);
    assert!(!run(&["m.wrl", "shot"]).shot.modes.error_map);
}

#[test]
fn the_crease_angle_is_for_the_viewer_and_shot() {
    assert_eq!(
        run(&["m.wrl", "--crease-angle", "180"]).crease_angle,
        Some(180.0)
    );
    assert_eq!(
        run(&["m.wrl", "shot", "--crease-angle", "60"]).crease_angle,
        Some(60.0)
    );
    assert_eq!(run(&["m.wrl"]).crease_angle, None);
    for (args, says) in [
        (
            &["m.wrl", "--crease-angle", "200"][..],
            "between 0 and 180, got 200",
        ),
        (
            &["m.wrl", "shot", "--crease-angle", "x"],
            "--crease-angle: expected a number",
        ),
        (
            &["m.wrl", "nogui", "-p", "5", "--crease-angle", "60"],
            "viewer and shot",
        ),
    ] {
        let e = parse(args.iter().copied()).unwrap_err();
        assert!(e.0.contains(says), "{args:?}: {e}");
    }
}

#[test]
fn a_list_of_targets_gives_each_decimated_viewport_its_own() {
    let a = run(&[
        "m.wrl",
        "shot",
        "-p",
        "60,80,90",
        "--mode",
        "triangles,edges",
    ]);
    assert_eq!(a.shot.viewports, 4);
    assert_eq!(
        a.shot.targets,
        [60.0, 80.0, 90.0].map(Target::RemovePercent).to_vec()
    );
    assert_eq!(a.params.target, Target::RemovePercent(60.0));
    let a = run(&[
        "m.wrl",
        "shot",
        "--keep-triangles",
        "500,100",
        "--viewports",
        "3",
    ]);
    assert_eq!(a.shot.viewports, 3);
    assert_eq!(
        a.shot.targets,
        [500, 100].map(Target::KeepTriangles).to_vec()
    );
    let a = run(&["m.wrl", "shot", "-p", "60"]);
    assert_eq!((a.shot.viewports, a.shot.targets.len()), (1, 0));
    let white = Some([1.0; 3]);
    assert_eq!(
        run(&["m.wrl", "shot", "--background", "255,255,255"])
            .shot
            .background,
        white
    );
    assert_eq!(
        run(&["m.wrl", "shot", "--background", "#ffffff"])
            .shot
            .background,
        white
    );
    for (args, says) in [
        (
            &["m.wrl", "shot", "-p", "60,80,90", "--viewports", "3"][..],
            "need 4 viewports",
        ),
        (
            &["m.wrl", "shot", "-p", "60,80", "--viewports", "4"][..],
            "2 targets need 3 viewports",
        ),
        (&["m.wrl", "shot", "-p", "10,20,30,40"], "at most 3"),
        (&["m.wrl", "shot", "--background", "1,2"], "expected R,G,B"),
        (
            &["m.wrl", "shot", "--background", "#12345g"],
            "expected R,G,B",
        ),
        (
            &["m.wrl", "shot", "--background", "0,0,256"],
            "expected R,G,B",
        ),
        (
            &["m.wrl", "shot", "-p", "60,180"],
            "between 0 and 100, got 180",
        ),
        (
            &["m.wrl", "shot", "-p", "60,,90"],
            "-p: expected a number, got ''",
        ),
        (&["m.wrl", "nogui", "-p", "60,80"], "nogui takes one"),
        (&["m.wrl", "-v", "6,8"], "the viewer takes one"),
    ] {
        let e = parse(args.iter().copied()).unwrap_err();
        assert!(e.0.contains(says), "{args:?}: {e}");
    }
}

#[test]
fn every_option_the_usage_shows_is_accepted() {
    // The tile steps' own options are shown in the usage's tail; the rest come from the table.
    let tile_steps = ["--work", "--tile-triangles"];
    let text = usage();
    let body = &text[..text.find("typical usage:").expect("the usage's tail")];
    let mut checked = 0;
    for word in body.split(|c: char| c.is_whitespace() || c == ',' || c == '(' || c == ')') {
        if !word.starts_with('-') || word.len() < 2 || word.starts_with("-p/") {
            continue;
        }
        if tile_steps.contains(&word)
            || !word
                .chars()
                .nth(1)
                .is_some_and(|c| c.is_alphabetic() || c == '-')
        {
            continue;
        }
        assert!(
            options::find(word).is_some(),
            "{word} is shown but not accepted"
        );
        checked += 1;
    }
    assert!(checked >= 30, "only {checked} options found in the usage");
}

#[test]
fn threads_is_a_count_of_at_least_one_and_defaults_to_the_pool() {
    assert_eq!(run(&["m.wrl", "nogui", "-p", "90"]).threads, None);
    let a = run(&["m.wrl", "nogui", "-p", "90", "--threads", "3"]);
    assert_eq!(a.threads, Some(3));
    let e = parse(["m.wrl", "nogui", "-p", "90", "--threads", "0"]);
    assert_eq!(
        e,
        Err(CliError("--threads: expected at least 1, got 0".into()))
    );
}
