//! The one door between Python and the core. Every `_core` entry point runs its core call
//! through [`call`] (or [`call_with_deadline`] for the generator's time-bounded work, run
//! on a worker thread): the GIL is released, an unwinding panic is caught and becomes a typed
//! `InternalError` (an `ArenaError` subclass) with a one-line message, and every core error
//! maps to its `roboracer_arena.errors` class. A `PanicException` reaching Python is a bug.

use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, Once};
use std::time::Duration;

use arena_core::generate::deadline::Deadline;
use pyo3::prelude::*;

use crate::errors::{to_py, InternalError};

thread_local! {
    /// Where the last panic on this thread happened, for the error message.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

static HOOK: Once = Once::new();

/// Replace the default panic hook (which prints "thread '…' panicked at …" to stderr)
/// with one that records the location for [`call`]'s message. With `RUST_BACKTRACE` set
/// the default hook still runs, for debugging.
pub fn install_panic_hook() {
    HOOK.call_once(|| {
        let default = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let at = info
                .location()
                .map(|l| format!("{}:{}", l.file(), l.line()))
                .unwrap_or_default();
            LAST_PANIC.with(|p| *p.borrow_mut() = Some(at));
            if std::env::var_os("RUST_BACKTRACE").is_some() {
                default(info);
            }
        }));
    });
}

fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown cause".to_string()
    }
}

/// A core call's result, or the one-line message of the panic that unwound it.
type Caught<T> = Result<arena_core::Result<T>, String>;

/// Run `f` on this thread with unwinds caught; a panic becomes the message naming `what`,
/// the cause and the source location the hook recorded on this thread.
fn caught<T>(what: &str, f: impl FnOnce() -> arena_core::Result<T>) -> Caught<T> {
    panic::catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let cause = payload_text(payload.as_ref()).replace('\n', " ");
        let at = LAST_PANIC
            .with(|p| p.borrow_mut().take())
            .unwrap_or_default();
        format!("{what}: internal error on this input ({cause}; at {at}); please report it")
    })
}

/// Core errors to their typed Python class, a caught panic to `InternalError`.
fn to_python<T>(out: Caught<T>) -> PyResult<T> {
    match out {
        Ok(result) => result.map_err(to_py),
        Err(message) => Err(InternalError::new_err(message)),
    }
}

/// Run the core call `f` for the entry point `what` with the GIL released and unwinds
/// caught. Core errors map to their typed Python class; a panic becomes `InternalError`
/// naming `what`, the cause and the source location, on one line.
pub fn call<T, F>(py: Python<'_>, what: &str, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> arena_core::Result<T> + Send,
{
    to_python(py.detach(|| caught(what, f)))
}

/// [`call`] for a core function that cannot fail except by panicking.
pub fn call_ok<T, F>(py: Python<'_>, what: &str, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    call(py, what, move || Ok(f()))
}

/// How often the waiting thread looks for Ctrl-C in [`call_with_deadline`] (Python
/// signal handlers only run on the main thread, so the core runs on a worker while it polls).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Grace (s) past the deadline before [`call_with_deadline`] stops waiting for a worker
/// that is inside one long step (rasterising or validating a very large map).
const DEADLINE_GRACE_S: f64 = 1.0;

/// [`call`] for time-bounded generator work: `work` runs on a worker thread with a
/// [`Deadline`] of `timeout` seconds (checked by the core; `None` = unbounded) while this
/// thread polls Python signals. On KeyboardInterrupt the deadline's cancellation flag is
/// set and the signal's exception raised at once; once the deadline (plus a short grace) has
/// passed, `Ok(None)` is returned at once. Either way the worker is left to stop at its
/// next deadline check, its result discarded, so one long step cannot hold the caller.
/// Errors and panics map as in [`call`].
pub fn call_with_deadline<T, F>(
    py: Python<'_>,
    what: &'static str,
    timeout: Option<f64>,
    work: F,
) -> PyResult<Option<T>>
where
    T: Send + 'static,
    F: FnOnce(&Deadline) -> arena_core::Result<T> + Send + 'static,
{
    let flag = Arc::new(AtomicBool::new(false));
    let cancel = flag.clone();
    let deadline = call(py, what, move || {
        Deadline::with_timeout(timeout, Some(cancel))
    })?;
    let hard_stop = Deadline::new(timeout.map(|t| t + DEADLINE_GRACE_S), None);
    // The worker's result slot: None while running.
    type Slot<T> = (Mutex<Option<Caught<T>>>, Condvar);
    let slot: Arc<Slot<T>> = Arc::new((Mutex::new(None), Condvar::new()));
    let worker_slot = slot.clone();
    std::thread::spawn(move || {
        let out = caught(what, || work(&deadline));
        let (lock, cv) = &*worker_slot;
        *lock.lock().unwrap_or_else(|e| e.into_inner()) = Some(out);
        cv.notify_all();
    });
    loop {
        // Wait up to `SIGNAL_POLL` (GIL released) for the worker; `None` = still running.
        let s = slot.clone();
        let done = py.detach(move || {
            let (lock, cv) = &*s;
            let g = lock.lock().unwrap_or_else(|e| e.into_inner());
            let (mut g, _) = cv
                .wait_timeout_while(g, SIGNAL_POLL, |v| v.is_none())
                .unwrap_or_else(|e| e.into_inner());
            g.take()
        });
        if let Some(out) = done {
            return to_python(out).map(Some);
        }
        if let Err(e) = py.check_signals() {
            flag.store(true, Ordering::Relaxed);
            return Err(e);
        }
        if hard_stop.stopped().is_some() {
            flag.store(true, Ordering::Relaxed);
            return Ok(None);
        }
    }
}

/// Panics inside [`call`] (or, with `budgeted`, on [`call_with_deadline`]'s worker thread)
/// on purpose, so a test can prove that a core panic reaches Python as `InternalError`
/// (never `PanicException`) and leaves the process running.
#[pyfunction]
#[pyo3(signature = (budgeted=false))]
fn _boundary_self_test(py: Python<'_>, budgeted: bool) -> PyResult<()> {
    fn boom() -> arena_core::Result<()> {
        panic!("deliberate panic for the boundary self-test")
    }
    if budgeted {
        call_with_deadline(py, "_boundary_self_test", Some(60.0), |_| boom()).map(|_| ())
    } else {
        call(py, "_boundary_self_test", boom)
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_boundary_self_test, m)?)?;
    Ok(())
}
