//! The local scheduler: a bounded pool of `jobs` worker threads, each running one point's
//! `aster-nl run` at a time, so at most `jobs` processes run at once.

use super::layout::{Layout, Manifest, PointStatus};
use super::point::run_point;
use crate::error::Result;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

/// What the pool reports as it goes.
#[derive(Debug)]
pub enum Event {
    Started(usize),
    Finished(usize, PointStatus),
}

/// Run the points `pending` (indices into the manifest), `jobs` at a time; `on_event` sees
/// every start and end, on the calling thread. Stops early only for an error of the
/// sweep's own files (a point that fails is an outcome, not an error).
pub fn run_pool(
    layout: &Layout,
    manifest: &Manifest,
    pending: &[usize],
    jobs: usize,
    exe: &Path,
    on_event: &mut dyn FnMut(Event),
) -> Result<()> {
    let next = AtomicUsize::new(0);
    let workers = jobs.clamp(1, pending.len().max(1));
    let (tx, rx) = mpsc::channel::<Result<Event>>();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let tx = tx.clone();
            let next = &next;
            scope.spawn(move || loop {
                let k = next.fetch_add(1, Ordering::SeqCst);
                let Some(&index) = pending.get(k) else { break };
                if tx.send(Ok(Event::Started(index))).is_err() {
                    break;
                }
                let r = run_point(layout, manifest, index, exe, "local")
                    .map(|s| Event::Finished(index, s));
                let failed = r.is_err();
                if tx.send(r).is_err() || failed {
                    // An error of our own files: the others stop taking points.
                    next.store(pending.len(), Ordering::SeqCst);
                    break;
                }
            });
        }
        drop(tx);
        let mut first_error = None;
        for r in rx {
            match r {
                Ok(ev) => on_event(ev),
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
        }
        first_error.map_or(Ok(()), Err)
    })
}
