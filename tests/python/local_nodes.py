"""python canopen's LocalNode (a CANopen node nobody here wrote) for our async master to talk to over vcan:
`python3 tests/python/local_nodes.py EDS NODE_ID...` serves each node-ID from the EDS on vcan0 (one python-can
socket), prints "ready" and runs until its stdin closes (tests/vcan_master_python.rs drives it).
"""

import sys

import canopen


def main():
    eds, ids = sys.argv[1], [int(a, 0) for a in sys.argv[2:]]
    network = canopen.Network()
    network.connect(interface="socketcan", channel="vcan0")
    for node_id in ids:
        node = canopen.LocalNode(node_id, eds)
        # Its serial number tells the nodes apart (1018h:04 = 1000 + node-ID).
        node.sdo[0x1018][4].raw = 1000 + node_id
        network.add_node(node)
    print("ready", flush=True)
    sys.stdin.read()
    network.disconnect()


if __name__ == "__main__":
    main()
