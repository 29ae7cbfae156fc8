//! Malformed progressive files: cut anywhere, or with a wrong magic, version, index, count
//! or number, each refused with a message naming the file and the byte.

use std::path::Path;

use decimate_core::io::progressive_file::{read_progressive, MAGIC};
use decimate_core::mesh::shapes;

use super::{decimate, refused, stderr, write_input};

/// A valid progressive file of a small cube, no attributes; its bytes.
fn small_pm(dir: &Path) -> Vec<u8> {
    write_input(dir, vec![shapes::cube(3, 1.0)]);
    let o = decimate(
        dir,
        &[
            "in.wrl",
            "nogui",
            "-p",
            "90",
            "-q",
            "--progressive",
            "ok.pm",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "-q prints nothing: {}", stderr(&o));
    std::fs::read(dir.join("ok.pm")).unwrap_or_else(|e| panic!("{e}"))
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Byte offset of the first split's `keep` field in a one-model file without attributes.
fn first_split_offset(b: &[u8]) -> (usize, u32) {
    let name_len = u32_at(b, 16) as usize;
    let counts = 16 + 4 + name_len + 64 + 12 + 5 + 1 + 1;
    let (v, f) = (u32_at(b, counts) as usize, u32_at(b, counts + 4) as usize);
    (counts + 8 + 12 * v + 12 * f + 4, v as u32)
}

#[test]
fn truncated_files_are_refused_at_every_cut() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let b = small_pm(dir.path());
    assert!(read_progressive(&dir.path().join("ok.pm")).is_ok());
    for cut in [
        0,
        4,
        8,
        11,
        12,
        16,
        40,
        b.len() / 3,
        b.len() / 2,
        b.len() - 1,
    ] {
        let text = refused(dir.path(), "cut.pm", &b[..cut]);
        if cut == 0 {
            assert!(text.contains("empty"), "{text}");
        } else if cut < 8 {
            assert!(text.contains("byte 0: not a progressive mesh"), "{text}");
        } else {
            assert!(
                text.contains("the file ends before") || text.contains("truncated"),
                "{cut}: {text}"
            );
        }
    }
    let text = refused(dir.path(), "long.pm", &[&b[..], &[0]].concat());
    assert!(text.contains("1 byte after the last model"), "{text}");
}

#[test]
fn wrong_magic_version_index_count_or_number_is_named_with_its_byte() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let b = small_pm(dir.path());
    assert_eq!(&b[..8], &MAGIC);

    let mut bad = b.clone();
    bad[0] ^= 0x20;
    let text = refused(dir.path(), "magic.pm", &bad);
    assert!(
        text.ends_with(
            "byte 0: not a progressive mesh: the file does not start with \"DECIMPM\\0\""
        ),
        "{text}"
    );

    let mut bad = b.clone();
    bad[8..12].copy_from_slice(&3u32.to_le_bytes());
    let text = refused(dir.path(), "version.pm", &bad);
    assert!(
        text.contains("byte 8: format version 3 is not supported"),
        "{text}"
    );

    let (at, v) = first_split_offset(&b);
    assert!(u32_at(&b, at) < v, "the offset computed is a split's keep");
    let mut bad = b.clone();
    bad[at..at + 4].copy_from_slice(&v.to_le_bytes());
    let text = refused(dir.path(), "index.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {at}: model 0: split 0: the vertex that splits {v} is out of range (expected below {v})"
        )),
        "{text}"
    );

    // An absurd base vertex count: refused before anything is allocated for it.
    let name_len = u32_at(&b, 16) as usize;
    let vertex_count = 16 + 4 + name_len + 64 + 12 + 5 + 1 + 1;
    let mut bad = b.clone();
    bad[vertex_count..vertex_count + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let text = refused(dir.path(), "count.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {vertex_count}: model 0: the base vertex count is 4294967295, but"
        )),
        "{text}"
    );

    // A NaN position.
    let first_position = vertex_count + 8;
    let mut bad = b.clone();
    bad[first_position..first_position + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let text = refused(dir.path(), "nan.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {first_position}: model 0: a position is not a finite number"
        )),
        "{text}"
    );

    let text = refused(dir.path(), "empty.pm", &[]);
    assert!(text.contains("byte 0: the file is empty"), "{text}");
}
