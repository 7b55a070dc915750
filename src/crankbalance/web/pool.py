"""The worker processes of the web app's studies: bounded, cancellable, never in the way.

A study of a tab (the counterweight optimiser, the explorer, the crank loads, the balance
shop, the performance sweep, the single cylinder, the balance shaft) is pure Python and
numpy, CPU-bound: in a thread of the server it holds the GIL for long stretches and the
pages and requests of every other user wait (one optimiser once stalled ``/api/presets``
for 17 s). So each run is a process of its own (:func:`run`):

* **bounded**: at most :data:`WORKERS` run at once in the whole server, at most
  :data:`MAX_WAITING` more wait for a worker (more are refused in one line, :class:`Busy`);
  one page runs one study at a time (the page's :class:`Job`);
* **second to the server**: a worker runs at niceness :data:`NICE`, so the server's event
  loop (one core of the two) gets the processor first, and its address space is capped at
  :data:`MEMORY_LIMIT`;
* **cancellable**: :meth:`Job.cancel` kills the process (the work stops, not just its
  result), as the tab's *Cancel* button and the page going away do.

The processes come from a fork server (``multiprocessing``'s ``forkserver``, a clean
single-threaded process that has imported :data:`PRELOAD` once), so a run starts in
milliseconds and never forks the threads of the web server. The function and its arguments
go to the worker by pickle: module-level functions of :mod:`.studies` and plain data.
"""

from __future__ import annotations

import asyncio
import logging
import multiprocessing
import os
import resource
import signal
import traceback
import weakref
from collections.abc import Callable
from typing import Any

from ..errors import InputError

log = logging.getLogger("crankbalance.web")

#: studies running at once in the whole server (one per core of the 2-core machine the
#: app is sized for; the server itself runs before them, :data:`NICE`)
WORKERS = 2
#: studies waiting for a worker at once, all pages together; one more is refused
MAX_WAITING = 8
#: niceness of a worker process: the server's pages and API come first
NICE = 5
#: address space of one worker [bytes]: the work budgets keep the largest study near 1.5 GB
#: (docs/web.md, "Studies: budget, workers, cancel"); a run past this ends as out of memory
MEMORY_LIMIT = 6 * 2**30
#: modules the fork server imports once, so that a worker starts without importing them:
#: the tabs' study functions, and the balance shop's study with its MILP solver (scipy's
#: ``milp``) and parts reader, which a first shop run spent about 0.45 s importing on an
#: idle machine (issue 28, item 8)
PRELOAD = [
    "crankbalance.web.studies",
    "crankbalance.studies.shop",
    "crankbalance.io.parts_file",
    "scipy.optimize",
]

_context: Any = None
#: in a worker process: the sending end of its pipe, for :func:`report`
_sender: Any = None
_slots: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, asyncio.Semaphore] = (
    weakref.WeakKeyDictionary()
)
_waiting = 0


class Cancelled(Exception):
    """The run was cancelled (:meth:`Job.cancel`): its process was ended, no result."""


class Busy(InputError):
    """No worker free and :data:`MAX_WAITING` studies already waiting."""


class Job:
    """One run of a study in a worker process; :meth:`cancel` stops it.

    Parameters
    ----------
    what : str
        What runs, for messages ("the counterweight optimiser").
    owner : str
        The tab that runs it (its Cancel button cancels it).
    """

    def __init__(self, what: str, owner: str = "") -> None:
        self.what = what
        self.owner = owner
        self.cancelled = False
        self.process: Any = None
        self._stop: asyncio.Event | None = None
        #: called on the server's event loop with each progress report of the study
        #: (:func:`report` in the worker), if set
        self.on_progress: Callable[[Any], None] | None = None

    def cancel(self) -> None:
        """Stop the run: a waiting one never starts, a running one's process is killed."""
        self.cancelled = True
        if self.process is not None and self.process.is_alive():
            self.process.kill()
        if self._stop is not None:
            self._stop.set()

    @property
    def running(self) -> bool:
        """Whether the study's process is at work now."""
        return self.process is not None and self.process.is_alive()


def context() -> Any:
    """The ``forkserver`` context of the workers (set up once, with :data:`PRELOAD`)."""
    global _context
    if _context is None:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(PRELOAD)
        _context = ctx
    return _context


def warm_up() -> None:
    """Start the fork server (it imports :data:`PRELOAD`): the server calls this in the
    background as it starts, so that the first study does not wait for the imports."""
    from multiprocessing import forkserver

    context()
    forkserver.ensure_running()


def _slots_of_loop() -> asyncio.Semaphore:
    loop = asyncio.get_running_loop()
    if loop not in _slots:
        _slots[loop] = asyncio.Semaphore(WORKERS)
    return _slots[loop]


async def run(job: Job, function: Callable[..., Any], *args: Any) -> Any:
    """``function(*args)`` in a worker process; its result.

    Raises
    ------
    Cancelled
        When ``job`` was cancelled before or while it ran.
    InputError
        The study's own (bad input, a budget), or :class:`Busy` when too many wait, or the
        worker ended without a result (out of memory).
    """
    global _waiting
    if job.cancelled:
        raise Cancelled
    job._stop = asyncio.Event()
    slots = _slots_of_loop()
    if slots.locked() and _waiting >= MAX_WAITING:
        raise Busy(
            "server",
            f"{WORKERS} studies running, {_waiting} waiting",
            "is busy with the studies of other users; run this one again in a moment",
        )
    _waiting += 1
    try:
        await _acquire(slots, job)
    finally:
        _waiting -= 1
    try:
        return await _in_process(job, function, args)
    finally:
        slots.release()


async def _acquire(slots: asyncio.Semaphore, job: Job) -> None:
    """Wait for a free worker, or for the job's cancel."""
    assert job._stop is not None
    acquire = asyncio.ensure_future(slots.acquire())
    stop = asyncio.ensure_future(job._stop.wait())
    try:
        await asyncio.wait({acquire, stop}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        stop.cancel()
        if not acquire.done():
            acquire.cancel()
    if acquire.cancelled():
        raise Cancelled
    if job.cancelled:
        slots.release()
        raise Cancelled


async def _in_process(job: Job, function: Callable[..., Any], args: tuple[Any, ...]) -> Any:
    loop = asyncio.get_running_loop()
    ctx = context()
    receive, send = ctx.Pipe(duplex=False)
    process = ctx.Process(target=_work, args=(send, function, args), daemon=True)
    try:
        # the start talks to the fork server (the first time: starts it): not on the loop
        await loop.run_in_executor(None, process.start)
        job.process = process
        send.close()  # the worker holds the only sending end: its exit ends the receive
        if job.cancelled:  # cancelled while it started
            process.kill()
        answer = await loop.run_in_executor(None, _receive, receive, job, loop)
    finally:
        if process.pid is not None and process.is_alive():
            process.kill()  # the page's handler itself was cancelled: the work stops too
        receive.close()
    await loop.run_in_executor(None, process.join)
    if job.cancelled:
        raise Cancelled
    if answer is None:
        code = process.exitcode
        log.warning("a worker of %s ended without a result (exit code %s)", job.what, code)
        raise InputError(
            "study",
            job.what,
            "ended without a result: the worker ran out of memory or was stopped "
            f"(exit code {code}); lower its settings",
        )
    kind, *rest = answer
    if kind == "ok":
        return rest[0]
    if kind == "input":
        raise InputError(*rest)
    name, text = rest
    log.error("%s failed in its worker: %s\n%s", job.what, name, text)
    raise InputError(
        "study", job.what, f"failed ({name}); this is a bug of crankbalance, please report it"
    )


def _receive(connection: Any, job: Job, loop: asyncio.AbstractEventLoop) -> Any:
    """The worker's answer, or None when it ended without one (killed, out of memory);
    each progress report before it goes to ``job.on_progress`` on the event loop."""
    try:
        while True:
            answer = connection.recv()
            if answer[0] != "progress":
                return answer
            if job.on_progress is not None:
                loop.call_soon_threadsafe(job.on_progress, answer[1])
    except (EOFError, OSError):
        return None


def report(progress: Any) -> None:
    """In a worker process: send ``progress`` (plain data) to the page that runs the study
    (its :attr:`Job.on_progress`); elsewhere (a study run in the server's own process, the
    command line) nothing."""
    if _sender is not None:
        _sender.send(("progress", progress))


def _work(send: Any, function: Callable[..., Any], args: tuple[Any, ...]) -> None:
    """The worker process: lower its priority, cap its memory, run, send the answer."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C of the server ends it through its parent
    os.nice(NICE)
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    global _sender
    _sender = send
    try:
        answer: tuple[Any, ...] = ("ok", function(*args))
    except InputError as error:
        answer = ("input", error.field, error.value, error.allowed)
    except MemoryError:
        answer = ("input", "study", None, "needs more memory than a worker has; lower its settings")
    except Exception as error:  # a bug: its traceback goes to the server's log
        answer = ("bug", type(error).__name__, traceback.format_exc())
    try:
        send.send(answer)
    except Exception as error:  # an answer that does not pickle is a bug too
        send.send(("bug", type(error).__name__, traceback.format_exc()))
    finally:
        send.close()
