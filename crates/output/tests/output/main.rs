//! Destinations of every kind, created in a temporary directory: regular files are replaced
//! atomically, devices and FIFOs are streamed to and survive, links survive and their targets
//! get the data, directories and sockets are refused.

use std::io::{Read, Write};
use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::Command;

use tumble_output::{Destination, Mode, OutputError};

mod table;

/// Whether this process runs as root (device nodes can only be made by root).
fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {} failed", path.display());
}

#[test]
fn a_new_path_is_written_atomically_and_appears_only_when_finished() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.csv");
    let dest = Destination::check(&path).unwrap();
    assert_eq!(
        dest.mode(),
        &Mode::Atomic {
            target: std::fs::canonicalize(dir.path()).unwrap().join("out.csv")
        }
    );
    let mut out = dest.create().unwrap();
    out.write_all(b"a,b\n1,2\n").unwrap();
    assert!(!path.exists(), "visible before finish");
    out.finish().unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"a,b\n1,2\n");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "a temporary file is left"
    );
}

#[test]
fn an_unfinished_output_leaves_the_old_file_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.csv");
    std::fs::write(&path, b"old").unwrap();
    {
        let mut out = Destination::check(&path).unwrap().create().unwrap();
        out.write_all(b"new, half written").unwrap();
        // dropped without finish: an interrupted run
    }
    assert_eq!(std::fs::read(&path).unwrap(), b"old");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn a_character_device_is_streamed_to_and_stays_a_device() {
    if !is_root() {
        eprintln!("skipped: making a device node needs root");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let node = dir.path().join("null");
    // c 1 3 is the null device.
    let ok = Command::new("mknod")
        .args([node.as_os_str(), "c".as_ref(), "1".as_ref(), "3".as_ref()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "mknod failed");
    let dest = Destination::check(&node).unwrap();
    assert_eq!(dest.mode(), &Mode::Stream);
    dest.write_all(&[b'x'; 100_000]).unwrap();
    // A plot-style writer (scratch file, then commit) streams too.
    let scratch = dest.scratch().unwrap();
    std::fs::write(&scratch, b"image").unwrap();
    dest.commit_scratch(scratch).unwrap();
    let meta = std::fs::symlink_metadata(&node).unwrap();
    assert!(
        meta.file_type().is_char_device(),
        "the device node was replaced"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "a temporary file is left"
    );
}

#[test]
fn a_fifo_delivers_the_data_to_its_reader_and_stays_a_fifo() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe");
    mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            let mut got = Vec::new();
            std::fs::File::open(&fifo)
                .unwrap()
                .read_to_end(&mut got)
                .unwrap();
            got
        })
    };
    let dest = Destination::check(&fifo).unwrap();
    assert_eq!(dest.mode(), &Mode::Stream);
    let payload: Vec<u8> = (0..200_000u32).map(|i| (i % 251) as u8).collect();
    dest.write_all(&payload).unwrap();
    assert_eq!(reader.join().unwrap(), payload);
    let meta = std::fs::symlink_metadata(&fifo).unwrap();
    assert!(meta.file_type().is_fifo(), "the FIFO was replaced");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn a_link_to_a_regular_file_survives_and_its_target_gets_the_data() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("data");
    std::fs::create_dir(&sub).unwrap();
    let target = sub.join("real.csv");
    std::fs::write(&target, b"old").unwrap();
    // A relative link, through a second link: both are followed.
    let link = dir.path().join("link.csv");
    let link2 = dir.path().join("link2.csv");
    std::os::unix::fs::symlink("data/real.csv", &link).unwrap();
    std::os::unix::fs::symlink("link.csv", &link2).unwrap();
    let dest = Destination::check(&link2).unwrap();
    assert_eq!(dest.file(), std::fs::canonicalize(&target).unwrap());
    dest.write_all(b"new").unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        std::fs::symlink_metadata(&link2)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
    assert_eq!(std::fs::read(&link2).unwrap(), b"new");
}

#[test]
fn a_dangling_link_is_written_at_the_path_it_points_to() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink("later.csv", &link).unwrap();
    Destination::check(&link)
        .unwrap()
        .write_all(b"data")
        .unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(
        std::fs::read(dir.path().join("later.csv")).unwrap(),
        b"data"
    );
}

#[test]
fn a_link_loop_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a");
    let b = dir.path().join("b");
    std::os::unix::fs::symlink(&b, &a).unwrap();
    std::os::unix::fs::symlink(&a, &b).unwrap();
    // The kernel reports the loop when asked to follow it; either way it is an error.
    assert!(Destination::check(&a).is_err());
}

#[test]
fn a_directory_is_refused_and_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("results.csv");
    std::fs::create_dir(&sub).unwrap();
    let err = Destination::check(&sub).unwrap_err();
    assert!(
        matches!(
            err,
            OutputError::Unsupported {
                what: "a directory",
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string().contains("results.csv: is a directory"),
        "{err}"
    );
    // Through a link too.
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(&sub, &link).unwrap();
    assert!(matches!(
        Destination::check(&link).unwrap_err(),
        OutputError::Unsupported {
            what: "a directory",
            ..
        }
    ));
    assert!(sub.is_dir());
}

#[test]
fn a_socket_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sock");
    let _listener = std::os::unix::net::UnixListener::bind(&path).unwrap();
    assert!(matches!(
        Destination::check(&path).unwrap_err(),
        OutputError::Unsupported {
            what: "a socket",
            ..
        }
    ));
    assert!(
        std::fs::symlink_metadata(&path)
            .unwrap()
            .file_type()
            .is_socket()
    );
}

#[test]
fn a_missing_directory_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nowhere").join("out.csv");
    let err = Destination::check(&path).unwrap_err();
    assert!(matches!(err, OutputError::NoDirectory { .. }), "{err}");
}

#[test]
fn stdout_and_its_aliases_are_the_standard_output() {
    for p in ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
        assert_eq!(
            Destination::check(Path::new(p)).unwrap().mode(),
            &Mode::Stdout,
            "{p}"
        );
    }
}
