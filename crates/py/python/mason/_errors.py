"""Mason's exceptions. Every error Mason raises is a ``MasonError``; bad input is also a
``ValueError``, with the same one-line message as the command line's (file, line or pixel,
and what is wrong)."""


class MasonError(Exception):
    """Base class of every error Mason raises."""


class InputError(MasonError, ValueError):
    """Bad input or a bad argument (the CLI's exit code 2)."""


class NoSolutionError(MasonError):
    """No solution within the budget, or none exists (the CLI's exit code 1)."""


class ValidationError(MasonError, ValueError):
    """A validator found a broken rule in a plan, schedule, trace or crew plan."""
