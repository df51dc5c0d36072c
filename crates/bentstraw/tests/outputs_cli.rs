//! How the commands treat the user's files: a failed, refused or interrupted run keeps the previous
//! files byte for byte and leaves no temporary; only regular files are replaced; work is bounded.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const SCENE: [&str; 6] = [
    "--observer",
    "0,0.1,0.1",
    "--straw",
    "0.02,0.01",
    "--water-height",
    "0.15",
];

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
}

fn run(dir: &Path, args: &[&str]) -> Output {
    bin().current_dir(dir).args(args).output().unwrap()
}

/// `command args…` with the scene arguments in between.
fn with_scene<'a>(command: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![command];
    args.extend(SCENE);
    args.extend(extra);
    args
}

/// Runs the binary with files limited to `blocks` blocks (as on a nearly full disk): writes past the
/// limit fail with "File too large" (SIGXFSZ is ignored, as the shell's `trap '' XFSZ` does).
fn run_limited(dir: &Path, blocks: u64, args: &[&str]) -> Output {
    // The shell's block for `ulimit -f` is 512 bytes (dash) or 1024 (bash); the sizes used here
    // are far from both limits.
    Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f \"$1\"; shift; exec \"$@\"")
        .arg("sh")
        .arg(blocks.to_string())
        .arg(env!("CARGO_BIN_EXE_bentstraw"))
        .args(args)
        .output()
        .unwrap()
}

/// Like [`run`], with the processor time (user and system) the run used, read from its exit
/// status in /proc before it is reaped (`None` where there is no /proc).
fn run_with_cpu_time(dir: &Path, args: &[&str]) -> (Output, Option<Duration>) {
    let child = bin()
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stat = format!("/proc/{}/stat", child.id());
    // The fields after the command's name (which may hold spaces) in parentheses.
    let fields = |text: &str| -> Vec<String> {
        let after = text.rsplit_once(')').map_or("", |(_, rest)| rest);
        after.split_whitespace().map(str::to_string).collect()
    };
    let mut cpu = None;
    if Path::new(&stat).exists() {
        // Polled until the process has ended (a zombie, not yet reaped: its times are final); a
        // deadline only so that a hung run cannot hang the suite.
        let deadline = Instant::now() + Duration::from_secs(120);
        loop {
            let f = fields(&fs::read_to_string(&stat).unwrap());
            if f[0] == "Z" {
                // utime and stime (fields 14 and 15 of the line), in clock ticks of 1/100 s (the
                // kernel's USER_HZ on every Linux).
                let ticks: u64 = f[11].parse::<u64>().unwrap() + f[12].parse::<u64>().unwrap();
                cpu = Some(Duration::from_millis(ticks * 10));
                break;
            }
            assert!(Instant::now() < deadline, "{args:?} did not end in 120 s");
            std::thread::sleep(Duration::from_millis(5));
        }
    }
    (child.wait_with_output().unwrap(), cpu)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Temporaries (ours, or the old scheme's) left in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".bentstraw-") || n.ends_with(".partial") || n.ends_with(".tmp"))
        .collect()
}

/// Exit code 2 and one line, naming each of `names`.
fn assert_refused(out: &Output, names: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.starts_with("error: "), "{err}");
    for n in names {
        assert!(err.contains(n), "{n} not in: {err}");
    }
}

#[test]
fn a_failed_simulate_keeps_the_previous_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let first = run(
        d,
        &with_scene(
            "simulate",
            &["--points", "500", "--output", "o.csv", "--plot", "p.png"],
        ),
    );
    assert!(first.status.success(), "{}", stderr(&first));
    let (csv, png) = (
        fs::read(d.join("o.csv")).unwrap(),
        fs::read(d.join("p.png")).unwrap(),
    );
    // 300 points make a CSV of about 25 kB, but the figure is about 140 kB: more than the 100 blocks
    // (50 or 100 KiB) allowed. The new points are complete before the figure fails.
    let out = run_limited(
        d,
        100,
        &with_scene(
            "simulate",
            &["--points", "300", "--output", "o.csv", "--plot", "p.png"],
        ),
    );
    assert_refused(&out, &["p.png", "File too large"]);
    assert_eq!(fs::read(d.join("o.csv")).unwrap(), csv, "o.csv changed");
    assert_eq!(fs::read(d.join("p.png")).unwrap(), png, "p.png changed");
    assert_eq!(temporaries(d), Vec::<String>::new());
    // With no previous file, a failure leaves none.
    let out = run_limited(
        d,
        200,
        &with_scene("simulate", &["--points", "20000", "--output", "new.csv"]),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(!d.join("new.csv").exists());
    assert_eq!(temporaries(d), Vec::<String>::new());
}

#[test]
fn a_failed_raw_file_keeps_the_previous_picture() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let small = [
        "--mode",
        "course",
        "--backdrop",
        "none",
        "--samples",
        "1",
        "--output",
        "v.png",
        "--raw",
        "v.csv",
    ];
    let mut args = small.to_vec();
    args.extend(["--size", "40x30"]);
    let first = run(d, &with_scene("render", &args));
    assert!(first.status.success(), "{}", stderr(&first));
    let (png, csv) = (
        fs::read(d.join("v.png")).unwrap(),
        fs::read(d.join("v.csv")).unwrap(),
    );
    // At 400x300 the picture is a few kB but the raw file (120 000 rows) about 1.4 MB.
    let mut args = small.to_vec();
    args.extend(["--size", "400x300"]);
    let out = run_limited(d, 200, &with_scene("render", &args));
    assert_refused(&out, &["v.csv", "File too large"]);
    assert_eq!(
        fs::read(d.join("v.png")).unwrap(),
        png,
        "the picture changed"
    );
    assert_eq!(
        fs::read(d.join("v.csv")).unwrap(),
        csv,
        "the raw file changed"
    );
    assert_eq!(temporaries(d), Vec::<String>::new());
}

/// A table whose files cannot all be written (a full disk, as a limit on file sizes makes it)
/// replaces none of the previous table. Run on a gallery scene's report on few points (two seconds,
/// where the reference report took many): the same failure in the same place, every figure
/// written, some refused, then nothing put in place.
#[test]
fn a_failed_table_replaces_none_of_the_previous_table() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let folder = d.join("t");
    // A previous table: its page and a points file it writes again.
    let previous = |folder: &Path, points: &str| {
        fs::create_dir(folder).unwrap();
        fs::write(folder.join("index.html"), b"previous report").unwrap();
        fs::write(folder.join(points), b"previous points").unwrap();
    };
    let kept = |folder: &Path, points: &str| {
        assert_eq!(
            fs::read(folder.join("index.html")).unwrap(),
            b"previous report"
        );
        assert_eq!(fs::read(folder.join(points)).unwrap(), b"previous points");
        assert_eq!(
            fs::read_dir(folder).unwrap().count(),
            2,
            "new files appeared"
        );
    };
    previous(&folder, "obs1.csv.gz");
    const SCENE: [&str; 5] = ["table", "--scene", "reversing-arrow", "--points", "100"];
    let args = |out: &'static str| [&SCENE[..], &["--out", out]].concat();
    // 100 to 200 kB: under the scene's picture and the observers' pictures, over the report (about
    // 30 kB).
    let out = run_limited(d, 200, &args("t"));
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("could not be written")
            && stderr(&out).contains("no file in t was replaced"),
        "{}",
        stderr(&out)
    );
    kept(&folder, "obs1.csv.gz");
    // A folder the failed run made is gone again.
    let out = run_limited(d, 100, &args("new/deeper"));
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!d.join("new").exists());

    // The reference report failing before its work (its files' reservation stopped half-way by
    // a limit of open files): its temporaries removed, the previous files kept, a folder it made
    // removed.
    let reference = d.join("r");
    previous(&reference, "sim1.csv.gz");
    for out in ["r", "new/deeper"] {
        let ran = Command::new("sh")
            .current_dir(d)
            .arg("-c")
            .arg("ulimit -n 24; exec \"$@\"")
            .arg("sh")
            .arg(env!("CARGO_BIN_EXE_bentstraw"))
            .args(["table", "--points", "3000", "--out", out])
            .output()
            .unwrap();
        assert_refused(&ran, &["Too many open files", &format!("--out {out}/")]);
    }
    kept(&reference, "sim1.csv.gz");
    assert!(!d.join("new").exists());
}

#[cfg(unix)]
#[test]
fn only_regular_files_are_replaced() {
    use std::os::unix::fs::{symlink, FileTypeExt};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A device (run as root this replaced /dev/null with a regular file), through a link.
    symlink("/dev/null", d.join("null.png")).unwrap();
    symlink("/dev/null", d.join("null.csv")).unwrap();
    let out = run(
        d,
        &with_scene("render", &["--size", "8x6", "--output", "null.png"]),
    );
    assert_refused(&out, &["--output null.png", "not a regular file"]);
    let out = run(d, &with_scene("simulate", &["--output", "null.csv"]));
    assert_refused(&out, &["--output null.csv", "not a regular file"]);
    assert!(fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    assert!(fs::symlink_metadata(d.join("null.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    // A named pipe.
    let made = Command::new("mkfifo").arg(d.join("pipe.csv")).status();
    if made.is_ok_and(|s| s.success()) {
        let out = run(d, &with_scene("simulate", &["--output", "pipe.csv"]));
        assert_refused(&out, &["pipe.csv", "not a regular file"]);
        assert!(fs::metadata(d.join("pipe.csv"))
            .unwrap()
            .file_type()
            .is_fifo());
    }
    // A folder, and a link to nothing.
    fs::create_dir(d.join("dir.png")).unwrap();
    let out = run(
        d,
        &with_scene("render", &["--size", "8x6", "--output", "dir.png"]),
    );
    assert_refused(&out, &["dir.png", "folder"]);
    symlink("nowhere.csv", d.join("dangling.csv")).unwrap();
    let out = run(d, &with_scene("simulate", &["--output", "dangling.csv"]));
    assert_refused(&out, &["dangling.csv", "link to nothing"]);
    assert_eq!(temporaries(d), Vec::<String>::new());
    // A link to a regular file: the file is replaced, the link stays a link.
    fs::write(d.join("real.csv"), b"old").unwrap();
    symlink("real.csv", d.join("link.csv")).unwrap();
    let out = run(
        d,
        &with_scene("simulate", &["--points", "100", "--output", "link.csv"]),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(fs::symlink_metadata(d.join("link.csv"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(fs::read_to_string(d.join("real.csv"))
        .unwrap()
        .starts_with("x,y,z,color\n"));
}

#[test]
fn render_checks_extensions_and_refuses_the_same_file_twice() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let refused = [
        (vec!["--output", "v.jpg"], vec!["--output v.jpg", ".png"]),
        (
            vec!["--output", "v.png", "--raw", "v.txt"],
            vec!["--raw v.txt", ".csv"],
        ),
        (
            vec!["--output", "v.png", "--raw", "./v.png"],
            vec!["same file"],
        ),
        (
            vec!["--output", "v.png", "--raw", "../x/v.png"],
            vec!["../x/v.png"],
        ),
    ];
    fs::create_dir(d.join("x")).unwrap();
    let x = d.join("x");
    for (extra, names) in &refused {
        let mut args = vec!["--size", "8x6"];
        args.extend(extra);
        let out = run(&x, &with_scene("render", &args));
        assert_refused(&out, names);
        assert_eq!(fs::read_dir(&x).unwrap().count(), 0, "{extra:?}");
    }
    // Through a link, two names of one file are still one file.
    fs::write(x.join("v.png"), b"old").unwrap();
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("v.png", x.join("w.csv")).unwrap();
        let out = run(
            &x,
            &with_scene(
                "render",
                &["--size", "8x6", "--output", "v.png", "--raw", "w.csv"],
            ),
        );
        assert_refused(&out, &["same file"]);
        assert_eq!(fs::read(x.join("v.png")).unwrap(), b"old");
    }
}

#[cfg(unix)]
#[test]
fn a_read_only_target_is_refused_before_any_work() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("ro.csv"), b"keep me").unwrap();
    fs::set_permissions(d.join("ro.csv"), fs::Permissions::from_mode(0o444)).unwrap();
    // Ten million points take many seconds of processor time (about 13 s on two cores): a refusal
    // after the work would show in the processor time the run used, whatever else the machine
    // does meanwhile.
    let (out, cpu) = run_with_cpu_time(
        d,
        &with_scene("simulate", &["--points", "10000000", "--output", "ro.csv"]),
    );
    assert_refused(&out, &["--output ro.csv", "read-only"]);
    if let Some(cpu) = cpu {
        assert!(
            cpu < Duration::from_secs(1),
            "the refusal took {cpu:?} of work"
        );
    }
    assert_eq!(fs::read(d.join("ro.csv")).unwrap(), b"keep me");
    assert_eq!(temporaries(d), Vec::<String>::new());
}

#[cfg(unix)]
#[test]
fn replaced_files_keep_their_permissions_and_new_ones_get_the_usual() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("mine.csv"), b"old").unwrap();
    fs::set_permissions(d.join("mine.csv"), fs::Permissions::from_mode(0o640)).unwrap();
    let out = run(
        d,
        &with_scene(
            "simulate",
            &[
                "--points", "100", "--output", "mine.csv", "--html", "new.html",
            ],
        ),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let mode = |f: &str| fs::metadata(d.join(f)).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode("mine.csv"), 0o640);
    // What `File::create` would give under the same umask (not the temporary's private 0600).
    fs::write(d.join("probe"), b"").unwrap();
    assert_eq!(mode("new.html"), mode("probe"));
}

#[test]
fn long_file_names_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stem = "s".repeat(246);
    let (csv, png) = (format!("{stem}.csv"), format!("{stem}.png"));
    assert_eq!(csv.len(), 250);
    let out = run(
        d,
        &with_scene(
            "simulate",
            &["--points", "100", "--output", &csv, "--plot", &png],
        ),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(d.join(&csv).is_file() && d.join(&png).is_file());
    let out = run(
        d,
        &with_scene(
            "render",
            &["--size", "8x6", "--output", &png, "--raw", &csv],
        ),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    // Longer than file systems allow: refused before the work, clipped in the message.
    let too_long = format!("{}.csv", "s".repeat(300));
    let out = run(d, &with_scene("simulate", &["--output", &too_long]));
    assert_refused(&out, &["at most 255"]);
    assert!(stderr(&out).len() < 400, "{}", stderr(&out));
    assert_eq!(temporaries(d), Vec::<String>::new());
}

/// Starts `args` in `dir`, waits until its temporaries exist in `watch` (the work has begun: the
/// event waited for, polled, with a deadline only against a hang), sends `signal`, and checks that
/// it ends with code 130, leaving no temporary.
fn interrupt(dir: &Path, watch: &Path, args: &[&str], signal: &str) {
    let mut child = bin()
        .current_dir(dir)
        .args(args)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while temporaries(watch).is_empty() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "{args:?} ended before its files were reserved"
        );
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "no temporary appeared"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(
        child.try_wait().unwrap().is_none(),
        "{args:?} ended before the signal"
    );
    let sent = Command::new("kill")
        .args([format!("-{signal}"), child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", stderr(&out));
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
    assert_eq!(temporaries(watch), Vec::<String>::new());
}

#[cfg(unix)]
#[test]
fn interruptions_leave_the_previous_files_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for f in ["o.csv", "p.png", "v.png", "v.csv"] {
        fs::write(d.join(f), format!("previous {f}")).unwrap();
    }
    // The stereo model takes many seconds for 300 000 points.
    interrupt(
        d,
        d,
        &with_scene(
            "simulate",
            &[
                "--points",
                "300000",
                "--image-model",
                "stereo",
                "--output",
                "o.csv",
                "--plot",
                "p.png",
            ],
        ),
        "TERM",
    );
    interrupt(
        d,
        d,
        &with_scene(
            "render",
            &[
                "--size",
                "4000x3000",
                "--samples",
                "8",
                "--output",
                "v.png",
                "--raw",
                "v.csv",
            ],
        ),
        "INT",
    );
    for f in ["o.csv", "p.png", "v.png", "v.csv"] {
        assert_eq!(
            fs::read_to_string(d.join(f)).unwrap(),
            format!("previous {f}")
        );
    }
    // The table: a previous table stays whole, and a folder the run made is removed.
    let t = d.join("t");
    fs::create_dir(&t).unwrap();
    fs::write(t.join("index.html"), b"previous").unwrap();
    interrupt(
        d,
        &t,
        &["table", "--out", "t", "--points", "200000"],
        "TERM",
    );
    assert_eq!(fs::read(t.join("index.html")).unwrap(), b"previous");
    assert_eq!(fs::read_dir(&t).unwrap().count(), 1);
}

#[test]
fn a_full_stderr_does_not_make_the_program_panic() {
    let full = || {
        Stdio::from(
            fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap(),
        )
    };
    if !Path::new("/dev/full").exists() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let status = bin()
        .current_dir(d)
        .args(with_scene(
            "simulate",
            &["--points", "100", "--output", "o.csv"],
        ))
        .stderr(full())
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(0));
    assert!(d.join("o.csv").is_file());
    for bad in [
        &["simulate", "--observer", "x"][..],
        &["simulate", "--output", "o.txt"],
    ] {
        let status = bin()
            .current_dir(d)
            .args(bad)
            .stderr(full())
            .status()
            .unwrap();
        assert_eq!(status.code(), Some(2), "{bad:?}");
    }
    // A full stdout ends bench with a message, not a panic.
    let out = bin()
        .current_dir(d)
        .args(["bench", "--repeat", "1", "--size", "8x6"])
        .stdout(full())
        .output()
        .unwrap();
    assert_refused(&out, &["standard output"]);
}

#[test]
fn point_counts_are_bounded_by_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = run(
        d,
        &with_scene("simulate", &["--points", "100000000", "--output", "o.csv"]),
    );
    assert_refused(&out, &["--points 100000000", "at most 10000000"]);
    let out = run(
        d,
        &with_scene(
            "simulate",
            &[
                "--points",
                "2000001",
                "--image-model",
                "eye",
                "--output",
                "o.csv",
            ],
        ),
    );
    assert_refused(&out, &["--points 2000001", "at most 2000000"]);
    let out = run(d, &["table", "--out", "t", "--points", "1000000"]);
    assert_refused(&out, &["--points 1000000", "at most 200000"]);
    assert_eq!(fs::read_dir(d).unwrap().count(), 0);
}

#[test]
fn hostile_values_are_clipped_in_messages() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let huge = "1".repeat(5000);
    let (size, flag) = (format!("{huge}x3"), format!("--{huge}"));
    let (bad_ext, far) = (format!("o.{huge}"), format!("{huge}/o.csv"));
    // (command, observer, straw, output, extra)
    let cases: Vec<(&str, &str, &str, &str, Vec<&str>)> = vec![
        ("simulate", &huge, "0,0", "o.csv", vec![]),
        ("simulate", "0,0,1", &huge, "o.csv", vec![]),
        ("simulate", "0,0,1", "0,0", "o.csv", vec![&flag]),
        ("simulate", "0,0,1", "0,0", &bad_ext, vec![]),
        ("simulate", "0,0,1", "0,0", &huge, vec![]),
        ("simulate", "0,0,1", "0,0", &far, vec![]),
        ("render", "0,0,1", "0,0", "o.png", vec!["--size", &size]),
        ("render", "0,0,1", "0,0", "o.png", vec!["--mode", &huge]),
        ("render", "0,0,1", "0,0", "o.png", vec!["--fov", "-1e-320"]),
        ("render", "0,0,1", "0,0", &huge, vec![]),
    ];
    for (command, observer, straw, output, extra) in &cases {
        let mut args = vec![
            *command,
            "--observer",
            observer,
            "--straw",
            straw,
            "--water-height",
            "0.1",
            "--output",
            output,
        ];
        args.extend(extra);
        let out = run(d, &args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1);
        let start: String = err.chars().take(300).collect();
        assert!(err.chars().count() < 300, "{} bytes: {start}", err.len());
    }
    assert_eq!(fs::read_dir(d).unwrap().count(), 0);
}
