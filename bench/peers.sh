#!/bin/sh
# Every ratio of bench/README.md's current table in one command, on a fresh machine of this kind:
# whitted against POV-Ray 3.7 on Whitted's scene (every sampling mode, 1 and 2 threads) and
# against Embree on the meshes (4.4, embreex) and spheres-10k (3.13, Debian's libembree-dev through
# bench/embree_harness.c), one thread. Installs what is missing, builds the release
# binary, generates the scenes, then runs bench/run.py and bench/embree.py; each writes its
# results file to bench/results/ and prints its tables.
#
#   sh bench/peers.sh                       # 5 rounds each
#   RUNS=3 POVRAY_DIR=/path/to/bench/povray sh bench/peers.sh
set -eu
cd "$(dirname "$0")/.."
RUNS=${RUNS:-5}
if ! command -v povray >/dev/null; then
    apt-get update && apt-get install -y povray
fi
if [ ! -e /usr/include/embree3/rtcore.h ]; then
    apt-get update && apt-get install -y libembree-dev
fi
python3 -c 'import embreex' 2>/dev/null || python3 -m pip install 'embreex==4.4.0.post1'
cargo build --release
python3 bench/gen_scenes.py ${POVRAY_DIR:+--povray-dir "$POVRAY_DIR"}
python3 bench/run.py --only whitted --runs "$RUNS" ${POVRAY_DIR:+--povray-dir "$POVRAY_DIR"}
python3 bench/embree.py --runs "$RUNS"
