#!/usr/bin/env bash
# Builds the Debian package from the release build (scripts/test.sh built
# it; only what is missing is built here), checks it with lintian (no
# errors), installs it with apt-get and, from a folder outside the
# checkout, runs what a user and a toolchain would: `vcpost --version`, its
# man page, a post of an installed sample (byte-identical to the build
# tree's vcpost), and the consumer example examples/post_sample built with
# find_package(vcpost) against the installed package; then removes it.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
build=$repo/build/release
bash scripts/setup.sh dev  # the dev layer: lintian, dpkg-shlibdeps, man-db
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
deb=$build/vcpost_${version}_amd64.deb
rm -f "$deb"
(cd "$build" && cpack -G DEB >/dev/null)
echo "package-test: built $(basename "$deb") ($(du -h "$deb" | cut -f1))"
dpkg-deb --field "$deb" Depends
lintian --fail-on error --tag-display-limit 0 "$deb" || {
  echo "package-test: lintian found errors" >&2
  exit 1
}

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
export DEBIAN_FRONTEND=noninteractive
work=$(mktemp -d)
cleanup() {
  "${as_root[@]}" apt-get remove -y -qq --purge vcpost >/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "$deb" >/dev/null
cd "$work"

[ "$(command -v vcpost)" = /usr/bin/vcpost ]
vcpost --version
[ "$(vcpost --version)" = "$("$build/postproc/cli/vcpost" --version)" ]
man -w vcpost-post
# grep reads all (no -q): an early exit would kill the writer with SIGPIPE,
# which pipefail counts as a failure.
man vcpost-post 2>/dev/null | grep -- "--adjust-feed" >/dev/null

samples=/usr/share/vcpost/samples
job=(--model "$samples/wavy.step" --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -q)
vcpost post "$samples/wavy_raster_a0_ae2.nc" "${job[@]}" -o posted.nc
"$build/postproc/cli/vcpost" post "$repo/samples/wavy_raster_a0_ae2.nc" "${job[@]}" -o tree.nc
cmp posted.nc tree.nc
vcpost verify "$samples/wavy_raster_a0_ae2.nc" posted.nc --machine mazak-3axis

# The consumer example, against the installed package only.
cmake -S "$repo/examples/post_sample" -B example -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >/dev/null
grep -q '^vcpost_DIR:PATH=/usr/lib/.*cmake/vcpost$' example/CMakeCache.txt
cmake --build example >/dev/null
./example/post_sample "$samples/wavy_raster_a0_ae2.nc" "$samples/wavy.step" mazak-3axis > library.nc
cmp library.nc posted.nc
# Debian 12 merges /usr: the loader may name /lib for /usr/lib.
ldd example/post_sample | grep -E "libvcpost.so.* => (/usr)?/lib/" >/dev/null
echo "package-test: vcpost $version installed, run, linked and removed"
