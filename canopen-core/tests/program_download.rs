//! CiA 302-3 program download (`canopen_core::program`) through our SDO client and server, in simulated
//! time: the image streams into the sink chunk by chunk (segmented and block transfer), an abort mid-way
//! tells the sink, program control answers as CiA 302-3 asks.
//!
//! Run: `cargo test -p canopen-core --test program_download`.

use canopen_core::od::{AbortCode, NoApplication, ObjectDictionary};
use canopen_core::program::{
    ProgramCommand, ProgramDownload, ProgramSink, FLASH_DATA_FORMAT_ERROR, FLASH_IN_PROGRESS, FLASH_NO_VALID_PROGRAM,
};
use canopen_core::sdo::client::{ClientError, ClientEvent, Mode, SliceData};
use canopen_core::sdo::{SdoClient, SdoClientParams, SdoEvent, SdoServer, SdoServerParams};
use canopen_core::wire::sdo::Multiplexer;
use canopen_core::{Instant, NodeId};

const DATA: Multiplexer = Multiplexer::new(0x1F50, 1);
const CONTROL: Multiplexer = Multiplexer::new(0x1F51, 1);

/// What the sink was told, in order; the image it received; a chunk size limit to prove streaming.
#[derive(Default)]
struct Recorder {
    calls: Vec<String>,
    image: Vec<u8>,
    largest_chunk: usize,
    /// Refuse the image at `end` (a bad CRC, say).
    refuse_end: bool,
}

impl ProgramSink for Recorder {
    fn begin(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
        self.calls.push(format!("begin {size:?}"));
        self.image.clear();
        Ok(())
    }
    fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        assert_eq!(offset, self.image.len(), "chunks come in contiguous offsets");
        self.largest_chunk = self.largest_chunk.max(data.len());
        self.image.extend_from_slice(data);
        Ok(())
    }
    fn end(&mut self, total: usize) -> Result<(), AbortCode> {
        self.calls.push(format!("end {total}"));
        if self.refuse_end {
            return Err(AbortCode::GeneralError);
        }
        Ok(())
    }
    fn abort(&mut self) {
        self.calls.push("abort".into());
    }
    fn control(&mut self, command: ProgramCommand) -> Result<(), AbortCode> {
        self.calls.push(format!("{command:?}"));
        Ok(())
    }
    fn software_id(&self) -> u32 {
        crc32(&self.image)
    }
}

fn crc32(data: &[u8]) -> u32 {
    crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(data)
}

type Od = ProgramDownload<Recorder, NoApplication>;

fn image(len: usize) -> Vec<u8> {
    (0..len).map(|i| (i * 7 + i / 251) as u8).collect()
}

/// One transfer between our client and server, lossless; `abort_after` makes the client abort once that
/// many request frames went out. Returns the client's result and the server's events.
fn transfer(
    od: &mut Od,
    mux: Multiplexer,
    payload: &[u8],
    mode: Mode,
    abort_after: Option<usize>,
) -> (Option<ClientEvent>, Vec<SdoEvent>) {
    let node = NodeId::new(4).unwrap();
    let mut client = SdoClient::new(SdoClientParams::for_server(node));
    let mut server = SdoServer::new(SdoServerParams::default_server(node));
    let mut now = Instant::from_millis(1);
    let mut buf = payload.to_vec();
    client.start_download(now, mux, payload.len(), mode).unwrap();
    let (mut result, mut events, mut sent) = (None, Vec::new(), 0);
    for _ in 0..100_000 {
        now += canopen_core::Duration::from_micros(100);
        let mut data = SliceData::download(&mut buf);
        let Some(req) = client.poll_transmit(now, &mut data) else {
            if client.is_idle() && server.is_idle() {
                break;
            }
            // Waiting on the server: nothing in flight on a lossless link means a bug.
            panic!("stalled");
        };
        sent += 1;
        let r = server.handle_request(now, &req, od);
        events.extend(r.event);
        if let Some(resp) = r.frame {
            if let Some(ev) = client.handle_response(now, &resp, &mut data) {
                result.get_or_insert(ev);
            }
        }
        if abort_after == Some(sent) {
            if let Some(ev) = client.abort(AbortCode::GeneralError) {
                result.get_or_insert(ev);
            }
        }
    }
    (result, events)
}

fn write_control(od: &mut Od, value: u8) -> Option<ClientEvent> {
    transfer(od, CONTROL, &[value], Mode::Auto, None).0
}

fn read_u32(od: &Od, index: u16) -> u32 {
    let mut b = [0u8; 4];
    assert_eq!(od.read(index, 1, 0, &mut b), Ok(4));
    u32::from_le_bytes(b)
}

/// Segmented and block (with and without CRC) downloads of 1F50h:01 stream the image into the sink, never
/// more than one SDO block segment (7 bytes) at a time; 1F57h then says "valid" and 1F56h the sink's id.
/// PRG-01, PRG-05, PRG-06.
#[test]
fn image_streams_into_the_sink_segmented_and_block() {
    for mode in [
        Mode::Segmented,
        Mode::Block { crc: true, blksize: 127, pst: 0 },
        Mode::Block { crc: false, blksize: 16, pst: 0 },
    ] {
        for len in [0usize, 5, 889, 10_000] {
            let mut od = ProgramDownload::new(Recorder::default(), NoApplication);
            let img = image(len);
            let (result, events) = transfer(&mut od, DATA, &img, mode, None);
            assert_eq!(result, Some(ClientEvent::Done { len }), "{mode:?} {len}");
            assert_eq!(events, [SdoEvent::Written { index: 0x1F50, sub: 1 }], "{mode:?} {len}");
            assert_eq!(od.sink.image, img, "{mode:?} {len}");
            assert!(od.sink.largest_chunk <= 7, "{mode:?}: chunks of {} bytes", od.sink.largest_chunk);
            assert_eq!(od.sink.calls.last().map(String::as_str), Some(format!("end {len}").as_str()));
            assert_eq!(read_u32(&od, 0x1F57), 0, "flash status: program valid");
            assert_eq!(read_u32(&od, 0x1F56), crc32(&img));
        }
    }
}

/// A client abort in the middle of a segmented or block download reaches the sink as `abort`; 1F57h then
/// says "no valid program" and start is refused with 0800 0022h. PRG-04, PRG-03.
#[test]
fn abort_mid_way_tells_the_sink() {
    for mode in [Mode::Segmented, Mode::Block { crc: true, blksize: 32, pst: 0 }] {
        let mut od = ProgramDownload::new(Recorder::default(), NoApplication);
        let (result, _) = transfer(&mut od, DATA, &image(5000), mode, Some(40));
        assert_eq!(result, Some(ClientEvent::Failed(ClientError::Local(AbortCode::GeneralError))), "{mode:?}");
        // The abort frame goes out on the next poll; the server takes it.
        assert!(od.sink.calls.contains(&"abort".to_string()), "{mode:?}: {:?}", od.sink.calls);
        assert!(!od.sink.calls.iter().any(|c| c.starts_with("end")), "{mode:?}");
        assert_eq!(od.flash_status(), FLASH_NO_VALID_PROGRAM, "{mode:?}");
        assert_eq!(write_control(&mut od, 1), Some(ClientEvent::Failed(ClientError::Server(0x0800_0022))));
    }
}

/// An image the sink refuses at its end is answered with the sink's code; 1F57h says "data format error".
/// PRG-04, PRG-06.
#[test]
fn refused_image_is_not_a_program() {
    let mut od = ProgramDownload::new(Recorder { refuse_end: true, ..Recorder::default() }, NoApplication);
    let (result, events) = transfer(&mut od, DATA, &image(300), Mode::Segmented, None);
    assert_eq!(result, Some(ClientEvent::Failed(ClientError::Server(AbortCode::GeneralError.code()))));
    assert!(events.iter().all(|e| !matches!(e, SdoEvent::Written { .. })));
    assert_eq!(od.flash_status(), FLASH_DATA_FORMAT_ERROR);
    assert_eq!(od.sink.calls, ["begin Some(300)", "end 300", "abort"]);
}

/// Program control (1F51h:01): values other than 00h..03h are 0609 0030h; start/reset without a valid
/// program, clear and download while running are 0800 0022h; the accepted commands reach the sink and
/// 1F51h reads the state back. PRG-02, PRG-03.
#[test]
fn program_control_answers() {
    let refused = |code: u32| Some(ClientEvent::Failed(ClientError::Server(code)));
    let done1 = Some(ClientEvent::Done { len: 1 });
    let mut od = ProgramDownload::new(Recorder::default(), NoApplication);
    for bad in [4u8, 0x7F, 0x80, 0xFF] {
        assert_eq!(write_control(&mut od, bad), refused(0x0609_0030), "value {bad:#x}");
    }
    assert_eq!(write_control(&mut od, 1), refused(0x0800_0022), "start without a program");
    assert_eq!(write_control(&mut od, 2), refused(0x0800_0022), "reset without a program");
    assert_eq!(write_control(&mut od, 0), done1, "stop is always accepted");
    assert_eq!(transfer(&mut od, CONTROL, &[1, 0], Mode::Segmented, None).0, refused(0x0607_0012));
    assert_eq!(transfer(&mut od, DATA, &image(100), Mode::Segmented, None).0, Some(ClientEvent::Done { len: 100 }));
    assert_eq!(write_control(&mut od, 1), done1);
    assert!(od.running());
    let mut b = [0u8; 1];
    assert_eq!(od.read(0x1F51, 1, 0, &mut b), Ok(1));
    assert_eq!(b, [1]);
    assert_eq!(write_control(&mut od, 3), refused(0x0800_0022), "clear while running");
    assert_eq!(transfer(&mut od, DATA, &image(10), Mode::Segmented, None).0, refused(0x0800_0022));
    assert_eq!(write_control(&mut od, 2), done1, "reset a running program");
    assert_eq!(write_control(&mut od, 0), done1);
    assert_eq!(write_control(&mut od, 3), done1, "clear when stopped");
    assert_eq!(od.flash_status(), FLASH_NO_VALID_PROGRAM);
    assert_eq!(write_control(&mut od, 1), refused(0x0800_0022));
    assert_eq!(od.sink.calls, ["Stop", "begin Some(100)", "end 100", "Start", "Reset", "Stop", "Clear"]);
}

/// The objects' shape: sub 0 counts one program area, 1F50h:01 is write-only, 1F56h/1F57h read-only,
/// a second area does not exist, other indices reach the application. PRG-05, PRG-06.
#[test]
fn object_shape() {
    let mut od = ProgramDownload::new(Recorder::default(), NoApplication);
    let mut b = [0u8; 4];
    for index in [0x1F50, 0x1F51, 0x1F56, 0x1F57] {
        assert_eq!(od.read(index, 0, 0, &mut b), Ok(1));
        assert_eq!(b[0], 1);
        assert_eq!(od.info(index, 2).err(), Some(AbortCode::SubIndexDoesNotExist));
    }
    assert_eq!(od.read(0x1F50, 1, 0, &mut b), Err(AbortCode::ReadOfWriteOnly));
    assert_eq!(od.write(0x1F56, 1, &[0; 4]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.write(0x1F57, 1, &[0; 4]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.info(0x1F52, 0).err(), Some(AbortCode::ObjectDoesNotExist));
    assert_eq!(od.info(0x2000, 0).err(), Some(AbortCode::ObjectDoesNotExist));
    assert_eq!(read_u32(&od, 0x1F57), FLASH_NO_VALID_PROGRAM);
    assert_eq!(FLASH_IN_PROGRESS, 1);
}

/// The merged dictionary routes 1F50h–1F57h to an application that serves them
/// (`ObjectDictionary::SERVES_PROGRAM`), and to the communication profile, which has none of them,
/// otherwise. PRG-06.
#[test]
fn merged_routes_the_program_objects() {
    use canopen_core::od::Merged;
    use canopen_core::profile::{CommProfile, NodeConfig};
    type Z = canopen_core::Sizes<1, 16, 16, 0, 0>;
    let app = ProgramDownload::new(Recorder::default(), NoApplication);
    let mut m = Merged { comm: CommProfile::<Z>::new(NodeConfig::DEFAULT), app };
    let mut b = [0u8; 4];
    assert_eq!(m.read(0x1F57, 1, 0, &mut b), Ok(4));
    assert_eq!(u32::from_le_bytes(b), FLASH_NO_VALID_PROGRAM);
    assert_eq!(m.write(0x1F51, 1, &[9]), Err(AbortCode::InvalidValue));
    assert_eq!(m.read(0x1000, 0, 0, &mut b), Ok(4), "the rest of 1000h-1FFFh still reaches the profile");
    let mut plain = Merged { comm: CommProfile::<Z>::new(NodeConfig::DEFAULT), app: NoApplication };
    assert_eq!(plain.read(0x1F57, 1, 0, &mut b), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(plain.write(0x1F51, 1, &[1]), Err(AbortCode::ObjectDoesNotExist));
}

/// The merged dictionary lists every object in index order (OD-12: the EDS object lists and sections),
/// the program objects of the application half (1F50h–1F57h) before the profile's 1F80h: the EDS has
/// them all, sorted. PRG-06.
#[test]
fn merged_eds_lists_the_program_objects_in_order() {
    use canopen_core::od::{Merged, OdDescribe};
    use canopen_core::profile::{eds, CommProfile, NodeConfig};
    type Z = canopen_core::Sizes<1, 16, 16, 1, 1>;
    let app = ProgramDownload::new(Recorder::default(), NoApplication);
    let m = Merged { comm: CommProfile::<Z>::new(NodeConfig::DEFAULT), app };
    let all: Vec<u16> = (0..m.object_count()).map(|n| m.object(n).unwrap().index).collect();
    assert!(all.windows(2).all(|w| w[0] < w[1]), "{all:X?}");
    // The MPDO lists 1FA0h/1FD0h (feature `mpdo`) come after 1F80h.
    let mpdo: &[u16] = if cfg!(feature = "mpdo") { &[0x1FA0, 0x1FD0] } else { &[] };
    let tail = [&[0x1F50, 0x1F51, 0x1F56, 0x1F57, 0x1F80][..], mpdo].concat();
    assert_eq!(all[all.len() - tail.len()..], tail[..]);
    assert_eq!(m.object(all.len()), None);
    let mut text = String::new();
    eds::write_eds(&mut text, &eds::EdsInfo::DEFAULT, &m).unwrap();
    let sections: Vec<u16> = text
        .lines()
        .filter_map(|l| l.strip_prefix('[')?.strip_suffix(']'))
        .filter(|s| s.len() == 4)
        .filter_map(|s| u16::from_str_radix(s, 16).ok())
        .collect();
    assert_eq!(sections, all, "one section per object, in index order");
    let listed = text.split("[OptionalObjects]").nth(1).unwrap();
    let pos = |index: &str| listed.find(index).unwrap();
    assert!(pos("=0x1F50\n") < pos("=0x1F57\n") && pos("=0x1F57\n") < pos("=0x1F80\n"), "{listed}");
}
