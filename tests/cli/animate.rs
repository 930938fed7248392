//! `tumble animate`: a GIF with the requested number of frames; scenes without a 3D view, MP4
//! and bad sizes refused before any step, nothing written.

use tempfile::TempDir;

use crate::support::{stderr, succeeds, tumble_in};

/// Frames and size of the GIF at `path`.
fn gif_frames(path: &std::path::Path) -> (usize, (u16, u16)) {
    let file = std::fs::File::open(path).unwrap();
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(file).unwrap();
    let size = (decoder.width(), decoder.height());
    let mut n = 0;
    while decoder.read_next_frame().unwrap().is_some() {
        n += 1;
    }
    (n, size)
}

#[test]
fn an_animation_has_one_frame_per_output_time() {
    let tmp = TempDir::new().unwrap();
    for (scene, name) in [
        ("free-hoop", "hoop.gif"),
        ("heavy-top", "top.gif"),
        ("free-body", "body.gif"),
        ("spinning-hoop", "spin.gif"),
        ("driven-hoop", "driven.gif"),
        ("dzhanibekov", "t-handle.gif"),
    ] {
        succeeds(
            tmp.path(),
            &[
                "animate",
                scene,
                "--t-end",
                "1",
                "--duration",
                "2",
                "--fps",
                "10",
                "--size",
                "160x120",
                "-o",
                name,
            ],
        );
        // 2 s at 10 frames per second, both ends included.
        assert_eq!(
            gif_frames(&tmp.path().join(name)),
            (21, (160, 120)),
            "{scene}"
        );
    }
}

#[test]
fn animations_that_cannot_be_made_are_refused_before_any_step() {
    let tmp = TempDir::new().unwrap();
    for (args, expect) in [
        (vec!["coriolis-drop"], "no 3D view"),
        (vec!["free-hoop", "-o", "a.mp4"], "ffmpeg"),
        (vec!["free-hoop", "-o", "a.png"], "expected a .gif"),
        (vec!["free-hoop", "--size", "10x10"], "--size"),
        (vec!["free-hoop", "--fps", "0"], "--fps"),
        (vec!["free-hoop", "--duration", "1e6"], "frames"),
        (vec!["free-hoop", "--t-end", "-1"], "--t-end"),
    ] {
        let mut all = vec!["animate"];
        all.extend(&args);
        if !args.contains(&"-o") {
            all.extend(["-o", "bad.gif"]);
        }
        let out = tumble_in(tmp.path(), &all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(expect), "{args:?}: {}", stderr(&out));
        let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().collect();
        assert!(left.is_empty(), "{args:?} left {left:?}");
    }
}

#[test]
fn a_saved_csv_is_animated_at_the_requested_frames() {
    let tmp = TempDir::new().unwrap();
    succeeds(
        tmp.path(),
        &[
            "simulate",
            "free-hoop",
            "--t-end",
            "2",
            "--output-dt",
            "0.05",
            "-o",
            "run.csv",
        ],
    );
    succeeds(
        tmp.path(),
        &[
            "animate",
            "run.csv",
            "--duration",
            "1.5",
            "--fps",
            "8",
            "--size",
            "160x120",
            "-o",
            "run.gif",
        ],
    );
    // 1.5 s at 8 frames per second, both ends included.
    assert_eq!(gif_frames(&tmp.path().join("run.gif")), (13, (160, 120)));
    // A CSV keeps its own parameters.
    let out = tumble_in(
        tmp.path(),
        &["animate", "run.csv", "--set", "m=1", "-o", "x.gif"],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("--set"), "{}", stderr(&out));
}
