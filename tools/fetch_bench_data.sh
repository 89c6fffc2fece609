#!/usr/bin/env bash
# Fetches CGAL's closed test meshes (Debian package libcgal-demo, data/meshes/*.off) into
# build/bench-data for the benchmark programs, without installing the package.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dest=${1:-$root/build/bench-data}
mkdir -p "$dest"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
apt-get download libcgal-demo >/dev/null
dpkg -x libcgal-demo_*.deb pkg
tar -xzf pkg/usr/share/doc/libcgal-dev/data.tar.gz
for m in bunny00 fandisk_large armadillo refined_elephant turbine blade; do
  f=$(find . -path "*meshes/$m.off" | head -n 1)
  if [ -n "$f" ]; then cp "$f" "$dest/"; fi
done
ls -l "$dest"
