"""IRIS GL input events for headless runs.

:mod:`vgxsim.events.queue` models the event queue and device state
(:class:`EventQueue`); :mod:`vgxsim.events.script` parses the plain-text input
scripts that stand in for a user (:func:`parse_script`, :func:`load_script`).
A scripted run ends with :class:`ScriptExhausted`, which the runner catches.
"""

from vgxsim.events.queue import AUTO_QUEUED, EventQueue, EventSource, ScriptExhausted, Step
from vgxsim.events.script import KEY_NAMES, ScriptError, keystroke, load_script, parse_script

__all__ = [
    "AUTO_QUEUED",
    "EventQueue",
    "EventSource",
    "KEY_NAMES",
    "ScriptError",
    "ScriptExhausted",
    "Step",
    "keystroke",
    "load_script",
    "parse_script",
]
