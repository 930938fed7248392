//! `tumble plot` and the figure formats: a saved result redrawn without recomputing gives the
//! figure its command wrote; SVG and PDF are well-formed with the shipped font embedded;
//! legends cover no data.

use std::path::Path;

use tempfile::TempDir;

use crate::support::{root, stderr, succeeds, tumble_in};
use crate::sweep::{small, write_sweep};

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn plot_redraws_a_simulation_csv_as_simulate_drew_it() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    succeeds(
        dir,
        &[
            "simulate",
            "free-hoop",
            "--t-end",
            "1",
            "-o",
            "run.csv",
            "--plot",
            "cmd.svg",
        ],
    );
    succeeds(dir, &["plot", "run.csv", "-o", "again.svg"]);
    assert_eq!(read(&dir.join("cmd.svg")), read(&dir.join("again.svg")));
    // A column and time range chosen: fewer series, and no panel without one.
    succeeds(
        dir,
        &[
            "plot",
            "run.csv",
            "--columns",
            "alpha",
            "--t-range",
            "0,0.5",
            "-o",
            "alpha.svg",
        ],
    );
    let alpha = read(&dir.join("alpha.svg"));
    // The column's legend entry is its symbol.
    assert!(alpha.contains(">\nα\n</text>"), "no α");
    assert!(!alpha.contains("relative energy error"));
}

/// A run of a model file: its record names the file, which `tumble plot` reads again for the
/// model's columns and symbols; the figure is the PNG `simulate --plot` drew, byte for byte.
/// With the file gone, the error names it.
#[test]
fn plot_redraws_a_model_runs_csv_as_simulate_drew_it() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    std::fs::copy(
        root().join("models/free-hoop-euler.toml"),
        dir.join("hoop.toml"),
    )
    .unwrap();
    succeeds(
        dir,
        &[
            "simulate",
            "hoop.toml",
            "--t-end",
            "1",
            "-o",
            "run.csv",
            "--plot",
            "cmd.png",
        ],
    );
    succeeds(dir, &["plot", "run.csv", "-o", "again.png"]);
    let drawn = std::fs::read(dir.join("cmd.png")).unwrap();
    assert!(drawn.starts_with(b"\x89PNG"), "not a PNG");
    assert_eq!(drawn, std::fs::read(dir.join("again.png")).unwrap());
    // The model's own coordinate, by name.
    succeeds(
        dir,
        &["plot", "run.csv", "--columns", "theta", "-o", "theta.svg"],
    );
    assert!(
        read(&dir.join("theta.svg")).contains(">\nθ\n</text>"),
        "no θ"
    );
    std::fs::rename(dir.join("hoop.toml"), dir.join("moved.toml")).unwrap();
    let out = tumble_in(dir, &["plot", "run.csv", "-o", "gone.png"]);
    assert!(!out.status.success());
    let err = stderr(&out);
    assert!(
        err.contains("run.csv.json") && err.contains("hoop.toml") && err.contains("not a file"),
        "{err}"
    );
    assert!(!dir.join("gone.png").exists());
}

#[test]
fn plot_redraws_a_sweep_folder_as_the_sweep_drew_it() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.5, 4));
    succeeds(tmp.path(), &["sweep", file.to_str().unwrap(), "-o", "s"]);
    let dir = tmp.path().join("s");
    succeeds(tmp.path(), &["plot", "s", "-o", "map.svg"]);
    assert_eq!(
        read(&dir.join("tilt-map.svg")),
        read(&tmp.path().join("map.svg"))
    );
    succeeds(
        tmp.path(),
        &["plot", "s", "--figure", "slices", "-o", "slices.svg"],
    );
    assert_eq!(
        read(&dir.join("tilt-slices.svg")),
        read(&tmp.path().join("slices.svg"))
    );
    // Another metric, by name; an unknown one is refused naming the ones there are.
    succeeds(
        tmp.path(),
        &["plot", "s", "--metric", "final_tilt", "-o", "final.svg"],
    );
    assert!(read(&tmp.path().join("final.svg")).contains("tilt"));
    let out = tumble_in(
        tmp.path(),
        &["plot", "s", "--metric", "nope", "-o", "x.svg"],
    );
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("max_tilt"), "{err}");
    assert!(!tmp.path().join("x.svg").exists());
    // A sweep drawn at a journal's column width and redrawn so.
    let journal = ["--figure-size", "single", "--font-size", "9"];
    let mut args = vec!["sweep", file.to_str().unwrap(), "-o", "j"];
    args.extend(journal);
    succeeds(tmp.path(), &args);
    let mut args = vec!["plot", "j", "-o", "j.svg"];
    args.extend(journal);
    succeeds(tmp.path(), &args);
    let map = read(&tmp.path().join("j/tilt-map.svg"));
    assert_eq!(map, read(&tmp.path().join("j.svg")));
    assert!(map.contains(r#"<svg width="3.4000in""#), "{}", &map[..200]);
}

#[test]
fn plot_redraws_a_work_precision_folder_as_the_command_drew_it() {
    let tmp = TempDir::new().unwrap();
    succeeds(
        tmp.path(),
        &[
            "work-precision",
            "free-body",
            "--t-end",
            "1",
            "--max-seconds",
            "0.02",
            "--integrators",
            "split2,rk4",
            "-o",
            "wp",
        ],
    );
    succeeds(tmp.path(), &["plot", "wp", "-o", "wp.svg"]);
    assert_eq!(
        read(&tmp.path().join("wp/work-precision.svg")),
        read(&tmp.path().join("wp.svg"))
    );
}

/// The two figure kinds whose commands write no result `tumble plot` read before: a long run
/// (`long.csv` and the record in `manifest.json`) and a hard-case atlas (`atlas.csv` and its
/// manifest's cases and methods) redraw to the same file.
#[test]
fn plot_redraws_a_long_run_and_an_atlas_as_their_commands_drew_them() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    succeeds(
        dir,
        &[
            "work-precision",
            "free-body",
            "--long",
            "--long-steps",
            "2000",
            "--integrators",
            "split2,lgvi",
            "-o",
            "long",
        ],
    );
    succeeds(dir, &["plot", "long", "-o", "long.svg"]);
    assert_eq!(
        read(&dir.join("long/long.svg")),
        read(&dir.join("long.svg"))
    );
    succeeds(
        dir,
        &[
            "hard-cases",
            "--cases",
            "sleeping-top,nearly-symmetric-body",
            "--integrators",
            "gauss8,rk4:dt=0.1",
            "-o",
            "atlas",
        ],
    );
    succeeds(dir, &["plot", "atlas", "-o", "atlas.png"]);
    assert_eq!(
        std::fs::read(dir.join("atlas/atlas.png")).unwrap(),
        std::fs::read(dir.join("atlas.png")).unwrap()
    );
}

#[test]
fn svg_embeds_the_shipped_font_and_keeps_hundredths_of_a_pixel() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    succeeds(
        dir,
        &[
            "simulate",
            "driven-hoop",
            "--t-end",
            "1",
            "-o",
            "run.csv",
            "--plot",
            "run.svg",
        ],
    );
    let svg = read(&dir.join("run.svg"));
    // The font: an @font-face with TrueType data (a TrueType file starts 00 01 00 00, which
    // base64 writes AAEAAA), and text set in its family.
    assert!(
        svg.contains("@font-face{font-family:'DejaVu Sans';src:url(data:font/ttf;base64,AAEAAA")
    );
    assert!(svg.contains(r#"font-family="DejaVu Sans""#));
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).expect("well-formed SVG");
    assert_eq!(
        (tree.size().width(), tree.size().height()),
        (1100.0, svg_height(&svg))
    );
    // Coordinates are in hundredths of a pixel: the view box is 100 times the size.
    assert!(svg.contains(r#"viewBox="0 0 110000 "#), "{}", &svg[..300]);
    // Text as paths: no <text> left, and usvg reads it back.
    succeeds(
        dir,
        &["plot", "run.csv", "--svg-text", "paths", "-o", "paths.svg"],
    );
    let paths = read(&dir.join("paths.svg"));
    assert!(!paths.contains("<text"), "text left in the paths SVG");
    usvg::Tree::from_str(&paths, &usvg::Options::default()).expect("well-formed SVG");
}

/// The `height` attribute of an SVG root.
fn svg_height(svg: &str) -> f32 {
    let rest = &svg[svg.find("height=\"").unwrap() + 8..];
    rest[..rest.find('"').unwrap()].parse().unwrap()
}

#[test]
fn pdf_is_a_single_column_page_with_the_shipped_font_embedded() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    succeeds(
        dir,
        &[
            "simulate",
            "spinning-hoop",
            "--t-end",
            "1",
            "-o",
            "run.csv",
            "--plot",
            "run.pdf",
            "--figure-size",
            "single",
        ],
    );
    let doc = lopdf::Document::load(dir.join("run.pdf")).expect("a PDF lopdf can parse");
    let pages = doc.get_pages();
    assert_eq!(pages.len(), 1);
    // 3.4 in = 244.8 pt wide.
    let page = doc.get_dictionary(*pages.values().next().unwrap()).unwrap();
    let media = page.get(b"MediaBox").unwrap().as_array().unwrap();
    let width = media[2].as_float().unwrap() - media[0].as_float().unwrap();
    assert!((width - 244.8).abs() < 0.5, "page width {width} pt");
    // A font descriptor naming DejaVu Sans with the font program embedded (FontFile2).
    let embedded = doc.objects.values().any(|o| {
        o.as_dict().is_ok_and(|d| {
            d.get(b"FontName")
                .ok()
                .and_then(|n| n.as_name().ok())
                .is_some_and(|n| String::from_utf8_lossy(n).contains("DejaVuSans"))
                && d.get(b"FontFile2").is_ok()
        })
    });
    assert!(embedded, "no embedded DejaVu Sans font program");
}

#[test]
fn figure_options_are_checked_before_the_run() {
    let tmp = TempDir::new().unwrap();
    for (flag, value, says) in [
        ("--figure-size", "wide", "single"),
        ("--figure-size", "1x1", "no room"),
        ("--dpi", "0", "--dpi"),
        ("--font-size", "0", "--font-size"),
    ] {
        let mut args = vec![
            "simulate",
            "driven-hoop",
            "-o",
            "run.csv",
            "--plot",
            "run.png",
            flag,
            value,
        ];
        if value == "1x1" {
            args.extend(["--font-size", "40"]);
        }
        let out = tumble_in(tmp.path(), &args);
        assert_eq!(out.status.code(), Some(1), "{flag} {value}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{flag} {value}: {err}");
        assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0);
    }
}

/// The value of attribute `name` in an SVG element's text.
fn attr(element: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let rest = &element[element.find(&key)? + key.len()..];
    Some(rest[..rest.find('"')?].to_string())
}

/// Whether an SVG colour `#RRGGBB` is a colour, not a grey (axes, grid, frames are grey or
/// black; series are drawn in the palette's colours).
fn coloured(c: &str) -> bool {
    let channel = |k: usize| c.get(1 + 2 * k..3 + 2 * k).map(str::to_ascii_uppercase);
    c.len() == 7 && !(channel(0) == channel(1) && channel(1) == channel(2))
}

/// Legend boxes (the white, 85 %-opaque rectangles) and series curves (the coloured
/// polylines) of a figure's SVG.
type Boxes = Vec<[f64; 4]>;
type Curves = Vec<Vec<(f64, f64)>>;

fn legends_and_curves(svg: &str) -> (Boxes, Curves) {
    let elements = |tag: &str| -> Vec<String> {
        svg.split(&format!("<{tag} "))
            .skip(1)
            .map(|e| format!(" {}", &e[..e.find('>').unwrap_or(e.len())]))
            .collect()
    };
    let num = |e: &str, n: &str| -> f64 { attr(e, n).unwrap().parse().unwrap() };
    let boxes = elements("rect")
        .iter()
        .filter(|e| attr(e, "opacity").as_deref() == Some("0.85"))
        .map(|e| {
            let (x, y) = (num(e, "x"), num(e, "y"));
            [x, y, x + num(e, "width"), y + num(e, "height")]
        })
        .collect();
    let curves = elements("polyline")
        .iter()
        .filter(|e| attr(e, "stroke").is_some_and(|c| coloured(&c)))
        .map(|e| {
            attr(e, "points")
                .unwrap()
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect();
    (boxes, curves)
}

/// Points of the curves inside a legend box, sampled every 0.25 px along each segment; a
/// polyline wholly inside a box is the box's own sample and does not count.
fn covered_points(svg: &str) -> usize {
    let (boxes, curves) = legends_and_curves(svg);
    assert!(
        !boxes.is_empty() && !curves.is_empty(),
        "no legend or curve"
    );
    let inside =
        |b: &[f64; 4], (x, y): (f64, f64)| b[0] <= x && x <= b[2] && b[1] <= y && y <= b[3];
    let mut covered = 0;
    for b in &boxes {
        for curve in &curves {
            if curve.iter().all(|&p| inside(b, p)) {
                continue;
            }
            for w in curve.windows(2) {
                let (a, c) = (w[0], w[1]);
                let n = (((c.0 - a.0).hypot(c.1 - a.1) / 25.0).ceil() as usize).max(1);
                covered += (0..=n)
                    .map(|k| k as f64 / n as f64)
                    .filter(|&f| inside(b, (a.0 + f * (c.0 - a.0), a.1 + f * (c.1 - a.1))))
                    .count();
            }
        }
    }
    covered
}

#[test]
fn legends_cover_no_curve_of_the_shipped_figures() {
    let tmp = TempDir::new().unwrap();
    let dir = tmp.path();
    let root = crate::support::root();
    let scene = |name: &str| root.join("scenes").join(name).display().to_string();
    let spin = scene("spinning-hoop-worked-example.toml");
    let hoop = scene("free-hoop.toml");
    // The README's trajectory figures, at their own size and at a journal column's width.
    for (input, name) in [(&spin, "spin"), (&hoop, "hoop")] {
        let csv = format!("{name}.csv");
        succeeds(dir, &["simulate", input, "-o", &csv]);
        for size in ["own", "single", "double"] {
            let svg = format!("{name}-{size}.svg");
            let mut args = vec!["plot", csv.as_str(), "-o", svg.as_str()];
            if size != "own" {
                args.extend(["--figure-size", size]);
            }
            succeeds(dir, &args);
            assert_eq!(covered_points(&read(&dir.join(&svg))), 0, "{svg}");
        }
    }
    // A work–precision figure, a long-run energy figure and a sweep's slices.
    succeeds(
        dir,
        &[
            "work-precision",
            "free-body",
            "--t-end",
            "1",
            "--max-seconds",
            "0.02",
            "--integrators",
            "split2,split4,rk4,dop853,gauss4,lgvi",
            "-o",
            "wp",
        ],
    );
    succeeds(
        dir,
        &[
            "work-precision",
            "free-body",
            "--long",
            "--long-steps",
            "4000",
            "--integrators",
            "split2,lgvi",
            "-o",
            "long",
        ],
    );
    let file = write_sweep(dir, "small.sweep.toml", &small(0.5, 4));
    succeeds(dir, &["sweep", file.to_str().unwrap(), "-o", "s"]);
    for svg in [
        "wp/work-precision.svg",
        "long/long.svg",
        "s/tilt-slices.svg",
    ] {
        assert_eq!(covered_points(&read(&dir.join(svg))), 0, "{svg}");
    }
}

#[test]
fn the_overlap_measure_sees_a_curve_through_a_legend() {
    // The measure itself: a curve crossing a legend box is counted, one beside it is not.
    let svg = r##"<rect x="100" y="100" width="1000" height="500" opacity="0.85" fill="#FFFFFF"/>
<polyline stroke="#0072B2" points="0,300 2000,300 "/>"##;
    assert!(covered_points(svg) > 0);
    let clear = svg.replace("0,300 2000,300", "0,700 2000,700");
    assert_eq!(covered_points(&clear), 0);
}

/// The distinct `fill="#rrggbb"` colours of an SVG.
fn fills(svg: &str) -> std::collections::BTreeSet<(u8, u8, u8)> {
    svg.split("fill=\"#")
        .skip(1)
        .filter_map(|rest| {
            let hex = rest.get(..6)?;
            let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
            Some((byte(0)?, byte(2)?, byte(4)?))
        })
        .collect()
}

#[test]
fn a_sweep_map_is_drawn_in_the_colour_map_asked_for() {
    let tmp = TempDir::new().unwrap();
    let file = write_sweep(tmp.path(), "small.sweep.toml", &small(0.5, 4));
    succeeds(tmp.path(), &["sweep", file.to_str().unwrap(), "-o", "s"]);
    succeeds(tmp.path(), &["plot", "s", "-o", "viridis.svg"]);
    succeeds(
        tmp.path(),
        &["plot", "s", "--colour-map", "grey", "-o", "grey.svg"],
    );
    let greys = |set: &std::collections::BTreeSet<(u8, u8, u8)>| {
        set.iter()
            .filter(|&&(r, g, b)| r == g && g == b && r > 0 && r < 0xe7)
            .count()
    };
    let viridis = fills(&read(&tmp.path().join("viridis.svg")));
    let grey = fills(&read(&tmp.path().join("grey.svg")));
    // The cells and the colour bar's steps are greys in the grey map; viridis has no greys of
    // its own (what greys it has are the figure's frame and text, in both).
    assert!(greys(&grey) >= 10, "{grey:?}");
    assert!(
        greys(&viridis) < greys(&grey),
        "viridis {viridis:?} grey {grey:?}"
    );
    // The same plot in cividis differs from both; an unknown map is refused before any work.
    succeeds(
        tmp.path(),
        &["plot", "s", "--colour-map", "cividis", "-o", "cividis.svg"],
    );
    let cividis = read(&tmp.path().join("cividis.svg"));
    assert_ne!(cividis, read(&tmp.path().join("viridis.svg")));
    let out = tumble_in(
        tmp.path(),
        &["plot", "s", "--colour-map", "rainbow", "-o", "r.svg"],
    );
    assert!(!out.status.success());
    assert!(stderr(&out).contains("cividis"), "{}", stderr(&out));
    assert!(!tmp.path().join("r.svg").exists());
}
