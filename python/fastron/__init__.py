"""Fastron: learned proxy collision detection for robot motion planning.

Configurations are numpy arrays of joint values: shape (d,) for one, (n, d) for many. Labels are
+1 (in collision) and -1 (free), or booleans. Every error raises a subclass of fastron.Error that
also derives from the matching builtin (InvalidArgument from ValueError, FileError from OSError,
FileNotFound from FileNotFoundError). See docs/python.md.
"""

from ._fastron import *  # noqa: F401,F403
from ._fastron import __doc__ as _extension_doc  # noqa: F401

__version__ = "0.1.0"
