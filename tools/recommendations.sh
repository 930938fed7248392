#!/bin/sh
# Measures what `tumble scenes` recommends, for every built-in scene at its default parameters,
# into crates/scenarios/data/recommendations.toml (the file the binary embeds at build time),
# with the command, version, date, CPU, cores and load average beside each scene's numbers.
#
#   tools/recommendations.sh                 every built-in scene
#   tools/recommendations.sh heavy-top ...   only these (the other entries are kept)
#
# Times are only comparable within one scene's entry (its ladders are retimed in turns); run on
# an otherwise idle machine for figures worth quoting, and rebuild afterwards (`cargo build`)
# so that `tumble scenes` prints them.
set -eu
cd "$(dirname "$0")/.."
cargo build --release --locked
t=target/release/tumble
file=crates/scenarios/data/recommendations.toml
if [ "$#" -eq 0 ]; then
    # the scenes whose listing has a `recommended` line
    set -- $($t scenes | awk '/^[a-z0-9-]+ — /{s=$1} /^  recommended/{print s}')
fi
for scene in "$@"; do
    $t work-precision "$scene" --recommend "$file"
done
