//! [`Drive`] as one dictionary: the CiA 402 objects serve 6000h–67FFh (the profile area of the first
//! logical device), the application's dictionary every other index, with one comparison per access (as
//! the core's `od::Merged` splits the communication profile from the application: both are the core's
//! `route_by_index!`). The EDS lists both halves in index order (`describe_merged!`), so the application
//! may own objects above 67FFh too.

use canopen_core::od::{EntryDesc, ObjectDictionary, OdDescribe};

use crate::Drive;

/// Whether `index` is one of the drive's (6000h–67FFh).
///
/// ```
/// assert!(canopen_cia402::is_drive_index(0x6041));
/// assert!(!canopen_cia402::is_drive_index(0x2000));
/// ```
pub const fn is_drive_index(index: u16) -> bool {
    index >= 0x6000 && index <= 0x67FF
}

impl<A: ObjectDictionary> ObjectDictionary for Drive<A> {
    const SERVES_PROGRAM: bool = A::SERVES_PROGRAM;
    const STREAMS: bool = A::STREAMS;
    const SEGMENTED_UPLOADS: bool = A::SEGMENTED_UPLOADS;

    canopen_core::route_by_index!(is_drive_index, objects, app);

    /// Reset Application: both halves back to their defaults.
    fn restore_defaults(&mut self) {
        self.objects.reset();
        self.app.restore_defaults();
    }
    /// The drive's objects are always reported (the application cycles the drive when 6040h, 6060h or a
    /// target is written by SDO); the application's as it says.
    fn write_events(&self) -> bool {
        true
    }
}

impl<A: OdDescribe> OdDescribe for Drive<A> {
    canopen_core::describe_merged!(objects, app);
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if is_drive_index(index) {
            self.objects.entry(index, sub)
        } else {
            self.app.entry(index, sub)
        }
    }
}
