//! `bentstraw explore`'s server under hostile clients: more connections than it may open files,
//! clients that never read, foreign pages, huge heads, clients that leave mid-computation and
//! more work than it takes at once. No client may stop it or freeze the others. The tests wait for
//! events, not for fixed times: the server's address, an answer, bytes waiting on a socket, the
//! server's threads computing or all asleep (from /proc); every wait is bounded (socket timeouts,
//! deadlines) only so that a hang fails the test, and each server is killed when its test ends.
//! Where "at once" is what is checked, the bound is the server's own: before a timeout of its
//! could have freed it (an idle connection's [`HEAD_TIMEOUT`], a stuck write's [`WRITE_TIMEOUT`]),
//! or the processor time it used, which other work on the machine does not change.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The server's time for a request's head, after which an idle connection is closed (its
/// `server::HEAD_TIMEOUT`).
const HEAD_TIMEOUT: Duration = Duration::from_secs(15);
/// The server's time for a write a client does not take, after which it gives up on that client
/// (its `guard::WRITE_TIMEOUT`).
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// Most processor time the server may use for work it must not do or must abandon: a heavy export
/// takes about 17 s of it (8.5 s on two cores), a request refused or given up a few milliseconds.
const LITTLE_WORK: Duration = Duration::from_secs(3);
/// Safety net of the waits for the server's threads: a hang fails the test.
const DEADLINE: Duration = Duration::from_secs(60);

/// Holds the machine for one test of this file at a time: each starts a server and measures it
/// (its processor time, its memory, its timeouts), which another test's server computing beside
/// it on the same cores would blur.
fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static ONE: std::sync::Mutex<()> = std::sync::Mutex::new(());
    ONE.lock().unwrap_or_else(|e| e.into_inner())
}

/// A running `bentstraw explore`, killed when dropped.
struct Server {
    child: Child,
    /// `host:port` as its URL gives it.
    host: String,
    /// The token its address carries, when it asks for one.
    token: Option<String>,
    /// Its standard error's first line, if it printed one before the address.
    stderr: Option<std::process::ChildStderr>,
}

impl Server {
    /// `bentstraw explore --no-open --port 0 ARGS…`, once it listens.
    fn start(args: &[&str]) -> Server {
        Server::start_with(Command::new(env!("CARGO_BIN_EXE_bentstraw")), args)
    }

    /// The same, its limit of open files lowered to `files` (as a user's `ulimit -n`), with
    /// `taken` of them already open (inherited from the shell, as a careless parent leaves them).
    #[cfg(unix)]
    fn start_with_file_limit(files: u32, taken: u32, args: &[&str]) -> Server {
        let mut bash = Command::new("bash");
        bash.arg("-c")
            .arg(format!(
                "for i in $(seq {taken}); do exec {{f}}</dev/null; done; \
                 ulimit -n {files} && exec \"$0\" \"$@\""
            ))
            .arg(env!("CARGO_BIN_EXE_bentstraw"));
        Server::start_with(bash, args)
    }

    fn start_with(mut command: Command, args: &[&str]) -> Server {
        let mut child = command
            .args(["explore", "--no-open", "--port", "0"])
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("bentstraw runs");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("no address in {line:?}"));
        let (host, token) = url
            .trim_start_matches("http://")
            .split_once('/')
            .expect("an address ends its host with '/'");
        let token = token.strip_prefix("?token=").map(str::to_string);
        let stderr = child.stderr.take();
        Server {
            child,
            host: host.to_string(),
            token,
            stderr,
        }
    }

    fn addr(&self) -> SocketAddr {
        use std::net::ToSocketAddrs;
        self.host.to_socket_addrs().unwrap().next().unwrap()
    }

    fn connect(&self) -> TcpStream {
        let s = TcpStream::connect_timeout(&self.addr(), Duration::from_secs(5)).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        s.set_write_timeout(Some(Duration::from_secs(20))).unwrap();
        s
    }

    /// `GET target` with the server's own `Host` and `extra` header lines.
    fn get(&self, target: &str, extra: &str) -> Answer {
        let mut s = self.connect();
        write!(
            s,
            "GET {target} HTTP/1.1\r\nHost: {}\r\n{extra}Connection: close\r\n\r\n",
            self.host
        )
        .unwrap();
        read_answer(&mut s)
    }

    fn alive(&mut self) -> bool {
        self.child.try_wait().unwrap().is_none()
    }

    /// Resident memory of the server (kB), from /proc.
    fn resident_kb(&self) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).ok()?;
        let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
        line.split_whitespace().nth(1)?.parse().ok()
    }

    /// The processor time (user and system) the server has used so far, from /proc (Linux; `None`
    /// elsewhere).
    fn cpu(&self) -> Option<Duration> {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.child.id())).ok()?;
        // The fields after the command's name in parentheses: utime and stime are the 12th and
        // 13th, in clock ticks of 1/100 s (USER_HZ on every Linux).
        let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
        let ticks = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
        Some(Duration::from_millis(ticks * 10))
    }

    /// Whether one of the server's threads is running or ready to run (state R in /proc):
    /// computing. `None` where there is no /proc.
    fn computing(&self) -> Option<bool> {
        let tasks = std::fs::read_dir(format!("/proc/{}/task", self.child.id())).ok()?;
        Some(tasks.filter_map(Result::ok).any(|task| {
            std::fs::read_to_string(task.path().join("stat"))
                .ok()
                .and_then(|s| {
                    let (_, rest) = s.rsplit_once(')')?;
                    Some(rest.trim_start().starts_with('R'))
                })
                .unwrap_or(false)
        }))
    }

    /// Waits until the server has used processor time since `mark` (it is computing what it was
    /// sent). Without /proc, waits for nothing.
    fn wait_computing(&self, mark: Option<Duration>) {
        let (Some(mark), Some(_)) = (mark, self.cpu()) else {
            return;
        };
        let deadline = Instant::now() + DEADLINE;
        while self.cpu().unwrap() < mark + Duration::from_millis(50) {
            assert!(
                Instant::now() < deadline,
                "the server did not start computing"
            );
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Waits until none of the server's threads is computing (twice in a row, 10 ms apart), and
    /// returns the processor time it used since `mark` (`None` without /proc).
    fn wait_idle(&self, mark: Option<Duration>) -> Option<Duration> {
        let deadline = Instant::now() + DEADLINE;
        let mut quiet = 0;
        while quiet < 2 {
            match self.computing() {
                None => return None,
                Some(true) => quiet = 0,
                Some(false) => quiet += 1,
            }
            assert!(Instant::now() < deadline, "the server kept computing");
            std::thread::sleep(Duration::from_millis(10));
        }
        Some(self.cpu()? - mark?)
    }

    /// Waits until the server is idle, and checks that it used little processor time since
    /// `mark`: it did not do (or stopped) the work `what`.
    fn assert_little_work_since(&self, mark: Option<Duration>, what: &str) {
        if let Some(used) = self.wait_idle(mark) {
            assert!(
                used < LITTLE_WORK,
                "{what}: the server computed for {used:?} of processor time"
            );
        }
    }

    /// What it printed on standard error so far (it is killed first).
    fn stderr_after_kill(&mut self) -> String {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let mut text = String::new();
        if let Some(mut e) = self.stderr.take() {
            let _ = e.read_to_string(&mut text);
        }
        text
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A response: status, header lines (lowercase names), body.
struct Answer {
    status: u16,
    headers: Vec<(String, String)>,
    body: Vec<u8>,
}

impl Answer {
    fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
}

/// Reads one response from `s` (its body by its `Content-Length`).
fn read_answer(s: &mut impl Read) -> Answer {
    let mut reader = BufReader::new(s);
    let mut status_line = String::new();
    reader.read_line(&mut status_line).expect("a status line");
    let status = status_line
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status in {status_line:?}"));
    let mut headers = Vec::new();
    loop {
        let mut line = String::new();
        reader.read_line(&mut line).unwrap();
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        let (name, value) = line.split_once(':').unwrap();
        headers.push((name.to_ascii_lowercase(), value.trim().to_string()));
    }
    let length: usize = headers
        .iter()
        .find(|(n, _)| n == "content-length")
        .map(|(_, v)| v.parse().unwrap())
        .expect("every answer has a Content-Length");
    let mut body = vec![0; length];
    reader.read_exact(&mut body).unwrap();
    Answer {
        status,
        headers,
        body,
    }
}

/// A small view of reference 2.
const VIEW: &str = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15";

/// The heaviest export the explorer takes: a 4K picture with 16×16 samples per pixel (tens of
/// seconds on two cores).
fn heavy_export() -> String {
    format!("/api/export?{VIEW}&format=png&size=3840x2160&samples=16&mode=fresnel")
}

/// Sends `GET target` on a new connection and leaves it unread.
fn send_only(server: &Server, target: &str) -> TcpStream {
    let mut s = server.connect();
    write!(s, "GET {target} HTTP/1.1\r\nHost: {}\r\n\r\n", server.host).unwrap();
    s
}

/// A small frame is computed and answered (the connection's read timeout is the safety net), with
/// the engine's time for it in `Server-Timing`.
fn frame_answered(server: &Server) {
    let started = Instant::now();
    let a = server.get(&format!("/api/frame?{VIEW}&size=64x48&points=500"), "");
    assert_eq!(a.status, 200, "{}", a.text());
    // The engine's own time goes with the answer, within the time the client waited.
    let engine_ms: f64 = a
        .header("server-timing")
        .and_then(|t| t.strip_prefix("engine;dur="))
        .and_then(|ms| ms.parse().ok())
        .expect("Server-Timing: engine;dur=MS on a computed answer");
    assert!(engine_ms > 0.0 && engine_ms <= started.elapsed().as_secs_f64() * 1e3);
}

/// Waits until answer bytes have come on `s` (the server is writing to it), without reading them.
fn wait_for_answer_bytes(s: &TcpStream) {
    let mut first = [0u8; 1];
    let n = s.peek(&mut first).expect("an answer begins");
    assert_eq!(n, 1, "the server closed the connection");
}

/// Whether `s` has nothing to read yet (no answer, no end).
fn nothing_yet(s: &TcpStream) -> bool {
    s.set_nonblocking(true).unwrap();
    let mut early = [0u8; 64];
    let got = s.peek(&mut early);
    s.set_nonblocking(false).unwrap();
    matches!(got, Err(e) if e.kind() == std::io::ErrorKind::WouldBlock)
}

/// More idle connections than the process may open files: the server neither exits nor stops
/// answering; a new client gets the page at once.
#[test]
#[cfg(unix)]
fn more_connections_than_files_leave_the_server_serving() {
    let _one_at_a_time = one_at_a_time();
    let mut server = Server::start_with_file_limit(256, 0, &[]);
    let opened = Instant::now();
    let mut idle = Vec::new();
    for _ in 0..300 {
        if let Ok(s) = TcpStream::connect_timeout(&server.addr(), Duration::from_secs(3)) {
            idle.push(s);
        }
    }
    assert!(idle.len() >= 250, "{} connections opened", idle.len());
    let page = server.get("/", "");
    assert_eq!(page.status, 200);
    assert!(page.text().contains("<html"), "{}", page.text());
    frame_answered(&server);
    // At once: room was made, not waited for until the idle connections timed out.
    assert!(
        opened.elapsed() < HEAD_TIMEOUT,
        "served only after {:?}",
        opened.elapsed()
    );
    assert!(server.alive());
    // Its open files stayed under the limit.
    let fds = std::fs::read_dir(format!("/proc/{}/fd", server.child.id()))
        .map(|d| d.count())
        .unwrap_or(0);
    assert!(fds <= 256, "{fds} files open");
    drop(idle);
    assert_eq!(server.get("/api/scenes", "").status, 200);
    assert!(server.alive());
}

/// With every connection taken, the one quiet the longest makes room: not a page's kept-alive
/// connection that asked something a moment ago, though it is the oldest.
#[test]
#[cfg(unix)]
fn the_connection_quiet_the_longest_makes_room() {
    let _one_at_a_time = one_at_a_time();
    // 96 files: room for 64 connections.
    let server = Server::start_with_file_limit(96, 0, &[]);
    let ask = |s: &mut TcpStream| {
        write!(
            s,
            "GET /api/scenes HTTP/1.1\r\nHost: {}\r\n\r\n",
            server.host
        )
        .unwrap();
        read_answer(s).status
    };
    let mut page = server.connect();
    assert_eq!(ask(&mut page), 200);
    let mut quiet: Vec<TcpStream> = (0..62).map(|_| server.connect()).collect();
    // Served once all are accepted: the page asks again, and is the latest to have spoken. (The
    // server notes times in whole milliseconds, and a loaded machine starts the connections'
    // tasks late: the page speaks a clear 50 ms after the last of them.)
    assert_eq!(ask(&mut quiet[61]), 200);
    std::thread::sleep(Duration::from_millis(50));
    assert_eq!(ask(&mut page), 200);
    // Eight more: the server is full and closes eight quiet ones, the longest quiet first.
    let mut more: Vec<TcpStream> = (0..8).map(|_| server.connect()).collect();
    assert_eq!(ask(&mut more[7]), 200);
    assert_eq!(ask(&mut page), 200, "the page's connection was closed");
    drop(quiet);
}

/// Clients that sent a malformed request and were answered make room at once for a good one:
/// they do not keep their slots while the server drops what they still send.
#[test]
#[cfg(unix)]
fn refused_clients_make_room_at_once() {
    let _one_at_a_time = one_at_a_time();
    // 96 files: room for 64 connections, all taken by clients sending nonsense.
    let server = Server::start_with_file_limit(96, 0, &[]);
    let mut refused: Vec<TcpStream> = (0..64).map(|_| server.connect()).collect();
    for s in &mut refused {
        s.write_all(b"\x01\x02 nonsense\r\n\r\n").unwrap();
    }
    for s in &mut refused {
        // A 400, or the connection closed to make room before this side read its answer (the
        // reset then drops the answer waiting here): refused either way, never served.
        let mut line = String::new();
        match BufReader::new(s).read_line(&mut line) {
            Ok(_) => assert!(line.starts_with("HTTP/1.1 400"), "{line:?}"),
            Err(e) => assert_eq!(e.kind(), std::io::ErrorKind::ConnectionReset, "{e}"),
        }
    }
    let asked = Instant::now();
    assert_eq!(server.get("/api/scenes", "").status, 200);
    // Well within the two seconds a refused connection's leftovers are read for.
    assert!(
        asked.elapsed() < Duration::from_secs(1),
        "served after {:?}",
        asked.elapsed()
    );
    drop(refused);
}

/// Descriptors running out while accepting (most of them taken before the server started):
/// the server waits it out and makes room, and a new client is served.
#[test]
#[cfg(unix)]
fn running_out_of_descriptors_is_survived() {
    let _one_at_a_time = one_at_a_time();
    let mut server = Server::start_with_file_limit(64, 40, &[]);
    let opened = Instant::now();
    let idle: Vec<TcpStream> = (0..100)
        .filter_map(|_| TcpStream::connect_timeout(&server.addr(), Duration::from_secs(3)).ok())
        .collect();
    assert!(idle.len() >= 64, "{} connections opened", idle.len());
    assert_eq!(server.get("/", "").status, 200);
    frame_answered(&server);
    // At once: room was made, not waited for until the idle connections timed out.
    assert!(
        opened.elapsed() < HEAD_TIMEOUT,
        "served only after {:?}",
        opened.elapsed()
    );
    assert!(server.alive());
}

/// A client that sends request after request and reads none of the answers holds up nobody,
/// nor do two clients that never read their large frames.
#[test]
fn clients_that_never_read_freeze_nobody() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    // Pipelined requests for the page's largest file, never read: megabytes of answers.
    let mut greedy = server.connect();
    let one = format!("GET /i18n.js HTTP/1.1\r\nHost: {}\r\n\r\n", server.host);
    let sender = {
        let mut s = greedy.try_clone().unwrap();
        s.set_write_timeout(Some(Duration::from_secs(3))).unwrap();
        std::thread::spawn(move || {
            for _ in 0..2000 {
                if s.write_all(one.as_bytes()).is_err() {
                    break;
                }
            }
        })
    };
    // Two large frames asked for and never read.
    let big = format!("/api/frame?{VIEW}&size=1920x1080&samples=1&points=20000");
    let unread: Vec<TcpStream> = (0..2).map(|_| send_only(&server, &big)).collect();
    // The server is writing to all three, which read nothing.
    wait_for_answer_bytes(&greedy);
    for s in &unread {
        wait_for_answer_bytes(s);
    }
    let stuck = Instant::now();
    for _ in 0..3 {
        assert_eq!(server.get("/", "").status, 200);
        assert_eq!(server.get("/api/scenes", "").status, 200);
    }
    frame_answered(&server);
    // Served while its writes to them were stuck, not once it gave up on those writes.
    assert!(
        stuck.elapsed() < WRITE_TIMEOUT,
        "served only after {:?}",
        stuck.elapsed()
    );
    sender.join().unwrap();
    let _ = greedy.flush();
}

/// Sockets read a little at a time by a slow reader, each with what it has read so far.
type Trickled = std::sync::Arc<std::sync::Mutex<Vec<(TcpStream, Vec<u8>)>>>;

/// Clients that read their large answers slowly do not make the server hold them all in memory:
/// sixty full-HD frames (8 MB each, 500 MB in all) waiting for their readers grow it by less than
/// the memory it keeps for answers and a little more; each answer then arrives whole.
#[test]
#[cfg(target_os = "linux")]
fn slow_readers_are_sent_their_answers_without_holding_them_in_memory() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let big = format!("/api/frame?{VIEW}&size=1920x1080&samples=1&points=100&mode=course");
    // Both workers' buffers grown to this size first (each computes one while the other works).
    let warm: Vec<TcpStream> = (0..2).map(|_| send_only(&server, &big)).collect();
    for mut s in warm {
        assert_eq!(read_answer(&mut s).status, 200);
    }
    let before = server.resident_kb().unwrap();
    // Slow readers: 8 KB from each every 10 ms (a frame takes some ten seconds to arrive, and no
    // write of the server's waits long enough to be given up, even on a loaded machine: its
    // socket takes more only once about half its buffer, a megabyte or so, has been read), the
    // rest held by the server meanwhile.
    let trickled: Trickled = Default::default();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let reader = {
        let (trickled, stop) = (trickled.clone(), stop.clone());
        std::thread::spawn(move || {
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                for (s, got) in trickled.lock().unwrap().iter_mut() {
                    let mut buf = [0u8; 8192];
                    if let Ok(n) = s.read(&mut buf) {
                        got.extend_from_slice(&buf[..n]);
                    }
                }
                std::thread::sleep(Duration::from_millis(10));
            }
        })
    };
    let mut slow = Vec::new();
    for _ in 0..60 {
        let s = send_only(&server, &big);
        wait_for_answer_bytes(&s);
        let clone = s.try_clone().unwrap();
        clone.set_nonblocking(true).unwrap();
        trickled.lock().unwrap().push((clone, Vec::new()));
        slow.push(s);
    }
    let grown_mb = (server.resident_kb().unwrap().saturating_sub(before)) / 1024;
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    reader.join().unwrap();
    // 128 MB kept for answers in memory, and a margin for the connections' buffers.
    assert!(
        grown_mb < 220,
        "the server grew by {grown_mb} MB with 60 frames waiting for their readers"
    );
    // Every one arrives whole (its length as announced, a picture of the size asked). Each is
    // read by a thread of its own: read one after the other, the last ones would wait on the
    // others for longer than the server waits for a write to be taken on a loaded machine.
    let trickled = std::mem::take(&mut *trickled.lock().unwrap());
    let readers: Vec<_> = slow
        .into_iter()
        .zip(trickled)
        .map(|(s, (_, got))| {
            std::thread::spawn(move || {
                s.set_nonblocking(false).unwrap();
                read_answer(&mut std::io::Cursor::new(got).chain(s))
            })
        })
        .collect();
    for reader in readers {
        let a = reader.join().unwrap();
        assert_eq!(a.status, 200);
        let header_len = u32::from_le_bytes(a.body[..4].try_into().unwrap()) as usize;
        let header: serde_json::Value = serde_json::from_slice(&a.body[4..4 + header_len]).unwrap();
        assert_eq!(header["width"], 1920);
        assert!(a.body.len() > 1920 * 1080 * 4);
    }
    frame_answered(&server);
}

/// Only this machine's pages: a foreign `Host` (DNS rebinding), a foreign `Origin` or a
/// cross-site request is refused with 403 and computes nothing.
#[test]
fn foreign_pages_are_refused() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let port = server.addr().port();
    let export = heavy_export();
    let before = server.cpu();
    let mut s = server.connect();
    write!(
        s,
        "GET {export} HTTP/1.1\r\nHost: rebound.example:{port}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let a = read_answer(&mut s);
    assert_eq!(a.status, 403, "{}", a.text());
    assert!(a.text().contains("Host"), "{}", a.text());
    for extra in [
        "Origin: http://evil.example\r\n",
        "Origin: null\r\n",
        "Sec-Fetch-Site: cross-site\r\n",
    ] {
        let a = server.get(&export, extra);
        assert_eq!(a.status, 403, "{extra}: {}", a.text());
    }
    // Refused without computing the export.
    server.assert_little_work_since(before, "four refused exports");
    // The page's own requests, and those of no page (a program), are served.
    let own = format!(
        "Origin: http://{}\r\nSec-Fetch-Site: same-origin\r\n",
        server.host
    );
    assert_eq!(server.get("/api/scenes", &own).status, 200);
    for host in ["localhost", "127.0.0.1"] {
        let mut s = server.connect();
        write!(
            s,
            "GET / HTTP/1.1\r\nHost: {host}:{port}\r\nConnection: close\r\n\r\n"
        )
        .unwrap();
        assert_eq!(read_answer(&mut s).status, 200, "{host}");
    }
    // Two Host headers, the own one first: which server was meant cannot be known.
    let mut s = server.connect();
    write!(
        s,
        "GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nHost: rebound.example\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let a = read_answer(&mut s);
    assert_eq!(a.status, 400, "{}", a.text());
    assert!(a.text().contains("two Host headers"), "{}", a.text());
    // Nothing was computed for the refusals (checked above): a frame comes.
    frame_answered(&server);
}

/// A 1 MB header line is refused with 431 at once, without the server holding it; a 64 KB
/// request line with 414 before it has even ended.
#[test]
fn huge_heads_are_refused_before_they_are_read() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let before = server.resident_kb();
    for _ in 0..4 {
        let mut s = server.connect();
        let head = format!("GET / HTTP/1.1\r\nHost: {}\r\nX-Big: ", server.host);
        s.write_all(head.as_bytes()).unwrap();
        let mut writer = s.try_clone().unwrap();
        let sender = std::thread::spawn(move || {
            let chunk = vec![b'a'; 64 * 1024];
            for _ in 0..16 {
                if writer.write_all(&chunk).is_err() {
                    break;
                }
            }
            let _ = writer.write_all(b"\r\n\r\n");
        });
        let a = read_answer(&mut s);
        assert_eq!(a.status, 431);
        sender.join().unwrap();
    }
    if let (Some(before), Some(after)) = (before, server.resident_kb()) {
        assert!(after < before + 16 * 1024, "{before} kB, then {after} kB");
    }
    // The request line: 64 KB of address, never ended (so a 414 is refused before its end: a
    // server waiting for it would have timed the head out instead).
    let mut s = server.connect();
    s.write_all(b"GET /").unwrap();
    s.write_all(&vec![b'a'; 64 * 1024]).unwrap();
    let a = read_answer(&mut s);
    assert_eq!(a.status, 414, "{}", a.text());
    // The longest address the page may send is still served (a scene file travels in it).
    let long = format!(
        "/api/scenes?pad={}",
        "a".repeat(bentstraw_explore_max_url() - 20)
    );
    assert_eq!(server.get(&long, "").status, 200);
    let too_long = format!(
        "/api/scenes?pad={}",
        "a".repeat(bentstraw_explore_max_url())
    );
    assert_eq!(server.get(&too_long, "").status, 414);
    frame_answered(&server);
}

/// The explorer's longest address (bytes), as its crate says.
fn bentstraw_explore_max_url() -> usize {
    16 * 1024
}

/// Clients that hang up mid-computation stop their work; more work than the server takes at
/// once is refused with 503 and `Retry-After`; heavy work never makes a page's frames wait; then
/// everything is served promptly again.
#[test]
fn work_of_clients_that_left_is_abandoned_and_overload_gets_503() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let export = heavy_export();
    // One heavy request at work and two waiting fill the server's room for heavy work, even when
    // they come all at once: of four sent at once, one is refused with 503 (its answer is the
    // event waited for: by then the three others are in), and the three others are not answered.
    let mut sent: Vec<TcpStream> = (0..4).map(|_| send_only(&server, &export)).collect();
    let refused = wait_for_first_answer(&sent);
    let mut s = sent.remove(refused);
    let a = read_answer(&mut s);
    assert_eq!(a.status, 503, "{}", a.text());
    assert_eq!(a.header("retry-after"), Some("1"));
    let held = sent;
    assert!(
        held.iter().all(nothing_yet),
        "one of the three was answered at once"
    );
    // The page's frames are computed beside them, by the worker kept for light work.
    for _ in 0..3 {
        frame_answered(&server);
    }
    // Cheap requests are not queued behind the exports: answered while all six still wait.
    assert_eq!(server.get("/", "").status, 200);
    assert_eq!(server.get("/api/scenes", "").status, 200);
    assert_eq!(server.get("/api/sketch?scene=tank-pencil", "").status, 200);
    assert!(
        held.iter().all(nothing_yet),
        "the cheap requests and frames were answered after an export"
    );
    // Everyone hangs up: the work stops (the server goes idle having used little processor time,
    // where finishing the export under way would take tens of seconds of it), and a frame comes.
    let mark = server.cpu();
    drop(held);
    server.assert_little_work_since(mark, "exports whose clients left");
    frame_answered(&server);
    // A single client that leaves mid-export frees its worker too.
    hang_up_twice(&server, &export, "an export whose client left");
    frame_answered(&server);
}

/// Twice: `target` sent, its client hanging up once the server computes it, after which the server
/// must go idle having done little more (`what` names the work in the failure).
fn hang_up_twice(server: &Server, target: &str, what: &str) {
    for _ in 0..2 {
        let mark = server.cpu();
        let one = send_only(server, target);
        server.wait_computing(mark);
        let mark = server.cpu();
        drop(one);
        server.assert_little_work_since(mark, what);
    }
}

/// A hundred straws under 32 layers of liquid in a wide glass (a scene file of about 4 KB).
fn crowded_scene() -> String {
    let mut text = String::from("[container]\nshape = \"glass\"\nradius = 0.3\nheight = 0.5\n");
    for k in 0..32 {
        let top = 0.4 * (k + 1) as f64 / 32.0;
        let index = 1.3 + 0.005 * k as f64;
        text += &format!("[[liquid]]\nname = \"l{k}\"\nindex = {index}\ntop = {top}\n");
    }
    for k in 0..100 {
        let (x, y) = (
            (k % 10) as f64 * 0.03 - 0.135,
            (k / 10) as f64 * 0.03 - 0.135,
        );
        text += &format!("[[straw]]\nx = {x}\ny = {y}\n");
    }
    text
}

/// A client that hangs up while the points are sampled (a million of them in a crowded scene, with
/// a thousand events each: seconds of work) stops that work too, not only a picture's.
#[test]
fn point_sampling_stops_when_its_client_leaves() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let export = format!(
        "/api/export?format=csv&points=1000000&max-events=1000&observer=1,0,0.3&scene-file={}",
        bentstraw_explore::query_value(&crowded_scene())
    );
    hang_up_twice(&server, &export, "points whose client left");
    // The same asked beyond the explorer's work: refused at once, saying what to lower.
    let too_much = format!(
        "/api/frame?size=3840x2160&samples=16&points=1000000&max-events=1000&observer=1,0,0.3&scene-file={}",
        bentstraw_explore::query_value(&crowded_scene())
    );
    let mark = server.cpu();
    let a = server.get(&too_much, "");
    assert_eq!(a.status, 400, "{}", a.text());
    assert!(a.text().contains("ray-surface tests"), "{}", a.text());
    server.assert_little_work_since(mark, "a view beyond the explorer's work");
    frame_answered(&server);
}

/// The index of the first of `sockets` on which an answer arrives (each has its read timeout as
/// the safety net).
fn wait_for_first_answer(sockets: &[TcpStream]) -> usize {
    let deadline = Instant::now() + DEADLINE;
    loop {
        if let Some(k) = sockets.iter().position(|s| !nothing_yet(s)) {
            return k;
        }
        assert!(Instant::now() < deadline, "none of them was answered");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// A request superseded by a newer one of the same page (its channel's sequence number) is
/// answered 409, as the page expects.
#[test]
fn superseded_requests_are_stale() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&[]);
    let chan = "chan=test-frame";
    let mark = server.cpu();
    let slow = send_only(&server, &format!("{}&{chan}&seq=1", heavy_export()));
    // The slow export is being computed.
    server.wait_computing(mark);
    let mark = server.cpu();
    let newer = server.get(
        &format!("/api/frame?{VIEW}&size=64x48&points=500&{chan}&seq=2"),
        "",
    );
    assert_eq!(newer.status, 200);
    let mut slow = slow;
    let old = read_answer(&mut slow);
    assert_eq!(old.status, 409, "{}", old.text());
    // Abandoned, not computed to its end first.
    server.assert_little_work_since(mark, "a superseded export");
    let older = server.get(&format!("/api/frame?{VIEW}&size=64x48&{chan}&seq=1"), "");
    assert_eq!(older.status, 409);
}

/// The answers name no file of the user's: a scene file given by its path appears by its name.
#[test]
fn no_answer_names_the_users_folders() {
    let _one_at_a_time = one_at_a_time();
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().display().to_string();
    let gallery = |name: &str| {
        std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../scenes")
                .join(name),
        )
        .unwrap()
    };
    let mine = dir.path().join("mine.toml");
    std::fs::write(
        &mine,
        gallery("tank-pencil.toml").replace("half_x = 0.10", "half_x = 0.12"),
    )
    .unwrap();
    let glass = dir.path().join("glass.toml");
    std::fs::write(&glass, gallery("spec.toml")).unwrap();
    for file in [&mine, &glass] {
        let server = Server::start(&["--scene", &file.display().to_string()]);
        let page = server.get("/", "");
        assert_eq!(page.status, 200);
        let start = page.text();
        let from = start.find("data-initial=\"").expect("the starting view") + 14;
        let end = start[from..].find('"').unwrap();
        let view = start[from..from + end].replace("&amp;", "&");
        assert!(view.contains("observer="), "{view}");
        let mut bodies = vec![page];
        for target in [
            format!("/api/frame?{view}&size=32x24&points=300"),
            format!("/api/export?{view}&format=ply&points=300"),
            format!("/api/export?{view}&format=ply&model=eye&points=300"),
            format!("/api/export?{view}&format=csv&points=300"),
            format!("/api/scene-file?{view}"),
            format!("/api/frame?{view}&size=0x0"),
        ] {
            let a = server.get(&target, "");
            assert!(a.status == 200 || a.status == 400, "{target}: {}", a.status);
            bodies.push(a);
        }
        for a in &bodies {
            let all = format!("{:?}{}", a.headers, a.text());
            assert!(
                !all.contains(&folder),
                "{folder} in {}",
                &all[..all.len().min(3000)]
            );
        }
    }
}

/// `--host` other than this machine's own address warns that the network can use it; an IPv6
/// address is written in brackets.
#[test]
fn host_addresses_are_shown_usable_and_warned_about() {
    let _one_at_a_time = one_at_a_time();
    let mut any = Server::start(&["--host", "0.0.0.0"]);
    assert!(any.host.starts_with("127.0.0.1:"), "{}", any.host);
    // Reachable from the network: a token in the address, asked for on every request.
    let token = any.token.clone().expect("a token in the printed address");
    assert_eq!(token.len(), 32);
    assert_eq!(any.get("/", "").status, 403);
    assert_eq!(
        any.get(&format!("/api/frame?{VIEW}&size=64x48"), "").status,
        403
    );
    assert!(any.get("/", "").text().contains("token"));
    assert_eq!(
        any.get(&format!("/?token={}", &token[..31]), "").status,
        403
    );
    let page = any.get(&format!("/?token={token}"), "");
    assert_eq!(page.status, 200);
    // The browser keeps it as a cookie, which its page's requests then carry.
    let cookie = page
        .header("set-cookie")
        .expect("the token as a cookie")
        .to_string();
    assert!(
        cookie.contains("HttpOnly") && cookie.contains("SameSite=Strict"),
        "{cookie}"
    );
    let pair = cookie.split(';').next().unwrap();
    let frame = any.get(
        &format!("/api/frame?{VIEW}&size=64x48&points=500"),
        &format!("Cookie: {pair}\r\n"),
    );
    assert_eq!(frame.status, 200, "{}", frame.text());
    let err = any.stderr_after_kill();
    assert!(
        err.starts_with("warning: ") && err.contains("network") && err.lines().count() == 1,
        "{err}"
    );
    // Only where this machine has IPv6.
    if std::net::TcpListener::bind("[::1]:0").is_ok() {
        let mut v6 = Server::start(&["--host", "::1"]);
        assert!(v6.host.starts_with("[::1]:"), "{}", v6.host);
        assert!(v6.token.is_none());
        assert_eq!(v6.get("/", "").status, 200);
        assert_eq!(v6.stderr_after_kill(), "");
    }
    let mut local = Server::start(&[]);
    assert!(local.host.starts_with("127.0.0.1:"));
    assert!(local.token.is_none());
    assert_eq!(local.stderr_after_kill(), "");
}

/// A classroom machine's name is answered to when allowed (`--allow-host`), and only then; a name
/// that cannot be one is refused, with every such name said at once.
#[test]
fn allowed_host_names_are_answered() {
    let _one_at_a_time = one_at_a_time();
    let server = Server::start(&["--allow-host", "lab-pc.school.example"]);
    let port = server.host.rsplit_once(':').unwrap().1.to_string();
    let as_named = |name: &str| {
        let mut s = server.connect();
        write!(
            s,
            "GET / HTTP/1.1\r\nHost: {name}:{port}\r\nConnection: close\r\n\r\n"
        )
        .unwrap();
        read_answer(&mut s).status
    };
    assert_eq!(as_named("lab-pc.school.example"), 200);
    assert_eq!(as_named("LAB-PC.school.example"), 200);
    assert_eq!(as_named("other-pc.school.example"), 403);
    let out = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .args([
            "explore",
            "--no-open",
            "--port",
            "0",
            "--allow-host",
            "a b",
            "--allow-host",
            "ok",
            "--allow-host",
            "c/d",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("\"a b\"") && err.contains("\"c/d\"") && !err.contains("\"ok\""),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}
