"""The ground both engines stand on, and nothing else: one error base, one reader of text and of TOML files, one
grammar of ranges ``A..B``, one reader of a pair of finite numbers (:func:`finite_pair`), one way to quote a value as a file writes it, one way a typed result
becomes a row (:class:`Row`) and one way a figure is written (:func:`save_figure`, byte-reproducible);
the dialect of TOML tables is :mod:`mechbase.schema`.

``synth`` and ``balance`` may import this package; it imports neither of them (tests/test_layering.py).

>>> from mechbase import parse_range, show
>>> parse_range("2..5"), parse_range("3.."), show([1, True])
((2, 5), (3, None), '[1, true]')
"""

from .errors import ProjectError
from .figures import save_figure
from .files import read_text
from .pairs import finite_pair
from .ranges import RangeSyntax, parse_range
from .rows import Row, as_row
from .text import show
from .toml import read_toml, read_toml_text, toml_value

__all__ = ["ProjectError", "RangeSyntax", "parse_range", "finite_pair", "Row", "as_row", "show", "read_toml", "read_toml_text", "toml_value", "read_text",
           "save_figure"]
