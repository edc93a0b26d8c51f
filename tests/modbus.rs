//! The Modbus TCP server, driven from the test by `rmodbus`' client over
//! a std `TcpStream` on 127.0.0.1 (free port): every function code, the
//! exceptions, malformed frames, connection limits and idle timeouts,
//! forcing, and a real-time run. The program is numbered the `iec` way
//! (the default): `%QW1` is holding register 1, `%MD2` registers 2052-2053;
//! tests/modbus_openplc.rs serves the `openplc` convention.

use plcrun::{
    ModbusConfig, ModbusExchange, ModbusServer, Options, Plc, Session, TaskRunner, TraceFormat,
    TraceWriter,
};
use rmodbus::client::ModbusRequest;
use rmodbus::{ErrorKind, ModbusProto};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

const PROGRAM: &str = "
PROGRAM P
VAR
    start AT %QX0.0 : BOOL;      (* coil 0, written by the client *)
    running AT %QX0.1 : BOOL;    (* coil 1 *)
    count AT %QW1 : INT;         (* holding register 1: cycles while start *)
    level_copy AT %QW2 : INT;    (* holding register 2: level + 1 *)
    setpoint AT %MW0 : INT;      (* holding register 1024, written by the client *)
    doubled AT %MW1 : INT;       (* holding register 1025 *)
    big AT %MD2 : DINT;          (* holding registers 2052 (high), 2053 (low) *)
    huge AT %ML2 : LINT;         (* holding registers 4104..4107 *)
    sensor AT %IX0.2 : BOOL;     (* discrete input 2, written by the host *)
    level AT %IW2 : INT;         (* input register 2, written by the host *)
END_VAR
running := start;
IF start THEN count := count + 1; END_IF;
doubled := setpoint * 2;
big := DINT#100000 + INT_TO_DINT(setpoint);
huge := LINT#16#0102030405060708;
level_copy := level + 1;
END_PROGRAM
";

fn plc() -> Plc {
    Plc::compile_files(&[("p.st", PROGRAM)], &Options::default()).unwrap()
}

fn serve(config: ModbusConfig) -> (ModbusServer, ModbusExchange, Plc) {
    let (server, mut exchange) = ModbusServer::bind("127.0.0.1:0", config).unwrap();
    let mut plc = plc();
    exchange.exchange(&mut plc);
    (server, exchange, plc)
}

/// One cycle as a host runs it: the cycle, then the exchange.
fn cycle(plc: &mut Plc, exchange: &mut ModbusExchange) {
    plc.run_cycle().unwrap();
    exchange.exchange(plc);
}

/// A Modbus TCP client: `rmodbus` builds the requests and parses the
/// responses; this reads one response frame off the socket.
struct Client {
    stream: TcpStream,
    tr_id: u16,
}

impl Client {
    fn connect(addr: SocketAddr) -> Client {
        let stream = TcpStream::connect(addr).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(5)))
            .unwrap();
        Client { stream, tr_id: 0 }
    }

    fn request(&mut self) -> ModbusRequest {
        self.tr_id = self.tr_id.wrapping_add(1);
        ModbusRequest::new_tcp_udp(1, self.tr_id)
    }

    /// Sends `frame`, returns the response frame.
    fn exchange(&mut self, frame: &[u8]) -> std::io::Result<Vec<u8>> {
        self.stream.write_all(frame)?;
        read_frame(&mut self.stream)
    }

    fn call(
        &mut self,
        build: impl FnOnce(&mut ModbusRequest, &mut Vec<u8>) -> Result<(), ErrorKind>,
    ) -> (ModbusRequest, Vec<u8>) {
        let mut req = self.request();
        let mut frame = Vec::new();
        build(&mut req, &mut frame).unwrap();
        let response = self.exchange(&frame).unwrap();
        (req, response)
    }

    fn coils(&mut self, start: u16, count: u16) -> Result<Vec<bool>, ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_get_coils(start, count, f));
        let mut out = Vec::new();
        req.parse_bool(&resp, &mut out).map(|()| out)
    }

    fn discretes(&mut self, start: u16, count: u16) -> Result<Vec<bool>, ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_get_discretes(start, count, f));
        let mut out = Vec::new();
        req.parse_bool(&resp, &mut out).map(|()| out)
    }

    fn holdings(&mut self, start: u16, count: u16) -> Result<Vec<u16>, ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_get_holdings(start, count, f));
        let mut out = Vec::new();
        req.parse_u16(&resp, &mut out).map(|()| out)
    }

    fn inputs(&mut self, start: u16, count: u16) -> Result<Vec<u16>, ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_get_inputs(start, count, f));
        let mut out = Vec::new();
        req.parse_u16(&resp, &mut out).map(|()| out)
    }

    fn set_coil(&mut self, n: u16, on: bool) -> Result<(), ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_set_coil(n, u8::from(on), f));
        req.parse_ok(&resp)
    }

    fn set_coils(&mut self, start: u16, values: &[bool]) -> Result<(), ErrorKind> {
        let values: Vec<u8> = values.iter().map(|&b| u8::from(b)).collect();
        let (req, resp) = self.call(|r, f| r.generate_set_coils_bulk(start, &values, f));
        req.parse_ok(&resp)
    }

    fn set_holding(&mut self, n: u16, value: u16) -> Result<(), ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_set_holding(n, value, f));
        req.parse_ok(&resp)
    }

    fn set_holdings(&mut self, start: u16, values: &[u16]) -> Result<(), ErrorKind> {
        let (req, resp) = self.call(|r, f| r.generate_set_holdings_bulk(start, values, f));
        req.parse_ok(&resp)
    }

    /// Sends a hand-made PDU (function code first) and returns the
    /// response's PDU.
    fn raw(&mut self, pdu: &[u8]) -> Vec<u8> {
        self.tr_id = self.tr_id.wrapping_add(1);
        let response = self.exchange(&adu(self.tr_id, pdu)).unwrap();
        assert_eq!(
            &response[..2],
            &self.tr_id.to_be_bytes(),
            "transaction id echoed"
        );
        assert_eq!(&response[2..4], &[0, 0], "protocol 0");
        assert_eq!(
            usize::from(u16::from_be_bytes([response[4], response[5]])),
            response.len() - 6
        );
        response[7..].to_vec()
    }
}

/// A Modbus TCP frame for `pdu` (unit 1).
fn adu(tr_id: u16, pdu: &[u8]) -> Vec<u8> {
    let mut frame = tr_id.to_be_bytes().to_vec();
    frame.extend_from_slice(&[0, 0]);
    frame.extend_from_slice(&u16::try_from(pdu.len() + 1).unwrap().to_be_bytes());
    frame.push(1);
    frame.extend_from_slice(pdu);
    frame
}

fn read_frame(stream: &mut TcpStream) -> std::io::Result<Vec<u8>> {
    let mut frame = vec![0u8; 6];
    stream.read_exact(&mut frame)?;
    let len = usize::from(u16::from_be_bytes([frame[4], frame[5]]));
    frame.resize(6 + len, 0);
    stream.read_exact(&mut frame[6..])?;
    Ok(frame)
}

/// True when the server closed `stream` (EOF or reset) within `limit`.
fn closed_within(stream: &mut TcpStream, limit: Duration) -> bool {
    stream.set_read_timeout(Some(limit)).unwrap();
    let mut byte = [0u8; 1];
    match stream.read(&mut byte) {
        Ok(0) => true,
        Ok(_) => false,
        Err(e) => !matches!(
            e.kind(),
            std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
        ),
    }
}

fn wait_until(limit: Duration, mut done: impl FnMut() -> bool) -> bool {
    let until = Instant::now() + limit;
    while Instant::now() < until {
        if done() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    done()
}

#[test]
fn a_coil_written_by_a_client_drives_the_program_and_its_registers() {
    let (server, mut exchange, mut plc) = serve(ModbusConfig::default());
    let mut client = Client::connect(server.local_addr());
    assert_eq!(client.coils(0, 2), Ok(vec![false, false]));
    client.set_coil(0, true).unwrap();
    // Reads show the last completed cycle: the write is not in it yet.
    assert_eq!(client.coils(0, 1), Ok(vec![false]));
    cycle(&mut plc, &mut exchange); // publishes, then applies the write
    assert_eq!(client.coils(0, 1), Ok(vec![false]));
    assert_eq!(plc.read("start").unwrap().to_literal(), "FALSE");
    cycle(&mut plc, &mut exchange); // latches it: start, running, count = 1
    assert_eq!(client.coils(0, 2), Ok(vec![true, true]));
    assert_eq!(client.holdings(1, 1), Ok(vec![1]));
    for _ in 0..4 {
        cycle(&mut plc, &mut exchange);
    }
    assert_eq!(client.holdings(1, 1), Ok(vec![5]));
    assert_eq!(plc.read("count").unwrap().to_literal(), "5");
    client.set_coil(0, false).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(client.coils(0, 2), Ok(vec![false, false]));
    // The cycle that ran before the write was applied still counted.
    assert_eq!(client.holdings(1, 1), Ok(vec![6]));
    let stats = server.stats();
    assert_eq!((stats.writes_queued, stats.writes_applied), (2, 2));
    assert_eq!(stats.exceptions, 0);
}

#[test]
fn every_function_code_reaches_its_part_of_the_image() {
    let (server, mut exchange, mut plc) = serve(ModbusConfig::default());
    let mut client = Client::connect(server.local_addr());
    // FC 2 and 4: the host's inputs, latched by a cycle, then published.
    plc.process_image_mut().write_bit("%IX0.2", true).unwrap();
    plc.process_image_mut().write_word("%IW2", 1234).unwrap();
    // FC 6: %MW0 (holding register 1024).
    client.set_holding(1024, 21).unwrap();
    // FC 16: two registers of the %MD block past the program's %M area:
    // kept by the server, read back like the rest.
    client.set_holdings(3000, &[0xBEEF, 0x0042]).unwrap();
    // FC 15: coils 8..18 (%QX1.0 to %QX2.2), no variable there.
    let pattern = [
        true, false, true, true, false, false, true, false, true, true, false,
    ];
    client.set_coils(8, &pattern).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(client.discretes(0, 4), Ok(vec![false, false, true, false]));
    assert_eq!(client.inputs(2, 1), Ok(vec![1234]));
    assert_eq!(client.holdings(2, 1), Ok(vec![1235])); // level_copy, %QW2
    assert_eq!(client.holdings(1024, 2), Ok(vec![21, 42]));
    // %MD2 = 100021 = 16#000186B5, most significant word first.
    assert_eq!(client.holdings(2052, 2), Ok(vec![0x0001, 0x86B5]));
    assert_eq!(
        client.holdings(4104, 4),
        Ok(vec![0x0102, 0x0304, 0x0506, 0x0708])
    );
    assert_eq!(client.holdings(3000, 2), Ok(vec![0xBEEF, 0x0042]));
    assert_eq!(client.coils(8, 11), Ok(pattern.to_vec()));
    // The program sees the bytes too: %QB1 is coils 8..15.
    assert_eq!(plc.process_image().read_byte("%QB1"), Ok(0b0100_1101));
    // The largest quantities the protocol allows.
    assert_eq!(client.coils(0, 2000).map(|v| v.len()), Ok(2000));
    assert_eq!(client.holdings(8192 - 125, 125).map(|v| v.len()), Ok(125));
    let many: Vec<u16> = (0..123).collect();
    client.set_holdings(5000, &many).unwrap();
    let bits = vec![true; 1968];
    client.set_coils(8192 - 1968, &bits).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(client.holdings(5000, 123), Ok(many));
    assert_eq!(client.coils(8192 - 1968, 1968), Ok(bits));
    assert_eq!(server.stats().exceptions, 0);
}

#[test]
fn bad_requests_get_the_protocol_s_exceptions() {
    let (server, _exchange, _plc) = serve(ModbusConfig::default());
    let mut c = Client::connect(server.local_addr());
    let cases: &[(&[u8], u8)] = &[
        // Functions not implemented: 01.
        (&[7], 0x01),
        (&[8, 0, 0, 0xA5, 0x37], 0x01),
        (&[23, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0], 0x01),
        (&[0x2B, 0x0E, 1, 0], 0x01),
        (&[0x41], 0x01),
        // Addresses past the tables: 02.
        (&[1, 0x1F, 0xFF, 0, 2], 0x02),
        (&[2, 0x20, 0x00, 0, 1], 0x02),
        (&[3, 0x1F, 0xFE, 0, 3], 0x02),
        (&[4, 0x04, 0x00, 0, 1], 0x02),
        (&[5, 0x20, 0x00, 0xFF, 0], 0x02),
        (&[6, 0xFF, 0xFF, 0, 1], 0x02),
        (&[15, 0x1F, 0xFF, 0, 2, 1, 3], 0x02),
        (&[16, 0x20, 0x00, 0, 1, 2, 0, 1], 0x02),
        // Quantity 0 or over the limits, bad values, bad lengths: 03.
        (&[1, 0, 0, 0, 0], 0x03),
        (&[1, 0, 0, 0x07, 0xD1], 0x03),
        (&[2, 0, 0, 0, 0], 0x03),
        (&[3, 0, 0, 0, 0], 0x03),
        (&[3, 0, 0, 0, 126], 0x03),
        (&[4, 0, 0, 0, 126], 0x03),
        (&[5, 0, 0, 0x12, 0x34], 0x03),
        (&[15, 0, 0, 0, 0, 0], 0x03),
        (&[15, 0, 0, 0x07, 0xB1, 0xF7], 0x03),
        (&[15, 0, 0, 0, 9, 1, 0xFF], 0x03),
        (&[16, 0, 0, 0, 124, 248], 0x03),
        (&[16, 0, 0, 0, 2, 4, 0, 1], 0x03),
        (&[16, 0, 0, 0, 1, 4, 0, 1, 0, 2], 0x03),
        (&[3, 0, 0, 0], 0x03),
        (&[3, 0, 0, 0, 1, 0], 0x03),
        (&[16], 0x03),
    ];
    for (pdu, code) in cases {
        let resp = c.raw(pdu);
        assert_eq!(resp, vec![pdu[0] | 0x80, *code], "request {pdu:?}");
    }
    // The connection still serves after all of them.
    assert_eq!(c.holdings(0, 1), Ok(vec![0]));
    assert_eq!(server.stats().exceptions, cases.len() as u64);
}

#[test]
fn malformed_frames_close_their_connection_and_the_server_serves_on() {
    let config = ModbusConfig {
        idle_timeout: Duration::from_millis(500),
        ..ModbusConfig::default()
    };
    let (server, mut exchange, mut plc) = serve(config);
    let addr = server.local_addr();
    let mut good = Client::connect(addr);
    let garbage: &[&[u8]] = &[
        b"GET / HTTP/1.1\r\nHost: x\r\n\r\n",  // protocol id "/ "
        &[0, 1, 0, 1, 0, 6, 1, 3, 0, 0, 0, 1], // protocol id 1
        &[0, 1, 0, 0, 0, 0],                   // length 0
        &[0, 1, 0, 0, 0, 1, 1],                // length 1: no function code
        &[0, 1, 0, 0, 1, 0, 1, 3],             // length 256 > 254
        &[0, 1, 0, 0, 0xFF, 0xFF, 1, 3],       // length 65535
    ];
    for bytes in garbage {
        let mut s = TcpStream::connect(addr).unwrap();
        s.write_all(bytes).unwrap();
        assert!(
            closed_within(&mut s, Duration::from_secs(2)),
            "not closed: {bytes:?}"
        );
        assert_eq!(good.holdings(0, 1), Ok(vec![0]));
    }
    // A truncated frame (the header promises 6 bytes, 3 come): closed
    // after the idle timeout, like a half-open connection.
    let mut s = TcpStream::connect(addr).unwrap();
    s.write_all(&[0, 1, 0, 0, 0, 6, 1, 3, 0]).unwrap();
    let t0 = Instant::now();
    assert!(closed_within(&mut s, Duration::from_secs(3)));
    assert!(
        t0.elapsed() >= Duration::from_millis(200),
        "{:?}",
        t0.elapsed()
    );
    // A length field one short of the PDU: the cut PDU gets exception 03,
    // the stray byte then starts a header that never completes.
    let mut s = Client::connect(addr);
    let mut frame = adu(9, &[3, 0, 0, 0, 1]);
    frame[5] -= 1;
    s.stream.write_all(&frame).unwrap();
    let resp = read_frame(&mut s.stream).unwrap();
    assert_eq!(&resp[7..], &[0x83, 0x03]);
    assert!(closed_within(&mut s.stream, Duration::from_secs(3)));
    // Random bytes on many connections: never a panic, never a stall.
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    for _ in 0..100 {
        let mut s = TcpStream::connect(addr).unwrap();
        let n = 1 + (seed % 300) as usize;
        let bytes: Vec<u8> = (0..n)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                seed as u8
            })
            .collect();
        let _ = s.write_all(&bytes);
        let _ = s.shutdown(std::net::Shutdown::Write);
        let mut sink = Vec::new();
        s.set_read_timeout(Some(Duration::from_secs(3))).unwrap();
        let _ = s.read_to_end(&mut sink);
        assert!(sink.len() <= 260 * n, "{} bytes of response", sink.len());
    }
    // The server still serves (the first client went idle meanwhile).
    assert!(closed_within(&mut good.stream, Duration::from_secs(1)));
    let mut good = Client::connect(addr);
    good.set_coil(0, true).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(good.coils(0, 2), Ok(vec![true, true]));
    assert!(wait_until(Duration::from_secs(3), || server
        .stats()
        .connections_open
        == 1));
    assert!(server.stats().connections_dropped_malformed >= 6);
}

#[test]
fn clients_over_the_limit_are_refused_and_idle_ones_closed() {
    let config = ModbusConfig {
        max_clients: 4,
        idle_timeout: Duration::from_millis(400),
        ..ModbusConfig::default()
    };
    let (server, _exchange, _plc) = serve(config);
    let addr = server.local_addr();
    let mut clients: Vec<Client> = (0..4).map(|_| Client::connect(addr)).collect();
    for c in &mut clients {
        assert_eq!(c.holdings(0, 1), Ok(vec![0]));
    }
    // Many more: each is closed on arrival; the open count never passes 4.
    for _ in 0..50 {
        // The four keep asking, so none goes idle meanwhile.
        for c in &mut clients {
            assert_eq!(c.coils(0, 1), Ok(vec![false]));
        }
        let mut extra = TcpStream::connect(addr).unwrap();
        assert!(closed_within(&mut extra, Duration::from_secs(2)));
        assert!(server.stats().connections_open <= 4);
    }
    assert_eq!(server.stats().connections_refused, 50);
    // The four stay silent: closed after the idle timeout.
    for c in &mut clients {
        assert!(closed_within(&mut c.stream, Duration::from_secs(3)));
    }
    assert!(wait_until(Duration::from_secs(2), || server
        .stats()
        .connections_open
        == 0));
    assert_eq!(server.stats().connections_timed_out, 4);
    // Room again.
    let mut again = Client::connect(addr);
    assert_eq!(again.holdings(0, 1), Ok(vec![0]));
    // A client that keeps asking is not idle.
    for _ in 0..8 {
        std::thread::sleep(Duration::from_millis(100));
        assert_eq!(again.coils(0, 1), Ok(vec![false]));
    }
}

#[test]
fn a_full_write_queue_answers_busy_and_the_scan_takes_a_bounded_batch() {
    let config = ModbusConfig {
        write_queue: 8,
        ..ModbusConfig::default()
    };
    let (server, mut exchange, mut plc) = serve(config);
    let mut c = Client::connect(server.local_addr());
    for n in 0..8 {
        c.set_holding(1100 + n, n).unwrap();
    }
    assert_eq!(c.set_holding(1200, 1), Err(ErrorKind::SlaveDeviceBusy));
    let report = exchange.exchange(&mut plc);
    assert_eq!(report.writes_applied, 8);
    c.set_holding(1200, 1).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(c.holdings(1100, 8), Ok((0..8).collect::<Vec<u16>>()));
    assert_eq!(c.holdings(1200, 1), Ok(vec![1]));
    assert_eq!(server.stats().writes_refused_busy, 1);
    // The scan side gone: writes get exception 04, reads still work.
    drop(exchange);
    assert_eq!(c.set_holding(1200, 2), Err(ErrorKind::SlaveDeviceFailure));
    assert_eq!(c.holdings(1200, 1), Ok(vec![1]));
}

#[test]
fn a_forced_variable_stays_forced_whatever_a_client_writes() {
    let (server, mut exchange, mut plc) = serve(ModbusConfig::default());
    plc.force("start", "FALSE").unwrap();
    plc.force("setpoint", "7").unwrap();
    let mut c = Client::connect(server.local_addr());
    c.set_coil(0, true).unwrap();
    c.set_holding(1024, 500).unwrap();
    for _ in 0..3 {
        cycle(&mut plc, &mut exchange);
    }
    assert_eq!(c.coils(0, 2), Ok(vec![false, false]));
    assert_eq!(c.holdings(1024, 2), Ok(vec![7, 14]));
    assert_eq!(c.holdings(1, 1), Ok(vec![0]));
    plc.unforce("start").unwrap();
    c.set_coil(0, true).unwrap();
    cycle(&mut plc, &mut exchange);
    cycle(&mut plc, &mut exchange);
    assert_eq!(c.coils(0, 2), Ok(vec![true, true]));
}

#[test]
fn served_in_real_time_from_the_between_ticks_hook() {
    let options = Options {
        cycle_time: 2_000_000,
        ..Options::default()
    };
    let plc = Plc::compile_files(&[("p.st", PROGRAM)], &options).unwrap();
    let (server, mut exchange) =
        ModbusServer::bind("127.0.0.1:0", ModbusConfig::default()).unwrap();
    let stop = plc.stop_handle();
    let mut session = Session::new(plc);
    exchange.exchange(session.plc_mut());
    let mut runner = TaskRunner::real_time(session.plc());
    runner.set_between_ticks(exchange.into_between_ticks());
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let thread = runner.spawn(session, None, trace);
    let mut c = Client::connect(server.local_addr());
    c.set_coil(0, true).unwrap();
    let counted = wait_until(Duration::from_secs(10), || {
        c.holdings(1, 1).is_ok_and(|v| v[0] >= 10)
    });
    stop.stop();
    let outcome = thread.join();
    outcome.result.unwrap();
    assert!(counted, "the count never reached 10");
    let count: u16 = outcome
        .session
        .plc()
        .read("count")
        .unwrap()
        .to_literal()
        .parse()
        .unwrap();
    assert!(count >= 10);
    server.shutdown();
}

#[test]
fn shutdown_closes_every_connection_and_frees_the_port() {
    let (server, _exchange, _plc) = serve(ModbusConfig::default());
    let addr = server.local_addr();
    let mut clients: Vec<Client> = (0..3).map(|_| Client::connect(addr)).collect();
    for c in &mut clients {
        assert_eq!(c.coils(0, 1), Ok(vec![false]));
    }
    let t0 = Instant::now();
    server.shutdown();
    assert!(t0.elapsed() < Duration::from_secs(2), "{:?}", t0.elapsed());
    for c in &mut clients {
        assert!(closed_within(&mut c.stream, Duration::from_secs(2)));
    }
    let (again, _exchange) = ModbusServer::bind(&addr.to_string(), ModbusConfig::default())
        .expect("the port is free again");
    drop(again);
}

#[test]
fn bad_settings_and_addresses_are_typed_errors() {
    let zero = ModbusConfig {
        max_clients: 0,
        ..ModbusConfig::default()
    };
    let err = ModbusServer::bind("127.0.0.1:0", zero).unwrap_err();
    assert!(matches!(
        err,
        plcrun::ModbusError::ZeroSetting {
            setting: "max_clients"
        }
    ));
    let err = ModbusServer::bind("not an address", ModbusConfig::default()).unwrap_err();
    assert!(err.to_string().contains("not an address"), "{err}");
    assert!(std::error::Error::source(&err).is_some());
    let _ = ModbusProto::TcpUdp;
}
