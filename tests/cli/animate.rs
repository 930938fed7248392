//! `tumble animate`: a GIF with the requested number of frames, its bodies shaded; an MP4 at
//! 1280 x 720 where ffmpeg is installed; scenes without a 3D view, MP4 without ffmpeg and bad
//! sizes refused before any step, nothing written.

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
        ("models/gyroscope-gimbals.toml", "gimbals.gif"),
        ("models/double-pendulum.toml", "pendulum.gif"),
        (
            "models/double-spherical-pendulum-so3.toml",
            "two-bodies.gif",
        ),
    ] {
        let scene = if scene.ends_with(".toml") {
            crate::support::root().join(scene).display().to_string()
        } else {
            scene.to_string()
        };
        let scene = scene.as_str();
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
        (vec!["free-hoop", "-o", "a.png"], "expected a .gif"),
        (vec!["free-hoop", "--size", "10x10"], "--size"),
        (
            vec!["free-hoop", "--size", "641x480", "-o", "odd.mp4"],
            "even",
        ),
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

/// Whether ffmpeg runs here.
fn ffmpeg() -> bool {
    std::process::Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The RGB pixels of frame `k` of the GIF at `path`.
fn gif_frame(path: &std::path::Path, k: usize) -> Vec<[u8; 3]> {
    let file = std::fs::File::open(path).unwrap();
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(file).unwrap();
    for _ in 0..k {
        decoder.read_next_frame().unwrap().unwrap();
    }
    let frame = decoder.read_next_frame().unwrap().unwrap();
    frame
        .buffer
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

#[test]
fn bodies_are_shaded_by_the_light_on_each_face() {
    // The T-handle (blue, #0072b2), a prism seen from above a corner, shows several faces lit
    // differently: distinct shades of its hue, each covering many pixels.
    let tmp = TempDir::new().unwrap();
    succeeds(
        tmp.path(),
        &[
            "animate",
            "dzhanibekov",
            "--t-end",
            "0.5",
            "--duration",
            "0.2",
            "--fps",
            "5",
            "-o",
            "handle.gif",
        ],
    );
    let pixels = gif_frame(&tmp.path().join("handle.gif"), 0);
    assert_eq!(pixels.len(), 640 * 480, "the GIF's default size");
    let mut shades = std::collections::BTreeMap::new();
    for [r, g, b] in pixels {
        // The body's hue: blue dominant, red low (the trail is orange, the axes other hues).
        if b > 60 && r < 40 && i32::from(b) - i32::from(g) > 40 {
            *shades.entry(b / 16).or_insert(0usize) += 1;
        }
    }
    let large: Vec<_> = shades.iter().filter(|&(_, &n)| n > 500).collect();
    assert!(
        large.len() >= 2,
        "the faces are not shaded apart: {shades:?}"
    );
}

#[test]
fn an_mp4_is_made_for_slides_where_ffmpeg_is_installed() {
    let tmp = TempDir::new().unwrap();
    let args = [
        "animate",
        "free-hoop",
        "--t-end",
        "1",
        "--duration",
        "1",
        "--fps",
        "10",
        "-o",
        "hoop.mp4",
    ];
    if !ffmpeg() {
        // Refused before any step, nothing written.
        let out = tumble_in(tmp.path(), &args);
        assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
        assert!(stderr(&out).contains("ffmpeg"), "{}", stderr(&out));
        assert!(std::fs::read_dir(tmp.path()).unwrap().next().is_none());
        return;
    }
    succeeds(tmp.path(), &args);
    let probe = std::process::Command::new("ffprobe")
        .args([
            "-v",
            "error",
            "-select_streams",
            "v:0",
            "-count_frames",
            "-show_entries",
            "stream=width,height,nb_read_frames,codec_name",
            "-of",
            "csv=p=0",
        ])
        .arg(tmp.path().join("hoop.mp4"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&probe.stdout);
    // 1 s at 10 frames per second, both ends included, 1280 x 720 by default.
    assert_eq!(text.trim(), "h264,1280,720,11", "{text}");
}
