#!/usr/bin/env bash
# Packs what a run on the device machine (the `device` tool's GPU host) needs,
# for a session that is lent one. That machine has no OpenCV, dlib or FFmpeg
# and cannot reach ../shared, so this carries:
#   - build/facecap and build/tests/refine_tests, with every shared library they
#     load except glibc's (the host's own glibc and CUDA driver serve);
#   - the model and landmark caches, built here for the paths the bundle has
#     there (/tmp/facecap-device/...), and in place of the model files and
#     dlib's 68-point file, stand-ins of the same names, sizes and nanosecond
#     modification times (sparse files), so the caches' fingerprints match and
#     nothing is decoded there (vertex_indices.json goes as it is; the archive
#     is a POSIX tar, whose headers keep the nanoseconds: GNU's format drops them);
#   - the clip address_720p_a.mp4 and, with --problems, the displacement
#     problems of its frames 20-29 for `facecap bench displacement`.
# The archive is split into parts of at most 56 MiB under .gpu/ (git-ignored),
# one part a device call (a call carries at most 64 MiB):
#   calls 1..N-1: `mkdir -p /tmp/parts && cp .gpu/pK/* /tmp/parts/`, carry [".gpu/pK"]
#   call N:       `cp .gpu/pN/* /tmp/parts/ && bash .gpu/pN/unpack.sh && . /tmp/facecap-device/env.sh && ...`
# back to back (a warm machine is released after 30 s idle), e.g. with
# `facecap -q bench track $FACECAP_DATA_DIR/address_720p_a.mp4 --refine --device cuda`
# after the env.sh. Checked here by unpacking the parts into a fresh
# /tmp/facecap-device and running that (on the CPU) from `env -i` with HOME
# elsewhere: the caches are found and the stand-ins never read.
# Usage: scripts/device-bundle.sh [--problems]   (after ./setup.sh)
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"
problems=0
[ "${1:-}" = "--problems" ] && problems=1
stage=/tmp/facecap-device
model_src=${FACECAP_MODEL_DIR:-$top/../shared/models/ict-facekit}
data_src=${FACECAP_DATA_DIR:-$top/../shared/data}
landmarks_src=${FACECAP_LANDMARK_MODEL:-/usr/share/dlib/shape_predictor_68_face_landmarks.dat}
clip=address_720p_a.mp4
for f in build/facecap build/tests/refine_tests "$model_src/vertex_indices.json" "$data_src/$clip" "$landmarks_src"; do
  [ -e "$f" ] || { echo "device-bundle: missing $f (run ./setup.sh first)" >&2; exit 1; }
done

rm -rf "$stage" .gpu
mkdir -p "$stage"/{bin,lib,model,dlib,cache,data} .gpu

echo "==> binaries and their libraries"
cp build/facecap build/tests/refine_tests "$stage/bin/"
ldd build/facecap build/tests/refine_tests | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
  grep -vE '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*)\.so' | xargs -r cp -L -t "$stage/lib/"

echo "==> caches, built for the bundle's paths"
# The model folder as links to the real files: the cache is named after the
# folder's path and fingerprinted by each file's name, size and mtime.
for f in "$model_src"/*; do ln -s "$(readlink -f "$f")" "$stage/model/$(basename "$f")"; done
# dlib's file copied with its mtime: its cache is fingerprinted by its path.
cp -p "$landmarks_src" "$stage/dlib/"
export FACECAP_MODEL_DIR=$stage/model FACECAP_CACHE_DIR=$stage/cache
export FACECAP_LANDMARK_MODEL=$stage/dlib/$(basename "$landmarks_src")
build/facecap -q model >/dev/null
build/facecap -q probe "$data_src/lfpw_image_0010.png" >/dev/null
cp "$data_src/$clip" "$stage/data/"
if [ "$problems" = 1 ]; then
  echo "==> displacement problems of frames 20-29"
  build/facecap -q eval refine --video "$stage/data/$clip" --max-frames 30 --save-problems "$stage/problems" >/dev/null
  find "$stage/problems" -name 'frame00[01]*' -delete
fi

echo "==> stand-ins for the model files and dlib's file"
stand_in() {  # FILE SOURCE: a sparse file of SOURCE's size and nanosecond mtime
  rm -f "$1"
  truncate -s "$(stat -L -c %s "$2")" "$1"
  touch -d "@$(stat -L -c %.9Y "$2")" "$1"
}
for f in "$stage"/model/*; do
  src=$(readlink -f "$f")
  if [ "$(basename "$f")" = vertex_indices.json ]; then
    rm "$f" && cp -p "$src" "$f"
  else
    stand_in "$f" "$src"
  fi
done
stand_in "$FACECAP_LANDMARK_MODEL" "$landmarks_src"

cat >"$stage/env.sh" <<EOF
export FACECAP_MODEL_DIR=$stage/model FACECAP_CACHE_DIR=$stage/cache FACECAP_DATA_DIR=$stage/data
export FACECAP_LANDMARK_MODEL=$FACECAP_LANDMARK_MODEL
export LD_LIBRARY_PATH=$stage/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}
export PATH=$stage/bin:\$PATH
EOF

echo "==> archive"
tar --format=posix --sparse -C /tmp -cf - facecap-device | xz -T2 -6 | split -b 56M -d - .gpu/part.
n=0
for part in .gpu/part.*; do
  n=$((n + 1))
  mkdir -p ".gpu/p$n"
  mv "$part" ".gpu/p$n/"
done
cat >".gpu/p$n/unpack.sh" <<'EOF'
#!/usr/bin/env bash
# On the device machine, once every part is in /tmp/parts: the bundle into /tmp/facecap-device.
set -euo pipefail
rm -rf /tmp/facecap-device
cat /tmp/parts/part.* | xz -d | tar --sparse -C /tmp -xf -
echo "bundle ready: . /tmp/facecap-device/env.sh"
EOF
du -sh .gpu/p* | sed 's/^/    /'
echo "==> $n part(s) in .gpu/; see the comment at the top of this script for the device calls"
