//! Progress on stderr, shown only when the work takes over a second and stderr is a terminal, so
//! that quick runs, pipes and tests see nothing.

use std::io::{IsTerminal, Write};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long work may run before its progress appears.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// Runs `work` with a progress bar of `total` steps (a spinner when `None`) drawn by `template`
/// (indicatif's syntax); the bar stays hidden for the first second and when stderr is no terminal.
pub fn with_progress<T>(
    total: Option<u64>,
    template: &str,
    work: impl FnOnce(&ProgressBar) -> T,
) -> T {
    let bar = ProgressBar::with_draw_target(total, ProgressDrawTarget::hidden());
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    let interactive = std::io::stderr().is_terminal();
    let (done, finished) = mpsc::channel::<()>();
    let out = std::thread::scope(|s| {
        if interactive {
            let shown = bar.clone();
            s.spawn(move || {
                // Woken early (disconnected) when the work ends within the first second.
                if let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(SHOW_AFTER) {
                    shown.set_draw_target(ProgressDrawTarget::stderr());
                    shown.enable_steady_tick(Duration::from_millis(120));
                }
            });
        }
        let out = work(&bar);
        drop(done);
        out
    });
    bar.finish_and_clear();
    out
}

/// Writes `text` to stderr as it is; a closed or full stderr is ignored (the files are what
/// matters, and a message that cannot be shown is no reason to fail).
pub fn tell(text: &str) {
    let _ = std::io::stderr().write_all(text.as_bytes());
}

/// Waits while the interruption's handler ends the program (exit code 130, with its message).
pub fn wait_for_interruption() -> ! {
    loop {
        std::thread::park();
    }
}

/// Exit code after Ctrl-C or SIGTERM (128 + SIGINT, the shell's convention for an interruption).
const INTERRUPTED_EXIT: i32 = 130;

/// Makes Ctrl-C, SIGTERM and SIGHUP remove every live temporary output (and every folder this run
/// made that is still empty) before the program ends with exit code 130.
pub fn remove_temporaries_on_interrupt() {
    let _ = ctrlc::set_handler(|| {
        // Asked to stop once the files are all in place (just before the program would have
        // ended): nothing was lost, and the message says so.
        let complete = bentstraw_io::files::outputs_complete();
        let replaced_none = bentstraw_io::files::remove_all_temporaries();
        tell(if complete {
            "stopped after every output file was written: they are complete\n"
        } else if replaced_none {
            "interrupted: no output file was replaced\n"
        } else {
            "interrupted\n"
        });
        std::process::exit(INTERRUPTED_EXIT);
    });
}
