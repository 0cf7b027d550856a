#!/usr/bin/env bash
# Sets up facecap on a fresh Debian 12 machine: installs the Debian packages
# it needs, configures and builds it in Release into build/ (-j2), and builds
# the face-model cache. Safe to run again: it installs only what is missing
# and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

step() { printf '\n==> %s\n' "$*"; }
fail() { printf 'setup.sh: error: %s\n' "$*" >&2; exit 1; }
trap 'fail "a step failed (line $LINENO); see the output above"' ERR

PACKAGES=(
  build-essential cmake pkg-config git
  libeigen3-dev libopencv-dev libdlib-dev libdlib-data libceres-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  ffmpeg libavformat-dev libavcodec-dev libavutil-dev libswscale-dev libpng-dev libjpeg62-turbo-dev zlib1g-dev
  libtorch-dev
  blender python3-numpy  # tests only: Blender's own importer opens the animated glTF output
)

# Tests only: three.js's own glTF loader (from npm, below) reads the animated
# glTF under node. Debian's nodejs and npm where the machine has no node of its own.
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then
  PACKAGES+=(nodejs npm)
fi

step "Checking Debian packages"
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || fail "installing packages needs root (or sudo): ${missing[*]}"
    SUDO="sudo"
  fi
  $SUDO apt-get update || fail "apt-get update failed (no network?)"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}" ||
    fail "apt-get install failed for: ${missing[*]}"
else
  echo "all ${#PACKAGES[@]} packages present"
fi
[ -f /usr/share/dlib/shape_predictor_68_face_landmarks.dat ] ||
  fail "dlib's landmark model is missing (package libdlib-data)"

step "three.js for the tests (npm, into tests/app/threejs)"
threejs_dir=tests/app/threejs
if [ -f "$threejs_dir/node_modules/three/package.json" ]; then
  echo "three.js present"
elif (cd "$threejs_dir" && npm ci --no-audit --no-fund --loglevel=error); then
  echo "three.js installed"
elif [ "${CI:-}" = "true" ]; then
  fail "npm could not install three.js into $threejs_dir (CI runs its test)"
else
  echo "npm could not install three.js (no registry?): its test will be skipped"
fi

step "Configuring (Release) into build/"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release || fail "cmake configure failed"

step "Building with 2 jobs"
cmake --build build -j2 || fail "build failed"

step "Preparing the face-model cache"
model_dir="${FACECAP_MODEL_DIR:-$(pwd)/../shared/models/ict-facekit}"
if [ -f "$model_dir/vertex_indices.json" ]; then
  build/facecap --model-dir "$model_dir" model > /dev/null || fail "the face model at $model_dir does not load"
  echo "model cache ready for $model_dir"
elif [ "${CI:-}" = "true" ]; then
  fail "face model not found at $model_dir (CI needs it)"
else
  echo "face model not found at $model_dir: run scripts/fetch-model.sh or set FACECAP_MODEL_DIR"
fi

step "Done: build/facecap is ready (try: build/facecap demo)"
