"""One way a test reads a refusal: the sentence of the error a call raises.

>>> refused(ValueError, int, "x")
"invalid literal for int() with base 10: 'x'"
"""

from __future__ import annotations

import pytest


def refused(error: type[Exception], call, *args, **kwargs) -> str:
    """The message of the ``error`` that ``call(*args, **kwargs)`` raises, checked to be one line
    (a refusal is one sentence)."""
    with pytest.raises(error) as info:
        call(*args, **kwargs)
    text = str(info.value)
    assert text and "\n" not in text, text
    return text
