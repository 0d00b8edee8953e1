//! Lookup cost of a derive-generated dictionary with 100 entries (10 ARRAYs of 9 UNSIGNED32 + their sub 0):
//! `info` (binary search), `read` of one UNSIGNED32 (search + jump-table dispatch + encode), `write`
//! (search + decode + limits), a PDO read through a resolved handle (no search), and a read of 1000h
//! through the merged comm profile.

use canopen_core::profile::NodeConfig;
use canopen_core::Sizes;
use canopen_core::{
    od::{Merged, ObjectDictionary, PdoDir},
    profile::CommProfile,
};
use canopen_od_derive::ObjectDictionary;
use criterion::{black_box, criterion_group, criterion_main, Criterion};

#[derive(ObjectDictionary, Default)]
struct Hundred {
    #[od(index = 0x2000, pdo = "both")]
    a0: [u32; 9],
    #[od(index = 0x2001, pdo = "both")]
    a1: [u32; 9],
    #[od(index = 0x2002, pdo = "both")]
    a2: [u32; 9],
    #[od(index = 0x2003, pdo = "both")]
    a3: [u32; 9],
    #[od(index = 0x2004, pdo = "both")]
    a4: [u32; 9],
    #[od(index = 0x6000, pdo = "both")]
    a5: [u32; 9],
    #[od(index = 0x6001, pdo = "both")]
    a6: [u32; 9],
    #[od(index = 0x6002, pdo = "both", max = 1000)]
    a7: [u32; 9],
    #[od(index = 0x6003, pdo = "both")]
    a8: [u32; 9],
    #[od(index = 0x6004, pdo = "both")]
    a9: [u32; 9],
}

fn bench(c: &mut Criterion) {
    assert_eq!(Hundred::OD_ENTRIES.len(), 100);
    let mut od = Hundred::default();
    let keys: Vec<(u16, u8)> = Hundred::OD_ENTRIES.iter().map(|e| (e.index, e.sub)).collect();
    c.bench_function("info: 100 lookups (binary search)", |b| {
        b.iter(|| {
            for &(i, s) in &keys {
                black_box(od.info(black_box(i), black_box(s)).ok());
            }
        })
    });
    c.bench_function("read u32 6004h:09 (search + dispatch)", |b| {
        let mut buf = [0u8; 4];
        b.iter(|| black_box(od.read(black_box(0x6004), black_box(9), 0, &mut buf)))
    });
    c.bench_function("write u32 6002h:05 with limit", |b| {
        b.iter(|| black_box(od.write(black_box(0x6002), black_box(5), black_box(&[7, 0, 0, 0]))))
    });
    c.bench_function("miss: unknown index", |b| b.iter(|| black_box(od.info(black_box(0x3000), 0))));
    let h = od.pdo_resolve(0x6004, 9, PdoDir::Tpdo).expect("mappable");
    c.bench_function("pdo_read via handle (no search)", |b| {
        let mut buf = [0u8; 4];
        b.iter(|| black_box(od.pdo_read(black_box(&h), &mut buf)))
    });
    let merged =
        Merged { comm: CommProfile::<Sizes<4, 16, 16, 0, 0>>::new(NodeConfig::DEFAULT), app: Hundred::default() };
    c.bench_function("merged read 1000h", |b| {
        let mut buf = [0u8; 4];
        b.iter(|| black_box(merged.read(black_box(0x1000), 0, 0, &mut buf)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
