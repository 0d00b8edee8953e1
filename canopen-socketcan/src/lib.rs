//! Linux SocketCAN adapter for `canopen-core` (filled by the SocketCAN issue).
