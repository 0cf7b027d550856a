#!/usr/bin/env bash
# Rebuilds the shipped expression-mapping models (models/expressions/) from
# what this project has (SAVEE is not available to us):
#  1. neutral speech: facecap track on the neutral talking clips of ../shared/data;
#  2. emotions: FACS prototypes laid over that speech (facecap-train expr-dataset),
#     plus the real frames of emotions_pexels_640x360.mp4 that show one
#     (crying 0-2 s, before the hands come up: sadness; smiling 10-19.7 s: happiness);
#  3. CycleGAN neutral <-> each emotion (facecap-train expr-all).
# Takes a few minutes on 2 cores. Usage: scripts/train-expression-models.sh [DATA_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
data="${1:-${FACECAP_DATA_DIR:-../shared/data}}"
out="${2:-models/expressions}"
[ -x build/facecap-train ] || { echo "build/facecap-train is missing (LibTorch: apt-get install libtorch-dev, then ./setup.sh)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
csvs=()
for clip in talking_webcam_400x300 talking_webcam2_400x300 address_720p_a address_720p_b; do
  [ -f "$data/$clip.mp4" ] || { echo "missing $data/$clip.mp4" >&2; exit 1; }
  build/facecap -q track "$data/$clip.mp4" -o "$work/$clip" > /dev/null
  csvs+=("$work/$clip/frames.csv")
done
[ -f "$data/emotions_pexels_640x360.mp4" ] || { echo "missing $data/emotions_pexels_640x360.mp4" >&2; exit 1; }
build/facecap -q track "$data/emotions_pexels_640x360.mp4" -o "$work/emotions" > /dev/null
build/facecap-train expr-dataset --neutral "${csvs[@]}" --per-emotion 3000 --seed 1 \
  --real "sadness=$work/emotions/frames.csv@0-2" --real "happiness=$work/emotions/frames.csv@10-19.7" \
  -o "$work/expressions.csv"
build/facecap-train expr-all "$work/expressions.csv" -o "$out" --iterations 4000
echo "models written to $out"
