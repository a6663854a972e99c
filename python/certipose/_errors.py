# certipose._errors — the library's error types as Python exceptions (docs/python.md#errors).
#
# Every error certipose raises is a certipose.Error, and also the built-in exception a Python
# user would catch for that kind of mistake: a bad value is a ValueError, an index out of range
# an IndexError (and a ValueError), a file that cannot be read an OSError. The message is the
# library's, naming the offending field, index, value or file.


class Error(Exception):
    """Root of every exception certipose raises."""


class InvalidArgument(Error, ValueError):
    """An impossible parameter value; ``field`` names the parameter (or JSON path)."""

    def __init__(self, message: str, field: str = ""):
        super().__init__(message)
        self.field = field


class OutOfRange(Error, IndexError, ValueError):
    """An index (facet, vertex) outside its range: ``field``, ``index`` and ``size`` say which."""

    field: str = ""
    index: int = 0
    size: int = 0


class MeshError(Error, ValueError):
    """A mesh the method cannot work on (empty, non-finite, degenerate faces, not a solid where one is required)."""


class FileError(Error, OSError):
    """A file that is missing, unreadable or unparsable; ``filename`` names it."""

    def __str__(self) -> str:  # the library's message, which names the file (not "[Errno None] ...")
        return str(self.args[0]) if self.args else ""


class GeometryError(Error, ValueError):
    """The geometric kernel (CGAL) failed where the method needs a result, on this input."""
