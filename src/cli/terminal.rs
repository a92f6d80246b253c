//! Whether a terminal is awl's to use. A job started in the background (`awl run … &`, or under
//! `timeout`, which runs its command in a process group of its own) shares the terminal with
//! the shell's foreground job: drawing a progress line or prompting there would garble that
//! job's screen, and the terminal driver may stop awl for it (SIGTTOU, SIGTTIN), so a SIGTERM
//! could never reach the summary. Plain output (the summary, diagnostics) is still written.

use std::io::IsTerminal;

/// Whether `stream` is a terminal whose foreground process group is awl's.
#[cfg(unix)]
pub fn in_foreground(stream: &(impl IsTerminal + std::os::fd::AsFd)) -> bool {
    stream.is_terminal()
        && rustix::termios::tcgetpgrp(stream)
            .is_ok_and(|foreground| foreground == rustix::process::getpgrp())
}

#[cfg(not(unix))]
pub fn in_foreground(stream: &impl IsTerminal) -> bool {
    stream.is_terminal()
}
