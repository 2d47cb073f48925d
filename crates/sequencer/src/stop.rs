//! [`StopRequest`](crate::stop::StopRequest): how a signal handler asks a running sequence to stop.
//!
//! The handler (the CLI's, on SIGINT/SIGTERM) calls [`StopRequest::request`](crate::stop::StopRequest::request); the sequence
//! checks it before each frame, so it stops right after the frame in flight is committed.
//! The run keeps [`StopRequest::committed`](crate::stop::StopRequest::committed) up to date, so that a handler which must stop at
//! once (a second signal) can still say how many frames are safe on disk. Stopping at once is
//! safe at any moment: every file is written under a temporary name and renamed, and the next
//! run cleans up and resumes.
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicUsize, Ordering};

#[derive(Debug, Default)]
pub struct StopRequest {
    /// The signal that asked to stop, 0 while none did.
    signal: AtomicI32,
    /// Frames of the run's plan committed in its directory.
    committed: AtomicUsize,
    /// The run is past its frames (writing the report).
    reporting: AtomicBool,
}

impl StopRequest {
    /// Asks the run to stop after the frame in flight (`signal` names the cause).
    pub fn request(&self, signal: i32) {
        self.signal.store(signal, Ordering::SeqCst);
    }

    /// The signal that asked to stop, if any did.
    pub fn requested(&self) -> Option<i32> {
        match self.signal.load(Ordering::SeqCst) {
            0 => None,
            s => Some(s),
        }
    }

    pub fn set_committed(&self, n: usize) {
        self.committed.store(n, Ordering::SeqCst);
    }

    pub fn committed(&self) -> usize {
        self.committed.load(Ordering::SeqCst)
    }

    pub fn set_reporting(&self) {
        self.reporting.store(true, Ordering::SeqCst);
    }

    pub fn reporting(&self) -> bool {
        self.reporting.load(Ordering::SeqCst)
    }
}
