//! A wake-up of the network's runtime at a precise moment (Linux: a timerfd the runtime polls
//! with the sockets). The runtime's own timers count whole milliseconds, and a cycle of the
//! SPEED7 takes 60 µs: the CPU would start its cycles up to a millisecond late.

use std::io;
use std::os::fd::OwnedFd;
use std::time::Duration;

use rustix::time::{
    Itimerspec, TimerfdClockId, TimerfdFlags, TimerfdTimerFlags, Timespec, timerfd_create,
    timerfd_settime,
};
use tokio::io::Interest;
use tokio::io::unix::AsyncFd;

pub struct Alarm {
    timer: AsyncFd<OwnedFd>,
}

impl Alarm {
    /// An alarm on the runtime entered now.
    pub fn new() -> io::Result<Alarm> {
        let flags = TimerfdFlags::NONBLOCK | TimerfdFlags::CLOEXEC;
        let timer = timerfd_create(TimerfdClockId::Monotonic, flags)?;
        // tokio deprecates its safe constructor because an arbitrary `AsRawFd` may change its
        // descriptor; an `OwnedFd`, which the `AsyncFd` owns, cannot (the crate forbids
        // `unsafe`, which the constructor tokio now wants needs).
        #[allow(deprecated)]
        let timer = AsyncFd::with_interest(timer, Interest::READABLE)?;
        Ok(Alarm { timer })
    }

    /// Rings once `after` has passed (at the least a nanosecond: no time would disarm it).
    pub fn set(&self, after: Duration) -> io::Result<()> {
        let after = after.max(Duration::from_nanos(1));
        let value = Itimerspec {
            it_interval: Timespec {
                tv_sec: 0,
                tv_nsec: 0,
            },
            it_value: Timespec {
                tv_sec: after.as_secs() as _,
                tv_nsec: after.subsec_nanos() as _,
            },
        };
        timerfd_settime(self.timer.get_ref(), TimerfdTimerFlags::empty(), &value)?;
        Ok(())
    }

    /// Resolves when the alarm rings.
    pub async fn rung(&self) {
        loop {
            let Ok(mut ready) = self.timer.readable().await else {
                // The runtime is shutting down: nothing is waited for any more.
                return;
            };
            let mut count = [0u8; 8];
            match rustix::io::read(self.timer.get_ref(), &mut count) {
                Ok(_) => return,
                Err(_) => ready.clear_ready(),
            }
        }
    }
}
