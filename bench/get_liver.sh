#!/usr/bin/env bash
# Prints the path of CGAL's demo liver segmentation (data/images/liver.inr.gz of
# Debian's libcgal-demo: 438x353x165 voxels, labels 0/84/85/127/255), fetching it
# into DIR first when it is not there yet (apt-get download, no root needed).
# Usage: bench/get_liver.sh DIR
set -euo pipefail
dir=$1
liver=$dir/liver.inr.gz
if [ ! -s "$liver" ]; then
  mkdir -p "$dir/deb"
  (cd "$dir/deb" && apt-get download libcgal-demo >&2)
  # The package's data.tar.* (xz in Debian 12) holds CGAL's data.tar.gz, which holds the image.
  dpkg-deb --fsys-tarfile "$dir"/deb/libcgal-demo_*.deb | tar -xO ./usr/share/doc/libcgal-dev/data.tar.gz |
    tar -xzO data/images/liver.inr.gz >"$liver.part"
  mv "$liver.part" "$liver"
fi
# (gzip dies of SIGPIPE when head has read enough: not a failure here.)
magic=$(gzip -dc "$liver" 2>/dev/null | head -c 13 || true)
[ "$magic" = '#INRIMAGE-4#{' ] || { echo "get_liver.sh: $liver is not an INR image" >&2 && exit 3; }
echo "$liver"
