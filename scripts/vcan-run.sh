# Sourced by the scripts that need SocketCAN interfaces: `vcan_run IFACES -- COMMAND...` runs COMMAND
# where the interfaces (comma-separated, e.g. vcan0,vcan1) exist.
#   - On a Linux whose kernel has CAN and where they are up (`sudo modprobe vcan; sudo ip link add dev
#     vcan0 type vcan; sudo ip link set up vcan0`): COMMAND runs right here.
#   - Otherwise (a kernel without CAN, like this project's CI machine): inside the small User-Mode Linux VM
#     that CI's environment provides, `$SHARED/vcan/with-vcan` (SHARED defaults to ../shared beside the
#     repository; it is not part of the repository). A VM that cannot start exits 125. The helper itself
#     copes with CPUs the stock User-Mode Linux cannot start on (it fetches a newer one); nothing here does.

# True when every interface of IFACES (comma-separated) exists on this host, so vcan_run runs here, not in a VM.
vcan_present() {
    local i
    for i in ${1//,/ }; do
        [[ -e /sys/class/net/$i ]] || return 1
    done
}
vcan_run() {
    local ifaces=$1
    shift
    [[ ${1:-} == -- ]] && shift
    if vcan_present "$ifaces"; then
        "$@"
    else
        local shared=${SHARED:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/../shared}
        if [[ ! -x $shared/vcan/with-vcan ]]; then
            echo "vcan_run: no interface $ifaces here and no VM helper at $shared/vcan/with-vcan;" \
                "create it: sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0" >&2
            return 125
        fi
        "$shared/vcan/with-vcan" --ifaces "$ifaces" -- "$@"
    fi
}
# Stops process PID and every process below it: a `vcan_run ... &` started in the background (the VM helper and
# its User-Mode Linux processes), when a step beside it fails or the caller is interrupted.
kill_tree() {
    local c
    for c in $(pgrep -P "$1"); do kill_tree "$c"; done
    kill "$1" 2>/dev/null || true
}
