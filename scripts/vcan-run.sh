# Sourced by the scripts that need SocketCAN interfaces: `vcan_run IFACES -- COMMAND...` runs COMMAND
# where the interfaces (comma-separated, e.g. vcan0,vcan1) exist.
#   - On a Linux whose kernel has CAN and where they are up (`sudo modprobe vcan; sudo ip link add dev
#     vcan0 type vcan; sudo ip link set up vcan0`): COMMAND runs right here.
#   - Otherwise (a kernel without CAN, like this project's CI machine): inside the small User-Mode Linux VM
#     that CI's environment provides, `$SHARED/vcan/with-vcan` (SHARED defaults to ../shared beside the
#     repository; it is not part of the repository). A VM that cannot start exits 125. The helper itself
#     copes with CPUs the stock User-Mode Linux cannot start on (it fetches a newer one); nothing here does.
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
        "$shared/vcan/with-vcan" --ifaces "$ifaces" -- "$@"
    fi
}
