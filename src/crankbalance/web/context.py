"""What a tab of the web page may read and call: its context.

The page shell (:class:`crankbalance.web.app.Page`) builds one context per browser tab and
passes it to each of its tabs (``tab_*.py``, :class:`~.widgets.Tab`); a tab holds it as
``self.page`` and never imports the shell, so the modules of the tabs, the widgets, the
messages and the crank editor sit below :mod:`.app` in the import graph (no circle). A
context is the :class:`TabContext` protocol: the current project and computation, the
study settings' inputs and messages, the server's default preset, the running study of
the page (one at a time, in the worker pool, :mod:`.pool`) and the shell's actions a tab
triggers (recompute, load another project, downloads).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from .computation import Computed

if TYPE_CHECKING:
    from .form import FormField
    from .pool import Job
    from .project import Project


class TabContext(Protocol):
    """What a tab may read and call (the page shell implements it)."""

    #: the user's project: form texts, study settings, the last computation
    project: Project
    #: the name of the preset the server opens a page on (``crankbalance web --preset``)
    default_preset: str
    #: the inputs of the engine form and of the study settings, by key
    inputs: dict[str, Any]
    setting_inputs: dict[str, Any]
    #: what the computed results belong to (engine spec, orders); see :meth:`fresh`
    computed_for: tuple[Any, int] | None
    #: the page's study running in a worker process (one at a time), if any
    job: Job | None

    def field(self, f: FormField) -> None:
        """Lay out the input of an engine field (inside the current layout element)."""

    def setting(self, key: str, on_change: Callable[[], None] | None = None) -> None:
        """Lay out the input of a study setting; ``on_change`` runs after an edit."""

    def show_setting_errors(self, extra: dict[str, str] | None = None) -> None:
        """Show the messages of the settings (and ``extra`` ones, by key) under their inputs."""

    def on_mode(self, key: str, value: str) -> None:
        """A mode of the form changed (mass mode, conrod split): validate and update."""

    def update_all(self) -> None:
        """Validate the form, recompute a valid engine and refresh what is shown."""

    def fresh(self) -> Computed | None:
        """The computation when it belongs to the form as it is now, else None."""

    def problem(self) -> str:
        """Why the form cannot be computed, in the form's words."""

    def refresh_cards(self, tab: str) -> None:
        """Draw again the stale figures of the tab ``tab`` shown."""

    def load(self, project: Project, preset: str | None = None) -> None:
        """Show another project (``preset``: the preset it is) in the form and every tab."""

    def save(self, fmt: str) -> None:
        """Send the project as an engine file (``"toml"`` or ``"json"``) to the browser."""

    def download_data(self, what: str) -> None:
        """Send the computed data (``"analysis"``, ``"balance"``, ``"orders"``)."""

    async def download_report(self, fmt: str = "html") -> None:
        """Send the report of the computed engine (``fmt``: ``"html"`` or ``"pdf"``)."""
