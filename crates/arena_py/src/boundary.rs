//! The one door between Python and the core. Every `_core` entry point runs its core call
//! through [`call`]: the GIL is released, an unwinding panic is caught and becomes a typed
//! `InternalError` (an `ArenaError` subclass) with a one-line message, and every core error
//! maps to its `roboracer_arena.errors` class. A `PanicException` reaching Python is a bug.

use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

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

/// Run the core call `f` for the entry point `what` with the GIL released and unwinds
/// caught. Core errors map to their typed Python class; a panic becomes `InternalError`
/// naming `what`, the cause and the source location, on one line.
pub fn call<T, F>(py: Python<'_>, what: &str, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> arena_core::Result<T> + Send,
{
    match py.detach(|| panic::catch_unwind(AssertUnwindSafe(f))) {
        Ok(result) => result.map_err(to_py),
        Err(payload) => {
            let cause = payload_text(payload.as_ref()).replace('\n', " ");
            let at = LAST_PANIC
                .with(|p| p.borrow_mut().take())
                .unwrap_or_default();
            Err(InternalError::new_err(format!(
                "{what}: internal error on this input ({cause}; at {at}); please report it"
            )))
        }
    }
}

/// [`call`] for a core function that cannot fail except by panicking.
pub fn call_ok<T, F>(py: Python<'_>, what: &str, f: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    call(py, what, move || Ok(f()))
}

/// Panics inside [`call`] on purpose, so a test can prove that a core panic reaches
/// Python as `InternalError` (never `PanicException`) and leaves the process running.
#[pyfunction]
fn _boundary_self_test(py: Python<'_>) -> PyResult<()> {
    call(py, "_boundary_self_test", || -> arena_core::Result<()> {
        panic!("deliberate panic for the boundary self-test")
    })
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_boundary_self_test, m)?)?;
    Ok(())
}
