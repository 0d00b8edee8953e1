#!/usr/bin/env bash
# Real EDS files nobody here wrote, for tests/eds_real.rs (issue 23 item 3): python canopen's test and
# example EDS files, from the PyPI sdist of the version tests/python/requirements.txt pins, unpacked into
# target/real-eds/canopen-<version>/ with the package's LICENSE.txt beside them. Nothing of it is committed
# (other repositories' content stays out of our commits). Idempotent: a second run with the files in place
# downloads nothing. The sdist's SHA-256 is checked, so a changed upload fails loudly.
# Usage: scripts/fetch-eds.sh            (prints the directory holding the .eds files)
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=$(sed -n 's/^canopen==//p' tests/python/requirements.txt)
[[ -n "$VERSION" ]] || { echo "fetch-eds: no canopen==VERSION in tests/python/requirements.txt" >&2; exit 1; }
# The sdist's hash as PyPI lists it; a new pin needs its own (pip download, then sha256sum).
declare -A SHA256=([2.4.1]=20a84bc498b34dadd79cece467d3bbe19591c1c02a8f39331bcc6065c4d8b2eb)
OUT=target/real-eds
DIR=$OUT/canopen-$VERSION
FILES=(LICENSE.txt test/sample.eds test/datatypes.eds examples/eds/e35.eds)
if [[ -f $DIR/.complete ]]; then
    echo "$DIR"
    exit 0
fi
want=${SHA256[$VERSION]:-}
[[ -n "$want" ]] || { echo "fetch-eds: no SHA-256 recorded for canopen $VERSION in $0" >&2; exit 1; }
mkdir -p "$OUT"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tarball=$OUT/canopen-$VERSION.tar.gz
if [[ ! -f $tarball ]] || ! echo "$want  $tarball" | sha256sum -c --quiet - 2>/dev/null; then
    # pip of the project's own environment (scripts/python-env.sh; made here if missing, nothing installed).
    SKIP_PIP=1 source scripts/python-env.sh
    python3 -m pip download --quiet --disable-pip-version-check --no-deps --no-binary :all: \
        "canopen==$VERSION" -d "$tmp" >&2
    mv "$tmp/canopen-$VERSION.tar.gz" "$tarball"
fi
echo "$want  $tarball" | sha256sum -c --quiet - || { echo "fetch-eds: $tarball: SHA-256 mismatch" >&2; exit 1; }
rm -rf "$DIR"
mkdir -p "$DIR"
tar -xzf "$tarball" -C "$tmp" "${FILES[@]/#/canopen-$VERSION/}"
for f in "${FILES[@]}"; do
    cp "$tmp/canopen-$VERSION/$f" "$DIR/$(basename "$f")"
done
touch "$DIR/.complete"
echo "$DIR"
