"""The exceptions of topoplex: every error the library raises is a :class:`TopoplexError`,
carrying the library's message (the file, the line, the simplex), and also the standard
exception it is a kind of, so ``except ValueError`` and ``except OSError`` catch them too."""


class TopoplexError(Exception):
    """Base of every error topoplex raises."""


class InputError(TopoplexError, ValueError):
    """Bad input: arrays of the wrong shape or values, ids out of range, a simplex that is not
    in the complex, an unknown name."""


class DomainError(InputError):
    """A structure's domain excludes the complex (e.g. ``ia`` on a non-pseudo-manifold); the
    message names the first offending simplex."""


class EditRefused(InputError):
    """A live-mesh edit was refused (link condition, not a top simplex, ...). Edits of a batch
    before the refused row stay applied; the refused one changed nothing."""


class FileError(TopoplexError, OSError):
    """A file could not be read or written."""


class ReadError(FileError):
    """A file could not be read: missing, unreadable, or malformed (bad syntax, ids out of
    range; the message names the file and the line or cell)."""


class WriteError(FileError):
    """A file could not be written (the format cannot hold the complex, or the OS refused)."""


class TopoplexMemoryError(TopoplexError, MemoryError):
    """The complex is too large for memory or for 32-bit ids."""


__all__ = [
    "TopoplexError",
    "InputError",
    "DomainError",
    "EditRefused",
    "FileError",
    "ReadError",
    "WriteError",
    "TopoplexMemoryError",
]
