//! SDO: server and client state machines (CiA 301 §7.2.4). Frame formats are in [`crate::wire::sdo`].
