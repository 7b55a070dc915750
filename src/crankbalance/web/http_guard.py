"""A deadline for the head of every HTTP request the web server reads.

uvicorn times out a connection only while it is idle between requests (its keep-alive
timeout, which every received byte resets); a client that sends part of a request's head
and then stalls, or trickles it a byte at a time, holds its connection open for ever (the
"slowloris" pattern) and is never answered. The server binds 127.0.0.1 only, but one such
local client could still hold connections without end.

:func:`head_deadline_protocol` gives uvicorn's h11 protocol with one addition: from the
moment a connection opens, and again after each response, the head of the next request must
arrive within ``seconds``; otherwise the connection is closed, with one log line when part
of a head had arrived (a connection a browser opens ahead of use and never uses is closed
without a word). Once the head is in, the deadline no longer applies: the body has its own
(:data:`crankbalance.web.api.BODY_TIMEOUT`), and a response may take as long as its study.
"""

from __future__ import annotations

import asyncio
import logging
from typing import Any

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

log = logging.getLogger("crankbalance.web")

#: seconds a request's head (request line and headers) may take to arrive: a browser or a
#: script sends it at once, so this only ends a client that stalled or trickles
HEAD_TIMEOUT = 30.0


def head_deadline_protocol(seconds: float = HEAD_TIMEOUT) -> type[H11Protocol]:
    """uvicorn's h11 HTTP protocol with a deadline of ``seconds`` for each request's head.

    Parameters
    ----------
    seconds : float
        Time allowed for a request's head [s].

    Returns
    -------
    type
        A protocol class for uvicorn's ``http`` setting.
    """

    class HeadDeadline(H11Protocol):
        _deadline: asyncio.TimerHandle | None = None
        _received = 0

        def connection_made(self, transport: Any) -> None:
            super().connection_made(transport)
            self._arm()

        def data_received(self, data: bytes) -> None:
            self._received += len(data)
            super().data_received(data)

        def handle_events(self) -> None:
            super().handle_events()
            if self.conn.their_state is not h11.IDLE:  # the head is in
                self._disarm()

        def on_response_complete(self) -> None:
            super().on_response_complete()
            if not self.transport.is_closing() and self.conn.their_state is h11.IDLE:
                self._received = 0
                self._arm()

        def connection_lost(self, exc: Exception | None) -> None:
            self._disarm()
            super().connection_lost(exc)

        def _arm(self) -> None:
            self._disarm()
            self._deadline = self.loop.call_later(seconds, self._expired)

        def _disarm(self) -> None:
            if self._deadline is not None:
                self._deadline.cancel()
                self._deadline = None

        def _expired(self) -> None:
            self._deadline = None
            if self.transport.is_closing() or self.conn.their_state is not h11.IDLE:
                return
            if self._received:
                client = f"{self.client[0]}:{self.client[1]}" if self.client else "a client"
                log.warning(
                    "%s: the head of a request did not arrive within %g s (%d bytes came); "
                    "connection closed",
                    client,
                    seconds,
                    self._received,
                )
            self.transport.close()

    return HeadDeadline
