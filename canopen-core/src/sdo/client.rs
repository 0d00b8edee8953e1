//! SDO client (placeholder).
#![allow(missing_docs)]
pub struct SdoClient;
pub struct SdoClientParams;
