#!/usr/bin/env bash
# Downloads the ICT Face Model Light (MIT licence) for machines without
# ../shared/models/ict-facekit: clones the public ICT-FaceKit repository at the
# commit facecap was built against and prints the FACECAP_MODEL_DIR to use.
set -euo pipefail
dest="${1:-$HOME/.local/share/facecap/ICT-FaceKit}"
commit="da5f95a607f5e6b37755b38d3385d7f2853732e5"
if [ ! -d "$dest/.git" ]; then
  git clone https://github.com/ICT-VGL/ICT-FaceKit.git "$dest"
fi
git -C "$dest" checkout --quiet "$commit"
[ -f "$dest/FaceXModel/vertex_indices.json" ] || { echo "fetch-model.sh: $dest/FaceXModel looks incomplete" >&2; exit 1; }
echo "model ready; use:"
echo "  export FACECAP_MODEL_DIR=$dest/FaceXModel"
