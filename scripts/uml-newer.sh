#!/usr/bin/env bash
# A User-Mode Linux that starts on a CPU with a large XSAVE state, for scripts/vcan-run.sh.
#
# Why: the with-vcan VM runs Debian bookworm's UML (Linux 6.1), which saves a process's FPU registers with
# ptrace(PTRACE_SETREGSET, NT_X86_XSTATE) from an 832-byte buffer. On this project's CI machine (a CPU with
# AVX-512 and AMX) that fails with EFAULT and the VM's init dies at once: "userspace - ptrace set fp regs
# failed, errno = 14". The likely cause is the host kernel's rule that such a write pass the whole XSAVE area
# (arch/x86/kernel/fpu/regset.c, xstateregs_set), which these features make far larger. Debian trixie's UML
# (6.12) fails the same way here; the UML of Debian testing (7.2 when this was written) boots.
#
# What: unpacks Debian testing's user-mode-linux (the kernel binary and its modules) and the C library it
# needs (glibc >= 2.38; bookworm has 2.36) from testing's libc6 into target/uml/root, and points the
# binary's interpreter and library path at that C library (patchelf). Packages are found through testing's
# Packages index and checked against its SHA256. Nothing is installed into the system but patchelf.
# Idempotent: a second run only prints the directory.
#
# Usage: scripts/uml-newer.sh      prints the directory DIR: DIR/linux.uml is the kernel, DIR/modules its
#                                  modules (one folder per kernel release, as /usr/lib/uml/modules)
# Environment: DEBIAN_MIRROR (default http://deb.debian.org/debian), DEBIAN_SUITE (default testing).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DIR=$ROOT/target/uml
MIRROR=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
SUITE=${DEBIAN_SUITE:-testing}

if [[ -x $DIR/linux.uml && -d $DIR/modules/ ]]; then
    echo "$DIR"
    exit 0
fi
say() { echo "uml-newer: $*" >&2; }

if ! command -v patchelf >/dev/null; then
    sudo=
    [[ $(id -u) == 0 ]] || sudo=sudo
    { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq patchelf; } \
        </dev/null >&2 || { say "cannot install patchelf"; exit 1; }
fi

rm -rf "$DIR"
mkdir -p "$DIR/root"
index=$DIR/Packages
say "reading $MIRROR $SUITE's package index"
curl -fsS --retry 3 -m 300 "$MIRROR/dists/$SUITE/main/binary-amd64/Packages.xz" | xz -dc >"$index"

# Downloads package $1 as the index names it, checks its SHA256 and unpacks it into $DIR/root.
unpack() {
    local fields file sum
    fields=$(awk -v p="$1" '
        $0 == "Package: " p { hit = 1 }
        hit && /^Filename: / { f = $2 }
        hit && /^SHA256: / { s = $2 }
        hit && /^$/ { exit }
        END { if (f != "" && s != "") print f, s }' "$index")
    [[ -n $fields ]] || { say "no package $1 in $SUITE"; exit 1; }
    read -r file sum <<<"$fields"
    say "fetching $file"
    curl -fsS --retry 3 -m 600 -o "$DIR/pkg.deb" "$MIRROR/$file"
    echo "$sum  $DIR/pkg.deb" | sha256sum -c --quiet - || { say "$file: SHA256 differs from the index"; exit 1; }
    dpkg-deb -x "$DIR/pkg.deb" "$DIR/root"
    rm -f "$DIR/pkg.deb"
}
unpack user-mode-linux
unpack libc6
rm -f "$index"

lib=$DIR/root/usr/lib/x86_64-linux-gnu
[[ -e $lib/ld-linux-x86-64.so.2 ]] || { say "no ld-linux-x86-64.so.2 in $SUITE's libc6"; exit 1; }
modules=$(find "$DIR/root/usr/lib/uml/modules" -mindepth 1 -maxdepth 1 -type d -name '[0-9]*' | head -n 1)
[[ -n $modules ]] || { say "no modules in $SUITE's user-mode-linux"; exit 1; }
cp "$DIR/root/usr/bin/linux.uml" "$DIR/linux.uml.new"
patchelf --set-interpreter "$lib/ld-linux-x86-64.so.2" --set-rpath "$lib" "$DIR/linux.uml.new"
mv "$DIR/root/usr/lib/uml/modules" "$DIR/modules"
mv "$DIR/linux.uml.new" "$DIR/linux.uml"
say "User-Mode Linux ${modules##*/} ready in $DIR"
echo "$DIR"
