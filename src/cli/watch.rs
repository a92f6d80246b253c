//! Long runs: a progress line on a terminal, and Ctrl-C or SIGTERM halting the run at the next
//! cycle boundary (a second one ends the process at once).

use std::sync::Once;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::terminal::in_foreground;
use crate::trace::format_ms;
use crate::vm::Cpu;

/// Set by Ctrl-C or SIGTERM.
static HALT: AtomicBool = AtomicBool::new(false);

/// The exit code of a run halted by Ctrl-C or SIGTERM (128 + SIGINT, as shells report it).
pub const EXIT_HALTED: u8 = 130;

/// Wall time before the progress line appears: short runs print nothing.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// Cycles between two looks at the clock.
const CYCLES_PER_LOOK: u64 = 64;

/// A second signal this soon after the first is the same request: `timeout` sends its SIGTERM
/// both to the command and to the command's process group, so awl receives it twice at once.
const SAME_REQUEST_WITHIN: Duration = Duration::from_millis(500);

pub fn install_handler() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let first = std::sync::Mutex::new(None::<Instant>);
        // Without a handler (the platform refused) Ctrl-C simply ends the process.
        let _ = ctrlc::set_handler(move || {
            let mut first = first
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            let repeated = first.is_some_and(|at| at.elapsed() >= SAME_REQUEST_WITHIN);
            if HALT.swap(true, Ordering::SeqCst) && repeated {
                std::process::exit(i32::from(EXIT_HALTED));
            }
            first.get_or_insert_with(Instant::now);
        });
    });
}

/// Whether Ctrl-C or SIGTERM asked to end (`awl serve` ends then).
pub fn halt_requested() -> bool {
    HALT.load(Ordering::Relaxed)
}

/// Whether Ctrl-C was pressed since the last look (the debugger pauses then, instead of
/// halting).
pub fn take_interrupt() -> bool {
    HALT.swap(false, Ordering::SeqCst)
}

/// Watches one run from its cycle boundaries.
pub struct Watch {
    started: Instant,
    boundaries: u64,
    bar: Option<ProgressBar>,
    /// Whether a progress line may be shown (not with `--quiet`).
    progress: bool,
}

impl Watch {
    pub fn start() -> Self {
        install_handler();
        Watch {
            started: Instant::now(),
            boundaries: 0,
            bar: None,
            progress: true,
        }
    }

    /// The same watch without a progress line (`--quiet`).
    pub fn without_progress(self) -> Self {
        Watch {
            progress: false,
            ..self
        }
    }

    /// Whether the run goes on; updates the progress line now and then.
    pub fn go_on(&mut self, cpu: &Cpu) -> bool {
        if HALT.load(Ordering::Relaxed) {
            return false;
        }
        self.boundaries += 1;
        if !self.progress || !self.boundaries.is_multiple_of(CYCLES_PER_LOOK) {
            return true;
        }
        let wall = self.started.elapsed();
        if wall < QUIET_FOR {
            return true;
        }
        // Asked at every look: a job can be moved to the background and back (`bg`, `fg`).
        if !in_foreground(&std::io::stderr()) {
            self.remove_bar();
            return true;
        }
        let bar = self.bar.get_or_insert_with(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(ProgressStyle::with_template("{spinner} {msg}").expect("valid template"));
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        });
        let rate = cpu.instructions as f64 / wall.as_secs_f64() / 1e6;
        bar.set_message(format!(
            "running: simulated {}, {} cycles, {rate:.1} M instr/s (Ctrl-C halts at the next cycle end)",
            format_ms(cpu.clock),
            cpu.cycle
        ));
        true
    }

    /// Removes the progress line; whether the run was halted by Ctrl-C or SIGTERM.
    pub fn finish(mut self) -> bool {
        self.remove_bar();
        HALT.load(Ordering::Relaxed)
    }

    /// Clears the progress line, or leaves it as it is when the terminal is no longer awl's.
    fn remove_bar(&mut self) {
        if let Some(bar) = self.bar.take() {
            if !in_foreground(&std::io::stderr()) {
                bar.set_draw_target(ProgressDrawTarget::hidden());
            }
            bar.finish_and_clear();
        }
    }
}
