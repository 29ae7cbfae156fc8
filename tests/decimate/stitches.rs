//! Models that share a border stay stitched: a sphere delivered as two hemispheres (two OBJ
//! objects meeting at the equator) goes through the binary with either algorithm, and the
//! two decimated halves still meet without a crack — welded by position, the result is a
//! closed surface again.

use std::collections::HashMap;
use std::process::Command;

/// A unit sphere of `segments` meridians as two OBJ objects, north and south of the equator,
/// with `north` and `south` rings of triangles: halves of different density, so that each
/// is simplified its own way. Both list the equator's points, computed the same way, so
/// they coincide exactly.
fn hemispheres_obj(north: usize, south: usize, segments: usize) -> String {
    use std::f64::consts::FRAC_PI_2;
    let point = |theta: f64, s: usize| {
        let phi = 2.0 * std::f64::consts::PI * s as f64 / segments as f64;
        [
            (theta.sin() * phi.cos()) as f32,
            (theta.sin() * phi.sin()) as f32,
            theta.cos() as f32,
        ]
    };
    let mut text = String::new();
    let mut base = 1; // OBJ indices count from 1 over the whole file
    for (name, rings, from_pole) in [("north", north, true), ("south", south, false)] {
        text += &format!("o {name}\n");
        // Ring r's polar angle; the pole (a single point) is ring 0 north, ring `rings` south.
        let theta = |r: usize| match (from_pole, r) {
            (true, r) if r == rings => FRAC_PI_2,
            (true, r) => FRAC_PI_2 * r as f64 / rings as f64,
            (false, 0) => FRAC_PI_2,
            (false, r) => FRAC_PI_2 + FRAC_PI_2 * r as f64 / rings as f64,
        };
        let pole = if from_pole { 0 } else { rings };
        let mut index: HashMap<(usize, usize), usize> = HashMap::new();
        let mut count = 0;
        for r in 0..=rings {
            let columns = if r == pole { 1 } else { segments };
            for s in 0..columns {
                let [x, y, z] = point(theta(r), s);
                text += &format!("v {x} {y} {z}\n");
                index.insert((r, s), base + count);
                count += 1;
            }
        }
        let at = |r: usize, s: usize| index[&(r, if r == pole { 0 } else { s % segments })];
        for r in 0..rings {
            for s in 0..segments {
                let (a, b, c, d) = (at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1));
                if r != pole {
                    text += &format!("f {a} {b} {d}\n");
                }
                if r + 1 != pole {
                    text += &format!("f {d} {b} {c}\n");
                }
            }
        }
        base += count;
    }
    text
}

/// An OBJ's objects as read back: per object, its triangles as world positions.
fn read_objects(text: &str) -> Vec<Vec<[[f32; 3]; 3]>> {
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut objects: Vec<Vec<[[f32; 3]; 3]>> = Vec::new();
    for line in text.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("o") => objects.push(Vec::new()),
            Some("v") => {
                let n: Vec<f32> = w.take(3).map(|x| x.parse().expect("a number")).collect();
                positions.push([n[0], n[1], n[2]]);
            }
            Some("f") => {
                let corners: Vec<[f32; 3]> = w
                    .map(|c| {
                        let v: usize = c.split('/').next().unwrap().parse().expect("an index");
                        positions[v - 1]
                    })
                    .collect();
                assert_eq!(corners.len(), 3, "triangles only");
                objects
                    .last_mut()
                    .expect("faces after an 'o'")
                    .push([corners[0], corners[1], corners[2]]);
            }
            _ => {}
        }
    }
    objects
}

/// Edges used by exactly one triangle once all triangles are welded by exact position.
fn open_edges(triangles: impl Iterator<Item = [[f32; 3]; 3]>) -> usize {
    let key = |p: [f32; 3]| p.map(|x| (x + 0.0).to_bits());
    let mut uses: HashMap<([u32; 3], [u32; 3]), usize> = HashMap::new();
    for t in triangles {
        for i in 0..3 {
            let (a, b) = (key(t[i]), key(t[(i + 1) % 3]));
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    uses.values().filter(|&&n| n == 1).count()
}

#[test]
fn two_halves_of_a_sphere_stay_closed_after_decimation() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("hemispheres.obj");
    std::fs::write(&input, hemispheres_obj(12, 30, 64)).unwrap();
    let original = read_objects(&std::fs::read_to_string(&input).unwrap());
    assert_eq!(original.len(), 2);
    let before: usize = original.iter().map(Vec::len).sum();
    assert_eq!(before, 64 * (2 * 12 - 1) + 64 * (2 * 30 - 1));
    assert_eq!(open_edges(original.into_iter().flatten()), 0);
    for (algorithm, percent) in [("schroeder", "80"), ("qem", "80"), ("qem", "99")] {
        let output = dir.path().join(format!("{algorithm}.obj"));
        let run = Command::new(env!("CARGO_BIN_EXE_decimate"))
            .arg(&input)
            .args(["nogui", "-a", algorithm, "-p", percent, "-o"])
            .arg(&output)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success(), "{algorithm}: {stderr}");
        let objects = read_objects(&std::fs::read_to_string(&output).unwrap());
        assert_eq!(objects.len(), 2, "{algorithm}: both halves are kept apart");
        let after: usize = objects.iter().map(Vec::len).sum();
        // 80 % of the vertices go; the 64 equator points of each half stay.
        assert!(
            after < before / 3,
            "{algorithm}: {after} of {before} triangles left"
        );
        if percent == "99" {
            // The border's pinned points take in their neighbours: each half goes down to
            // the fewest triangles over its 64 border points, 62 (once 64: an interior
            // point was left in each, its edges all leading to pinned points).
            assert_eq!(after, 2 * 62, "{algorithm} at {percent} %");
        }
        assert_eq!(
            open_edges(objects.into_iter().flatten()),
            0,
            "{algorithm}: the halves no longer meet along the equator"
        );
    }
}

/// `triangles` as an OBJ of one object, corners at the same position as one vertex.
fn obj_of(triangles: &[[[f32; 3]; 3]]) -> String {
    let mut index: HashMap<[u32; 3], usize> = HashMap::new();
    let (mut points, mut faces) = (String::new(), String::new());
    for t in triangles {
        let ids = t.map(|p| {
            let next = index.len() + 1;
            *index.entry(p.map(f32::to_bits)).or_insert_with(|| {
                points += &format!("v {} {} {}\n", p[0], p[1], p[2]);
                next
            })
        });
        faces += &format!("f {} {} {}\n", ids[0], ids[1], ids[2]);
    }
    format!("o half\n{points}{faces}")
}

#[test]
fn halves_decimated_in_separate_runs_still_meet_with_keep_border() {
    let dir = tempfile::tempdir().unwrap();
    let halves = read_objects(&hemispheres_obj(12, 30, 64));
    let inputs: Vec<_> = ["north", "south"]
        .iter()
        .zip(&halves)
        .map(|(name, half)| {
            let path = dir.path().join(format!("{name}.obj"));
            std::fs::write(&path, obj_of(half)).unwrap();
            assert_eq!(open_edges(half.iter().copied()), 64, "{name}: the equator");
            path
        })
        .collect();
    let before: usize = halves.iter().map(Vec::len).sum();
    for (algorithm, percent, keep) in [
        ("schroeder", "80", true),
        ("qem", "80", true),
        ("qem", "99", true),
        ("schroeder", "80", false),
        ("qem", "80", false),
    ] {
        // Each half on its own, as a tile of a larger mesh would be.
        let outputs: Vec<Vec<[[f32; 3]; 3]>> = inputs
            .iter()
            .map(|input| {
                let output = input.with_extension(format!("{algorithm}-{percent}-{keep}.obj"));
                let mut command = Command::new(env!("CARGO_BIN_EXE_decimate"));
                command
                    .arg(input)
                    .args(["nogui", "-a", algorithm, "-p", percent, "-o"])
                    .arg(&output);
                if keep {
                    command.arg("--keep-border");
                }
                let run = command.output().unwrap();
                let stderr = String::from_utf8_lossy(&run.stderr);
                assert!(run.status.success(), "{algorithm}: {stderr}");
                let objects = read_objects(&std::fs::read_to_string(&output).unwrap());
                assert_eq!(objects.len(), 1, "{algorithm}: one object in, one out");
                objects.into_iter().flatten().collect()
            })
            .collect();
        let after: usize = outputs.iter().map(Vec::len).sum();
        let case = format!("{algorithm} -p {percent}, keep border {keep}");
        assert!(
            after < before / 3,
            "{case}: {after} of {before} triangles left"
        );
        let cracks = open_edges(outputs.iter().flatten().copied());
        if !keep {
            // Each run takes its own shortcuts along the equator: the halves part.
            assert!(cracks > 0, "{case}: the halves meet without the option");
            continue;
        }
        for half in &outputs {
            assert_eq!(
                open_edges(half.iter().copied()),
                64,
                "{case}: the equator kept"
            );
        }
        assert_eq!(
            cracks, 0,
            "{case}: the halves no longer meet along the equator"
        );
        if percent == "99" {
            // As in one run with the halves stitched: the fewest triangles over 64 border
            // points, 62 a half.
            assert_eq!(after, 2 * 62, "{case}");
        }
    }
}
