#!/bin/sh
# Regenerates every figure in docs/ (the README's figures) with the release build.
#
#   tools/figures.sh            all of them (about 15 minutes on 2 cores)
#   tools/figures.sh quick      the trajectory figures, the animation and the tilt map only
#
# Results go to out/figures/ (override with OUT=DIR); the figures are redrawn from them by
# `tumble plot`, so a figure can be restyled later without recomputing:
#   tumble plot out/figures/tilt-map --figure-size single -o tilt-map.pdf
set -eu
cd "$(dirname "$0")/.."
cargo build --release --locked
t=target/release/tumble
out=${OUT:-out/figures}
mkdir -p "$out"

$t simulate scenes/spinning-hoop-worked-example.toml -o "$out/spin.csv"
$t plot "$out/spin.csv" -o docs/spinning-hoop-worked-example.png
$t simulate scenes/free-hoop.toml -o "$out/free-hoop.csv"
$t plot "$out/free-hoop.csv" -o docs/free-hoop.png
$t animate free-hoop --set alpha0=2 --t-end 10 --fps 10 --size 400x300 \
    -o docs/free-hoop-tilting.gif
rm -rf "$out/tilt-map"
$t sweep -o "$out/tilt-map"
$t plot "$out/tilt-map" -o docs/tilt-map.png
$t plot "$out/tilt-map" --figure slices -o docs/tilt-slices.png
[ "${1:-}" = quick ] && exit 0

for scene in free-body heavy-top free-hoop; do
    rm -rf "$out/work-precision-$scene" "$out/long-$scene"
    $t work-precision "$scene" -o "$out/work-precision-$scene"
    $t plot "$out/work-precision-$scene" -o "docs/work-precision-$scene.png"
    $t work-precision "$scene" --long -o "$out/long-$scene"
    cp "$out/long-$scene/long.png" "docs/long-$scene.png"
done
rm -rf "$out/hard-cases"
$t hard-cases -o "$out/hard-cases"
cp "$out/hard-cases/atlas.png" docs/hard-cases-atlas.png
