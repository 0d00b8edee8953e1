# Sourced by the scripts that need SocketCAN interfaces: `vcan_run IFACES -- COMMAND...` runs COMMAND
# where the interfaces (comma-separated, e.g. vcan0,vcan1) exist.
#   - On a Linux whose kernel has CAN and where they are up (`sudo modprobe vcan; sudo ip link add dev
#     vcan0 type vcan; sudo ip link set up vcan0`): COMMAND runs right here.
#   - Otherwise (a kernel without CAN, like this project's CI machine): inside the small User-Mode Linux VM
#     that CI's environment provides, `$SHARED/vcan/with-vcan` (SHARED defaults to ../shared beside the
#     repository; it is not part of the repository). A VM that cannot start exits 125.
#     That VM is Debian bookworm's User-Mode Linux 6.1, which cannot start on some CPUs (one with AVX-512
#     and AMX here; scripts/uml-newer.sh says why). The first call probes it; where it fails that way, every call runs the
#     helper in a private mount namespace with a newer UML (scripts/uml-newer.sh, under target/uml) mounted
#     over the stock one, so the helper and the system stay as they are. VCAN_RUN_UML remembers the choice
#     ("stock" or the newer UML's directory) for the scripts this shell starts.
vcan_run() {
    local ifaces=$1
    shift
    [[ ${1:-} == -- ]] && shift
    local missing=0 i
    for i in ${ifaces//,/ }; do
        [[ -e /sys/class/net/$i ]] || missing=1
    done
    if [[ $missing == 0 ]]; then
        "$@"
    else
        local shared=${SHARED:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/../shared}
        if [[ ! -x $shared/vcan/with-vcan ]]; then
            echo "vcan_run: no interface $ifaces here and no VM helper at $shared/vcan/with-vcan;" \
                "create it: sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0" >&2
            return 125
        fi
        [[ -n ${VCAN_RUN_UML:-} ]] || vcan_pick_uml "$shared" || return 125
        if [[ $VCAN_RUN_UML == stock ]]; then
            "$shared/vcan/with-vcan" --ifaces "$ifaces" -- "$@"
        else
            vcan_newer_uml "$VCAN_RUN_UML" "$shared/vcan/with-vcan" --ifaces "$ifaces" -- "$@"
        fi
    fi
}

# Runs COMMAND... with the User-Mode Linux in DIR mounted over the stock one, in a mount namespace of its own.
vcan_newer_uml() {
    local dir=$1
    shift
    unshare --mount --propagation private -- bash -c \
        'mount --bind "$1/linux.uml" /usr/bin/linux.uml && mount --bind "$1/modules" /usr/lib/uml/modules &&
         shift && exec "$@"' vcan_newer_uml "$dir" "$@"
}

# Sets VCAN_RUN_UML: "stock" when the helper's VM starts, else the directory of a newer UML that does.
vcan_pick_uml() {
    local shared=$1 log=${TMPDIR:-/tmp}/with-vcan-console.log dir
    if "$shared/vcan/with-vcan" -- true 2>/dev/null; then
        export VCAN_RUN_UML=stock
        return 0
    fi
    if ! grep -q "ptrace set fp regs failed" "$log" 2>/dev/null; then
        echo "vcan_run: the with-vcan VM cannot start (its console: $log)" >&2
        return 1
    fi
    echo "vcan_run: the stock User-Mode Linux cannot start on this CPU (its XSAVE state is too large for it);" \
        "using a newer one (scripts/uml-newer.sh)" >&2
    dir=$(bash "$(dirname "${BASH_SOURCE[0]}")/uml-newer.sh") || return 1
    if ! vcan_newer_uml "$dir" "$shared/vcan/with-vcan" -- true; then
        echo "vcan_run: the newer User-Mode Linux in $dir cannot start either (its console: $log)" >&2
        return 1
    fi
    export VCAN_RUN_UML=$dir
}
